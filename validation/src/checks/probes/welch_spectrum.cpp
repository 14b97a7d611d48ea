#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::probe_analysis {

using reference::ProbeAmplitudes;
using reference::ProbeCase;
using reference::ProbeDirections;
using reference::ProbeFrequencies;
constexpr double kPi = std::numbers::pi;

namespace {

// Lines farther than this many Welch bins from a bin reach it through the Hann window's side
// lobes only (|W|² below 10⁻⁵ of its peak): they enter its mean, not its covariances.
constexpr int kNearBins = 6;
// The mean counts lines within this many bins exactly and bounds the rest (|W|² there is below
// 10⁻¹² of its peak).
constexpr int kMeanBins = 64;

// One declared line as the Welch law sees it: quadrature nodes of its frequency (one for a
// fixed frequency; a random one's bin split into equal sub-bins, each node weighing 1/J) with
// the line's variance v(ω) = E a²/2 at each.
struct LineNode {
  double omega = 0, variance = 0;
};
struct DeclaredLine {
  std::vector<LineNode> nodes;
  double lowest = 0, highest = 0;  // ω range of its nodes
};

// The Hann window's response W(ν) = Σ_n w_n e^(−iν n dt), w_n = ½ (1 − cos 2πn/L), less its
// linear phase e^(−iν dt (L−1)/2) (common to every line at one bin, so no product W_k W_l*
// over lines of one pair of bins depends on it): a sum of three Dirichlet kernels.
class HannResponse {
 public:
  HannResponse(int length, double dt) : length_(length), dt_(dt), shift_(2 * kPi / (length * dt)) {}
  Complex operator()(double nu) const {
    const Complex left = std::polar(0.25, -kPi / length_), right = std::polar(0.25, kPi / length_);
    return 0.5 * dirichlet(nu) + left * dirichlet(nu - shift_) + right * dirichlet(nu + shift_);
  }

 private:
  // sin(ν L dt/2) / sin(ν dt/2), its limit L cos(ν L dt/2)/cos(ν dt/2) where the sine vanishes.
  double dirichlet(double nu) const {
    const double half = nu * dt_ / 2, denominator = std::sin(half);
    if (std::abs(denominator) < 1e-9) return length_ * std::cos(length_ * half) / std::cos(half);
    return std::sin(length_ * half) / denominator;
  }
  int length_;
  double dt_, shift_;
};

// The Welch layout: segments of L samples (a power of two, N/8 or less, at least 32), Hann
// windowed, overlapping by half, K of them; bins ω_k = 2πk/(L dt).
struct WelchLayout {
  int length = 0, segments = 0;
  double dt = 0;
  double hop_time() const { return 0.5 * length * dt; }
  double bin_omega(int k) const { return 2 * kPi * k / (length * dt); }
};

WelchLayout welch_layout(const ProbeCase& c) {
  WelchLayout w;
  w.dt = c.layout.dt;
  w.length = 1;
  while (std::size_t(w.length) * 2 * 8 <= c.layout.samples) w.length *= 2;
  if (w.length < 32) {
    throw InvalidInput(fmt::format("{} samples are too few for Welch estimates of a record that is not whole "
                                   "repeat periods (at least 256: 8 segments of 32)",
                                   c.layout.samples));
  }
  w.segments = int((c.layout.samples - std::size_t(w.length)) / std::size_t(w.length / 2)) + 1;
  return w;
}

// Q_k = (1/K) Σ_s |Y_s(ω_k)|², Y_s the windowed transform of segment s, k = 0 … L/2.
std::vector<double> welch_estimate(const std::vector<double>& series, const WelchLayout& w) {
  impls::TransformSpec spec;
  spec.nx = w.length;
  spec.kind = impls::Kind::c2c;
  spec.direction = impls::Direction::forward;
  const auto plan = impls::make_backend("fftw")->plan(spec);
  std::vector<Complex> in(std::size_t(w.length)), out(std::size_t(w.length));
  std::vector<double> q(std::size_t(w.length / 2 + 1), 0.0);
  for (int s = 0; s < w.segments; ++s) {
    const std::size_t start = std::size_t(s) * std::size_t(w.length / 2);
    for (int n = 0; n < w.length; ++n) {
      const double window = 0.5 * (1 - std::cos(2 * kPi * n / w.length));
      in[std::size_t(n)] = window * series[start + std::size_t(n)];
    }
    plan->execute(std::span<const Complex>(in), std::span<Complex>(out));
    for (std::size_t k = 0; k < q.size(); ++k) q[k] += std::norm(out[k]) / w.segments;
  }
  return q;
}

// κ in E|c|⁴ = (2 − κ)(E|c|²)² of a line's complex amplitude c at one point: 0 for Rayleigh
// amplitudes (complex Gaussian), 1/n for n deterministic phasors of independent phases (one for
// a long-crested sea or one direction per frequency).
double fourth_moment_deficit(const ProbeCase& c) {
  if (c.synthesis.amplitudes == ProbeAmplitudes::rayleigh) return 0;
  return c.synthesis.directions == ProbeDirections::double_summation ? 1.0 / c.synthesis.n_directions : 1.0;
}

std::vector<DeclaredLine> declared_lines(const ProbeCase& c, const WelchLayout& w) {
  const auto sea = c.spectrum();
  const auto& spectrum = sea->omnidirectional();
  const auto& s = c.synthesis;
  std::vector<DeclaredLine> out;
  for (const auto& f : reference::probe_frequency_lines(c)) {
    DeclaredLine line;
    if (s.frequencies == ProbeFrequencies::random) {
      // Nodes a tenth of a Welch bin apart, at least 8: W varies within the line's bin.
      const int nodes = std::max(8, int(std::ceil(10 * f.band_width / (w.bin_omega(1)))));
      for (int j = 0; j < nodes; ++j) {
        const double omega = f.omega + ((j + 0.5) / nodes - 0.5) * f.band_width;
        line.nodes.push_back({omega, spectrum(omega) * f.band_width});
      }
    } else {
      line.nodes.push_back({f.omega, f.variance});
    }
    line.lowest = line.nodes.front().omega, line.highest = line.nodes.back().omega;
    out.push_back(std::move(line));
  }
  return out;
}

// The law of the Welch estimates over the declared lines: E Q_k and Cov(Q_k, Q_l). With
// z_isk = (c_i/2) e^(iω_i τ_s) W(ω_k − ω_i) line i's part of Y_s(ω_k) (c_i its complex
// amplitude at the probe, E|c_i|² = 2v),
//   E Q_k            = Σ_i E|z_ik|² (+ the negative frequency's |W(ω_k + ω_i)|² part),
//   Cov(|Y_sk|², |Y_s'l|²) = |Σ_i h_i|² + Σ_i (f_i − |h_i|² − μ_ik μ_il),
//   h_i = E[z_isk z*_is'l] (a function of m = s − s' only), f_i = E[|z_isk|² |z_is'l|²],
// the exact second moments of a sum of independent circular terms; Cov(Q_k, Q_l) sums them over
// segment pairs, (1/K²) Σ_m (K − |m|) (…). Expectations over a random frequency's placement are
// taken on its nodes. Lines in one Welch bin are not independent across segments (one line is
// the same in every segment), which is why the segments' count alone does not give the degrees
// of freedom.
class WelchLaw {
 public:
  WelchLaw(const ProbeCase& c, const WelchLayout& w)
      : layout_(w), response_(w.length, w.dt), kappa_(fourth_moment_deficit(c)), lines_(declared_lines(c, w)) {
    for (const auto& line : lines_) {
      for (const auto& node : line.nodes) total_half_variance_ += node.variance / 2 / double(line.nodes.size());
    }
    // The window's side lobes fall as ν⁻³: their largest |W|² beyond kMeanBins, sampled over
    // the next two bins, bounds every farther one.
    for (double x = kMeanBins; x <= kMeanBins + 2; x += 1.0 / 64) {
      far_response_ = std::max(far_response_, std::norm(response_(x * w.bin_omega(1))));
    }
  }

  // E Q_k over the lines within kMeanBins of ±ω_k (the negative frequency's image too), and a
  // bound on the rest: their variance times the window's largest |W|² that far out.
  struct Mean {
    double value = 0, far_bound = 0;
  };
  Mean mean(int k) const {
    const double omega_k = layout_.bin_omega(k), reach = kMeanBins * layout_.bin_omega(1);
    Mean out;
    double counted = 0;
    for (const double centre : {omega_k, -omega_k}) {
      for (auto line = first_line_above(centre - reach); line != lines_.end() && line->lowest <= centre + reach;
           ++line) {
        for (const auto& node : line->nodes) {
          const double share = node.variance / 2 / double(line->nodes.size());
          out.value += share * std::norm(response_(centre - node.omega));
          counted += share;
        }
      }
    }
    out.far_bound = std::max(0.0, 2 * total_half_variance_ - counted) * far_response_;
    return out;
  }

  // The part of E Q_k that lines within kNearBins carry at their positive frequency: the
  // covariances count only those.
  double near_mean(int k) const {
    const double omega_k = layout_.bin_omega(k), reach = kNearBins * layout_.bin_omega(1);
    double sum = 0;
    for (auto line = first_line_above(omega_k - reach); line != lines_.end() && line->lowest <= omega_k + reach;
         ++line) {
      for (const auto& node : line->nodes) {
        sum += node.variance / 2 / double(line->nodes.size()) * std::norm(response_(omega_k - node.omega));
      }
    }
    return sum;
  }

  double covariance(int k, int l) const {
    const double omega_k = layout_.bin_omega(k), omega_l = layout_.bin_omega(l);
    const double reach = kNearBins * layout_.bin_omega(1);
    const int lags = layout_.segments;
    std::vector<Complex> total(std::size_t(2 * lags - 1), 0.0);
    std::vector<double> own(std::size_t(2 * lags - 1), 0.0);
    double fourth = 0, product = 0;
    const double top = std::max(omega_k, omega_l) + reach;
    for (auto it = first_line_above(std::min(omega_k, omega_l) - reach); it != lines_.end() && it->lowest <= top;
         ++it) {
      const DeclaredLine& line = *it;
      const double weight = 1.0 / double(line.nodes.size());
      std::vector<Complex> h(total.size(), 0.0);
      double mu_k = 0, mu_l = 0, f = 0;
      for (const auto& node : line.nodes) {
        const Complex wk = response_(omega_k - node.omega), wl = response_(omega_l - node.omega);
        const double half = node.variance / 2;
        const Complex cross = weight * half * wk * std::conj(wl);
        mu_k += weight * half * std::norm(wk), mu_l += weight * half * std::norm(wl);
        f += weight * half * half * std::norm(wk) * std::norm(wl);
        // e^(iω m H) for m = −(K−1) … K−1 by rotation from m = −(K−1): K ≤ 10⁴ steps keep it
        // within 10⁻¹² of the direct value.
        const Complex step = std::polar(1.0, node.omega * layout_.hop_time());
        Complex turn = std::polar(1.0, -node.omega * (lags - 1) * layout_.hop_time());
        for (std::size_t m = 0; m < h.size(); ++m, turn *= step) h[m] += cross * turn;
      }
      for (std::size_t m = 0; m < h.size(); ++m) total[m] += h[m], own[m] += std::norm(h[m]);
      fourth += (2 - kappa_) * f, product += mu_k * mu_l;
    }
    double sum = 0;
    for (int m = -(lags - 1); m < lags; ++m) {
      const std::size_t i = std::size_t(m + lags - 1);
      sum += double(lags - std::abs(m)) * (std::norm(total[i]) + fourth - own[i] - product);
    }
    return sum / (double(lags) * lags);
  }

 private:
  // The first line whose highest node lies at `omega` or above (lines ascend in ω).
  std::vector<DeclaredLine>::const_iterator first_line_above(double omega) const {
    return std::partition_point(lines_.begin(), lines_.end(),
                                [omega](const DeclaredLine& line) { return line.highest < omega; });
  }
  WelchLayout layout_;
  HannResponse response_;
  double kappa_;
  std::vector<DeclaredLine> lines_;
  double total_half_variance_ = 0, far_response_ = 0;
};

// Rings of consecutive judged bins, their sums' means and variances (covariances within the
// ring included).
struct Ring {
  std::vector<int> bins;
  double mean = 0, variance = 0;
};

// The variance the covariances leave out at bin k: the far lines' (and negative frequencies')
// part μ_far of the mean, beating with the near part μ_near, Var ≤ 2 μ_far μ_near + μ_far²
// (each |z_far + z_near|² term's, before the segments average it): an upper bound, so that a
// bin whose own lines are deterministic is not held to a variance its neglected terms exceed.
double far_variance(double mean, double near) {
  const double far = std::max(0.0, mean - near);
  return 2 * far * near + far * far;
}

std::vector<Ring> rings_of(const std::vector<int>& bins, const WelchLaw& law, const std::vector<double>& means,
                           const std::vector<double>& nears) {
  const int count = int(bins.size()), rings = std::clamp(count / 6, 1, 24);
  std::vector<Ring> out;
  for (int r = 0; r < rings; ++r) {
    Ring ring;
    double far_sd = 0;  // bins' far parts taken as fully correlated: Var ≤ (Σ sd)²
    for (int i = r * count / rings; i < (r + 1) * count / rings; ++i) {
      ring.bins.push_back(bins[std::size_t(i)]);
      ring.mean += means[std::size_t(i)];
      far_sd += std::sqrt(far_variance(means[std::size_t(i)], nears[std::size_t(i)]));
    }
    ring.variance = far_sd * far_sd;
    for (int a : ring.bins) {
      for (int b : ring.bins) {
        if (std::abs(a - b) <= 2 * kNearBins) ring.variance += law.covariance(a, b);
      }
    }
    out.push_back(std::move(ring));
  }
  return out;
}

// P of a ring's sum against the Gamma of its mean and variance (Satterthwaite), two-sided.
double ring_p(const Ring& ring, double sum) {
  if (!(ring.variance > 0)) return sum == ring.mean ? 1.0 : 0.0;
  const double shape = ring.mean * ring.mean / ring.variance, scale = ring.variance / ring.mean;
  return std::min(1.0, 2 * std::min(stats::gamma_lower_p(shape, sum / scale), stats::gamma_upper_p(shape, sum / scale)));
}

// The mean square of the series, M = (1/N) Σ η_n²: E M = Σ_i E v_i and
//   Var M = Σ_{i≠j} E v_i E v_j |D(ω_i − ω_j)|² + Σ_i ((2 − κ) E v_i² − (E v_i)²),
// D(ν) = (1/N) Σ_n e^(iν t_n), the Hermitian form's exact variance, plus the sum-frequency
// terms' (below). Random frequencies' difference terms are left out: one line per bin of width
// w ≫ 2π/T leaves |D| ≤ 2/(T w).
struct EnergyLaw {
  double mean = 0, variance = 0;
};

EnergyLaw energy_law(const ProbeCase& c) {
  const double kappa = fourth_moment_deficit(c);
  const auto sea = c.spectrum();
  const auto& spectrum = sea->omnidirectional();
  const auto& s = c.synthesis;
  const auto frequencies = reference::probe_frequency_lines(c);
  std::vector<double> omega, mean_v;
  EnergyLaw law;
  for (const auto& f : frequencies) {
    double first = 0, second = 0;
    if (s.frequencies == ProbeFrequencies::random) {
      constexpr int kNodes = 32;
      for (int j = 0; j < kNodes; ++j) {
        const double v = spectrum(f.omega + ((j + 0.5) / kNodes - 0.5) * f.band_width) * f.band_width;
        first += v / kNodes, second += v * v / kNodes;
      }
    } else {
      first = f.variance;
      second = first * first;
    }
    law.mean += first;
    law.variance += (2 - kappa) * second - first * first;
    omega.push_back(f.omega), mean_v.push_back(first);
  }
  const double dt = c.layout.dt, n = double(c.layout.samples);
  // |D(ν)| = |sin(N ν dt/2) / (N sin(ν dt/2))|, 1 where ν dt is a multiple of 2π.
  const auto dirichlet = [&](double nu) {
    const double half = nu * dt / 2, denominator = n * std::sin(half);
    return std::abs(denominator) < 1e-9 ? 1.0 : std::abs(std::sin(n * half) / denominator);
  };
  if (s.frequencies != ProbeFrequencies::random) {
    // The difference terms: pairs within 64 record bins of each other (beyond, |D| < 1/(64π)
    // and falling).
    const double reach = 64 * 2 * kPi / c.layout.duration();
    for (std::size_t i = 0; i < omega.size(); ++i) {
      for (std::size_t j = i + 1; j < omega.size() && omega[j] - omega[i] <= reach; ++j) {
        const double d = dirichlet(omega[j] - omega[i]);
        law.variance += 2 * mean_v[i] * mean_v[j] * d * d;
      }
    }
  }
  // The sum terms ½ Re Σ c_i c_j D(ω_i + ω_j), zero in the mean, with variance
  //   (2 − κ)/2 Σ v_i² |D(2ω_i)|² + 2 Σ_{i<j} v_i v_j |D(ω_i + ω_j)|²,
  // exactly over the lines holding 10⁻³ of the largest line's variance and more, and bounded
  // for the rest by the largest |D| over their sums' range (an upper bound).
  double largest = 0, rest = 0, total = 0;
  for (double v : mean_v) largest = std::max(largest, v), total += v;
  std::vector<std::size_t> strong;
  double lowest = INFINITY, highest = 0;
  for (std::size_t i = 0; i < omega.size(); ++i) {
    lowest = std::min(lowest, omega[i]), highest = std::max(highest, omega[i]);
    if (mean_v[i] >= 1e-3 * largest) {
      strong.push_back(i);
    } else {
      rest += mean_v[i];
    }
  }
  for (std::size_t a = 0; a < strong.size(); ++a) {
    const std::size_t i = strong[a];
    const double d = dirichlet(2 * omega[i]);
    law.variance += (2 - kappa) / 2 * mean_v[i] * mean_v[i] * d * d;
    for (std::size_t b = a + 1; b < strong.size(); ++b) {
      const std::size_t j = strong[b];
      const double dij = dirichlet(omega[i] + omega[j]);
      law.variance += 2 * mean_v[i] * mean_v[j] * dij * dij;
    }
  }
  if (rest > 0) {
    // max |D| over [2 lowest, 2 highest]: 1 if the range holds a multiple of 2π/dt, else at an end.
    const double period = 2 * kPi / dt;
    const bool aliased = std::floor(2 * highest / period) > std::floor(2 * lowest / period) ||
                         std::fmod(2 * lowest, period) == 0;
    const double bound = aliased ? 1.0 : std::max(1 / std::abs(n * std::sin(lowest * dt)),
                                                  1 / std::abs(n * std::sin(highest * dt)));
    const double d = std::min(1.0, bound);
    law.variance += (2 * rest * total + rest * rest) * d * d;
  }
  return law;
}

std::string record_note(const ProbeCase& c, const WelchLayout& w) {
  const auto& s = c.synthesis;
  std::string why;
  if (s.frequencies != ProbeFrequencies::uniform) {
    why = fmt::format("frequencies = \"{}\": the lines do not fall on the record's bins", to_string(s.frequencies));
  } else if (!(s.repeat_period > 0)) {
    why = "no repeat period declared";
  } else if (c.layout.duration() < s.repeat_period) {
    why = fmt::format("the record ({:g} s) is shorter than the declared repeat period ({:g} s): its bins cannot "
                      "resolve the lines' spacing 2π/repeat_period",
                      c.layout.duration(), s.repeat_period);
  } else {
    why = fmt::format("the record ({:g} s) is not a whole number of repeat periods ({:g} s)", c.layout.duration(),
                      s.repeat_period);
  }
  return fmt::format("{}: judged by Welch estimates — {} Hann segments of {} samples overlapping by half, bins "
                     "{:.4g} rad/s apart",
                     why, w.segments, w.length, w.bin_omega(1));
}

}  // namespace

void welch_spectrum_and_energy(const ProbeCase& c, const std::vector<std::vector<double>>& elevation,
                               const std::vector<double>& rounding, double alpha, ProbeCheckReport& report) {
  const WelchLayout w = welch_layout(c);
  const WelchLaw law(c, w);
  const std::size_t probes = elevation.size();
  double largest_rounding = 0;
  for (double r : rounding) largest_rounding = std::max(largest_rounding, r);
  double largest_value = 0;
  for (const auto& series : elevation) {
    for (double v : series) largest_value = std::max(largest_value, std::abs(v));
  }
  // A bin is judged where its mean stands 10⁶ above what the values' rounding (stored, and the
  // transform's 8 u log2 L) can put there, (r Σ w)² = (r L/2)², and the lines within kNearBins
  // carry 99.9 % of it; bins 0, 1 and the last two are left out (their negative-frequency parts
  // make the terms non-circular).
  const double r = largest_rounding + 8 * 0x1p-53 * std::log2(double(w.length)) * largest_value;
  const double floor = 1e6 * (r * w.length / 2) * (r * w.length / 2);
  std::vector<int> bins;
  std::vector<double> means, nears, omega;
  for (int k = 2; k <= w.length / 2 - 2; ++k) {
    const auto [mean, far_bound] = law.mean(k);
    const double near = law.near_mean(k);
    if (!(mean > floor) || near < 0.999 * (mean + far_bound)) continue;
    bins.push_back(k), means.push_back(mean), nears.push_back(near), omega.push_back(w.bin_omega(k));
  }
  const std::string subject = c.describe();
  if (bins.size() < 2) {
    report.skipped.push_back({"series.spectrum", SkipReason::too_few_wave_vectors,
                              "fewer than two Welch bins stand 10⁶ above the rounding"});
  } else {
    const auto rings = rings_of(bins, law, means, nears);
    double worst_p = 1, worst_ratio = 1;
    std::size_t worst_probe = 0;
    std::vector<double> judged_measured;
    for (std::size_t p = 0; p < probes; ++p) {
      const auto q = welch_estimate(elevation[p], w);
      std::vector<double> p_values, measured;
      double probe_worst_p = 1, probe_worst_ratio = 1;
      for (const auto& ring : rings) {
        double sum = 0;
        for (int k : ring.bins) sum += q[std::size_t(k)];
        const double ring_p_value = ring_p(ring, sum);
        p_values.push_back(ring_p_value);
        if (ring_p_value <= probe_worst_p) probe_worst_p = ring_p_value, probe_worst_ratio = sum / ring.mean;
      }
      for (int k : bins) measured.push_back(q[std::size_t(k)]);
      const double combined = stats::fisher_combined_p(p_values);
      if (p == 0 || combined < worst_p) {
        worst_p = combined, worst_probe = p, worst_ratio = probe_worst_ratio, judged_measured = measured;
      }
    }
    const double p_value = std::min(1.0, worst_p * double(probes));
    std::string diagnosis;
    if (p_value < alpha) {
      const std::string rescaled = frequency_rescale_diagnosis(omega, means, omega, judged_measured);
      diagnosis = " — " + (rescaled.empty() ? spectrum_diagnosis(means, judged_measured,
                                                                 "the Welch estimates do not follow the declared "
                                                                 "lines' S(ω)")
                                            : rescaled);
    }
    report.results.push_back(statistical_check(
        "series.spectrum", subject, worst_ratio, 1, p_value, alpha,
        fmt::format("p ≥ α = {:.0e} (Welch estimates: rings of bins by the Gamma of their exact mean and "
                    "covariance over the declared lines, Fisher's method; Bonferroni over {} probes)",
                    alpha, probes),
        fmt::format("{}: worst ring of Welch bins at {:.3f} × its mean (p = {:.2g}){}", probe_name(worst_probe, c),
                    worst_ratio, worst_p, diagnosis)));
  }
  // series.energy: the mean square of each series.
  const EnergyLaw energy = energy_law(c);
  double worst_p = 1, worst_ratio = 1, low = 1, high = 1;
  std::size_t worst_probe = 0;
  const double shape = energy.mean * energy.mean / energy.variance, scale = energy.variance / energy.mean;
  for (std::size_t p = 0; p < probes; ++p) {
    double sum = 0;
    for (double v : elevation[p]) sum += v * v;
    const double mean_square = sum / double(elevation[p].size());
    const double p_value =
        energy.variance > 0 ? std::min(1.0, 2 * std::min(stats::gamma_lower_p(shape, mean_square / scale),
                                                         stats::gamma_upper_p(shape, mean_square / scale)))
                            : (std::abs(mean_square / energy.mean - 1) < 1e-9 ? 1.0 : 0.0);
    if (p == 0 || p_value < worst_p) {
      worst_p = p_value, worst_probe = p, worst_ratio = mean_square / energy.mean;
      // The ratios the law's central 1 − α/P holds, for naming a convention factor.
      const double spread = energy.variance > 0 ? 6 * std::sqrt(energy.variance) / energy.mean : 1e-9;
      low = worst_ratio / (1 + spread), high = worst_ratio / std::max(1e-3, 1 - spread);
    }
  }
  const double p_value = std::min(1.0, worst_p * double(probes));
  report.results.push_back(statistical_check(
      "series.energy", subject, worst_ratio, 1, p_value, alpha,
      fmt::format("p ≥ α = {:.0e} (the mean square against the Gamma of its exact mean and variance over the "
                  "declared lines; Bonferroni over {} probes)",
                  alpha, probes),
      fmt::format("{}: the series' mean square is {:.4g} × the lines' Σ v (p = {:.2g}){}", probe_name(worst_probe, c),
                  worst_ratio, worst_p,
                  p_value < alpha ? fmt::format(" — energy off by {:.3g} (Hs by {:.3g}){}", worst_ratio,
                                                std::sqrt(worst_ratio), energy_factor_meaning(worst_ratio, low, high, directions_per_frequency(c)))
                                  : "")));
  report.notes.push_back(record_note(c, w));
}

}  // namespace swell::validation::probe_analysis
