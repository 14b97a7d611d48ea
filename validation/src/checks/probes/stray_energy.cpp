#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace swell::validation::probe_analysis {

using reference::ProbeAmplitudes;
using reference::ProbeCase;
using reference::ProbeDirections;
using reference::ProbeFrequencies;
constexpr double kPi = std::numbers::pi;

void stray_energy(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                  ProbeCheckReport& report) {
  const std::size_t n = c.layout.samples;
  double worst = 0, worst_bound = 0, worst_share = 0;
  std::size_t worst_probe = 0, worst_bin = 0;
  for (std::size_t p = 0; p < spectra.size(); ++p) {
    std::vector<char> line(n / 2 + 1, 0);
    for (std::size_t q : lines.bins) line[q] = 1;
    if (n % 2 == 0) line[n / 2] = 1;  // a line on the Nyquist bin is not judged there
    double stray = 0, total = 0, largest = 0;
    std::size_t at = 0;
    for (std::size_t q = 0; q <= n / 2; ++q) {
      const double power = spectra[p].periodogram(q, n);
      total += power;
      if (line[q]) continue;
      stray += power;
      if (power > largest) largest = power, at = q;
    }
    const double bound = 2 * spectra[p].rounding * spectra[p].rounding;
    // The probe whose stray energy stands highest over its own bound.
    if (p == 0 || stray * worst_bound > worst * bound) {
      worst = stray, worst_bound = bound, worst_probe = p, worst_bin = at;
      worst_share = total > 0 ? stray / total : 0;
    }
  }
  const bool ok = worst <= worst_bound;
  const double omega = 2 * kPi * double(worst_bin) / c.layout.duration();
  std::string where = worst_bin == 0 ? "the mean level (ω = 0) is not 0"
                                     : fmt::format("largest at ω = {:.4g} rad/s", omega);
  if (!ok && worst_bin != 0) {
    // Between the lines' bins: lines that are not on the repeat period's grid.
    where += lines.whole_periods > 1 || worst_bin % std::max<std::size_t>(lines.whole_periods, 1) != 0
                 ? " — energy between the lines' frequencies: lines off the grid Δω = 2π/repeat_period "
                   "(frequencies rescaled, or another repeat period than declared)"
                 : " — a line outside the declared omega_cutoff band";
  }
  report.results.push_back(bounded_check(
      "series.stray_energy", c.describe(), worst, worst_bound,
      "Σ I over bins no line falls on ≤ 2 r² (Parseval; r the values' rounding bound)",
      ok ? fmt::format("only rounding outside the lines' bins ({:.2g} m² ≤ {:.2g} m²)", worst, worst_bound)
         : fmt::format("{}: {:.3g} of the variance sits where no line is ({})", probe_name(worst_probe, c),
                       worst_share, where)));
}

// One line per frequency (long-crested, or one direction per frequency): each line reaches every
// probe with the same amplitude, so |X_q^p| = |X_q^0| at every line's bin, exactly. An engine
// that interpolates its probes from a grid loses energy off the nodes, more at the shorter
}  // namespace swell::validation::probe_analysis
