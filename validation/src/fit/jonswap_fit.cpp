// The JONSWAP fit by maximum Whittle likelihood (docs/fit.md).
//
// Model. For every energy-carrying k of a half plane, μ(k; θ) = ½ (Ψ(k) + Ψ(−k)) Δkx Δky with
// Ψ = S(ω) D (dω/dk)/k. ω(k) is the same for k and −k, so μ factors into
//     μ(k; θ) = S(ω_k; θ) · A_k,
//     A_k = ½ (D(ω_k, θk − θw) + D(ω_k, θk + π − θw)) (dω/dk)/k Δk² · Φ(ω_k)
// where A_k (spreading, dispersion, TMA depth factor Φ) does not depend on θ and is computed
// once. S is JONSWAP normalized exactly (m0 = Hs²/16): with x = ω/ωp,
//     S(ω) = (Hs²/16) · x⁻⁵ e^(−5/4 x⁻⁴) γ^r(x) / (ωp F(γ, σa, σb)),
//     F = ∫₀^∞ x⁻⁵ e^(−5/4 x⁻⁴) γ^r(x) dx,   r = exp(−(x − 1)² / (2σ²)),  σ = σa (x ≤ 1), σb,
// so log μ_k = log A_k − 5 log ω_k + [2 log Hs − log 16 + log(Tp/2π) − 5 log(Tp/2π) − log F]
//              − 5/4 x⁻⁴ + r log γ:  per k one division and one exponential (and e^(−log μ)
//              in the likelihood).
//
// Likelihood. Whittle's −log L = Σ_realizations Σ_k [log μ_k + I_k/μ_k] = R Σ_k [log μ_k + Ī_k/μ_k]
// with Ī the mean periodogram over the R realizations (exact for a Gaussian surface: the I_k are
// independent exponentials of mean μ_k over the half plane).
#include "swell/validation/fit/jonswap_fit.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <tuple>

#include "swell/reference/errors.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/spreading.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "fit/jonswap_normalization.hpp"
#include "fit/whitened_bfgs.hpp"
#include "swell/validation/results/report.hpp"

namespace swell::validation {
namespace {

using reference::Grid;
using reference::OceanCase;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
const double kLogTwoPi = std::log(kTwoPi);
const double kLog16 = std::log(16.0);

// Ordinates whose model mean at the starting point is below this fraction of the largest carry
// no information worth their rounding (e^(−5/4 x⁻⁴) underflows far below the peak) and are left
// out of the likelihood.
constexpr double kNegligibleMu = 1e-12;
// ... and so are those within this factor of the rounding noise of the stored numbers: an
// ordinate whose mean is 1000 times the noise is biased by 0.1 %.
constexpr double kNoiseMargin = 1e3;

// ---------------------------------------------------------------- the normalization F

using fit_detail::jonswap_normalization;
using fit_detail::kZ975;
using fit_detail::minimize_bfgs;
using fit_detail::whitening;

// F for doubles, and for Ceres' Jets with the chain rule through the quadrature derivatives.
double normalization_of(double gamma, double sigma_a, double sigma_b) {
  return jonswap_normalization(gamma, sigma_a, sigma_b).value;
}
template <int N>
ceres::Jet<double, N> normalization_of(const ceres::Jet<double, N>& gamma,
                                       const ceres::Jet<double, N>& sigma_a,
                                       const ceres::Jet<double, N>& sigma_b) {
  const auto n = jonswap_normalization(gamma.a, sigma_a.a, sigma_b.a);
  ceres::Jet<double, N> out(n.value);
  out.v = n.d_gamma * gamma.v + n.d_sigma_a * sigma_a.v + n.d_sigma_b * sigma_b.v;
  return out;
}

double scalar(double x) { return x; }
// Value and derivatives finite: Ceres' line search must never see a finite value with a NaN
// gradient (its Wolfe zoom aborts the process with a CHECK failure; seen on 64² × 100 m).
bool all_finite(double x) { return std::isfinite(x); }
template <int N>
bool all_finite(const ceres::Jet<double, N>& x) {
  return std::isfinite(x.a) && x.v.allFinite();
}
template <int N>
double scalar(const ceres::Jet<double, N>& x) {
  return x.a;
}

// ---------------------------------------------------------------- the wave vectors

// What the model needs of each wave vector, independent of θ.
struct Geometry {
  std::vector<std::size_t> index;  // into the nx·ny grid, FFT order
  std::vector<double> omega;       // ω(|k|), rad/s
  std::vector<double> base;        // log A_k − 5 log ω_k
};

void require_family(const OceanCase& ocean_case) {
  if (ocean_case.is_composite()) {
    throw InvalidInput(fmt::format(
        "the JONSWAP fit needs a one-component sea; this case is a composite sea of {} "
        "components ([[spectrum]]: {})", ocean_case.more_components.size() + 1,
        ocean_case.describe()));
  }
  if (ocean_case.energy_factor != 1 || ocean_case.short_wave_fade != 0) {
    throw InvalidInput(fmt::format(
        "the JONSWAP fit fits the declared JONSWAP spectrum itself; this case declares {} "
        "(remove energy_factor and short_wave_fade to fit the engine's own spectrum)",
        ocean_case.energy_factor != 1 ? fmt::format("energy_factor = {:g}", ocean_case.energy_factor)
                                      : fmt::format("short_wave_fade = {:g} m", ocean_case.short_wave_fade)));
  }
  const auto& model = ocean_case.spectrum.model;
  if (model != "jonswap" && model != "tma" && model != "bretschneider" &&
      model != "pierson-moskowitz") {
    throw InvalidInput(
        "the JONSWAP fit needs a case whose spectrum is jonswap, tma, "
        "bretschneider or pierson-moskowitz (the JONSWAP family); got '" +
        model + "'");
  }
}

// The wave vectors of the half plane (or of the whole grid) that carry energy, with A_k > 0.
// The spreading D is the case's, built (for laws in ω/ωp) around the case's own ωp: it is held
// fixed while Tp is fitted. So are the dispersion relation (depth, gravity; a loop period only
// quantizes the time factor, not Ψ) and, for tma, the Kitaigorodskii factor at the case's depth.
Geometry geometry(const OceanCase& ocean_case, bool half_plane) {
  require_family(ocean_case);
  const auto directional = ocean_case.directional_spectrum();
  const auto* spread = dynamic_cast<const reference::SpreadSpectrum*>(directional.get());
  if (!spread) throw InvalidInput("the JONSWAP fit needs a spectrum with a spreading model");
  const auto& spreading = spread->spreading();
  const auto dispersion = ocean_case.dispersion();
  const double theta_w = spread->mean_direction();
  std::function<double(double)> depth_factor = [](double) { return 1.0; };
  if (ocean_case.spectrum.model == "tma") {
    const auto it = ocean_case.spectrum.choices.find("depth_factor");
    const bool tv = it != ocean_case.spectrum.choices.end() && it->second == "thompson-vincent";
    const double depth = ocean_case.depth, g = ocean_case.gravity;
    depth_factor = [tv, depth, g](double omega) {
      return tv ? reference::kitaigorodskii_thompson_vincent(omega, depth, g)
                : reference::kitaigorodskii_exact(omega, depth, g);
    };
  }
  const reference::Sampling sampling = ocean_case.sampling();
  const double dk2 = sampling.dkx() * sampling.dky();
  Geometry out;
  for (std::size_t e = 0; e < sampling.size(); ++e) {
    if (!sampling.carries_energy(e)) continue;
    const auto [n, m] = sampling.wave_index(e);
    if (half_plane && !in_half_plane(n, m)) continue;
    const double kx = n * sampling.dkx(), ky = m * sampling.dky();
    const double k = std::hypot(kx, ky);
    const double omega = dispersion.omega(k);
    const double theta = std::atan2(ky, kx) - theta_w;
    const double a = 0.5 *
                     (spreading(omega, theta) + spreading(omega, theta + std::numbers::pi)) *
                     dispersion.group_velocity(k) / k * dk2 * depth_factor(omega);
    if (!(a > 0) || !(omega > 0) || !std::isfinite(a)) continue;
    out.index.push_back(e);
    out.omega.push_back(omega);
    out.base.push_back(std::log(a) - 5.0 * std::log(omega));
  }
  return out;
}

// ---------------------------------------------------------------- the likelihood

class Whittle {
 public:
  Geometry geometry;
  std::vector<double> mean_i;          // Ī_k, mean over realizations
  std::vector<double> reference_term;  // log μ_k + Ī_k/μ_k at the start (subtracted, see nll)
  int realizations = 0;
  double fixed_sigma_a = 0.07, fixed_sigma_b = 0.09;  // σa, σb unless fitted

  // log μ_k for every used k, handed to f(i, log μ_i). T is double or a Ceres Jet.
  template <typename T, typename F>
  void for_each_log_mu(const T& log_hs, const T& log_tp, const T& log_gamma, const T& sigma_a,
                       const T& sigma_b, F&& f) const {
    using std::exp;
    using std::log;
    const T log_scale = log_tp - kLogTwoPi;  // x = ω Tp/2π = ω/ωp
    const T scale = exp(log_scale);
    const T c = 2.0 * log_hs - kLog16 + log_scale - 5.0 * log_scale -
                log(normalization_of(exp(log_gamma), sigma_a, sigma_b));
    const T ka = 0.5 / (sigma_a * sigma_a), kb = 0.5 / (sigma_b * sigma_b);
    const auto& omega = geometry.omega;
    const auto& base = geometry.base;
    for (std::size_t i = 0; i < omega.size(); ++i) {
      const T x = omega[i] * scale;
      const T d = x - 1.0;
      const T r = exp(-(d * d) * (scalar(x) <= 1.0 ? ka : kb));
      const T x2 = x * x;
      f(i, T(base[i] + c - 1.25 / (x2 * x2) + r * log_gamma));
    }
  }

  // −log L minus its value at the start. Subtracting each ordinate's starting term before
  // summing keeps the sum O(1) instead of O(K·R·20), so its rounding (summed in blocks of 256)
  // stays near 1e-12 and the line search can resolve the last steps of the optimization.
  template <typename T>
  T relative_nll(const T& log_hs, const T& log_tp, const T& log_gamma, const T& sigma_a,
                 const T& sigma_b) const {
    using std::exp;
    T total(0.0), block(0.0);
    int count = 0;
    for_each_log_mu(log_hs, log_tp, log_gamma, sigma_a, sigma_b,
                    [&](std::size_t i, const T& log_mu) {
                      block += log_mu + mean_i[i] * exp(-log_mu) - reference_term[i];
                      if (++count == 256) total += block, block = T(0.0), count = 0;
                    });
    total += block;
    return double(realizations) * total;
  }

  // Σ R (∂ log μ/∂p)(∂ log μ/∂p)ᵀ: the expected Fisher information in whatever parameters the
  // Jets are seeded with (for an exponential of mean μ, E[(∂/∂p(−log L))²] = (∂μ/∂p)²/μ²).
  template <int N>
  Eigen::Matrix<double, N, N> fisher(const ceres::Jet<double, N>& log_hs,
                                     const ceres::Jet<double, N>& log_tp,
                                     const ceres::Jet<double, N>& log_gamma,
                                     const ceres::Jet<double, N>& sigma_a,
                                     const ceres::Jet<double, N>& sigma_b) const {
    Eigen::Matrix<double, N, N> f = Eigen::Matrix<double, N, N>::Zero();
    for_each_log_mu(log_hs, log_tp, log_gamma, sigma_a, sigma_b,
                    [&](std::size_t, const ceres::Jet<double, N>& log_mu) {
                      f.noalias() += log_mu.v * log_mu.v.transpose();
                    });
    return double(realizations) * f;
  }
};

// The parameters the optimizer moves: φ = (log Hs, log Tp, η[, log σa, log σb]) with
// γ = 1 + η². Logarithms keep Hs, Tp, σ positive without bounds; γ = 1 + η² keeps γ ≥ 1, the
// JONSWAP family's valid region (γ < 1 would be a dip at the peak, which no JONSWAP sea has),
// without a bound the gradient solver cannot impose. Why not log γ: it lets BFGS
// wander to γ = 8e-311 on a 64² × 200 m surface, where the normalization's quadrature fails
// (a numerical error the user could not act on). Why not γ = 1 + e^ζ: γ = 1 sits at ζ = −∞, so
// a Pierson–Moskowitz sea would never converge. With η, γ = 1 is an ordinary point (η = 0) and
// the cost is smooth and even in η: a sea without enhancement converges to η ≈ 0 (γ̂ = 1 on the
// boundary) at the normal rate.
template <int N>
using Vector = Eigen::Matrix<double, N, 1>;

// What for_each_log_mu takes, (log Hs, log Tp, log γ, σa, σb), from φ.
template <int N, typename T>
std::array<T, 5> likelihood_arguments(const Whittle& w, const T* phi) {
  using std::exp;
  using std::log;
  const T log_gamma = log(T(1.0) + phi[2] * phi[2]);
  if constexpr (N == 5) {
    return {phi[0], phi[1], log_gamma, exp(phi[3]), exp(phi[4])};
  } else {
    return {phi[0], phi[1], log_gamma, T(w.fixed_sigma_a), T(w.fixed_sigma_b)};
  }
}

// φ's γ coordinate from γ ≥ 1 (the sign of η is immaterial: the cost is even in η).
double eta_of_gamma(double gamma, double sign = 1.0) {
  return std::copysign(std::sqrt(std::max(0.0, gamma - 1.0)), sign);
}

// Ceres minimizes over whitened coordinates u, φ = φ0 + M u (whitened_bfgs.hpp), M from the
// Fisher information F_φ of the free coordinates (zero rows for a coordinate held fixed by a
// profile).
//
// A step into a region where the model cannot be evaluated (the normalization's quadrature
// does not reach its accuracy, for γ beyond ~1e300 or σ at rounding level) is reported to
// Ceres as an infeasible point (return false), so its line search steps back; it never ends
// the fit with an error.
template <int N, int M>
struct WhittleCost {
  const Whittle* whittle;
  Vector<N> phi0;
  Eigen::Matrix<double, N, M> to_phi;

  template <typename T>
  bool operator()(const T* u, T* cost) const {
    T phi[N];
    for (int i = 0; i < N; ++i) {
      phi[i] = T(phi0[i]);
      for (int j = 0; j < M; ++j) phi[i] += to_phi(i, j) * u[j];
    }
    const auto p = likelihood_arguments<N>(*whittle, phi);
    try {
      *cost = whittle->relative_nll(p[0], p[1], p[2], p[3], p[4]);
    } catch (const NumericalError&) {
      return false;
    }
    return all_finite(*cost);
  }
};

// −log L at φ relative to the start (Whittle::relative_nll); +∞ where the model cannot be
// evaluated.
template <int N>
double nll_at(const Whittle& w, const Vector<N>& phi) {
  const auto p = likelihood_arguments<N>(w, phi.data());
  try {
    const double v = w.relative_nll(p[0], p[1], p[2], p[3], p[4]);
    return std::isfinite(v) ? v : HUGE_VAL;
  } catch (const NumericalError&) {
    return HUGE_VAL;
  }
}

// F in φ. At η = 0 (γ = 1) F_φ is singular in η (∂γ/∂η = 2η); for whitening only, η is taken
// as at least 0.1 in size (γ ≥ 1.01): whitening sets the optimizer's scale, not its answer.
template <int N>
Eigen::Matrix<double, N, N> fisher_for_whitening(const Whittle& w, Vector<N> phi) {
  if (std::abs(phi[2]) < 0.1) phi[2] = std::copysign(0.1, phi[2] == 0 ? 1.0 : phi[2]);
  using Jet = ceres::Jet<double, N>;
  Jet seeded[N];
  for (int i = 0; i < N; ++i) seeded[i] = Jet(phi[i], i);
  const auto p = likelihood_arguments<N>(w, seeded);
  try {
    return w.fisher<N>(p[0], p[1], p[2], p[3], p[4]);
  } catch (const NumericalError&) {
    return Eigen::Matrix<double, N, N>::Identity();
  }
}

// In the reported parameters (Hs, Tp, γ[, σa, σb]).
template <int N>
Eigen::Matrix<double, N, N> fisher_natural(const Whittle& w, const std::array<double, 5>& theta) {
  using Jet = ceres::Jet<double, N>;
  const Jet hs(theta[0], 0), tp(theta[1], 1), gamma(theta[2], 2);
  const Jet sa = N == 5 ? Jet(theta[3], 3 % N) : Jet(theta[3]);
  const Jet sb = N == 5 ? Jet(theta[4], 4 % N) : Jet(theta[4]);
  return w.fisher<N>(log(hs), log(tp), log(gamma), sa, sb);
}


struct Optimum {
  double nll = HUGE_VAL;  // relative (Whittle::relative_nll)
  int iterations = 0;
  bool converged = false;
  std::string report;
};

// Minimizes over the coordinates `to_phi` moves, from φ = start; returns φ at the optimum.
template <int N, int M>
std::pair<Vector<N>, Optimum> optimize(const Whittle& w, const Vector<N>& start,
                                       const Eigen::Matrix<double, N, M>& to_phi) {
  // Dense BFGS on 2 to 5 parameters, stopped at 1e-5 of a standard error (whitened_bfgs.hpp).
  double u[M] = {};
  const auto run = minimize_bfgs(new WhittleCost<N, M>{&w, start, to_phi}, u, 1e-5);
  Vector<N> phi = start + to_phi * Eigen::Map<const Vector<M>>(u);
  Optimum o;
  // Evaluated again at the returned point rather than taken from the solver's final cost, which
  // is not a cost at all when Ceres fails at its first evaluation (an infeasible warm start).
  o.nll = nll_at<N>(w, phi);
  o.iterations = run.iterations;
  o.converged = run.converged;
  o.report = run.report;
  return {phi, o};
}

struct Solution {
  std::array<double, 5> theta;  // Hs, Tp, γ, σa, σb
  Vector<5> phi5;               // φ (first N entries)
  Optimum optimum;
};

template <int N>
Solution minimize(const Whittle& w, const Vector<N>& phi0) {
  const auto to_phi = whitening<N, N>(fisher_for_whitening<N>(w, phi0), -1);
  const auto [phi, optimum] = optimize<N, N>(w, phi0, to_phi);
  Solution s;
  const auto p = likelihood_arguments<N>(w, phi.data());
  s.theta = {std::exp(p[0]), std::exp(p[1]), std::exp(p[2]), p[3], p[4]};
  s.phi5 = Vector<5>::Zero();
  s.phi5.template head<N>() = phi;
  s.optimum = optimum;
  return s;
}

// ---------------------------------------------------------------- profile-likelihood intervals

// The ends of the likelihood-ratio interval at kZ975 are found by root finding on the profile
// (Venzon & Moolgavkar 1988).
// The end of the profile interval of φ's coordinate `p` on one side, found in t: t = φ_p for
// log Hs, log Tp, log σ, and t = log γ for γ (profiles are close to quadratic in log γ, not in
// η, and t ≥ 0 is γ ≥ 1). Root finding on the signed root r(t) = √(2 Δnll), which is nearly
// linear in t: from the Wald point, secant steps outward until r ≥ z bracket the end, then
// Illinois (regula falsi with halving) to |r − z| < 1e-4, i.e. the end to ~1e-4 of a standard
// error. Each profile point re-optimizes the other parameters with Ceres, warm-started at the
// nearest evaluated point plus the linear (Fisher) prediction of how they move with t.
template <int N>
struct Profiler {
  const Whittle& w;
  Vector<N> phi_hat;
  double nll_hat;
  Eigen::Matrix<double, N, N> f_phi;  // F in φ at the estimate (for whitening, warm starts)
  int evaluations = 0;
  bool all_converged = true;

  double phi_coordinate(int p, double t) const {
    return p == 2 ? eta_of_gamma(std::exp(t), phi_hat[2] == 0 ? 1.0 : phi_hat[2]) : t;
  }
  double t_of(int p, const Vector<N>& phi) const {
    return p == 2 ? std::log1p(phi[2] * phi[2]) : phi[p];
  }

  // r(t) and the optimum of the other coordinates, from the warm start `near`.
  std::pair<double, Vector<N>> signed_root(int p, double t, const Vector<N>& near) {
    Vector<N> start = near;
    const double step = phi_coordinate(p, t) - near[p];
    start[p] = phi_coordinate(p, t);
    // The other coordinates' linear response to φ_p: −F_ff⁻¹ F_fp (the conditional mean).
    {
      Eigen::Matrix<double, N, N> f = f_phi;
      Vector<N> col = f.col(p);
      for (int i = 0; i < N; ++i) f(p, i) = f(i, p) = i == p ? 1.0 : 0.0;
      col[p] = 0;
      const Vector<N> shift = f.ldlt().solve(col);
      if (shift.allFinite()) {
        for (int i = 0; i < N; ++i) {
          if (i != p) start[i] -= shift[i] * step;
        }
      }
    }
    const auto to_phi = whitening<N, N - 1>(f_phi, p);
    auto [phi, optimum] = optimize<N, N - 1>(w, start, to_phi);
    ++evaluations;
    if (!optimum.converged) all_converged = false;
    // A point where the model cannot be evaluated is far outside: r large but finite, so that
    // regula falsi keeps working.
    const double d = std::isfinite(optimum.nll) ? 2.0 * (optimum.nll - nll_hat) : 1e6;
    return {std::sqrt(std::max(0.0, d)), phi};
  }

  struct End {
    double t = 0;
    bool found = false;     // r reached z inside the limits
    bool boundary = false;  // stopped at γ = 1 with r < z there: the end is γ = 1
  };

  // side = ±1; se_t: Wald standard error of t; t_min, t_max: where to stop looking.
  End find(int p, int side, double se_t, double t_min, double t_max) {
    const double t_hat = t_of(p, phi_hat);
    End end;
    double t_in = t_hat, r_in = 0;  // inside: r < z
    Vector<N> phi_in = phi_hat;
    double distance = kZ975 * se_t;
    double t_out = 0, r_out = 0;
    Vector<N> phi_out;
    bool bracketed = false;
    for (int expansion = 0; expansion < 40; ++expansion) {
      double t = t_hat + side * distance;
      bool at_limit = false;
      if (t <= t_min) t = t_min, at_limit = true;
      if (t >= t_max) t = t_max, at_limit = true;
      const auto [r, phi] = signed_root(p, t, phi_in);
      if (r >= kZ975) {
        t_out = t, r_out = r, phi_out = phi, bracketed = true;
        break;
      }
      t_in = t, r_in = r, phi_in = phi;
      end.t = t;  // where the search stopped, should it never bracket
      if (at_limit) {
        end.boundary = p == 2 && side < 0 && t == t_min;
        return end;
      }
      // Secant on r through (t̂, 0): r ∝ |t − t̂| where the profile is quadratic; at most ×4.
      const double d = std::abs(t - t_hat);
      distance = r > 0 ? std::min(4.0 * d, 1.05 * d * kZ975 / r) : 4.0 * d;
      if (!(distance > d)) distance = 1.5 * d;
    }
    if (!bracketed) return end;
    // Illinois on g(t) = r(t) − z between t_in (g < 0) and t_out (g ≥ 0).
    double g_in = r_in - kZ975, g_out = r_out - kZ975;
    int last = 0;
    for (int iteration = 0; iteration < 60; ++iteration) {
      if (std::abs(g_out) < 1e-4) {
        end.t = t_out, end.found = true;
        return end;
      }
      if (std::abs(g_in) < 1e-4) {
        end.t = t_in, end.found = true;
        return end;
      }
      const double t = t_in - g_in * (t_out - t_in) / (g_out - g_in);
      const bool closer_in = std::abs(t - t_in) < std::abs(t - t_out);
      const auto [r, phi] = signed_root(p, t, closer_in ? phi_in : phi_out);
      const double g = r - kZ975;
      if (g >= 0) {
        t_out = t, g_out = g, phi_out = phi;
        if (last == +1) g_in *= 0.5;
        last = +1;
      } else {
        t_in = t, g_in = g, phi_in = phi;
        if (last == -1) g_out *= 0.5;
        last = -1;
      }
    }
    end.t = 0.5 * (t_in + t_out), end.found = true;
    return end;
  }
};

// ---------------------------------------------------------------- the resolution rule

// A patch must hold at least this many peak wavelengths, λp = 2π/k(ωp) at the case's own Tp,
// along its longer side for any interval to be called calibrated. Measured (docs/fit.md §4,
// 1000–2000 seeds of 64² grids, one realization): at L = 1 λp the profile intervals that close
// cover Hs in only 90.6 % (59 misses of 628; 70 % of the Hs profiles do not close); at
// 1.1–1.5 λp the Hs and Tp profiles of 4–60 % of the seeds do not close and the γ intervals
// over-cover (97.7–97.9 %); from 2 λp up every parameter is within the binomial bound of 95 %.
// Why the case's λp and not the estimate's: a rule on the estimate selects seeds by their error
// (measured at 1 λp: keeping only fits with L/λ̂p ≥ 1.2 raised the Hs misses to 18 %), while a
// rule on the case's peak leaves the coverage of what it keeps unconditional.
constexpr double kMinPeakWavelengths = 2.0;

// Per parameter: (Σ w²)²/Σ w⁴ × R with w_k = (F⁻¹ g_k)_p, g_k = ∂ log μ_k/∂(log θ): the
// ordinate's share of the efficient score for θ_p (F⁻¹ g ∝ g_p − F_pn F_nn⁻¹ g_n, the score with
// the nuisance parameters projected out). For n equal shares it is n; when a handful of
// ordinates carry the information it is that handful. Reported as a diagnostic; measured, it
// is 4.5–7.3 both where intervals fail (1 λp) and where they hold (2 λp), so no rule uses it.
template <int N>
std::array<double, N> effective_ordinates(const Whittle& w, const std::array<double, 5>& theta,
                                          const Eigen::Matrix<double, N, N>& f_log_inverse) {
  using Jet = ceres::Jet<double, N>;
  const Jet lhs(std::log(theta[0]), 0), ltp(std::log(theta[1]), 1), lg(std::log(theta[2]), 2);
  const Jet sa = N == 5 ? exp(Jet(std::log(theta[3]), 3 % N)) : Jet(theta[3]);
  const Jet sb = N == 5 ? exp(Jet(std::log(theta[4]), 4 % N)) : Jet(theta[4]);
  Vector<N> s2 = Vector<N>::Zero(), s4 = Vector<N>::Zero();
  w.for_each_log_mu(lhs, ltp, lg, sa, sb, [&](std::size_t, const Jet& log_mu) {
    const Vector<N> share = f_log_inverse * log_mu.v;
    s2 += share.cwiseProduct(share);
    s4 += share.cwiseProduct(share).cwiseProduct(share.cwiseProduct(share));
  });
  std::array<double, N> out{};
  for (int p = 0; p < N; ++p) out[p] = s4[p] > 0 ? w.realizations * s2[p] * s2[p] / s4[p] : 0.0;
  return out;
}

// ---------------------------------------------------------------- starting values

// Tp from the peak of the periodogram binned in ω: the energy of each bin of 5 % in ω over its
// width estimates S(ω) whatever the spreading; a parabola through the log densities of the
// peak bin and its neighbours refines it within the bin.
double starting_tp(const Geometry& g, const std::vector<double>& mean_i) {
  const auto [lo_it, hi_it] = std::minmax_element(g.omega.begin(), g.omega.end());
  constexpr double kWidth = 0.05;  // in ln ω
  const double lo = std::log(*lo_it);
  const int bins = std::max(1, int(std::ceil((std::log(*hi_it) - lo) / kWidth)) + 1);
  std::vector<double> energy(bins, 0.0), density(bins, 0.0);
  for (std::size_t i = 0; i < g.omega.size(); ++i) {
    energy[std::min(bins - 1, int((std::log(g.omega[i]) - lo) / kWidth))] += mean_i[i];
  }
  for (int b = 0; b < bins; ++b) {
    density[b] = energy[b] / (std::exp(lo + (b + 1) * kWidth) - std::exp(lo + b * kWidth));
  }
  const int peak = int(std::max_element(density.begin(), density.end()) - density.begin());
  double log_omega = lo + (peak + 0.5) * kWidth;
  if (peak > 0 && peak + 1 < bins && density[peak - 1] > 0 && density[peak + 1] > 0) {
    const double a = std::log(density[peak - 1]), b = std::log(density[peak]),
                 c = std::log(density[peak + 1]);
    const double curvature = a - 2 * b + c;
    if (curvature < 0) log_omega += std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5) * kWidth;
  }
  return kTwoPi / std::exp(log_omega);
}

void require_finite_parameters(const JonswapParameters& p) {
  require(std::isfinite(p.hs) && p.hs > 0, "hs", "finite and > 0 m", p.hs);
  require(std::isfinite(p.tp) && p.tp > 0, "tp", "finite and > 0 s", p.tp);
  require(std::isfinite(p.gamma) && p.gamma > 0, "gamma", "finite and > 0", p.gamma);
  require(std::isfinite(p.sigma_a) && p.sigma_a > 0, "sigma_a", "finite and > 0", p.sigma_a);
  require(std::isfinite(p.sigma_b) && p.sigma_b > 0, "sigma_b", "finite and > 0", p.sigma_b);
}

Estimate wald(double value, double variance) {
  Estimate e;
  e.value = value;
  e.standard_error = std::sqrt(variance);
  // The Wald interval: estimate ± z_0.975 · se, z_0.975 = 1.959964.
  e.ci95_low = value - kZ975 * e.standard_error;
  e.ci95_high = value + kZ975 * e.standard_error;
  e.method = "wald";
  return e;
}

const char* const kNames[] = {"Hs", "Tp", "γ", "σa", "σb"};

template <int N>
JonswapFit assemble(const std::array<Estimate, N>& e) {
  JonswapFit fit;
  fit.hs = e[0];
  fit.tp = e[1];
  fit.gamma = e[2];
  if constexpr (N == 5) {
    fit.sigma_a = e[3];
    fit.sigma_b = e[4];
  }
  return fit;
}

// `peak_wavelengths`: the patch's longer side over the case's λp (the resolution rule).
template <int N>
JonswapFit finish(const Whittle& w, const Solution& s, const JonswapFitOptions& options,
                  double peak_wavelengths, double lambda_p) {
  const bool fit_sigma = options.fit_sigma;
  const bool resolved = peak_wavelengths >= kMinPeakWavelengths;
  auto apply_resolution_rule = [&](std::array<Estimate, N>& e) {
    if (resolved) return;
    for (int p = 0; p < N; ++p) {
      e[p].calibrated = false;
      e[p].reason = fmt::format(
          "the patch holds only {:.2f} peak wavelengths (λp = {:.4g} m at the case's Tp; fewer "
          "than {:g}): the spectral peak is resolved by too few wave vectors for a 95 % "
          "interval to hold its level (docs/fit.md §4; a patch of at least {:.4g} m)",
          peak_wavelengths, lambda_p, kMinPeakWavelengths, kMinPeakWavelengths * lambda_p);
    }
  };
  Eigen::Matrix<double, N, N> f = fisher_natural<N>(w, s.theta);
  if (!f.allFinite()) {
    throw NumericalError("Fisher information at the estimate is not finite");
  }
  // Singular: judged in relative units, on the information about the logarithms of the
  // parameters, F_log = diag(θ) F diag(θ) (unit-free): a condition number beyond 1e12 leaves no
  // digit of the covariance, and means that some combination of the parameters is determined
  // a million times less precisely (relatively) than another — not identifiable.
  Vector<N> theta;
  for (int i = 0; i < N; ++i) theta[i] = s.theta[i];
  const Eigen::Matrix<double, N, N> f_log = theta.asDiagonal() * f * theta.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(f_log);
  const double smallest = eigen.eigenvalues().minCoeff(), largest = eigen.eigenvalues().maxCoeff();
  const bool singular = !(smallest > 1e-12 * largest);
  if (singular && fit_sigma) {
    throw NumericalError(fmt::format(
        "Fisher information at the estimate is singular (eigenvalues of its relative form from "
        "{:.3g} to {:.3g}): the parameters are not identifiable from these wave vectors (σa and "
        "σb need a peak enhancement γ clearly above 1: fit without --sigma)",
        smallest, largest));
  }
  // Without σ, a singular information means the grid does not resolve the peak (seen on 64²
  // over one peak wavelength, where no wave vector lies below the peak): the estimates stand,
  // but no interval does. The fit says so instead of failing.
  if (singular) {
    std::array<Estimate, N> e;
    for (int p = 0; p < N; ++p) {
      e[p].value = s.theta[p];
      e[p].standard_error = HUGE_VAL;
      e[p].ci95_low = -HUGE_VAL, e[p].ci95_high = HUGE_VAL;
      e[p].method = "wald";  // infinite: se = ∞; no profile is tried
      e[p].calibrated = false;
      e[p].reason = fmt::format(
          "the Fisher information is singular (eigenvalues of its relative form from {:.3g} to "
          "{:.3g}): these wave vectors do not determine Hs, Tp and γ separately (a patch of more "
          "peak wavelengths)",
          smallest, largest);
    }
    apply_resolution_rule(e);
    return assemble<N>(e);
  }
  // F⁻¹ = diag(θ) F_log⁻¹ diag(θ), F_log⁻¹ = V Λ⁻¹ Vᵀ.
  const Eigen::Matrix<double, N, N>& v = eigen.eigenvectors();
  const Eigen::Matrix<double, N, N> log_covariance =
      v * eigen.eigenvalues().cwiseInverse().asDiagonal() * v.transpose();
  const Eigen::Matrix<double, N, N> covariance =
      theta.asDiagonal() * log_covariance * theta.asDiagonal();
  std::array<Estimate, N> e;
  for (int p = 0; p < N; ++p) e[p] = wald(s.theta[p], covariance(p, p));

  const auto n_eff = effective_ordinates<N>(w, s.theta, log_covariance);
  for (int p = 0; p < N; ++p) e[p].effective_ordinates = n_eff[p];

  // Profiles only where their interval can be calibrated; an unresolved peak keeps the Wald
  // interval, for diagnosis (and its profiles, which often do not close, would cost 50 fits).
  if (options.interval == IntervalMethod::profile_likelihood && resolved) {
    Profiler<N> profiler{w, s.phi5.template head<N>(), s.optimum.nll,
                         fisher_for_whitening<N>(w, s.phi5.template head<N>())};
    for (int p = 0; p < N; ++p) {
      // t's Wald standard error: se(log θ) = se/θ; for γ, t = log γ as well.
      const double se_t = std::sqrt(log_covariance(p, p));
      const double t_hat = profiler.t_of(p, profiler.phi_hat);
      // Where to stop looking: within a factor e^±(max(40 se, 3)) of the estimate — far beyond
      // any closing profile — and for γ also not below 1 (t = 0) nor, upward, short of 1e4.
      const double reach = std::max(40.0 * se_t, 3.0);
      const double t_min = p == 2 ? 0.0 : t_hat - reach;
      const double t_max = p == 2 ? std::max(std::log(1e4), t_hat + reach) : t_hat + reach;
      const auto low = profiler.find(p, -1, se_t, t_min, t_max);
      const auto high = profiler.find(p, +1, se_t, t_min, t_max);
      e[p].method = "profile-likelihood";
      e[p].ci95_low = std::exp(low.t);
      e[p].ci95_high = std::exp(high.t);
      if (p == 2 && low.boundary) e[p].ci95_low = 1.0;
      std::string open;
      if (!low.found && !low.boundary) open = fmt::format("below {:.4g}", std::exp(low.t));
      if (!high.found) {
        open += fmt::format("{}above {:.4g}", open.empty() ? "" : " and ", std::exp(high.t));
      }
      if (!open.empty()) {
        e[p].calibrated = false;
        e[p].ci95_low = low.found || low.boundary ? e[p].ci95_low : 0.0;
        e[p].ci95_high = high.found ? e[p].ci95_high : HUGE_VAL;
        e[p].reason = fmt::format(
            "the profile likelihood of {} does not fall by χ²₁(0.95)/2 = 1.92 {}: the data do "
            "not bound it (too few wave vectors resolve the spectral peak; a larger patch or "
            "more realizations)",
            kNames[p], open);
      }
    }
  }
  apply_resolution_rule(e);
  return assemble<N>(e);
}

}  // namespace

const char* interval_method_name(IntervalMethod method) {
  return method == IntervalMethod::wald ? "wald" : "profile-likelihood";
}

// ---------------------------------------------------------------- public

JonswapParameters case_jonswap_parameters(const OceanCase& ocean_case) {
  require_family(ocean_case);
  const auto& spec = ocean_case.spectrum;
  JonswapParameters p;
  auto given = [&](const char* name) -> std::optional<double> {
    const auto it = spec.numbers.find(name);
    return it == spec.numbers.end() ? std::nullopt : std::optional<double>(it->second);
  };
  if (spec.model == "jonswap" || spec.model == "tma") {
    reference::ModelSpec jonswap = spec;  // the JONSWAP part (tma: without its depth factor)
    jonswap.model = "jonswap";
    jonswap.choices.erase("depth_factor");
    jonswap.numbers["gravity"] = ocean_case.gravity;
    const auto s = std::dynamic_pointer_cast<const reference::Jonswap>(
        reference::make_frequency_spectrum(jonswap));
    const auto normalization = spec.choices.find("normalization");
    const bool exact = normalization == spec.choices.end() || normalization->second == "exact";
    p.hs = given("hs") && exact ? *given("hs") : 4.0 * std::sqrt(reference::spectral_moment(*s, 0));
    p.tp = given("tp") ? *given("tp") : kTwoPi / s->peak_omega();
    p.gamma = s->shape().gamma;
    p.sigma_a = s->shape().sigma_a;
    p.sigma_b = s->shape().sigma_b;
  } else {  // bretschneider, pierson-moskowitz: JONSWAP with γ = 1
    const auto s = reference::make_frequency_spectrum(ocean_case.full_spectrum_spec());
    p.hs = given("hs") ? *given("hs") : 4.0 * std::sqrt(reference::spectral_moment(*s, 0));
    p.tp = given("tp") ? *given("tp") : kTwoPi / s->peak_omega();
    p.gamma = 1.0;
  }
  return p;
}

std::vector<double> jonswap_model_periodogram(const OceanCase& ocean_case,
                                              const JonswapParameters& parameters) {
  ocean_case.validate();
  require_finite_parameters(parameters);
  Whittle w;
  w.geometry = geometry(ocean_case, false);
  std::vector<double> mu(ocean_case.sampling().size(), 0.0);
  w.for_each_log_mu(std::log(parameters.hs), std::log(parameters.tp), std::log(parameters.gamma),
                    parameters.sigma_a, parameters.sigma_b, [&](std::size_t i, double log_mu) {
                      mu[w.geometry.index[i]] = std::exp(log_mu);
                    });
  return mu;
}

JonswapFit fit_jonswap_periodograms(const OceanCase& ocean_case,
                                    const std::vector<std::vector<double>>& periodograms,
                                    const JonswapFitOptions& options, double unit_roundoff) {
  ocean_case.validate();
  require_family(ocean_case);
  const Grid& grid = ocean_case.grid;  // its lengths (a lattice's patch)
  const std::size_t count = ocean_case.sampling().size();
  if (periodograms.empty()) throw InvalidInput("the JONSWAP fit needs at least one realization");
  for (std::size_t r = 0; r < periodograms.size(); ++r) {
    if (periodograms[r].size() != count) {
      throw InvalidInput(
          fmt::format("periodogram of realization {} has {} values; the case's {} needs {}",
                      r, periodograms[r].size(), ocean_case.sampling().describe(), count));
    }
    for (double value : periodograms[r]) {
      if (!(std::isfinite(value) && value >= 0)) {
        throw InvalidInput(fmt::format(
            "periodogram of realization {} holds {} (must be finite and ≥ 0)", r, value));
      }
    }
  }
  require(std::isfinite(unit_roundoff) && unit_roundoff >= 0, "unit roundoff", "finite and ≥ 0",
          unit_roundoff);

  // Every energy-carrying k of the half plane, with the mean periodogram over realizations.
  Geometry all = geometry(ocean_case, true);
  const int realizations = int(periodograms.size());
  std::vector<double> mean_i(all.index.size(), 0.0);
  double energy = 0;  // Σ over the half plane: half of mean h²
  for (std::size_t i = 0; i < all.index.size(); ++i) {
    for (const auto& p : periodograms) mean_i[i] += p[all.index[i]];
    mean_i[i] /= realizations;
    energy += mean_i[i];
  }
  if (!(energy > 0)) {
    throw InvalidInput(
        "the frames carry no energy at any wave vector the case's spectrum "
        "fills (flat surfaces?)");
  }

  // Starting values from the data, never from the case: Hs from the variance (4√(Σ I) over
  // the whole plane, the band-limited Hs), Tp from the peak of the binned periodogram, γ = 2
  // (between Pierson–Moskowitz and the mean JONSWAP 3.3), σ at JONSWAP's 0.07 and 0.09.
  const auto truth_shape = case_jonswap_parameters(ocean_case);
  JonswapParameters start;
  start.hs = 4.0 * std::sqrt(2.0 * energy);
  start.tp = starting_tp(all, mean_i);
  start.gamma = 2.0;
  start.sigma_a = options.fit_sigma ? 0.07 : truth_shape.sigma_a;
  start.sigma_b = options.fit_sigma ? 0.09 : truth_shape.sigma_b;

  // Only ordinates the model gives a non-negligible mean at the start: above 1e-12 of the
  // largest, and above the rounding noise of the stored surface (a rounding error of relative
  // size u, white over the grid, adds u²·mean(h²)/(3 Nx Ny) to every ordinate on average).
  Whittle w;
  w.realizations = realizations;
  w.fixed_sigma_a = start.sigma_a;
  w.fixed_sigma_b = start.sigma_b;
  std::vector<double> log_mu0(all.index.size());
  w.geometry = all;
  w.for_each_log_mu(std::log(start.hs), std::log(start.tp), std::log(start.gamma), start.sigma_a,
                    start.sigma_b, [&](std::size_t i, double log_mu) { log_mu0[i] = log_mu; });
  const double log_max = *std::max_element(log_mu0.begin(), log_mu0.end());
  const double noise = kNoiseMargin * unit_roundoff * unit_roundoff * 2.0 * energy / (3.0 * count);
  const double log_floor = std::max(log_max + std::log(kNegligibleMu), std::log(noise));
  w.geometry = {};
  for (std::size_t i = 0; i < all.index.size(); ++i) {
    if (!(log_mu0[i] > log_floor)) continue;
    w.geometry.index.push_back(all.index[i]);
    w.geometry.omega.push_back(all.omega[i]);
    w.geometry.base.push_back(all.base[i]);
    w.mean_i.push_back(mean_i[i]);
    w.reference_term.push_back(log_mu0[i] + mean_i[i] * std::exp(-log_mu0[i]));
  }
  const int parameters = options.fit_sigma ? 5 : 3;
  if (int(w.mean_i.size()) < 10 * parameters) {
    throw InvalidInput(fmt::format(
        "only {} wave vectors of the grid carry a non-negligible share of the spectrum; the "
        "JONSWAP fit needs at least {} (a finer or larger grid)",
        w.mean_i.size(), 10 * parameters));
  }

  // The resolution rule's measure: the case's peak wavelength against the patch.
  const double lambda_p = kTwoPi / ocean_case.dispersion().wavenumber(kTwoPi / truth_shape.tp);
  const double peak_wavelengths = std::max(grid.lx, grid.ly) / lambda_p;

  Solution s;
  JonswapFit fit;
  const double eta0 = eta_of_gamma(start.gamma);
  if (options.fit_sigma) {
    Vector<5> phi0;
    phi0 << std::log(start.hs), std::log(start.tp), eta0, std::log(start.sigma_a),
        std::log(start.sigma_b);
    s = minimize<5>(w, phi0);
    fit = finish<5>(w, s, options, peak_wavelengths, lambda_p);
  } else {
    Vector<3> phi0;
    phi0 << std::log(start.hs), std::log(start.tp), eta0;
    s = minimize<3>(w, phi0);
    fit = finish<3>(w, s, options, peak_wavelengths, lambda_p);
  }
  {
    std::vector<double> log_mu(w.mean_i.size());
    w.for_each_log_mu(std::log(s.theta[0]), std::log(s.theta[1]), std::log(s.theta[2]),
                      s.theta[3], s.theta[4],
                      [&](std::size_t i, double value) { log_mu[i] = value; });
    const double half = *std::max_element(log_mu.begin(), log_mu.end()) - std::log(2.0);
    fit.peak_wave_vectors =
        realizations * int(std::count_if(log_mu.begin(), log_mu.end(),
                                          [half](double v) { return v >= half; }));
  }
  // The fitted peak itself must lie among the wave vectors: a peak below the lowest ω of the
  // ordinates is not seen, only its flank, and Hs and γ can then run off together (measured on
  // 64² over 400 m with γ = 1: 5 of 1000 seeds ended at Tp ≈ 16.9 s, γ ≈ 9e4, Hs ≈ 1150 m, with
  // "intervals" spanning 1e-24 to 3e5 m). Such a fit says so instead of giving intervals.
  {
    const double omega_min = *std::min_element(w.geometry.omega.begin(), w.geometry.omega.end());
    const double omega_p = kTwoPi / s.theta[1];
    if (omega_p < omega_min) {
      for (Estimate* e : {&fit.hs, &fit.tp, &fit.gamma}) {
        if (!e->calibrated) continue;  // keeps the resolution rule's reason, the root cause
        e->calibrated = false;
        e->reason = fmt::format(
            "the fitted peak (Tp = {:.4g} s, ωp = {:.4g} rad/s) lies below the lowest frequency "
            "of the wave vectors used ({:.4g} rad/s): the data see only its flank, and Hs, Tp "
            "and γ are not determined (a larger patch, or a case with a shorter Tp)",
            s.theta[1], omega_p, omega_min);
      }
      for (auto* e : {&fit.sigma_a, &fit.sigma_b}) {
        if (*e && e->value().calibrated) {
          e->value().calibrated = false, e->value().reason = fit.hs.reason;
        }
      }
    }
  }
  fit.peak_wavelengths = peak_wavelengths;
  fit.wave_vectors = int(w.mean_i.size());
  fit.wave_vector_index = w.geometry.index;
  fit.realizations = realizations;
  fit.iterations = s.optimum.iterations;
  fit.converged = s.optimum.converged;
  fit.report = s.optimum.report;
  double nll = 0;
  w.for_each_log_mu(
      std::log(s.theta[0]), std::log(s.theta[1]), std::log(s.theta[2]), s.theta[3], s.theta[4],
      [&](std::size_t i, double log_mu) { nll += log_mu + w.mean_i[i] * std::exp(-log_mu); });
  fit.negative_log_likelihood = realizations * nll;
  return fit;
}

JonswapFit fit_jonswap(const OceanCase& ocean_case,
                       const std::vector<reference::FrameSequence>& realizations,
                       const JonswapFitOptions& options) {
  ocean_case.validate();
  require_family(ocean_case);
  if (realizations.empty()) throw InvalidInput("the JONSWAP fit needs at least one realization");
  const reference::Sampling sampling = ocean_case.sampling();
  std::vector<std::vector<double>> periodograms;
  double unit_roundoff = 0;
  for (std::size_t r = 0; r < realizations.size(); ++r) {
    const auto& frames = realizations[r];
    const reference::Sampling g = frames.sampling();
    if (!g.same_as(sampling)) {
      throw InvalidInput(fmt::format("realization {}: frames on a {}, the case's is {}", r,
                                     g.describe(), sampling.describe()));
    }
    if (options.frame < 0 || options.frame >= int(frames.frames.size())) {
      throw InvalidInput(fmt::format("realization {}: frame {} requested, it has {} frame(s)", r,
                                     options.frame, frames.frames.size()));
    }
    if (!frames.frames[options.frame].fields.count(reference::Field::height)) {
      throw InvalidInput(
          fmt::format("realization {}: frame {} has no height field; the JONSWAP fit needs heights",
                      r, options.frame));
    }
    const auto spectrum = field_spectrum(frames.field(options.frame, reference::Field::height), sampling);
    std::vector<double> periodogram(spectrum.size());
    for (std::size_t i = 0; i < spectrum.size(); ++i) periodogram[i] = std::norm(spectrum[i]);
    periodograms.push_back(std::move(periodogram));
    unit_roundoff = std::max(unit_roundoff, frames.unit_roundoff);
  }
  return fit_jonswap_periodograms(ocean_case, periodograms, options, unit_roundoff);
}

nlohmann::json estimate_json(const Estimate& e) {
  const nlohmann::json interval = {json_number(e.ci95_low), json_number(e.ci95_high)};
  nlohmann::json j = {{"value", json_number(e.value)},
                      {"ci95", e.calibrated ? interval : nlohmann::json(nullptr)},
                      {"se", json_number(e.standard_error)},
                      {"method", e.method},
                      {"calibrated", e.calibrated},
                      {"effective_ordinates", json_number(e.effective_ordinates)}};
  if (!e.calibrated) {
    j["ci95_uncalibrated"] = interval;
    j["reason"] = e.reason;
  }
  return j;
}

nlohmann::json jonswap_fit_json(const JonswapFit& fit, const JonswapParameters& truth, bool free_scale,
                                IntervalMethod interval) {
  nlohmann::json parameters = nlohmann::json::object(), truths = nlohmann::json::object();
  auto add = [&](const char* name, const Estimate& estimate, std::optional<double> value) {
    parameters[name] = estimate_json(estimate);
    if (value) truths[name] = json_number(*value);
  };
  add("hs", fit.hs, free_scale ? std::nullopt : std::optional(truth.hs));
  add("tp", fit.tp, truth.tp);
  add("gamma", fit.gamma, truth.gamma);
  if (fit.sigma_a) add("sigma_a", *fit.sigma_a, truth.sigma_a);
  if (fit.sigma_b) add("sigma_b", *fit.sigma_b, truth.sigma_b);
  return {{"fit", parameters},
          {"converged", fit.converged},
          {"wave_vectors", fit.wave_vectors},
          {"realizations", fit.realizations},
          {"interval", interval_method_name(interval)},
          {"peak_wavelengths", json_number(fit.peak_wavelengths)},
          {"peak_wave_vectors", fit.peak_wave_vectors},
          {"truth", truths},
          {"negative_log_likelihood", json_number(fit.negative_log_likelihood)},
          {"iterations", fit.iterations}};
}

}  // namespace swell::validation
