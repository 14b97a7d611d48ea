#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"
#include "swell/validation/stats/sample_moments.hpp"
#include "swell/validation/stats/statistics.hpp"
#include "swell/reference/phase.hpp"

namespace swell::validation::ocean_analysis {

namespace {

// Gaussian amplitudes: u = I/μ are independent exponentials. Anderson–Darling against the
// exponential law with its scale estimated (mean u), so that this part judges the shape of
// the law only — an energy error is the energy check's to name.
CheckResult check_gaussian_amplitudes(const Analysis& a, double alpha) {
  std::vector<double> u;
  u.reserve(a.waves().size());
  double u_sum = 0;
  for (const Wave& w : a.waves()) {
    u.push_back(a.periodogram0(w.index) / w.mu);
    u_sum += u.back();
  }
  const double u_mean = u_sum / double(u.size());
  std::vector<double> cdf, log_survival;
  cdf.reserve(u.size());
  log_survival.reserve(u.size());
  for (double x : u) {
    cdf.push_back(-std::expm1(-x / u_mean));
    log_survival.push_back(-x / u_mean);
  }
  const double a2 = stats::anderson_darling_statistic(cdf, log_survival);
  const double p_ad = stats::anderson_darling_exponential_p(a2, int(cdf.size()));
  // Which failure it is: u normalized by its neighbours' level instead of the case's μ — cells
  // of 64 wave vectors, consecutive in |k| and then θ. Under complex Gaussian amplitudes one u
  // over its cell's sum is Beta(1, n − 1) whatever the spectrum; exponential there and not
  // against μ, the amplitudes are Gaussian and the spectrum (or spreading) is not the case's.
  std::string amplitude_reason = " — the amplitudes are not complex Gaussian (|h̃|² not exponential: "
                                 "uniform noise, or h̃0(k) and h̃0(−k) correlated?)";
  if (p_ad < alpha && u.size() >= 256) {
    std::vector<std::size_t> order(u.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    const auto& waves = a.waves();
    std::sort(order.begin(), order.end(),
              [&](std::size_t x, std::size_t y) { return waves[x].k < waves[y].k; });
    constexpr std::size_t kRing = 1024, kCell = 64;
    for (std::size_t begin = 0; begin < order.size(); begin += kRing) {
      const auto end = order.begin() + std::ptrdiff_t(std::min(order.size(), begin + kRing));
      std::sort(order.begin() + std::ptrdiff_t(begin), end,
                [&](std::size_t x, std::size_t y) { return waves[x].theta < waves[y].theta; });
    }
    std::vector<double> local_cdf, local_log_survival;
    for (std::size_t begin = 0; begin + kCell <= order.size(); begin += kCell) {
      double sum = 0;
      for (std::size_t i = begin; i < begin + kCell; ++i) sum += u[order[i]];
      if (!(sum > 0)) continue;
      for (std::size_t i = begin; i < begin + kCell; ++i) {
        const double y = u[order[i]] / sum;
        const double log_survival_y = double(kCell - 1) * std::log1p(-y);
        local_cdf.push_back(-std::expm1(log_survival_y));
        local_log_survival.push_back(log_survival_y);
      }
    }
    const double local_a2 = stats::anderson_darling_statistic(local_cdf, local_log_survival);
    if (stats::anderson_darling_p(local_a2, int(local_cdf.size())) >= alpha) {
      amplitude_reason = fmt::format(
          " — but normalized by their neighbours' level (cells of {} wave vectors in |k| and θ) the "
          "amplitudes are exponential (A² = {:.3g}): they are complex Gaussian, and the failure "
          "follows from a spectrum or spreading other than the case's (spectrum.shape, "
          "direction.distribution)",
          kCell, local_a2);
    }
  }
  return statistical_check(
      "statistics.gaussian_amplitudes", a.subject(), a2, 1.0, p_ad, alpha,
      fmt::format("p ≥ α = {:.1e} (Anderson–Darling, I/μ exponential, scale fitted, n = {})", alpha,
                  cdf.size()),
      fmt::format("A² = {:.3g} for the normalized periodogram{}", a2,
                  p_ad < alpha ? amplitude_reason : ""));
}

}  // namespace

Results check_statistics(const Analysis& a, OceanCheckReport& report) {
  Results out;
  const bool several_frames = a.times().size() >= 2;
  const double alpha = a.options().alpha / (several_frames ? 4 : 3);
  const double n = double(a.count());

  // Sample skewness and kurtosis of a Gaussian field on the torus: with covariance
  // C(d) = Σk μ(k) e^(ik·d), Var(mean h³) = (6/n) Σd C(d)³ and the kurtosis linearizes to
  // mean He4(h)/σ⁴ with Var = (24/n) Σd C(d)⁴ / σ⁸ (Isserlis; Σd C(d) = 0 as k = 0 is empty).
  // On a lattice the differences of sample points are lattice points again (x_n − x_n' =
  // x_(n−n')), so C over them is the lattice's own inverse transform of μ.
  // Its real parts, read where the transform leaves them (no field of its own beside them),
  // and the transform's array freed before the laws below are made.
  double sigma2 = 0, c3 = 0, c4 = 0;
  {
    InverseTransformArrays arrays;
    const auto covariance = inverse_transform(a.sampling(), arrays, [&](std::span<Complex> in) {
      std::copy(a.mu().begin(), a.mu().end(), in.begin());
    });
    sigma2 = covariance[0].real();
    for (const Complex& value : covariance) {
      const double c = value.real();
      c3 += c * c * c;
      c4 += c * c * c * c;
    }
  }
  // About 0: the case's field has no mean (k = 0 carries no energy), and a mean the engine adds
  // is the energy check's to find.
  const stats::SampleMoments<double>& moments = a.height_moments0();
  const double skewness = moments.skewness();
  const double kurtosis = moments.excess_kurtosis();
  // Plus the rounding of the normalized moments (64 u log2 N, the dispersion check's bound): a
  // law of zero variance (one wave pair: a sampled cosine's skewness is exactly 0) is judged
  // against rounding instead of dividing by zero; 16 u log2 N was measured too tight (a 16²
  // surface of one wave pair showed 550 u, the command line's property test).
  const double moment_rounding = rounding_budget(kCompoundRounding, a.unit_roundoff(), a.log2n());
  const double sd_skew = std::hypot(std::sqrt(6 * std::max(c3, 0.0) / n) / std::pow(sigma2, 1.5),
                                    moment_rounding);
  const double sd_kurt = std::hypot(std::sqrt(24 * std::max(c4, 0.0) / n) / (sigma2 * sigma2),
                                    moment_rounding);
  const double z_skew = skewness / sd_skew, z_kurt = kurtosis / sd_kurt;
  const double p_skew = stats::normal_two_sided_p(z_skew), p_kurt = stats::normal_two_sided_p(z_kurt);
  out.push_back(statistical_check("statistics.skewness", a.subject(), skewness, 0.0, p_skew, alpha,
                            fmt::format("p ≥ α = {:.1e}, sd {:.3g} from the spectrum", alpha, sd_skew),
                            fmt::format("skewness of heights {:.3g} (z = {:.2f}){}", skewness, z_skew,
                                        p_skew < alpha ? " — heights are not Gaussian" : "")));
  out.push_back(statistical_check("statistics.kurtosis", a.subject(), kurtosis, 0.0, p_kurt, alpha,
                            fmt::format("p ≥ α = {:.1e}, sd {:.3g} from the spectrum", alpha, sd_kurt),
                            fmt::format("excess kurtosis of heights {:.3g} (z = {:.2f}){}", kurtosis,
                                        z_kurt, p_kurt < alpha ? " — heights are not Gaussian" : "")));

  // Its arrays (three per wave vector) are freed before hs_steady's law is made.
  out.push_back(check_gaussian_amplitudes(a, alpha));

  // Hs steady: m0(t) − m0(t0) = 4 Σ half plane Re(a b̄ (e^(−2iωt) − e^(−2iωt0))), mean 0,
  // variance 8 Σ τ+ τ− |e^(−2iωt) − e^(−2iωt0)|², plus rounding.
  if (!several_frames) {
    report.skipped.push_back({"statistics.hs_steady", SkipReason::too_few_frames, "needs ≥ 2 frames"});
    return out;
  }
  const auto& times = a.times();
  const double m0_first = a.mean_square0();
  double worst_z = 0, hs_min = 1e300, hs_max = 0;
  int worst_frame = 0;
  // e^(−2iωt) once per distinct ω and frame (group_by_omega, made by the pass; one per wave
  // vector was 7 % of the gate's CPU at 512² × 64 frames).
  const auto& waves = a.half_plane();
  const OmegaGroups& by_omega = a.pass().half_plane_groups;
  auto phases_at = [&](double t, std::vector<Complex>& phases) {
    phases.resize(by_omega.omegas.size());
    for (std::size_t g = 0; g < by_omega.omegas.size(); ++g) {
      phases[g] = reference::unit_phasor(-reference::reduced_phase(2 * by_omega.omegas[g], t));
    }
  };
  std::vector<Complex> first_phase;  // e^(−2iωt0) per distinct ω
  phases_at(times[0], first_phase);
  const std::vector<double>& sums = a.pass().height_sums;  // Σh² per frame
  // m0(t) − m0(t0) = Σ over the half plane of 4 Re(a b (e^(−2iωt) − e^(−2iωt0))), a = h̃0(k) and
  // b = h̃0(−k) independent complex Gaussians of powers τ+ and τ−: each term is exactly
  // w (E1 − E2), E Exp(1) independent, w = 2 √(τ+ τ−) |e^(−2iωt) − e^(−2iωt0)| (Re x y of
  // independent circular Gaussians is ½ √(E|x|² E|y|²) (E1 − E2)). Its law is judged by the
  // saddlepoint (mixed_exponential_sum_cdf): the normal law it tends to is far too light in the
  // tails where a handful of waves carry the energy (a narrow swell on a small grid).
  // The stored values' rounding moves each m0 by at most this (a bound, taken off |Δm0|).
  const double rounding = rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n()) * m0_first;
  // Δm0 at the frames' measured level L (MeasuredLevel): a scale error alone multiplies every
  // change by L, which is energy's to name, not a drift.
  const MeasuredLevel& level = a.measured_level();
  const double level_scale = level.rings >= 4 && level.level > 0 ? level.level : 1.0;
  // Each frame's law on its own, the frames dealt out to the analysis' threads, then judged in
  // frame order.
  struct FrameChange {
    double p = 1, z = 0, m0 = 0;
  };
  std::vector<FrameChange> changes(times.size());
  // 2 √(τ+ τ−) per wave, once for every frame.
  std::vector<double> amplitude(waves.size());
  for (std::size_t i = 0; i < waves.size(); ++i) amplitude[i] = 2 * std::sqrt(waves[i].tau_plus * waves[i].tau_minus);
  const std::size_t compared = times.size() - 1;
  const std::size_t workers = std::min<std::size_t>(compared, std::size_t(std::max(1, a.threads())));
  detail::run_tasks(workers, a.threads(), [&](std::size_t worker) {
    std::vector<Complex> phase;    // e^(−2iωt) per distinct ω of frame f
    std::vector<double> modulus;   // |e^(−2iωt) − e^(−2iωt0)| per distinct ω
    std::vector<double> weights;   // w per wave (the law's coefficients are ±w)
    weights.reserve(waves.size());
    for (std::size_t f = 1 + worker; f < times.size(); f += workers) {
      phases_at(times[f], phase);
      modulus.resize(phase.size());
      for (std::size_t g = 0; g < phase.size(); ++g) modulus[g] = std::abs(phase[g] - first_phase[g]);
      weights.clear();
      double variance = 0;
      for (std::size_t i = 0; i < waves.size(); ++i) {
        const double weight = amplitude[i] * modulus[by_omega.group[i]];
        if (!(weight > 0)) continue;
        weights.push_back(weight);
        variance += 2 * weight * weight;
      }
      const double m0 = sums[f] / n;  // mean_square of frame f
      const double change = std::max(0.0, std::abs(m0 - m0_first) - rounding) / level_scale;
      // The law is symmetric: P(|D| ≥ d) = 2 P(D ≤ −d). No wave changes (every ω t the same
      // mod π): only rounding may move m0.
      changes[f].p = weights.empty() ? (change > 0 ? 0.0 : 1.0)
                                     : std::min(1.0, 2 * stats::exponential_difference_sum_cdf(weights, -change));
      changes[f].z = variance > 0 ? (m0 - m0_first) / (level_scale * std::sqrt(variance))
                                  : (change > 0 ? INFINITY : 0.0);
      changes[f].m0 = m0;
    }
  });
  double worst_p = 1;
  for (std::size_t f = 1; f < times.size(); ++f) {
    const FrameChange& c = changes[f];
    if (c.p <= worst_p) {
      worst_p = c.p;
      worst_z = c.z;
      worst_frame = int(f);
    }
    hs_min = std::min(hs_min, 4 * std::sqrt(c.m0));
    hs_max = std::max(hs_max, 4 * std::sqrt(c.m0));
  }
  hs_min = std::min(hs_min, 4 * std::sqrt(m0_first));
  hs_max = std::max(hs_max, 4 * std::sqrt(m0_first));
  const double frames_compared = double(times.size() - 1);
  const double p_steady = std::min(1.0, frames_compared * worst_p);
  out.push_back(statistical_check(
      "statistics.hs_steady", a.subject(), 4 * std::sqrt(m0_first), hs_max - hs_min, p_steady, alpha,
      fmt::format("p ≥ α = {:.1e} (the exact law of each frame's change of m0, saddlepoint; Bonferroni "
                  "over {} frames)", alpha, times.size() - 1),
      fmt::format("Hs {:.4g}…{:.4g} m over {} frames; largest change z = {:.2f} at frame {}{}", hs_min,
                  hs_max, times.size(), worst_z, worst_frame,
                  p_steady < alpha ? " — Hs drifts over the frames" : "")));
  return out;
}

}  // namespace swell::validation::ocean_analysis
