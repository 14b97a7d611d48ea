#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "checks/ocean/analysis.hpp"  // ring_shape
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::probe_analysis {

using reference::ProbeAmplitudes;
using reference::ProbeCase;
using reference::ProbeDirections;
using reference::ProbeFrequencies;
constexpr double kPi = std::numbers::pi;

namespace {

// Deterministic amplitudes, n directions per frequency: at any probe a line bin holds n equal
// phasors of independent uniform phases, u = I/(S Δω) = |Σ e^(iψ_j)|²/n, with E u = 1,
// Var u = 1 − 1/n and third central moment 2 (1 − 1/n)(1 − 2/n) (the moments of a planar random
// walk, E|S|⁴ = 2n² − n, E|S|⁶ = 6n³ − 9n² + 4n). A ring of m bins sums m of them; its law is
// taken as the Gamma of those two moments, shape m/(1 − 1/n), scale 1 − 1/n, whose third moment
// exceeds the true one by (1 − 1/n)/(1 − 2/n) (7 % at n = 15, ProbeCalibration measures the
// rate). Rings and Fisher's method as spectrum.shape's, Bonferroni over probes.
void equal_phasor_spectrum(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                           double alpha, ProbeCheckReport& report) {
  const std::size_t n = c.layout.samples, probes = spectra.size();
  const double scale = 1 - 1.0 / c.synthesis.n_directions;
  double worst_p = 1, worst_ratio = 1;
  std::size_t worst_probe = 0;
  std::vector<double> judged_expected, judged_measured;
  for (std::size_t p = 0; p < probes; ++p) {
    std::vector<double> u, expected, measured;
    for (std::size_t i = 0; i < lines.bins.size(); ++i) {
      const double e = lines.expected[i];
      if (!(e > 1e6 * 2 * spectra[p].rounding * spectra[p].rounding)) continue;
      const double m = spectra[p].periodogram(lines.bins[i], n);
      u.push_back(m / e), expected.push_back(e), measured.push_back(m);
    }
    if (u.empty()) continue;
    const int count = int(u.size()), rings = std::clamp(count / 64, 1, 24);
    std::vector<double> p_values;
    double ring_worst_p = 1, ring_worst_ratio = 1;
    for (int r = 0; r < rings; ++r) {
      const int begin = r * count / rings, end = (r + 1) * count / rings;
      double sum = 0;
      for (int i = begin; i < end; ++i) sum += u[std::size_t(i)];
      const double shape = (end - begin) / scale;
      const double ring_p = std::min(1.0, 2 * std::min(stats::gamma_lower_p(shape, sum / scale),
                                                       stats::gamma_upper_p(shape, sum / scale)));
      p_values.push_back(ring_p);
      if (ring_p <= ring_worst_p) ring_worst_p = ring_p, ring_worst_ratio = sum / (end - begin);
    }
    const double combined = stats::fisher_combined_p(p_values);
    if (combined <= worst_p) {
      worst_p = combined, worst_probe = p, worst_ratio = ring_worst_ratio;
      judged_expected = expected, judged_measured = measured;
    }
  }
  const double p_value = std::min(1.0, worst_p * double(probes));
  report.results.push_back(statistical_check(
      "series.spectrum", c.describe(), worst_ratio, 1, p_value, alpha,
      fmt::format("p ≥ α = {:.0e} (I/(S Δω) of {} equal phasors: rings of bins by the Gamma law of its mean "
                  "and variance, Fisher's method; Bonferroni over {} probes)",
                  alpha, c.synthesis.n_directions, probes),
      fmt::format("{}: worst ring of bins at {:.3f} × S Δω{}", probe_name(worst_probe, c), worst_ratio,
                  p_value < alpha ? " — " + spectrum_diagnosis(judged_expected, judged_measured,
                                                               "the periodogram does not follow S(ω) with "
                                                               "deterministic amplitudes")
                                  : "")));
  // series.energy: Σ e_q u_q, mean Σ e_q, variance (1 − 1/n) Σ e_q², by the Gamma of those two
  // moments as the rings.
  double energy_p = 1, energy_ratio = 1, energy_sd = 0;
  std::size_t energy_probe = 0;
  for (std::size_t p = 0; p < probes; ++p) {
    double mean = 0, variance = 0, measured = 0;
    for (std::size_t i = 0; i < lines.bins.size(); ++i) {
      const double e = lines.expected[i];
      if (!(e > 1e6 * 2 * spectra[p].rounding * spectra[p].rounding)) continue;
      mean += e, variance += scale * e * e, measured += spectra[p].periodogram(lines.bins[i], n);
    }
    if (!(mean > 0)) continue;
    const double shape = mean * mean / variance, theta = variance / mean;
    const double p_value = std::min(1.0, 2 * std::min(stats::gamma_lower_p(shape, measured / theta),
                                                      stats::gamma_upper_p(shape, measured / theta)));
    if (p == 0 || p_value < energy_p) {
      energy_p = p_value, energy_probe = p, energy_ratio = measured / mean, energy_sd = std::sqrt(variance) / mean;
    }
  }
  const double energy_combined = std::min(1.0, energy_p * double(probes));
  report.results.push_back(statistical_check(
      "series.energy", c.describe(), energy_ratio, 1, energy_combined, alpha,
      fmt::format("p ≥ α = {:.0e} (Σ of S Δω u over the lines, u = |Σ e^(iψ)|²/{}: the Gamma of its mean and "
                  "variance; Bonferroni over {} probes)",
                  alpha, c.synthesis.n_directions, probes),
      fmt::format("{}: the lines carry {:.4g} × Σ S Δω (p = {:.2g}){}", probe_name(energy_probe, c), energy_ratio,
                  energy_p,
                  energy_combined < alpha
                      ? fmt::format(" — energy off by {:.3g} (Hs by {:.3g}){}", energy_ratio, std::sqrt(energy_ratio),
                                    energy_factor_meaning(energy_ratio, energy_ratio / (1 + 6 * energy_sd),
                                                          energy_ratio / std::max(1e-3, 1 - 6 * energy_sd),
                                                          directions_per_frequency(c)))
                      : "")));
}

bool judged_scheme(const ProbeCase& c) {
  return c.synthesis.amplitudes == ProbeAmplitudes::rayleigh || exact_scheme(c);
}

void judged_spectrum_and_energy(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                         double alpha, ProbeCheckReport& report) {
  const std::size_t n = c.layout.samples, probes = spectra.size();
  const std::string subject = c.describe();
  if (exact_scheme(c)) {
    double worst = 0, worst_relative = 0, worst_omega = 0, energy_error = 0, energy_bound = 0, energy_ratio = 1;
    std::size_t worst_probe = 0;
    std::vector<double> measured_powers;  // probe 0's, for the diagnosis
    for (std::size_t p = 0; p < probes; ++p) {
      double measured_energy = 0, expected_energy = 0, bound_energy = 0;
      for (std::size_t i = 0; i < lines.bins.size(); ++i) {
        const std::size_t q = lines.bins[i];
        const double measured = spectra[p].periodogram(q, n), expected = lines.expected[i];
        if (p == 0) measured_powers.push_back(measured);
        // The reference's S(ω) and the sum: a few ulps of the bin's energy.
        const double bound = periodogram_error_bound(spectra[p].x[q], spectra[p].rounding) + 1e-12 * expected;
        const double ratio = std::abs(measured - expected) / bound;
        if (ratio > worst) {
          worst = ratio, worst_probe = p, worst_omega = lines.omega[i];
          worst_relative = expected > 0 ? measured / expected - 1 : INFINITY;
        }
        measured_energy += measured, expected_energy += expected, bound_energy += bound;
      }
      const double e = std::abs(measured_energy - expected_energy) / bound_energy;
      if (e >= energy_error) {
        energy_error = e, energy_bound = bound_energy / std::max(expected_energy, 1e-300);
        energy_ratio = measured_energy / expected_energy;
      }
    }
    report.results.push_back(exact_check(
        "series.spectrum", subject, worst, 1, worst <= 1,
        "|I_q − S Δω| ≤ the stored values' rounding, at every line's bin of every probe",
        worst <= 1 ? fmt::format("every line's periodogram is S(ω) Δω to its rounding ({} lines × {} probes)",
                                 lines.bins.size(), probes)
                   : fmt::format("{}: at ω = {:.4g} rad/s the periodogram is S Δω × {:.6g} ({:.3g}× the "
                                 "rounding bound) — {}",
                                 probe_name(worst_probe, c), worst_omega, 1 + worst_relative, worst,
                                 spectrum_diagnosis(lines.expected, measured_powers,
                                                    "the amplitudes are not √(2 S Δω)"))));
    report.results.push_back(exact_check(
        "series.energy", subject, energy_error, 1, energy_error <= 1,
        "|Σ I_q − Σ S Δω| ≤ the summed rounding bounds, every probe",
        energy_error <= 1
            ? fmt::format("the lines carry Σ S Δω to {:.2g} relative", energy_bound)
            : fmt::format("the lines carry {:.6g} × Σ S Δω (Hs × {:.4g}){}", energy_ratio, std::sqrt(energy_ratio),
                          energy_factor_meaning(energy_ratio, energy_ratio * (1 - 3 * energy_bound - 1e-9),
                                                energy_ratio * (1 + 3 * energy_bound + 1e-9), directions_per_frequency(c)))));
    return;
  }
  // Rayleigh: u_q = I_q/(S Δω) independent Exp(1) over the bins, at each probe.
  double spectrum_p = 1, energy_p = 1, worst_ratio = 1, worst_energy_ratio = 1, energy_low = 1, energy_high = 1;
  std::size_t spectrum_probe = 0, energy_probe = 0;
  std::vector<double> judged_expected, judged_measured;  // the worst probe's, for the diagnosis
  for (std::size_t p = 0; p < probes; ++p) {
    std::vector<ocean_analysis::NormalizedOrdinate> ordinates;
    std::vector<double> weights, measured_powers;
    double measured_energy = 0;
    for (std::size_t i = 0; i < lines.bins.size(); ++i) {
      const std::size_t q = lines.bins[i];
      const double expected = lines.expected[i];
      // A bin is judged where its expected power stands 10⁶ above the rounding's.
      if (!(expected > 1e6 * 2 * spectra[p].rounding * spectra[p].rounding)) continue;
      const double measured = spectra[p].periodogram(q, n);
      ordinates.push_back({lines.omega[i], measured / expected});
      weights.push_back(expected);
      measured_powers.push_back(measured);
      measured_energy += measured;
    }
    if (ordinates.empty()) continue;
    const auto shape = ocean_analysis::ring_shape(ordinates);
    if (shape.p <= spectrum_p) {
      spectrum_p = shape.p, spectrum_probe = p, worst_ratio = shape.worst_ratio;
      judged_expected = weights, judged_measured = measured_powers;
    }
    const stats::WeightedExponentialSum law(weights);
    const double p_energy = law.two_sided_p(measured_energy);
    if (p_energy <= energy_p) {
      energy_p = p_energy, energy_probe = p, worst_energy_ratio = measured_energy / law.mean();
      // The ratios the law's central 1 − α/P holds: the causes the sampling cannot tell apart.
      const double tail = alpha / (2 * double(probes));
      energy_low = measured_energy / law.quantile(1 - tail);
      energy_high = measured_energy / law.quantile(tail);
    }
  }
  // Bonferroni over the probes: each probe's test at α / P.
  const double spectrum_combined = std::min(1.0, spectrum_p * double(probes));
  const double energy_combined = std::min(1.0, energy_p * double(probes));
  report.results.push_back(statistical_check(
      "series.spectrum", subject, worst_ratio, 1, spectrum_combined, alpha,
      fmt::format("p ≥ α = {:.0e} (I/(S Δω) ~ Exp(1): Gamma per ring of bins, Fisher's method; "
                  "Bonferroni over {} probes)", alpha, probes),
      fmt::format("{}: worst ring of bins at {:.3f} × S Δω (p = {:.2g}){}", probe_name(spectrum_probe, c),
                  worst_ratio, spectrum_p,
                  spectrum_combined < alpha
                      ? " — " + spectrum_diagnosis(judged_expected, judged_measured,
                                                   "the periodogram does not follow S(ω) with Rayleigh amplitudes")
                      : "")));
  report.results.push_back(statistical_check(
      "series.energy", subject, worst_energy_ratio, 1, energy_combined, alpha,
      fmt::format("p ≥ α = {:.0e} (Σ of S Δω Exp(1) over the lines, saddlepoint law; Bonferroni over {} "
                  "probes)", alpha, probes),
      fmt::format("{}: the lines carry {:.4g} × Σ S Δω (p = {:.2g}){}", probe_name(energy_probe, c),
                  worst_energy_ratio, energy_p,
                  energy_combined < alpha ? fmt::format(" — energy off by {:.3g} (Hs by {:.3g}){}", worst_energy_ratio,
                                                        std::sqrt(worst_energy_ratio),
                                                        energy_factor_meaning(worst_energy_ratio, energy_low, energy_high, directions_per_frequency(c)))
                                          : "")));
}

}  // namespace

void line_spectrum_and_energy(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                              double alpha, ProbeCheckReport& report) {
  if (judged_scheme(c)) {
    judged_spectrum_and_energy(c, lines, spectra, alpha, report);
  } else {
    equal_phasor_spectrum(c, lines, spectra, alpha, report);
  }
}

}  // namespace swell::validation::probe_analysis
