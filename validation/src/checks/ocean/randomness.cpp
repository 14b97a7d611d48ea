#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::ocean_analysis {

// Reused random numbers: the initial amplitudes recovered from the frames — h̃0(k)
// and h̃0(−k) from the two-wave fit at every identifiable wave vector, or ĥ(k, 0) over the half
// plane from one frame at t = 0 — divided by their expected rms, z = h̃0/√τ, are independent
// unit complex normals on a right surface. Two distinct wave vectors that drew the same pair
// have the same z (up to the recovery's rounding σ). The check counts pairs closer than
// 8 √(σ1² + σ2²); for independent z, d = z1 − z2 ~ CN(0, 2) and P(|d| < ε) = 1 − e^(−ε²/2), so
// the count is Poisson with mean λ0 = Σ pairs (1 − e^(−ε²/2)) ≤ 32 (M − 1) Σ σ² (closed form),
// and p = P(Poisson(λ0) ≥ count). Only waves recovered to σ ≤ 10⁻⁵ enter (λ0 ≤ 32 M² 10⁻¹⁰).
// σ² = s²/(F τ): white rounding of variance s² = (16 u log2 N)² mean h² / N per coefficient
// and frame, through a least-squares fit over F frames.
Results check_randomness(const Analysis& a, OceanCheckReport& report) {
  struct Draw {
    Complex z;
    double sigma = 0;
    int n = 0, m = 0;
  };
  std::vector<Draw> draws;
  const double s2 = std::pow(rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n()), 2) * a.mean_square0() / double(a.count());
  constexpr double kLargestSigma = 1e-5;
  const auto frames = double(a.times().size());
  const Sampling& g = a.sampling();
  if (a.times().size() >= 2) {
    for (const WaveFit& f : a.wave_fits()) {
      const auto [n, m] = g.wave_index(f.wave->index);
      for (int side = 0; side < 2; ++side) {
        const double tau = side == 0 ? f.wave->tau_plus : f.wave->tau_minus;
        if (!(tau > 0)) continue;
        const double sigma = std::sqrt(s2 / (frames * tau));
        if (sigma > kLargestSigma) continue;
        const Complex amplitude = side == 0 ? f.a : std::conj(f.b);  // h̃0(k), h̃0(−k)
        draws.push_back({amplitude / std::sqrt(tau), sigma, side == 0 ? n : -n, side == 0 ? m : -m});
      }
    }
    if (draws.empty() && a.wave_fits().empty()) {
      report.skipped.push_back({"randomness", SkipReason::unidentifiable_times, "no wave vector's two waves are identifiable from these "
                               "frame times"});
      return {};
    }
  } else if (a.times().front() == 0) {
    for (const Wave& w : a.waves()) {
      const double sigma = std::sqrt(s2 / w.mu);
      if (sigma > kLargestSigma) continue;
      const auto [n, m] = g.wave_index(w.index);
      draws.push_back({a.spectrum0()[w.index] / std::sqrt(w.mu), sigma, n, m});
    }
  } else {
    report.skipped.push_back({"randomness", SkipReason::ambiguous_phase, "one frame at t ≠ 0 cannot tell h̃0(k) from conj h̃0(−k)"});
    return {};
  }
  // Close pairs, by a sweep in Re z.
  std::sort(draws.begin(), draws.end(), [](const Draw& x, const Draw& y) { return x.z.real() < y.z.real(); });
  double sigma_max = 0, sigma_sum = 0;
  // A z near 0 (a wave far weaker than its expected power: a field that is wrong otherwise) can
  // match nothing meaningfully; under the hypothesis P(|z| < 10⁻³) = 10⁻⁶.
  draws.erase(std::remove_if(draws.begin(), draws.end(), [](const Draw& d) { return std::abs(d.z) < 1e-3; }),
              draws.end());
  for (const Draw& d : draws) {
    sigma_max = std::max(sigma_max, d.sigma);
    sigma_sum += d.sigma * d.sigma;
  }
  const double reach = 8 * std::sqrt(2.0) * sigma_max;
  long long pairs = 0, mirror_pairs = 0;
  std::vector<char> shared(draws.size(), 0);
  for (std::size_t i = 0; i < draws.size(); ++i) {
    for (std::size_t j = i + 1; j < draws.size() && draws[j].z.real() - draws[i].z.real() <= reach; ++j) {
      const double epsilon = 8 * std::hypot(draws[i].sigma, draws[j].sigma);
      if (std::abs(draws[i].z - draws[j].z) > epsilon) continue;
      ++pairs;
      if (draws[i].n == -draws[j].n && draws[i].m == -draws[j].m) ++mirror_pairs;
      shared[i] = shared[j] = 1;
    }
  }
  const double count = double(draws.size());
  const double lambda0 = count > 1 ? 32 * (count - 1) * sigma_sum : 0;
  // P(Poisson(λ0) ≥ pairs) = regularized lower incomplete gamma P(pairs, λ0).
  const double p = pairs == 0 ? 1.0 : stats::gamma_lower_p(double(pairs), lambda0);
  const double alpha = a.options().alpha;
  const long long sharing = std::count(shared.begin(), shared.end(), 1);
  std::string reason = fmt::format("{} pairs of the {} recovered amplitudes coincide (chance: "
                                   "{:.2g} expected, p = {:.2g})",
                                   pairs, draws.size(), lambda0, p);
  if (p < alpha) {
    reason = mirror_pairs == pairs
                 ? fmt::format("h̃0(k) and h̃0(−k) share their random pair at {} wave vectors — the same "
                               "random numbers for k and −k; ",
                               pairs)
                 : fmt::format("{:.1f} % of the wave vectors ({} of {}) share their random pair with "
                               "another: reused random numbers (a hash of the index that collides, or "
                               "a seed per row?); ",
                               100 * double(sharing) / count, sharing, draws.size()) +
                       reason;
  }
  return {statistical_check(
      "randomness.reused_numbers", a.subject(), double(pairs), lambda0, p, alpha,
      fmt::format("p ≥ α = {:.1e} (coinciding pairs of h̃0/√τ, Poisson law, {} amplitudes)", alpha,
                  draws.size()),
      reason)};
}

}  // namespace swell::validation::ocean_analysis
