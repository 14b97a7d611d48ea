// JONSWAP fitted to a measured 1-D buoy spectrum (buoy_fit.hpp, docs/buoy_fit.md).
//
// In Hz, with x = f Tp (= ω/ωp), exact normalization gives
//     S(f) = (Hs²/16) Tp x⁻⁵ e^(−5/4 x⁻⁴) γ^r(x) / F(γ, σa, σb),   r = e^(−(x − 1)²/(2σ²)),
//     F = ∫₀^∞ x⁻⁵ e^(−5/4 x⁻⁴) γ^r dx   (F = 1/5 for γ = 1),
// the same family as docs/fit.md §1 (S_f(f) = 2π S_ω(2πf)); the test
// BuoyFitModel.MatchesTheReferenceJonswap checks it against swell::reference::Jonswap.
// Everything is computed in log S (band averages by log-sum-exp), so a model that is 1e-300 of
// a band's value costs a large finite amount instead of overflowing.
#include "swell/validation/fit/buoy_fit.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <numbers>

#include "fit/jonswap_normalization.hpp"
#include "fit/whitened_bfgs.hpp"
#include "swell/reference/errors.hpp"

namespace swell::validation {
namespace {

const double kLog16 = std::log(16.0);

// Values of at least this many quanta are taken as exact (density term); smaller ones as the
// interval they were rounded from. At 10 quanta the rounding's half-width is 5 % of the value,
// against a sampling scatter of √(2/ν) ≥ 20 % for ν ≤ 48: the density term's error is then
// (5 %)²/12 relative in the likelihood, negligible.
constexpr double kExactQuanta = 10;

// ---------------------------------------------------------------- the normalization F(γ)

using fit_detail::jonswap_normalization;
using fit_detail::kZ975;
using fit_detail::minimize_bfgs;
using fit_detail::whitening;

// log F and its derivative in γ (σa, σb fixed: jonswap_normalization.hpp).
double log_normalization(double gamma, double sa, double sb) {
  return std::log(jonswap_normalization(gamma, sa, sb, false).value);
}
template <int N>
ceres::Jet<double, N> log_normalization(const ceres::Jet<double, N>& gamma, double sa, double sb) {
  const auto n = jonswap_normalization(gamma.a, sa, sb, false);
  ceres::Jet<double, N> out(std::log(n.value));
  out.v = (n.d_gamma / n.value) * gamma.v;
  return out;
}

double scalar(double x) { return x; }
template <int N>
double scalar(const ceres::Jet<double, N>& x) {
  return x.a;
}
bool all_finite(double x) { return std::isfinite(x); }
template <int N>
bool all_finite(const ceres::Jet<double, N>& x) {
  return std::isfinite(x.a) && x.v.allFinite();
}

// ---------------------------------------------------------------- the law of one band value

// log P(a, x) and log Q(a, x) (regularized incomplete gamma functions) without underflow: the
// series for x < a + 1 and the continued fraction above (Numerical Recipes §6.2), each in
// logarithms, the complement by log1p.
double log_p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 1000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (term < sum * 1e-17) break;
  }
  return -x + a * std::log(x) - std::lgamma(a) + std::log(sum);
}
double log_q_fraction(double a, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return -x + a * std::log(x) - std::lgamma(a) + std::log(h);
}
double log_gamma_p(double a, double x) {
  if (x <= 0) return -HUGE_VAL;
  return x < a + 1 ? log_p_series(a, x) : std::log1p(-std::exp(log_q_fraction(a, x)));
}
double log_gamma_q(double a, double x) {
  if (x <= 0) return 0;
  return x < a + 1 ? std::log1p(-std::exp(log_p_series(a, x))) : log_q_fraction(a, x);
}

// One band: its value and how it enters the likelihood.
struct Band {
  std::array<double, 8> f{}, log_weight{};  // Gauss–Legendre nodes (Hz), log(weight/2)
  double a = 0;                             // ν/2
  double width = 0;                         // Δf (Hz)
  double value = 0;                         // Ŝ as printed
  bool censored = false;                    // value < 10 quanta: the interval [lo, hi)
  double lo = 0, hi = 0;
};

// The band's term of −log L at L = log S̄ and its derivative in L.
//  exact:    a (L + Ŝ e^(−L))                                  (χ²_ν/ν density, constants dropped)
//  censored: −log(P(a, a·hi/S̄) − P(a, a·lo/S̄))               (Ŝ·a/S̄ ~ Gamma(a, 1))
// with d P(a, a b e^(−L))/dL = −g(x_b), g(x) = x^a e^(−x)/Γ(a).
std::pair<double, double> band_term(const Band& b, double log_s) {
  if (!b.censored) {
    const double ratio = b.value * std::exp(-log_s);
    return {b.a * (log_s + ratio), b.a * (1.0 - ratio)};
  }
  const double x_hi = b.a * b.hi * std::exp(-log_s);
  const double x_lo = b.a * b.lo * std::exp(-log_s);
  double log_mass;
  if (b.lo <= 0) {
    log_mass = log_gamma_p(b.a, x_hi);
  } else if (x_lo < b.a) {
    const double p_hi = log_gamma_p(b.a, x_hi), p_lo = log_gamma_p(b.a, x_lo);
    log_mass = p_hi + std::log1p(-std::exp(p_lo - p_hi));
  } else {
    const double q_lo = log_gamma_q(b.a, x_lo), q_hi = log_gamma_q(b.a, x_hi);
    log_mass = q_lo + std::log1p(-std::exp(q_hi - q_lo));
  }
  auto log_g = [&](double x) { return b.a * std::log(x) - x - std::lgamma(b.a); };
  double derivative = std::exp(log_g(x_hi) - log_mass);
  if (b.lo > 0) derivative -= std::exp(log_g(x_lo) - log_mass);
  return {-log_mass, derivative};
}

double band_cost(const Band& b, double log_s) { return band_term(b, log_s).first; }
template <int N>
ceres::Jet<double, N> band_cost(const Band& b, const ceres::Jet<double, N>& log_s) {
  const auto [value, derivative] = band_term(b, log_s.a);
  ceres::Jet<double, N> out(value);
  out.v = derivative * log_s.v;
  return out;
}

// ---------------------------------------------------------------- the likelihood

struct Likelihood {
  std::vector<Band> bands;
  double sigma_a = 0.07, sigma_b = 0.09;

  // log S̄ of band b at (log Hs, log Tp, log γ): 8-point Gauss–Legendre average of S over the
  // band, by log-sum-exp (the front e^(−5/4 x⁻⁴) changes by orders of magnitude across a band).
  template <typename T>
  T log_band_mean(const Band& b, const T& c, const T& log_tp, const T& tp, const T& log_gamma) const {
    using std::exp;
    using std::log;
    std::array<T, 8> terms;
    double largest = -HUGE_VAL;
    for (int q = 0; q < 8; ++q) {
      const T x = b.f[q] * tp;
      const T d = x - 1.0;
      const double sigma = scalar(x) <= 1.0 ? sigma_a : sigma_b;
      const T r = exp(-(d * d) / (2.0 * sigma * sigma));
      const T x2 = x * x;
      terms[q] = b.log_weight[q] + c - 5.0 * (log(b.f[q]) + log_tp) - 1.25 / (x2 * x2) + r * log_gamma;
      largest = std::max(largest, scalar(terms[q]));
    }
    T sum(0.0);
    for (int q = 0; q < 8; ++q) sum += exp(terms[q] - largest);
    return largest + log(sum);
  }

  // The constant part of log S: 2 log Hs − log 16 + log Tp − log F(γ).
  template <typename T>
  T log_scale(const T& log_hs, const T& log_tp, const T& log_gamma) const {
    using std::exp;
    return 2.0 * log_hs - kLog16 + log_tp - log_normalization(exp(log_gamma), sigma_a, sigma_b);
  }

  template <typename T, typename F>
  void for_each_log_mean(const T& log_hs, const T& log_tp, const T& log_gamma, F&& f) const {
    using std::exp;
    const T c = log_scale(log_hs, log_tp, log_gamma);
    const T tp = exp(log_tp);
    for (std::size_t j = 0; j < bands.size(); ++j) f(j, log_band_mean(bands[j], c, log_tp, tp, log_gamma));
  }

  template <typename T>
  T cost(const T& log_hs, const T& log_tp, const T& log_gamma) const {
    T total(0.0);
    for_each_log_mean(log_hs, log_tp, log_gamma,
                      [&](std::size_t j, const T& log_s) { total += band_cost(bands[j], log_s); });
    return total;
  }
};

// φ = (log Hs, log Tp, η), γ = 1 + η² ≥ 1 (docs/fit.md §3: the valid region without a bound).
template <typename T>
T log_gamma_of(const T& eta) {
  using std::log;
  return log(T(1.0) + eta * eta);
}

double cost_at(const Likelihood& l, const Eigen::Vector3d& phi) {
  try {
    const double v = l.cost(phi[0], phi[1], log_gamma_of(phi[2]));
    return std::isfinite(v) ? v : HUGE_VAL;
  } catch (const NumericalError&) {
    return HUGE_VAL;
  }
}

// Minimized over u, φ = φ0 + M u (M: 3 × K, a zero row for a coordinate a profile holds).
template <int K>
struct Cost {
  const Likelihood* likelihood;
  Eigen::Vector3d phi0;
  Eigen::Matrix<double, 3, K> to_phi;
  template <typename T>
  bool operator()(const T* u, T* cost) const {
    T phi[3];
    for (int i = 0; i < 3; ++i) {
      phi[i] = T(phi0[i]);
      for (int j = 0; j < K; ++j) phi[i] += to_phi(i, j) * u[j];
    }
    try {
      *cost = likelihood->cost(phi[0], phi[1], log_gamma_of(phi[2]));
    } catch (const NumericalError&) {
      return false;  // infeasible: the line search steps back
    }
    return all_finite(*cost);
  }
};

// Σ a_j ∇φ log S̄_j ∇φᵀ over the exact bands: the expected information of those bands, used to
// whiten the optimizer's coordinates (its scale, never its answer). η taken as ≥ 0.1 in size
// (at η = 0 the information is singular in η).
Eigen::Matrix3d whitening_information(const Likelihood& l, Eigen::Vector3d phi) {
  if (std::abs(phi[2]) < 0.1) phi[2] = 0.1;
  using Jet = ceres::Jet<double, 3>;
  Eigen::Matrix3d f = Eigen::Matrix3d::Zero();
  try {
    l.for_each_log_mean(Jet(phi[0], 0), Jet(phi[1], 1), log_gamma_of(Jet(phi[2], 2)),
                        [&](std::size_t j, const Jet& log_s) {
                          if (!l.bands[j].censored) f += l.bands[j].a * log_s.v * log_s.v.transpose();
                        });
  } catch (const NumericalError&) {
    return Eigen::Matrix3d::Identity();
  }
  return f;
}


struct Optimum {
  Eigen::Vector3d phi;
  double cost = HUGE_VAL;
  int iterations = 0;
  bool converged = false;
  std::string report;
};

// Dense BFGS in whitened coordinates: there the gradient is the distance to the optimum in
// standard errors, and 1e-6 of one is far below anything reported.
template <int K>
Optimum optimize(const Likelihood& l, const Eigen::Vector3d& start, int fixed) {
  const auto to_phi = whitening<3, K>(whitening_information(l, start), fixed);
  double u[K] = {};
  const auto run = minimize_bfgs(new Cost<K>{&l, start, to_phi}, u, 1e-6);
  Optimum o;
  o.phi = start + to_phi * Eigen::Map<const Eigen::Matrix<double, K, 1>>(u);
  o.cost = cost_at(l, o.phi);
  o.iterations = run.iterations;
  o.converged = run.converged;
  o.report = run.report;
  return o;
}

// ---------------------------------------------------------------- intervals

// The observed information in ψ = (log Hs, log Tp, log γ) by central differences of the exact
// (autodiff) gradient; γ < 1 is evaluated too (the formula holds there), so the Hessian exists
// at γ̂ = 1. Standard errors: se(θ_i) = θ_i √(H⁻¹)_ii (delta method).
Eigen::Matrix3d observed_information(const Likelihood& l, const Eigen::Vector3d& psi) {
  using Jet = ceres::Jet<double, 3>;
  auto gradient = [&](const Eigen::Vector3d& p) {
    return l.cost(Jet(p[0], 0), Jet(p[1], 1), Jet(p[2], 2)).v;
  };
  Eigen::Matrix3d h;
  constexpr double step = 1e-4;
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3d up = psi, down = psi;
    up[j] += step, down[j] -= step;
    h.col(j) = (gradient(up) - gradient(down)) / (2 * step);
  }
  return 0.5 * (h + h.transpose());
}

// The profile of parameter i at t = log θ_i: min over the others of −log L, warm-started.
struct Profiler {
  const Likelihood& l;
  Eigen::Vector3d phi_hat;
  double cost_hat;
  double z = kZ975;  // the signed root's target: z₀.₉₇₅ √φ (quasi-likelihood) or z₀.₉₇₅

  static double t_of(int i, const Eigen::Vector3d& phi) {
    return i == 2 ? std::log1p(phi[2] * phi[2]) : phi[i];
  }
  static void set_t(int i, double t, Eigen::Vector3d& phi) {
    if (i == 2) {
      phi[2] = std::sqrt(std::max(0.0, std::expm1(t)));
    } else {
      phi[i] = t;
    }
  }
  // Signed root r = ±√(2 Δcost) at t, warm-starting (and updating) `phi`.
  double root(int i, double t, Eigen::Vector3d& phi) const {
    set_t(i, t, phi);
    const Optimum o = optimize<2>(l, phi, i);
    if (o.cost < HUGE_VAL) phi = o.phi;
    set_t(i, t, phi);
    const double delta = std::max(0.0, cost_at(l, phi) - cost_hat);
    return std::sqrt(2 * delta) * (t >= t_of(i, phi_hat) ? 1.0 : -1.0);
  }

  struct End {
    double t = 0;
    bool found = false, boundary = false;
  };
  // The end on side `side` (±1): secant steps outward from the Wald guess until |r| ≥ z brackets
  // it, then Illinois (regula falsi) to |r − z| < 1e-4 (docs/fit.md §4).
  End find(int i, int side, double se_t, double t_min, double t_max) const {
    const double t_hat = t_of(i, phi_hat);
    Eigen::Vector3d phi = phi_hat;
    double t_in = t_hat, r_in = 0;
    double t_out = std::clamp(t_hat + side * z * std::max(se_t, 1e-6), t_min, t_max);
    double r_out = side * root(i, t_out, phi);
    for (int step = 0; r_out < z; ++step) {
      if ((side < 0 && t_out <= t_min) || (side > 0 && t_out >= t_max) || step > 60) {
        return {t_out, false, i == 2 && side < 0 && t_out <= t_min};
      }
      double next = t_out + (z - r_out) * (t_out - t_in) / std::max(r_out - r_in, 1e-3);
      next = side > 0 ? std::min(std::max(next, t_out + 0.1 * std::abs(t_out - t_hat) + 1e-6), t_max)
                      : std::max(std::min(next, t_out - 0.1 * std::abs(t_out - t_hat) - 1e-6), t_min);
      t_in = t_out, r_in = r_out;
      t_out = next;
      r_out = side * root(i, t_out, phi);
    }
    // Bracket [t_in (r < z), t_out (r ≥ z)]: Illinois.
    double fa = r_in - z, fb = r_out - z, a = t_in, b = t_out;
    int last = 0;
    for (int iteration = 0; iteration < 60 && std::abs(fb) > 1e-4; ++iteration) {
      const double c = b - fb * (b - a) / (fb - fa);
      const double fc = side * root(i, c, phi) - z;
      if ((fc > 0) == (fb > 0)) {
        b = c, fb = fc;
        if (last == -1) fa *= 0.5;
        last = -1;
      } else {
        a = c, fa = fc;
        if (last == 1) fb *= 0.5;
        last = 1;
      }
      if (std::abs(fa) < std::abs(fb)) std::swap(a, b), std::swap(fa, fb), last = -last;
    }
    return {std::abs(fa) < std::abs(fb) ? a : b, true, false};
  }
};

// ---------------------------------------------------------------- misfit

// E[unit deviance] of a χ²_ν/ν value: 2a(log a − ψ(a)), a = ν/2 (≈ 1 + 1/(3ν)).
double deviance_expectation(double a) { return 2 * a * (std::log(a) - boost::math::digamma(a)); }

// The saturated term of a censored band: the least −log P(lo ≤ Ŝ < hi | S̄) over S̄ (0 for
// [0, hi): S̄ → 0 puts all mass there). Golden section in log S̄: P is unimodal in it.
double saturated_censored(const Band& b) {
  if (b.lo <= 0) return 0;
  double lo = std::log(b.lo) - 3, hi = std::log(b.hi) + 3;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = band_cost(b, x1), f2 = band_cost(b, x2);
  for (int i = 0; i < 80; ++i) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = band_cost(b, x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = band_cost(b, x2);
    }
  }
  return std::min(f1, f2);
}

// The energy test (buoy_fit.hpp, docs/buoy_fit.md §5), a Hausman-type test: two estimates of
// the energy in the likelihood's bands, the fitted model's m0_model = Σ S̄_j(θ̂) Δf_j (efficient
// when the model holds) and the measured m0 = Σ Ŝ_j Δf_j (consistent whatever the shape), differ
// under the model by a variable of variance Var m̂0 − Var m0_model (Hausman 1978: the efficient
// estimator is uncorrelated with its difference from any other consistent one), with
//     Var m̂0 = Σ (2 S̄_j²/νj + q²/12) Δf_j²,   Var m0_model = gᵀ H⁻¹ g,  g = ∂m0_model/∂ψ,
// both times φ = max(1, φ̂) (quasi-likelihood). The difference is referred to Student's t on the
// deviance's degrees of freedom (φ̂ is estimated from them). Where the subtraction leaves less
// than a tenth of Var m̂0 (a singular H, or censored bands that make the moment estimate the
// better one), a tenth is kept: the test stays conservative there. Returns whether it flags.
bool energy_test(const Likelihood& fitted, const Eigen::Vector3d& psi,
                 const Eigen::Matrix3d& covariance, double quantum, BuoyMisfit& m) {
  using Jet = ceres::Jet<double, 3>;
  Jet model(0.0);
  double variance = 0;
  m.energy_measured = 0;
  fitted.for_each_log_mean(Jet(psi[0], 0), Jet(psi[1], 1), Jet(psi[2], 2),
                           [&](std::size_t k, const Jet& log_s) {
                             const Band& b = fitted.bands[k];
                             const double s = std::exp(log_s.a);
                             model += exp(log_s) * b.width;
                             m.energy_measured += b.value * b.width;
                             variance += (s * s / b.a + quantum * quantum / 12) * b.width * b.width;
                           });
  m.energy_model = model.a;
  double fitted_variance = 0;
  if (covariance.allFinite()) {
    const Eigen::Vector3d g = model.v;
    fitted_variance = g.dot(covariance * g);
  }
  const double difference_variance = std::max(variance - fitted_variance, 0.1 * variance);
  m.energy_t = (m.energy_model - m.energy_measured) /
               std::sqrt(std::max(1.0, m.dispersion) * difference_variance);
  m.energy_t_limit = boost::math::quantile(
      boost::math::complement(boost::math::students_t(m.deviance_dof), kShapeAlpha / 2));
  m.energy_misfit = std::abs(m.energy_t) > m.energy_t_limit;
  return m.energy_misfit;
}

// The deviance over the fitted bands (`fitted`, model `fitted_log_mean`); the second peak over
// every band with a value (`all`, `index` into the spectrum, model `log_mean`), those below the
// likelihood's window included.
BuoyMisfit misfit(const Likelihood& fitted, const std::vector<double>& fitted_log_mean,
                  const Likelihood& all, const std::vector<std::size_t>& index,
                  const std::vector<double>& log_mean, const SpectralBands& bands,
                  const std::vector<double>& density, double tp_hat, double quantum,
                  const Eigen::Vector3d& psi, const Eigen::Matrix3d& covariance) {
  BuoyMisfit m;
  int informative = 0;
  for (std::size_t k = 0; k < fitted.bands.size(); ++k) {
    const Band& b = fitted.bands[k];
    const double term = 2 * (band_cost(b, fitted_log_mean[k]) -
                             (b.censored ? saturated_censored(b) : b.a * (std::log(b.value) + 1)));
    if (!b.censored) {
      m.deviance += term / deviance_expectation(b.a);
      ++informative;
    } else {
      // A censored band informs only where the model expects more than the quantum; where it
      // expects less, its term is ≈ 0 and it is not counted.
      m.deviance += term;
      if (std::exp(fitted_log_mean[k]) > quantum) ++informative;
    }
  }
  m.deviance_dof = std::max(1, informative - 3);
  m.deviance_p = boost::math::gamma_q(0.5 * m.deviance_dof, 0.5 * std::max(0.0, m.deviance));
  m.dispersion = std::max(0.0, m.deviance) / m.deviance_dof;


  // The second peak: runs of bands outside [0.8, 1.25] f̂p where the data exceed the model.
  const double fp = 1.0 / tp_hat;
  double m0 = 0;
  for (std::size_t k = 0; k < index.size(); ++k) m0 += density[index[k]] * bands.width[index[k]];
  auto smoothed = [&](std::size_t k) {  // 3-band running mean of the measured spectrum
    double s = 0;
    int n = 0;
    for (std::size_t q = k == 0 ? 0 : k - 1; q <= std::min(k + 1, index.size() - 1); ++q) {
      s += density[index[q]], ++n;
    }
    return s / n;
  };
  for (std::size_t start = 0; start < index.size();) {
    auto in_run = [&](std::size_t k) {
      const double f = bands.centre[index[k]];
      return (f < 0.8 * fp || f > 1.25 * fp) && density[index[k]] > std::exp(log_mean[k]);
    };
    if (!in_run(start)) {
      ++start;
      continue;
    }
    std::size_t end = start;
    double excess = 0, variance = 0;
    while (end < index.size() && in_run(end)) {
      const double s = std::exp(log_mean[end]), w = bands.width[index[end]];
      excess += (density[index[end]] - s) * w;
      // Var Ŝ = 2 S̄²/ν under the model, plus the rounding's q²/12.
      variance += (s * s / all.bands[end].a + quantum * quantum / 12) * w * w;
      ++end;
    }
    double best = -1, best_f = 0;
    for (std::size_t k = start; k < end; ++k) {
      const double here = smoothed(k);
      const bool local_max = (k == 0 || here > smoothed(k - 1)) &&
                             (k + 1 == index.size() || here > smoothed(k + 1));
      if (local_max && here > best) best = here, best_f = bands.centre[index[k]];
    }
    const double z = excess / std::sqrt(variance);
    const double fraction = m0 > 0 ? excess / m0 : 0;
    if (best > 0 && fraction >= 0.05 && z >= 4 && fraction > m.second_peak_energy_fraction) {
      m.second_peak = true;
      m.second_peak_frequency = best_f;
      m.second_peak_energy_fraction = fraction;
      m.second_peak_z = z;
    }
    start = end;
  }
  // The same question without the model: two peaks of the measured spectrum (3-band running
  // means s) with a valley between them. The fit can stretch over both systems (a broad
  // JONSWAP inflated to cover the swell and the wind sea), which hides the excess above; the
  // valley cannot hide. Rule: a local maximum k2 besides the highest k1, outside [0.8, 1.25]·f1,
  // whose valley v toward k1 is at most half of s(k2) and at least 4 standard deviations below
  // it (Var s ≈ Σ S_q²/a_q / 9 over its 3 bands, with S_q ≈ Ŝ_q), holding ≥ 5 % of m0 on its
  // side of the valley (the bands beyond the valley until s falls to v again).
  if (!m.second_peak && index.size() >= 3) {
    const std::size_t n = index.size();
    std::vector<double> s(n), var(n);
    for (std::size_t k = 0; k < n; ++k) {
      double sum = 0, v = 0;
      int count = 0;
      for (std::size_t q = k == 0 ? 0 : k - 1; q <= std::min(k + 1, n - 1); ++q) {
        sum += density[index[q]];
        v += density[index[q]] * density[index[q]] / all.bands[q].a + quantum * quantum / 12;
        ++count;
      }
      s[k] = sum / count;
      var[k] = v / (count * count);
    }
    const std::size_t k1 = std::size_t(std::max_element(s.begin(), s.end()) - s.begin());
    const double f1 = bands.centre[index[k1]];
    for (std::size_t k2 = 1; k2 + 1 < n; ++k2) {
      if (k2 == k1 || !(s[k2] > s[k2 - 1] && s[k2] > s[k2 + 1])) continue;
      const double f2 = bands.centre[index[k2]];
      if (f2 > 0.8 * f1 && f2 < 1.25 * f1) continue;
      const std::size_t a = std::min(k1, k2), b = std::max(k1, k2);
      std::size_t valley = a + 1;
      for (std::size_t k = a + 1; k < b; ++k) {
        if (s[k] < s[valley]) valley = k;
      }
      if (!(2 * s[valley] <= s[k2] && s[k2] - s[valley] >= 4 * std::sqrt(var[k2] + var[valley]))) {
        continue;
      }
      double energy = 0;
      const int step = k2 > k1 ? 1 : -1;
      for (long k = long(valley) + step; k >= 0 && k < long(n); k += step) {
        if (k != long(valley) + step && s[std::size_t(k)] <= s[valley]) break;
        energy += density[index[std::size_t(k)]] * bands.width[index[std::size_t(k)]];
      }
      const double fraction = m0 > 0 ? energy / m0 : 0;
      if (fraction >= 0.05 && fraction > m.second_peak_energy_fraction) {
        m.second_peak = true;
        m.second_peak_frequency = f2;
        m.second_peak_energy_fraction = fraction;
        m.second_peak_z = (s[k2] - s[valley]) / std::sqrt(var[k2] + var[valley]);
      }
    }
  }
  std::vector<std::string> reasons;
  if (m.second_peak) {
    reasons.push_back(fmt::format(
        "a second peak at {:.3f} Hz ({:.1f} s) holds {:.0f} % of m0 ({:.1f} σ)",
        m.second_peak_frequency, 1 / m.second_peak_frequency,
        100 * m.second_peak_energy_fraction, m.second_peak_z));
  }
  if (energy_test(fitted, psi, covariance, quantum, m)) {
    reasons.push_back(fmt::format(
        "the fitted JONSWAP holds {:.0f} % of the measured energy in its bands (t = {:+.1f} beyond "
        "±{:.2f}, p < {:g}, with φ = {:.1f})",
        100 * m.energy_model / m.energy_measured, m.energy_t, m.energy_t_limit, kShapeAlpha,
        std::max(1.0, m.dispersion)));
  }
  m.flagged = !reasons.empty();
  for (std::size_t i = 0; i < reasons.size(); ++i) m.reason += (i ? "; " : "") + reasons[i];
  return m;
}

// Gauss–Legendre, 8 points on [−1, 1].
constexpr std::array<double, 8> kNodes = {-0.9602898564975363, -0.7966664774136267,
                                          -0.5255324099163290, -0.1834346424956498,
                                          0.1834346424956498,  0.5255324099163290,
                                          0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeights = {0.1012285362903763, 0.2223810344533745,
                                            0.3137066458778873, 0.3626837833783620,
                                            0.3626837833783620, 0.3137066458778873,
                                            0.2223810344533745, 0.1012285362903763};

Band make_band(const SpectralBands& bands, std::size_t j) {
  Band b;
  const double mid = bands.centre[j], half = 0.5 * bands.width[j];
  b.width = bands.width[j];
  for (int q = 0; q < 8; ++q) {
    b.f[q] = mid + half * kNodes[q];
    b.log_weight[q] = std::log(0.5 * kWeights[q]);
  }
  return b;
}

Estimate wald(double value, double se) {
  Estimate e;
  e.value = value;
  e.standard_error = se;
  e.ci95_low = value - kZ975 * se;
  e.ci95_high = value + kZ975 * se;
  e.method = "wald";
  return e;
}

}  // namespace

std::vector<double> band_degrees_of_freedom(const SpectralBands& bands, double dof) {
  std::vector<double> nu;
  for (double w : bands.width) nu.push_back(dof * w / 0.01);
  return nu;
}

std::vector<double> jonswap_band_averages(const JonswapParameters& p, const SpectralBands& bands) {
  Likelihood l;
  l.sigma_a = p.sigma_a, l.sigma_b = p.sigma_b;
  for (std::size_t j = 0; j < bands.centre.size(); ++j) l.bands.push_back(make_band(bands, j));
  std::vector<double> out(bands.centre.size());
  l.for_each_log_mean(std::log(p.hs), std::log(p.tp), std::log(p.gamma),
                      [&](std::size_t j, double log_s) { out[j] = std::exp(log_s); });
  return out;
}

double peak_band_period(const std::vector<double>& density, const SpectralBands& bands) {
  std::size_t best = 0;
  for (std::size_t j = 0; j < density.size(); ++j) {
    if (density[j] > density[best] || std::isnan(density[best])) best = j;
  }
  return 1.0 / bands.centre[best];
}

BuoyFit fit_buoy_spectrum(const std::vector<double>& density, const SpectralBands& bands,
                          const BuoyFitOptions& options) {
  require(options.dof > 0 && std::isfinite(options.dof), "--dof", "finite and > 0", options.dof);
  require(options.quantum > 0 && std::isfinite(options.quantum), "quantum", "finite and > 0",
          options.quantum);
  if (density.size() != bands.centre.size()) {
    throw InvalidInput(fmt::format("a spectrum of {} values on {} bands", density.size(),
                                   bands.centre.size()));
  }
  const auto nu = band_degrees_of_freedom(bands, options.dof);
  Likelihood all;  // every band with a value
  all.sigma_a = options.sigma_a, all.sigma_b = options.sigma_b;
  std::vector<std::size_t> index;  // the bands used (not "MM")
  double m0 = 0;
  BuoyFit fit;
  for (std::size_t j = 0; j < density.size(); ++j) {
    if (std::isnan(density[j])) continue;
    require(density[j] >= 0, "spectral density", "≥ 0", density[j]);
    Band b = make_band(bands, j);
    b.a = 0.5 * nu[j];
    b.value = density[j];
    b.censored = density[j] < kExactQuanta * options.quantum;
    b.lo = std::max(0.0, density[j] - 0.5 * options.quantum);
    b.hi = density[j] + 0.5 * options.quantum;
    all.bands.push_back(b);
    index.push_back(j);
    m0 += density[j] * bands.width[j];
  }
  fit.bands_used = int(index.size());
  if (index.size() < 6) {
    throw InvalidInput(fmt::format("the spectrum has {} bands with values; the fit needs 6 or more",
                                   index.size()));
  }
  if (!(m0 > 0)) throw InvalidInput("the spectrum holds no energy (every band is 0)");

  // Starts: Hs from the moments, γ = 2, Tp at each of the two largest local maxima of the
  // measured spectrum (3-band running mean): on a bimodal hour the likelihood has a minimum
  // near each system, and the better one is kept.
  std::vector<std::pair<double, double>> maxima;  // (smoothed value, f)
  for (std::size_t k = 0; k < index.size(); ++k) {
    auto sm = [&](std::size_t q) {
      double s = 0;
      int n = 0;
      for (std::size_t r = q == 0 ? 0 : q - 1; r <= std::min(q + 1, index.size() - 1); ++r) {
        s += density[index[r]], ++n;
      }
      return s / n;
    };
    const double here = sm(k);
    if ((k == 0 || here >= sm(k - 1)) && (k + 1 == index.size() || here >= sm(k + 1)) && here > 0) {
      maxima.push_back({here, bands.centre[index[k]]});
    }
  }
  std::sort(maxima.rbegin(), maxima.rend());
  // The likelihood's window: bands from half the measured peak frequency up. Below x = f/fp =
  // 0.5 JONSWAP's front e^(−5/4 x⁻⁴) is under e^(−20) (its density < 1e-7 of the peak's), so
  // under the model any energy there — a swell, a noise floor — is all but impossible, and a
  // single 0.011 m²/Hz at 0.033 Hz would outweigh the whole wind sea (its term ν/2·Ŝ/S̄ reaches
  // e^(300) and more): the maximum-likelihood JONSWAP would then describe that band, not the
  // sea. Those bands are not dropped silently: the second-peak check reads them, and
  // bands_below_window counts them.
  fit.window_low = 0.5 * maxima.front().second;
  Likelihood window;
  window.sigma_a = options.sigma_a, window.sigma_b = options.sigma_b;
  for (std::size_t k = 0; k < index.size(); ++k) {
    if (bands.centre[index[k]] >= fit.window_low) {
      window.bands.push_back(all.bands[k]);
      fit.censored_bands += all.bands[k].censored;
    } else {
      ++fit.bands_below_window;
    }
  }
  if (window.bands.size() < 6) {
    throw InvalidInput(fmt::format(
        "only {} bands lie from half the peak frequency ({:.4g} Hz) up; the fit needs 6 or more",
        window.bands.size(), fit.window_low));
  }
  if (maxima.size() > 2) maxima.resize(2);
  Optimum best;
  for (const auto& [value, f] : maxima) {
    if (f < fit.window_low) continue;
    const Eigen::Vector3d start(std::log(4 * std::sqrt(m0)), std::log(1 / f), 1.0);
    Optimum o = optimize<3>(window, start, -1);
    if (o.cost < best.cost) best = o;
  }
  if (!(best.cost < HUGE_VAL)) {
    throw NumericalError("the buoy fit found no point where the likelihood can be evaluated");
  }
  const Eigen::Vector3d& phi = best.phi;
  const std::array<double, 3> theta = {std::exp(phi[0]), std::exp(phi[1]), 1 + phi[2] * phi[2]};
  fit.negative_log_likelihood = best.cost;
  fit.iterations = best.iterations;
  fit.converged = best.converged;
  fit.report = best.report;

  // Standard errors from the observed information in (log Hs, log Tp, log γ).
  const Eigen::Vector3d psi(phi[0], phi[1], std::log(theta[2]));
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Constant(HUGE_VAL);
  try {
    const Eigen::Matrix3d h = observed_information(window, psi);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(h);
    if (eigen.eigenvalues().minCoeff() > 1e-12 * eigen.eigenvalues().maxCoeff()) {
      covariance = h.inverse();
    }
  } catch (const NumericalError&) {
  }
  // A fitted peak outside the measured bands: only its flank is seen.
  const double fp = 1 / theta[1];
  const bool peak_inside = fp >= std::max(fit.window_low, bands.low_edge(index.front())) &&
                           fp <= bands.high_edge(index.back());

  std::vector<double> log_mean(all.bands.size()), window_log_mean(window.bands.size());
  all.for_each_log_mean(psi[0], psi[1], psi[2], [&](std::size_t k, double v) { log_mean[k] = v; });
  window.for_each_log_mean(psi[0], psi[1], psi[2],
                           [&](std::size_t k, double v) { window_log_mean[k] = v; });
  fit.misfit = misfit(window, window_log_mean, all, index, log_mean, bands, density, theta[1],
                      options.quantum, psi, covariance);
  if (options.quasi_likelihood) fit.dispersion = std::max(1.0, fit.misfit.dispersion);
  std::array<Estimate, 3> e;
  for (int i = 0; i < 3; ++i) {
    const double se_t = std::sqrt(fit.dispersion * covariance(i, i));
    e[i] = wald(theta[i], theta[i] * se_t);
    if (!std::isfinite(se_t)) {
      e[i].calibrated = false;
      e[i].reason = "the observed information is singular: these bands do not determine Hs, Tp and γ";
      continue;
    }
    if (!options.intervals) continue;
    const Profiler profiler{window, phi, best.cost, kZ975 * std::sqrt(fit.dispersion)};
    const double t_hat = Profiler::t_of(i, phi);
    const double reach = std::max(40 * se_t, 3.0);
    const double t_min = i == 2 ? 0.0 : t_hat - reach;
    const double t_max = i == 2 ? std::max(std::log(1e4), t_hat + reach) : t_hat + reach;
    const auto low = profiler.find(i, -1, se_t, t_min, t_max);
    const auto high = profiler.find(i, +1, se_t, t_min, t_max);
    e[i].method = fit.dispersion > 1
                      ? fmt::format("profile-likelihood, quasi (φ = {:.2f})", fit.dispersion)
                      : std::string("profile-likelihood");
    e[i].ci95_low = low.boundary ? 1.0 : std::exp(low.t);
    e[i].ci95_high = std::exp(high.t);
    if ((!low.found && !low.boundary) || !high.found) {
      e[i].calibrated = false;
      e[i].reason = fmt::format(
          "the profile likelihood does not fall by {:.3g} within the search range: the bands do "
          "not bound this parameter", 0.5 * kZ975 * kZ975 * fit.dispersion);
    }
  }
  for (auto& estimate : e) {
    if (!estimate.calibrated) continue;
    if (!peak_inside) {
      estimate.calibrated = false;
      estimate.reason = fmt::format("the fitted peak ({:.4g} Hz) lies outside the bands", fp);
    } else if (fit.misfit.flagged) {
      // The intervals are about a JONSWAP that does not describe this hour: their 95 % holds for
      // data drawn from the family (calibrated on such in buoy_fit_test), not for this hour.
      estimate.calibrated = false;
      estimate.reason = "one JONSWAP does not describe this hour: " + fit.misfit.reason;
    }
  }
  fit.hs = e[0], fit.tp = e[1], fit.gamma = e[2];
  return fit;
}

}  // namespace swell::validation
