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

void phase(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
           ProbeCheckReport& report) {
  const auto sea = c.spectrum();
  const double theta = sea->mean_direction();
  const auto dispersion = c.sea.dispersion();
  const double g = c.sea.gravity;
  double worst = 0, worst_error = 0, worst_omega = 0, deep_worst = 0, reversed_worst = 0;
  std::size_t worst_probe = 1, judged = 0;
  std::vector<double> in_phase(spectra.size(), 0.0);  // per probe: the largest |measured phase| / bound
  for (std::size_t p = 1; p < spectra.size(); ++p) {
    const double dx = c.layout.positions[p][0] - c.layout.positions[0][0];
    const double dy = c.layout.positions[p][1] - c.layout.positions[0][1];
    const double along = std::cos(theta) * dx + std::sin(theta) * dy;
    for (std::size_t i = 0; i < lines.bins.size(); ++i) {
      const std::size_t q = lines.bins[i];
      const Complex a = spectra[0].x[q], b = spectra[p].x[q];
      const double ra = spectra[0].rounding, rb = spectra[p].rounding;
      // Judged where both bins stand far above their rounding (the phase is then defined).
      if (!(std::abs(a) > 1e3 * ra && std::abs(b) > 1e3 * rb)) continue;
      const double measured = std::arg(std::conj(b) * a);
      const double k = dispersion.wavenumber(lines.omega[i]);
      const double bound = std::asin(std::min(1.0, ra / std::abs(a))) + std::asin(std::min(1.0, rb / std::abs(b))) +
                           1e-12 * (1 + std::abs(k * along));
      const double error = std::remainder(measured - k * along, 2 * kPi);
      const double deep = std::remainder(measured - lines.omega[i] * lines.omega[i] / g * along, 2 * kPi);
      const double reversed = std::remainder(measured + k * along, 2 * kPi);
      ++judged;
      if (std::abs(error) / bound > worst) {
        worst = std::abs(error) / bound, worst_error = error, worst_omega = lines.omega[i], worst_probe = p;
      }
      // An engine's own g may differ from the case's (9.80665 against 9.81 shifts k by 5e-4):
      // the deep-water diagnosis allows 10⁻³ of the deep-water phase.
      const double deep_k = lines.omega[i] * lines.omega[i] / g;
      deep_worst = std::max(deep_worst, std::abs(deep) / (bound + 1e-3 * std::abs(deep_k * along)));
      in_phase[p] = std::max(in_phase[p], std::abs(measured) / bound);
      reversed_worst = std::max(reversed_worst, std::abs(reversed) / bound);
    }
  }
  if (judged == 0) {
    report.skipped.push_back({"series.phase", SkipReason::too_few_wave_vectors,
                              "no line stands 10³ above the rounding at two probes"});
    return;
  }
  const bool ok = worst <= 1;
  std::string reason;
  if (ok) {
    reason = fmt::format("every line's phase between probes is k(ω) ê·Δx of the case's dispersion ({} "
                         "line-probe pairs)", judged);
  } else {
    reason = fmt::format("{}: at ω = {:.4g} rad/s the phase from probe 0 is off by {:.3g} rad", probe_name(worst_probe, c),
                         worst_omega, worst_error);
    const bool same_series = in_phase[worst_probe] <= 1 && judged > 0;
    if (same_series) {
      reason += fmt::format(" — probe {} moves in phase with probe 0 at every frequency, as if both stood at one "
                            "point: a probe clamped to the domain's edge, or two probes read from one grid node",
                            worst_probe);
    } else if (deep_worst <= 1 && std::isfinite(c.sea.depth)) {
      reason += fmt::format(" — the phases follow deep-water k = ω²/g where the case's depth is {:g} m "
                            "(a deep-water dispersion in finite depth)", c.sea.depth);
    } else if (reversed_worst <= 1) {
      reason += " — the phases are −k ê·Δx: the waves travel against the declared direction (θ + 180°), "
                "or the phase's sign is reversed (cos(ωt − k·x))";
    } else {
      reason += " — the waves do not travel toward the declared direction at the case's k(ω)";
    }
  }
  report.results.push_back(exact_check("series.phase", c.describe(), worst, 1, ok,
                                       "|arg(conj X_p X_0) − k ê·Δx| ≤ the rounding's phase bound", reason));
}
}  // namespace swell::validation::probe_analysis
