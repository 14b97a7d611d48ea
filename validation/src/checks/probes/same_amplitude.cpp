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

void same_amplitude(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                    ProbeCheckReport& report) {
  double worst = 0;
  std::size_t worst_probe = 1;
  double worst_omega = 0, worst_ratio = 1;
  for (std::size_t p = 1; p < spectra.size(); ++p) {
    for (std::size_t i = 0; i < lines.bins.size(); ++i) {
      const std::size_t q = lines.bins[i];
      const double a = std::abs(spectra[0].x[q]), b = std::abs(spectra[p].x[q]);
      const double bound = spectra[0].rounding + spectra[p].rounding + 1e-15 * (a + b);
      const double error = std::abs(b - a) / bound;
      if (error > worst) worst = error, worst_probe = p, worst_omega = lines.omega[i], worst_ratio = a > 0 ? b / a : 0;
    }
  }
  const bool ok = worst <= 1;
  std::string reason;
  if (ok) {
    reason = fmt::format("every line reaches the {} probes with one amplitude ({} lines)", spectra.size(),
                         lines.bins.size());
  } else {
    // The variance probe p carries against probe 0's, below and above the median line.
    const std::size_t half = lines.bins.size() / 2;
    double low_p = 0, low_0 = 0, high_p = 0, high_0 = 0;
    for (std::size_t i = 0; i < lines.bins.size(); ++i) {
      const std::size_t q = lines.bins[i];
      (i < half ? low_p : high_p) += std::norm(spectra[worst_probe].x[q]);
      (i < half ? low_0 : high_0) += std::norm(spectra[0].x[q]);
    }
    const double low = low_0 > 0 ? low_p / low_0 : 1, high = high_0 > 0 ? high_p / high_0 : 1;
    reason = fmt::format("{}: at ω = {:.4g} rad/s its amplitude is {:.6g} × probe 0's ({:.3g}× the rounding "
                         "bound); its line variance is {:.4g} × probe 0's below the median line and {:.4g} × above",
                         probe_name(worst_probe, c), worst_omega, worst_ratio, worst, low, high);
    if (high < low && high < 1) {
      reason += " — the shorter waves lose more: values interpolated between grid nodes (an off-node probe)";
    } else {
      reason += " — the lines do not reach every probe with one amplitude";
    }
  }
  report.results.push_back(exact_check("series.same_amplitude", c.describe(), worst, 1, ok,
                                       "||X_q^p| − |X_q^0|| ≤ the rounding, every line's bin and probe", reason));
}

}  // namespace swell::validation::probe_analysis
