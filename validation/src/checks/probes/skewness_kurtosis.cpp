#include "checks/probes/skewness_kurtosis.hpp"

#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <span>
#include <string>

#include "swell/impls/probe_synthesis.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/wave_noise.hpp"
#include "swell/validation/stats/sample_moments.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation {
namespace {

using Complex = std::complex<double>;
using reference::ProbeAmplitudes;
using reference::ProbeCase;
using reference::ProbeDirections;
constexpr double kPi = std::numbers::pi;

// The replicas' key and stream: apart from the case's own streams (2 and 3), so a series made
// with any seed shares no numbers with its null.
constexpr std::uint64_t kNullSeed = 0x5e11'0000'6d0eULL;
constexpr std::uint32_t kNullStream = 7;

// Indices of the 2¹² lattice phases, five from each SplitMix64 output (Steele, Lea & Flood
// 2014: a 64-bit generator whose outputs pass BigCrush), one stream per pair of replicas.
class LatticePhases {
 public:
  static constexpr std::size_t kPoints = 4096;
  explicit LatticePhases(std::uint64_t seed) : state_(seed) {}
  std::size_t next() {
    if (left_ == 0) bits_ = split_mix(), left_ = 5;
    const std::size_t index = std::size_t(bits_ & (kPoints - 1));
    bits_ >>= 12, --left_;
    return index;
  }

 private:
  std::uint64_t split_mix() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_, bits_ = 0;
  int left_ = 0;
};

// Sample skewness and excess kurtosis about the sample mean.
struct Moments {
  double skewness = 0, kurtosis = 0;
};

Moments sample_moments(std::span<const double> values) {
  double mean = 0;
  for (double v : values) mean += v;
  mean /= double(values.size());
  stats::SampleMoments<double> m;
  m.add(values, mean);
  return {m.skewness(), m.excess_kurtosis()};
}


// The law a statistic is judged by, fitted to its replicas by moments. A prediction for one new
// value: the sd carries the estimated mean's error, × √(1 + 1/R).
struct MomentLaw {
  double mean = 0, sd = 0, skewness = 0;
  double dof = 0;  // > 0: Student t on dof about the mean with scale sd (skewness unused)
  std::string name;
  // Pearson type III (a shifted Gamma) of the three moments; the normal law where |skewness|
  // < 1e-3 (the Gamma's shape 4/γ² then exceeds 4e6, indistinguishable from it).
  double two_sided_p(double x) const {
    if (std::isnan(x)) return NAN;
    if (!(sd > 0)) return x == mean ? 1.0 : 0.0;
    const double z = (x - mean) / sd;
    if (dof > 0) return std::min(1.0, 2 * boost::math::cdf(boost::math::complement(boost::math::students_t(dof), std::abs(z))));
    if (std::abs(skewness) < 1e-3) return stats::normal_two_sided_p(z);
    // X = mean + sd (G − k)/√k, G ~ Gamma(k, 1), k = 4/γ²; a negative γ mirrors it. On the
    // short side the Pearson III ends at mean − 2 sd/γ, where the true law (and a skewness
    // estimated from R replicas) does not: a value beyond it would get p = 0 (deterministic
    // amplitudes over 4096 samples put right series 2.2 sd below the mean, past that end at
    // γ = 1.14). There the normal law judges, whose tail is heavier than the skewed law's.
    const double k = 4 / (skewness * skewness);
    const double g = k + (skewness > 0 ? z : -z) * std::sqrt(k);
    const bool short_side = skewness > 0 ? z < 0 : z > 0;
    if (short_side) return std::min(1.0, std::max(stats::normal_two_sided_p(z), 2 * stats::gamma_lower_p(k, g)));
    return std::min(1.0, 2 * stats::gamma_upper_p(k, g));
  }
};

// g1's law: the declared model is symmetric in η → −η (B_i → −B_i leaves circular Gaussians
// and uniform phases as they were), so its replicas count with their mirrors: mean 0, variance
// the mean square, skewness 0.
MomentLaw symmetric_law(const std::vector<double>& replicas) {
  const double r = double(replicas.size());
  double square = 0;
  for (double v : replicas) square += v * v;
  MomentLaw law;
  law.sd = std::sqrt(square / r);
  law.dof = r;
  law.name = fmt::format("g1/sd ~ Student t on {:g} dof (its replicas' g1 and −g1: a normal law, excess kurtosis "
                         "within ±0.25 of 0 from 1024 to 43200 samples, its variance estimated from R squares)",
                         r);
  return law;
}

// A Pearson type III of the replicas' mean, sd and skewness (g2's law is skewed to the right,
// more so as the record shortens: 1.1–1.4 at 1024 samples, 0.2–0.5 at 43 200).
MomentLaw skewed_law(const std::vector<double>& replicas) {
  const double r = double(replicas.size());
  double mean = 0;
  for (double v : replicas) mean += v;
  mean /= r;
  double m2 = 0, m3 = 0;
  for (double v : replicas) {
    const double d = v - mean;
    m2 += d * d, m3 += d * d * d;
  }
  m2 /= r, m3 /= r;
  MomentLaw law;
  law.mean = mean;
  law.sd = std::sqrt(m2 * r / (r - 1) * (1 + 1 / r));
  law.skewness = m2 > 0 ? m3 / std::pow(m2, 1.5) : 0;
  law.name = fmt::format("Pearson III of their mean, sd and skewness {:.2f}", law.skewness);
  return law;
}

}  // namespace

bool moment_null_simulated(const ProbeCase& c) { return impls::probe_series_is_periodic(c); }

MomentNull simulate_moment_null(const ProbeCase& c, int replicas) {
  std::size_t period = 0;
  if (!impls::probe_series_is_periodic(c, &period)) {
    throw InvalidInput("the moments' null is simulated for uniform frequencies whose repeat_period is a whole "
                       "number of dt only");
  }
  if (replicas < 2 || replicas % 2 != 0) {
    throw InvalidInput(fmt::format("{} replicas: the null needs an even number, at least 2", replicas));
  }
  const auto sea = c.spectrum();
  const auto& spectrum = sea->omnidirectional();
  const double step = 2 * kPi / c.synthesis.repeat_period;
  const bool rayleigh = c.synthesis.amplitudes == ProbeAmplitudes::rayleigh;
  const int phasors = c.synthesis.directions == ProbeDirections::double_summation ? c.synthesis.n_directions : 1;
  struct Line {
    std::size_t bin;
    double scale;  // Rayleigh: √(S Δω); deterministic: √(2 S Δω/n)
  };
  std::vector<Line> lines;
  for (const auto& f : reference::probe_frequency_lines(c)) {
    const double energy = spectrum(f.omega) * f.band_width;
    if (!(energy > 0)) continue;
    const auto q = std::size_t(std::llround(f.omega / step)) % period;
    lines.push_back({q, rayleigh ? std::sqrt(energy) : std::sqrt(2 * energy / phasors)});
  }
  impls::TransformSpec spec;
  spec.nx = int(period);
  spec.kind = impls::Kind::c2c;
  spec.direction = impls::Direction::forward;
  const auto plan = impls::make_backend("fftw")->plan(spec);
  const std::size_t n = c.layout.samples, whole = n / period, rest = n % period;
  std::vector<Complex> coefficients(period), transform(period);
  std::vector<double> series(period);
  MomentNull out;
  out.skewness.reserve(std::size_t(replicas));
  out.kurtosis.reserve(std::size_t(replicas));
  // One point's moments over the record: `whole` repeats of the period plus its first `rest`.
  auto record_moments = [&](bool imaginary) {
    for (std::size_t k = 0; k < period; ++k) series[k] = imaginary ? transform[k].imag() : transform[k].real();
    if (whole == 0) return sample_moments(std::span<const double>(series.data(), rest));
    if (rest == 0) return sample_moments(series);
    double mean = 0;
    for (std::size_t k = 0; k < period; ++k) mean += double(whole) * series[k] + (k < rest ? series[k] : 0.0);
    mean /= double(n);
    stats::SampleMoments<double> m;
    for (std::size_t w = 0; w < whole; ++w) m.add(series, mean);
    m.add(std::span<const double>(series.data(), rest), mean);
    return Moments{m.skewness(), m.excess_kurtosis()};
  };
  // Deterministic amplitudes' phases on a lattice of 2¹² points of the circle: E e^(imψ) = 0
  // for every m that is not a multiple of 4096, as for continuous uniform phases, so every
  // moment of B of order below 4096 is theirs — and a phase costs a table read, not a sine.
  std::vector<Complex> lattice(LatticePhases::kPoints);
  for (std::size_t k = 0; k < lattice.size(); ++k) lattice[k] = std::polar(1.0, 2 * kPi * double(k) / double(lattice.size()));
  for (int r = 0; r < replicas; r += 2) {
    LatticePhases phases(kNullSeed + std::uint64_t(r));
    std::fill(coefficients.begin(), coefficients.end(), Complex(0));
    for (std::size_t i = 0; i < lines.size(); ++i) {
      Complex b[2];
      for (int s = 0; s < 2; ++s) {
        if (rayleigh) {
          const auto xi = reference::wave_noise(kNullSeed, int(i), r + s, kNullStream);
          b[s] = lines[i].scale * Complex(xi.xi1, xi.xi2);
        } else {
          Complex sum = 0;
          for (int j = 0; j < phasors; ++j) sum += lattice[phases.next()];
          b[s] = lines[i].scale * sum;
        }
      }
      // η1 + iη2 from one forward transform: Re Σ B e^(−iθ) = (B e^(−iθ) + conj B e^(iθ))/2, so
      // bin q takes (B1 + i B2)/2 and bin M − q (conj B1 + i conj B2)/2; the Nyquist bin, whose
      // e^(∓iπn) coincide, Re B1 + i Re B2.
      const std::size_t q = lines[i].bin;
      if (2 * q == period) {
        coefficients[q] += Complex(b[0].real(), b[1].real());
      } else {
        coefficients[q] += (b[0] + Complex(0, 1) * b[1]) / 2.0;
        coefficients[period - q] += (std::conj(b[0]) + Complex(0, 1) * std::conj(b[1])) / 2.0;
      }
    }
    plan->execute(std::span<const Complex>(coefficients), std::span<Complex>(transform));
    for (bool imaginary : {false, true}) {
      const Moments m = record_moments(imaginary);
      out.skewness.push_back(m.skewness);
      out.kurtosis.push_back(m.kurtosis);
    }
  }
  return out;
}


void skewness_and_kurtosis(const ProbeCase& c, const std::vector<std::vector<double>>& elevation, double alpha,
                    ProbeCheckReport& report) {
  if (elevation.size() != c.layout.positions.size() || elevation.empty()) {
    throw InvalidInput(fmt::format("{} series for {} probes", elevation.size(), c.layout.positions.size()));
  }
  for (const auto& series : elevation) {
    if (series.size() != c.layout.samples) {
      throw InvalidInput(fmt::format("a series of {} samples where the case has {}", series.size(), c.layout.samples));
    }
  }
  if (!(alpha > 0 && alpha < 1)) throw InvalidInput(fmt::format("α = {:g}: a false-alarm rate is in (0, 1)", alpha));
  if (!moment_null_simulated(c)) {
    const std::string why = "the null of skewness and kurtosis is simulated for uniform frequencies whose "
                            "repeat_period is a whole number of dt only";
    report.skipped.push_back({"series.skewness", SkipReason::scheme_not_judged, why});
    report.skipped.push_back({"series.kurtosis", SkipReason::scheme_not_judged, why});
    return;
  }
  const MomentNull null = simulate_moment_null(c, kMomentNullReplicas);
  // g2's right tail is heavier than any Pearson III of its moments fits (one wave group makes
  // it: over 1024 s of a Tp = 10 s sea, 4.5e-4 of 20 000 replicas lie 6 sd above the mean, where
  // the Pearson III gives 1e-5); y = −1/(3 + g2), monotone in g2, is near that law (skewness
  // 0.3–0.45, 1.5e-4 beyond 5 sd where its Pearson III gives 1–2e-4): g2 is judged through y.
  const auto kurtosis_scale = [](double g2) { return -1 / (3 + g2); };
  std::vector<double> scaled_kurtosis;
  for (double g2 : null.kurtosis) scaled_kurtosis.push_back(kurtosis_scale(g2));
  const MomentLaw skewness_law = symmetric_law(null.skewness), kurtosis_law = skewed_law(null.kurtosis);
  MomentLaw scaled_law = skewed_law(scaled_kurtosis);
  scaled_law.name = fmt::format("y = −1/(3 + g2) by the Pearson III of its replicas' mean, sd and skewness {:.2f}",
                                scaled_law.skewness);
  const std::size_t probes = elevation.size();
  std::vector<Moments> measured(probes);
  double skew_p = 2, kurt_p = 2;
  std::size_t skew_probe = 0, kurt_probe = 0;
  for (std::size_t p = 0; p < probes; ++p) {
    measured[p] = sample_moments(elevation[p]);
    // A constant series has no moments: NaN, which fails (a p-value of NaN fails its check).
    const double ps = skewness_law.two_sided_p(measured[p].skewness);
    const double pk = scaled_law.two_sided_p(kurtosis_scale(measured[p].kurtosis));
    if (!std::isnan(skew_p) && !(ps >= skew_p)) skew_p = ps, skew_probe = p;
    if (!std::isnan(kurt_p) && !(pk >= kurt_p)) kurt_p = pk, kurt_probe = p;
  }
  // Bonferroni over the probes: they see one sea and are correlated, so × P is conservative.
  const auto bonferroni = [&](double p) { return std::isnan(p) ? p : std::min(1.0, p * double(probes)); };
  const double skew_combined = bonferroni(skew_p), kurt_combined = bonferroni(kurt_p);
  const double g1 = measured[skew_probe].skewness, g2 = measured[kurt_probe].kurtosis;
  std::string skew_reason = fmt::format("{}: g1 = {:+.4f} against {:+.4f} ± {:.4f} (p = {:.2g})",
                                        probe_analysis::probe_name(skew_probe, c), g1, skewness_law.mean, skewness_law.sd, skew_p);
  if (!(skew_combined >= alpha)) {
    if (std::isnan(g1)) {
      skew_reason += " — the series is constant: it has no skewness";
    } else if (g1 > skewness_law.mean) {
      skew_reason += " — crests sharper and higher than troughs: second-order bound waves, or a series clipped "
                     "at its troughs, which the linear case does not declare";
    } else {
      skew_reason += " — troughs deeper than crests: a nonlinear series with its sign reversed, or one clipped at "
                     "its crests (a saturated gauge)";
    }
  }
  std::string kurt_reason = fmt::format("{}: g2 = {:+.4f} against {:+.4f} ± {:.4f} (p = {:.2g})",
                                        probe_analysis::probe_name(kurt_probe, c), g2, kurtosis_law.mean, kurtosis_law.sd, kurt_p);
  if (!(kurt_combined >= alpha)) {
    if (std::isnan(g2)) {
      kurt_reason += " — the series is constant: it has no kurtosis";
    } else if (g2 > kurtosis_law.mean) {
      kurt_reason += " — tails heavier than the declared linear sea's: spikes, dropouts, a series stitched from "
                     "pieces of different variance, or second-order waves";
    } else if (c.synthesis.amplitudes == ProbeAmplitudes::rayleigh) {
      kurt_reason += " — fewer extremes than a Gaussian sea's: amplitudes more uniform than the declared Rayleigh "
                     "law (deterministic amplitudes declared as rayleigh), or a series clipped at both ends";
    } else {
      kurt_reason += " — fewer extremes than the declared random-phase sum's: a series clipped at both ends, or "
                     "fewer lines carrying the energy than declared";
    }
  }
  report.results.push_back(statistical_check(
      "series.skewness", c.describe(), g1, skewness_law.mean, skew_combined, alpha,
      fmt::format("p ≥ α = {:.0e} (g1 = m3/m2^1.5 against {} replicas of the declared model at one point: "
                  "symmetric about 0, {}; Bonferroni over {} probes)",
                  alpha, null.skewness.size(), skewness_law.name, probes),
      skew_reason));
  report.results.push_back(statistical_check(
      "series.kurtosis", c.describe(), g2, kurtosis_law.mean, kurt_combined, alpha,
      fmt::format("p ≥ α = {:.0e} (g2 = m4/m2² − 3 against {} replicas of the declared model at one point: {}; "
                  "Bonferroni over {} probes)",
                  alpha, null.kurtosis.size(), scaled_law.name, probes),
      kurt_reason));
  report.notes.push_back(fmt::format("skewness and kurtosis judged against {} replicas of the declared model: "
                                     "g1 {:+.4f} ± {:.4f}, g2 {:+.4f} ± {:.4f} (skewness of g2's law {:.2f}); "
                                     "white noise's √(6/N) = {:.4f}, √(24/N) = {:.4f}",
                                     null.skewness.size(), skewness_law.mean, skewness_law.sd, kurtosis_law.mean,
                                     kurtosis_law.sd, kurtosis_law.skewness, std::sqrt(6.0 / double(c.layout.samples)),
                                     std::sqrt(24.0 / double(c.layout.samples))));
}

}  // namespace swell::validation
