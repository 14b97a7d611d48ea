#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::probe_analysis {

using reference::ProbeAmplitudes;
using reference::ProbeCase;
constexpr double kPi = std::numbers::pi;

namespace {

// The moments m_j = Σ ω^j P of powers P at frequencies ω (rad/s), j = 0, 1, 2.
struct Moments {
  double m0 = 0, m1 = 0, m2 = 0;
  double tm01() const { return 2 * kPi * m0 / m1; }          // s
  double tm02() const { return 2 * kPi * std::sqrt(m0 / m2); }  // s
};

Moments moments_of(const std::vector<double>& omega, const std::vector<double>& power) {
  Moments m;
  for (std::size_t i = 0; i < omega.size(); ++i) {
    m.m0 += power[i], m.m1 += omega[i] * power[i], m.m2 += omega[i] * omega[i] * power[i];
  }
  return m;
}

// The peak period of powers smoothed over a window of ±`half` lines (a box, the same for the
// measured and the expected powers so their peaks compare): reported, not judged — a
// periodogram's peak has no law a few lines can pin.
double smoothed_peak_period(const std::vector<double>& omega, const std::vector<double>& power, std::size_t half) {
  double best = -1, at = NAN, running = 0;
  std::vector<double> prefix(power.size() + 1, 0.0);
  for (std::size_t i = 0; i < power.size(); ++i) prefix[i + 1] = prefix[i] + power[i];
  for (std::size_t i = 0; i < power.size(); ++i) {
    const std::size_t lo = i >= half ? i - half : 0, hi = std::min(power.size(), i + half + 1);
    running = (prefix[hi] - prefix[lo]) / double(hi - lo);
    if (running > best) best = running, at = omega[i];
  }
  return 2 * kPi / at;
}

// P(Σ c_q u_q ≤ 0) for the line powers' law: u_q ~ Exp(1) (Rayleigh amplitudes) exactly by the
// saddlepoint of the mixed exponential sum; for n equal phasors per line (E u = 1,
// Var u = 1 − 1/n) by the normal law of the sum, which holds thousands of lines.
double linear_statistic_cdf(const ProbeCase& c, const std::vector<double>& coefficients) {
  if (c.synthesis.amplitudes == ProbeAmplitudes::rayleigh) {
    return stats::mixed_exponential_sum_cdf_at_zero(coefficients);
  }
  double mean = 0, variance = 0;
  for (double x : coefficients) mean += x, variance += x * x;
  variance *= 1 - 1.0 / c.synthesis.n_directions;
  return 0.5 * std::erfc(mean / std::sqrt(2 * variance));
}

double two_sided(double cdf) { return std::min(1.0, 2 * std::min(cdf, 1 - cdf)); }

}  // namespace

std::string frequency_rescale_diagnosis(const std::vector<double>& expected_omega, const std::vector<double>& expected,
                                        const std::vector<double>& measured_omega,
                                        const std::vector<double>& measured) {
  const Moments e = moments_of(expected_omega, expected), m = moments_of(measured_omega, measured);
  if (!(e.m0 > 0 && m.m0 > 0 && m.m1 > 0 && m.m2 > 0)) return "";
  const double energy = m.m0 / e.m0, scale01 = m.tm01() / e.tm01(), scale02 = m.tm02() / e.tm02();
  // Stretched alike in both periods (within 5 %), by more than 10 %, with the energy within
  // 20 %: the lines carry the right S Δω at the wrong frequencies.
  if (std::abs(std::log(scale01 / scale02)) > 0.05 || std::abs(std::log(scale01)) < 0.1 ||
      std::abs(std::log(energy)) > 0.2) {
    return "";
  }
  return fmt::format("Tm01 × {:.3g} and Tm02 × {:.3g} with the energy × {:.3g}: the spectrum is stretched in "
                     "frequency — frequencies rescaled, as when an engine puts the spectrum's lines on the "
                     "time grid's spacing 2π/(N dt) instead of their own Δω",
                     scale01, scale02, energy);
}

void spectral_moments(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                             double alpha, ProbeCheckReport& report) {
  const std::size_t n = c.layout.samples, probes = spectra.size();
  const Moments expected = moments_of(lines.omega, lines.expected);
  const bool exact = exact_scheme(c);
  double worst = exact ? 0 : 1;  // exact: error over bound; statistical: the smallest p
  std::size_t worst_probe = 0;
  Moments worst_measured;
  std::vector<double> worst_omega, worst_powers, worst_expected;  // the worst probe's judged lines
  for (std::size_t p = 0; p < probes; ++p) {
    std::vector<double> omega, powers, weights, bounds;
    for (std::size_t i = 0; i < lines.bins.size(); ++i) {
      const std::size_t q = lines.bins[i];
      // As series.energy: the bins whose expected power stands 10⁶ above the rounding's.
      if (!exact && !(lines.expected[i] > 1e6 * 2 * spectra[p].rounding * spectra[p].rounding)) continue;
      omega.push_back(lines.omega[i]);
      powers.push_back(spectra[p].periodogram(q, n));
      weights.push_back(lines.expected[i]);
      bounds.push_back(periodogram_error_bound(spectra[p].x[q], spectra[p].rounding) + 1e-12 * lines.expected[i]);
    }
    if (omega.empty()) continue;
    const Moments m = moments_of(omega, powers);
    double score;
    if (exact) {
      // |m1/m0 − e1/e0| ≤ (|m1| δ0 + m0 δ1)/m0² with δ_j = Σ ω^j bound: first order in the
      // bounds, which stand 10⁻⁸ and less below the moments.
      const Moments b = moments_of(omega, bounds);
      const double error1 = std::abs(m.m1 / m.m0 - expected.m1 / expected.m0) /
                            ((m.m1 * b.m0 + m.m0 * b.m1) / (m.m0 * m.m0));
      const double error2 = std::abs(m.m2 / m.m0 - expected.m2 / expected.m0) /
                            ((m.m2 * b.m0 + m.m0 * b.m2) / (m.m0 * m.m0));
      score = std::max(error1, error2);
    } else {
      // ω̄ = m1/m0 ≤ w ⇔ Σ P (ω − w) ≤ 0: the law of a linear statistic of the line powers.
      const Moments sample = m;
      std::vector<double> c1(omega.size()), c2(omega.size());
      for (std::size_t i = 0; i < omega.size(); ++i) {
        c1[i] = weights[i] * (omega[i] - sample.m1 / sample.m0);
        c2[i] = weights[i] * (omega[i] * omega[i] - sample.m2 / sample.m0);
      }
      score = std::min(1.0, 2 * std::min(two_sided(linear_statistic_cdf(c, c1)), two_sided(linear_statistic_cdf(c, c2))));
    }
    if (p == 0 || (exact ? score > worst : score < worst)) {
      worst = score, worst_probe = p, worst_measured = m;
      worst_omega = omega, worst_powers = powers, worst_expected = weights;
    }
  }
  if (worst_omega.empty()) {
    report.skipped.push_back({"series.moments", SkipReason::too_few_wave_vectors,
                              "no line stands 10³ above the rounding"});
    return;
  }
  const Moments& m = worst_measured;
  const std::string values =
      fmt::format("{}: Hs {:.4g} m, Tm01 {:.4g} s, Tm02 {:.4g} s (the lines: {:.4g} m, {:.4g} s, {:.4g} s)",
                  probe_name(worst_probe, c), 4 * std::sqrt(m.m0), m.tm01(), m.tm02(), 4 * std::sqrt(expected.m0),
                  expected.tm01(), expected.tm02());
  const double ratio = m.tm01() / expected.tm01();
  // The rescaling is looked for in the whole periodogram: rescaled lines leave the line bins.
  std::vector<double> all_omega, all_powers;
  for (std::size_t q = 1; 2 * q < n; ++q) {
    all_omega.push_back(2 * kPi * double(q) / c.layout.duration());
    all_powers.push_back(spectra[worst_probe].periodogram(q, n));
  }
  const std::string rescaled = frequency_rescale_diagnosis(lines.omega, lines.expected, all_omega, all_powers);
  if (exact) {
    report.results.push_back(exact_check(
        "series.moments", c.describe(), worst, 1, worst <= 1,
        "|m1/m0 − Σ ω S Δω/Σ S Δω| and |m2/m0 − …| ≤ the periodograms' rounding bounds, every probe",
        worst <= 1 ? values : values + (rescaled.empty() ? " — the energy sits at other frequencies than S(ω)"
                                                         : " — " + rescaled)));
  } else {
    const double p_value = std::min(1.0, worst * double(probes));
    report.results.push_back(statistical_check(
        "series.moments", c.describe(), ratio, 1, p_value, alpha,
        fmt::format("p ≥ α = {:.0e} (m1/m0 and m2/m0 of the line powers: {}; Bonferroni over the two and {} "
                    "probes)",
                    alpha,
                    c.synthesis.amplitudes == ProbeAmplitudes::rayleigh ? "mixed exponential sums, saddlepoint"
                                                                        : "normal law of the phasor sums",
                    probes),
        p_value < alpha ? values + (rescaled.empty() ? " — the energy sits at other frequencies than S(ω)"
                                                     : " — " + rescaled)
                        : values));
  }
  report.notes.push_back(fmt::format(
      "{}: Tp {:.4g} s of the periodogram smoothed over ±{} lines (the lines' own, smoothed alike: {:.4g} s)",
      probe_name(worst_probe, c), smoothed_peak_period(worst_omega, worst_powers, 16), 16,
      smoothed_peak_period(worst_omega, worst_expected, 16)));
}

}  // namespace swell::validation::probe_analysis
