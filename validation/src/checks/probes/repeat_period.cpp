#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace swell::validation::probe_analysis {

using reference::ProbeCase;
using reference::ProbeFrequencies;

namespace {

// The largest |η_{n+M} − η_n| over the record, against the bound 2r of two values' rounding.
double worst_repeat_error(const std::vector<double>& series, std::size_t period, double rounding) {
  double worst = 0;
  for (std::size_t n = 0; n + period < series.size(); ++n) {
    worst = std::max(worst, std::abs(series[n + period] - series[n]) / (2 * rounding));
  }
  return worst;
}

}  // namespace

std::size_t repeat_period_samples(const ProbeCase& c) {
  const auto& s = c.synthesis;
  if (s.frequencies != ProbeFrequencies::uniform || !(s.repeat_period > 0)) return 0;
  const double samples = s.repeat_period / c.layout.dt, whole = std::round(samples);
  if (!(whole >= 2) || std::abs(samples - whole) > 1e-9 * whole) return 0;
  return std::size_t(whole);
}

void repeat_period(const ProbeCase& c, const std::vector<std::vector<double>>& elevation,
                   const std::vector<double>& rounding, ProbeCheckReport& report) {
  const std::size_t period = repeat_period_samples(c);
  double worst = 0;
  std::size_t worst_probe = 0;
  for (std::size_t p = 0; p < elevation.size(); ++p) {
    // The rounding of a stored value, with the engine's own sum's (8 u of its largest value): the
    // two repeats come from different arguments, so their sums round differently.
    double largest = 0;
    for (double v : elevation[p]) largest = std::max(largest, std::abs(v));
    const double r = rounding[p] + 8 * 0x1p-53 * largest + 1e-300;
    const double error = worst_repeat_error(elevation[p], period, r);
    if (p == 0 || error > worst) worst = error, worst_probe = p;
  }
  const bool ok = worst <= 1;
  std::string reason;
  if (ok) {
    reason = fmt::format("η(t + {:g} s) = η(t) over the {:g} s the record repeats, every probe",
                         c.synthesis.repeat_period, c.layout.duration() - c.synthesis.repeat_period);
  } else {
    reason = fmt::format("{}: η(t + {:g} s) differs from η(t) by {:.3g}× the rounding bound — the series does not "
                         "repeat after the declared repeat period (lines off Δω = 2π/repeat_period, or another "
                         "period than declared)",
                         probe_name(worst_probe, c), c.synthesis.repeat_period, worst);
  }
  report.results.push_back(exact_check("series.repeat_period", c.describe(), worst, 1, ok,
                                       "|η_{n+M} − η_n| ≤ 2 r, M = repeat_period/dt, every probe", reason));
}

}  // namespace swell::validation::probe_analysis
