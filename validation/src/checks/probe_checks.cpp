#include "swell/validation/checks/probe_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "checks/ocean/analysis.hpp"  // ring_shape
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation {
namespace {

using Complex = std::complex<double>;
using reference::ProbeAmplitudes;
using reference::ProbeCase;
using reference::ProbeDirections;
using reference::ProbeFrequencies;
constexpr double kPi = std::numbers::pi;

// X_q = (1/N) Σ η_n e^(−2πi q n/N), q = 0 … N/2, by FFTW.
std::vector<Complex> half_spectrum(const std::vector<double>& series) {
  const std::size_t n = series.size();
  impls::TransformSpec spec;
  spec.nx = int(n);
  spec.kind = impls::Kind::c2c;
  spec.direction = impls::Direction::forward;
  const auto plan = impls::make_backend("fftw")->plan(spec);
  std::vector<Complex> in(series.begin(), series.end()), out(n);
  plan->execute(std::span<const Complex>(in), std::span<Complex>(out));
  out.resize(n / 2 + 1);
  for (auto& x : out) x /= double(n);
  return out;
}

// What the scheme and the record make of the bins: line i of Δω = 2π/repeat_period on bin
// q = m i when the record holds m whole repeat periods.
struct LineBins {
  bool periodic = false;
  std::size_t whole_periods = 0;  // m
  double step = 0;                // Δω, rad/s
  std::vector<std::size_t> bins;  // q of every line in the band below the Nyquist bin
  std::vector<double> expected;   // S(ω_q) Δω, m², per line bin
  std::vector<double> omega;      // ω_q, rad/s
};

LineBins line_bins(const ProbeCase& c) {
  LineBins out;
  const auto& s = c.synthesis;
  if (s.frequencies != ProbeFrequencies::uniform || !(s.repeat_period > 0)) return out;
  const double periods = c.layout.duration() / s.repeat_period;
  const double whole = std::round(periods);
  if (!(whole >= 1) || std::abs(periods - whole) > 1e-9 * whole) return out;
  out.periodic = true;
  out.whole_periods = std::size_t(whole);
  out.step = 2 * kPi / s.repeat_period;
  const auto sea = c.spectrum();
  const auto& spectrum = sea->omnidirectional();
  const std::size_t n = c.layout.samples;
  for (const auto& line : reference::probe_frequency_lines(c)) {
    const auto q = std::size_t(std::llround(line.omega / out.step)) * out.whole_periods;
    if (q == 0 || 2 * q >= n) continue;  // the Nyquist bin holds a line's real part only
    out.bins.push_back(q);
    out.omega.push_back(line.omega);
    out.expected.push_back(spectrum(line.omega) * out.step);
  }
  return out;
}

// One probe's spectrum and the rounding it carries: r bounds each value's error (its stored
// rounding plus the transform's, 8 u log2 N of its largest value).
struct ProbeSpectrum {
  std::vector<Complex> x;
  double rounding = 0;
  double periodogram(std::size_t q, std::size_t n) const {
    const double two_sided = std::norm(x[q]);
    return q == 0 || 2 * q == n ? two_sided : 2 * two_sided;
  }
};

ProbeSpectrum probe_spectrum(const std::vector<double>& series, double stored_rounding) {
  ProbeSpectrum out;
  out.x = half_spectrum(series);
  double largest = 0;
  for (double v : series) largest = std::max(largest, std::abs(v));
  out.rounding = stored_rounding + 8 * 0x1p-53 * std::log2(double(series.size())) * largest;
  return out;
}

// |I − I_true| for a bin whose X carries an error of at most r: 2 |(|X|² − |X − δ|²)|.
double periodogram_error_bound(const Complex& x, double r) {
  return 4 * (std::abs(x) + r) * r + 2 * r * r;
}

std::string probe_name(std::size_t p, const ProbeCase& c) {
  return fmt::format("probe {} at ({:g}, {:g}) m", p, c.layout.positions[p][0], c.layout.positions[p][1]);
}

// The factor an engine's series carry when it slips on a convention, named where the
// measured energy ratio's range [low, high] holds it (the nearest in log).
std::string energy_factor_meaning(double ratio, double low, double high) {
  const double two_pi = 2 * kPi;
  const std::pair<double, const char*> factors[] = {
      {two_pi * two_pi, "× 4π²: amplitudes × 2π"},
      {1 / (two_pi * two_pi), "× 1/(4π²): amplitudes ÷ 2π"},
      {two_pi, "× 2π: a density in m²/Hz used as m²·s/rad"},
      {1 / two_pi, "× 1/(2π): a density in m²·s/rad used as m²/Hz"},
      {0.5, "× ½: a two-sided density used as one-sided, or a = √(S Δω) without its 2"},
      {2.0, "× 2: a one-sided density counted twice, or a = √(4 S Δω)"},
      {16.0, "× 16: Hs² where m0 = Hs²/16 belongs"},
  };
  const char* best = nullptr;
  double nearest = INFINITY;
  for (const auto& [factor, meaning] : factors) {
    if (factor < low || factor > high) continue;
    const double distance = std::abs(std::log(ratio / factor));
    if (distance < nearest) nearest = distance, best = meaning;
  }
  return best ? std::string(" — ") + best : "";
}

// How the measured-to-expected ratio of the line bins scales with the expected power: the
// least-squares slope of log(I/E) on log(E) over the bins within 10⁻⁶ of the largest (E[log Exp(1)] is a constant, so Rayleigh ratios
// give it unbiased). 1 where the amplitudes are ∝ S Δω instead of √(2 S Δω): a missing √.
double ratio_slope(const std::vector<double>& expected, const std::vector<double>& measured) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, largest = 0;
  int n = 0;
  for (double e : expected) largest = std::max(largest, e);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    // The bins holding 10⁻⁶ of the largest line's power and more: in the far tails the measured
    // power is the stored values' rounding, which no slope of the engine's law describes.
    if (!(expected[i] >= 1e-6 * largest && measured[i] > 0)) continue;
    const double x = std::log(expected[i]), y = std::log(measured[i] / expected[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
  }
  if (n < 8) return NAN;
  const double spread = sxx - sx * sx / n;
  return spread > 0 ? (sxy - sx * sy / n) / spread : NAN;
}

// Whether the measured power sits on every r-th line only (r = 2 … 8), the others empty: the
// engine's lines are r Δω apart — its series repeats after repeat_period/r. Returns r, or 0.
int shorter_repeat(const std::vector<double>& measured) {
  double total = 0;
  for (double m : measured) total += m;
  if (!(total > 0)) return 0;
  for (int r = 2; r <= 8; ++r) {
    for (int offset = 0; offset < r; ++offset) {
      double on = 0;
      for (std::size_t i = std::size_t(offset); i < measured.size(); i += std::size_t(r)) on += measured[i];
      if (on >= (1 - 1e-6) * total) return r;
    }
  }
  return 0;
}

// A failed spectrum check's explanation in the engine's terms.
std::string spectrum_diagnosis(const std::vector<double>& expected, const std::vector<double>& measured,
                               const std::string& otherwise) {
  if (const int r = shorter_repeat(measured); r > 0) {
    return fmt::format("only one line in {} of Δω = 2π/repeat_period carries energy: the series repeats "
                       "after repeat_period/{}, sooner than declared",
                       r, r);
  }
  const double slope = ratio_slope(expected, measured);
  if (std::abs(slope - 1) < 0.1) {
    return fmt::format("the periodogram over S Δω grows as S Δω itself (slope {:.3f} in log–log): amplitudes ∝ S Δω "
                       "instead of √(2 S Δω) — a missing √",
                       slope);
  }
  return otherwise;
}

bool exact_scheme(const ProbeCase& c) {
  return c.synthesis.amplitudes == ProbeAmplitudes::deterministic &&
         (c.synthesis.directions != ProbeDirections::double_summation || c.synthesis.n_directions == 1);
}

bool equal_phasor_scheme(const ProbeCase& c) {
  return c.synthesis.amplitudes == ProbeAmplitudes::deterministic && !exact_scheme(c);
}

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
  report.skipped.push_back({"series.energy", SkipReason::scheme_not_judged,
                            "deterministic amplitudes with several directions per frequency: the law of the "
                            "lines' summed power is not judged yet (series.spectrum judges each line's)"});
}

bool judged_scheme(const ProbeCase& c) {
  return c.synthesis.amplitudes == ProbeAmplitudes::rayleigh || exact_scheme(c);
}

void spectrum_and_energy(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
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
                                                energy_ratio * (1 + 3 * energy_bound + 1e-9)))));
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
                                                        energy_factor_meaning(worst_energy_ratio, energy_low, energy_high))
                                          : "")));
}

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
    if (stray / bound >= worst / std::max(worst_bound, 1e-300) || p == 0) {
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
// waves; one that clamps them repeats a series.
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

// Long-crested: conj X_q^p / conj X_q^0 = e^(i k ê·Δx) exactly.
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
      deep_worst = std::max(deep_worst, std::abs(deep) / bound);
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

}  // namespace

int probe_statistical_check_count(const ProbeCase& c) {
  if (!line_bins(c).periodic) return 0;
  if (c.synthesis.amplitudes == ProbeAmplitudes::rayleigh) return 2;
  return equal_phasor_scheme(c) ? 1 : 0;
}

ProbeCheckReport run_probe_checks(const ProbeCase& c, const std::vector<std::vector<double>>& elevation,
                                  const std::vector<double>& rounding, double alpha) {
  if (elevation.size() != c.layout.positions.size() || rounding.size() != elevation.size()) {
    throw InvalidInput(fmt::format("{} series for {} probes", elevation.size(), c.layout.positions.size()));
  }
  for (const auto& series : elevation) {
    if (series.size() != c.layout.samples) {
      throw InvalidInput(fmt::format("a series of {} samples where the case has {}", series.size(), c.layout.samples));
    }
  }
  ProbeCheckReport report;
  const LineBins lines = line_bins(c);
  if (!lines.periodic) {
    // Refused rather than passed with every check skipped: a gate that judges nothing must not
    // say PASS.
    throw InvalidInput(
        c.synthesis.frequencies != ProbeFrequencies::uniform
            ? fmt::format("frequencies = \"{}\": the lines do not fall on the record's bins, and their "
                          "law (Welch estimates) is not one swell judges yet; swell judges records of "
                          "whole repeat periods of uniform lines",
                          to_string(c.synthesis.frequencies))
            : c.layout.duration() < c.synthesis.repeat_period
                  ? fmt::format("the record ({:g} s = samples × dt) is shorter than the declared repeat period "
                                "({:g} s): its bins are wider than the lines' spacing 2π/repeat_period, which "
                                "it cannot resolve; record at least one whole repeat period",
                                c.layout.duration(), c.synthesis.repeat_period)
                  : fmt::format("the record ({:g} s = samples × dt) is not a whole number of repeat periods "
                                "({:g} s): the lines do not fall on its bins; swell judges records of whole "
                                "repeat periods (give samples = a multiple of repeat_period/dt)",
                                c.layout.duration(), c.synthesis.repeat_period));
  }
  std::vector<ProbeSpectrum> spectra;
  for (std::size_t p = 0; p < elevation.size(); ++p) spectra.push_back(probe_spectrum(elevation[p], rounding[p]));
  if (judged_scheme(c)) {
    spectrum_and_energy(c, lines, spectra, alpha, report);
  } else {
    equal_phasor_spectrum(c, lines, spectra, alpha, report);
  }
  stray_energy(c, lines, spectra, report);
  if (c.synthesis.directions != ProbeDirections::double_summation && spectra.size() >= 2) {
    same_amplitude(c, lines, spectra, report);
  }
  if (c.synthesis.directions == ProbeDirections::long_crested && spectra.size() >= 2) {
    phase(c, lines, spectra, report);
  } else {
    report.skipped.push_back({"series.phase", SkipReason::scheme_not_judged,
                              spectra.size() < 2 ? "one probe: no phase between probes"
                                                 : "a spread sea: the phase between probes is judged by its "
                                                   "coherence, which swell does not judge yet"});
  }
  report.notes.push_back(fmt::format("{} lines on bins q = {} i of the record's {} samples ({} whole repeat "
                                     "period{})",
                                     lines.bins.size(), lines.whole_periods, c.layout.samples, lines.whole_periods,
                                     lines.whole_periods == 1 ? "" : "s"));
  return report;
}

}  // namespace swell::validation
