#include "fit/jonswap_normalization.hpp"

#include <fmt/format.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

#include "swell/reference/errors.hpp"

namespace swell::validation::fit_detail {
namespace {

// x⁻⁵ e^(−5/4 x⁻⁴), 0 where the exponential underflows (x < ~0.2).
double pm_shape(double x) {
  if (x <= 0) return 0;
  const double x4 = x * x * x * x;
  const double e = 1.25 / x4;
  return e > 745 ? 0.0 : std::exp(-e) / (x4 * x);
}

}  // namespace

// F(γ, σa, σb) and its gradient, each by its own Gauss–Kronrod quadrature of the differentiated
// integrand. Why not numeric differentiation: the likelihood's gradient must be exact to let
// the line search converge to 1e-5 of a standard error, and a finite difference of a
// quadrature carries the quadrature's error divided by the step. The analytic partials
//     ∂F/∂γ  = ∫ x⁻⁵ e^(…) r γ^(r−1) dx,
//     ∂F/∂σa = ∫_{x≤1} x⁻⁵ e^(…) γ^r log γ · r (x − 1)²/σa³ dx   (σb likewise over x > 1)
// are as cheap as F itself and accurate to the quadrature tolerance (1e-12).
//
// F = 1/5 + ∫ x⁻⁵ e^(−5/4 x⁻⁴) (γ^r − 1) dx: the Pierson–Moskowitz part in closed form
// (u = 5/4 x⁻⁴), the rest lives within a few σ of x = 1. It is integrated in d = (x − 1)/σ,
// r = e^(−d²/2), over [−12, 0] with σa and [0, 12] with σb (r < e^(−72) beyond), split at the
// kink of σ at x = 1; in d there is no cancellation in x − 1 for narrow peaks. In d:
//     F − 1/5 = Σ σ ∫ p(1 + σd) (γ^r − 1) dd,   ∂F/∂γ = Σ σ ∫ p r γ^(r−1) dd,
//     ∂F/∂σ = ∫ p γ^r log γ · r d² dd   (one side each),    p(x) = x⁻⁵ e^(−5/4 x⁻⁴).
JonswapNormalization jonswap_normalization(double gamma, double sigma_a, double sigma_b,
                                           bool sigma_derivatives) {
  const double log_gamma = std::log(gamma);
  constexpr double kTolerance = 1e-12;
  // Each piece to 1e-10 of its own L1 norm, or to 1e-13 absolute: F ≥ 0.2 for γ ≥ 1 (and
  // ~0.2 near it), so that is 5e-13 of F, and what the likelihood uses is log F and
  // ∂(log F) = ∂F/F. A piece that is tiny (a peak narrower than anything the data hold)
  // need not be resolved relative to itself.
  auto integrate = [&](auto&& f, double a, double b, const char* what) {
    double error = 0, l1 = 0;
    const double value = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        f, a, b, 12, kTolerance, &error, &l1);
    if (!(std::isfinite(value) && error <= 1e-10 * l1 + 1e-13)) {
      throw NumericalError(fmt::format(
          "JONSWAP normalization: {} for γ = {:.6g}, σa = {:.6g}, σb = {:.6g} reached only "
          "{:.3g} (L1 norm {:.3g}), not 1e-10 of it nor 1e-13",
          what, gamma, sigma_a, sigma_b, error, l1));
    }
    return value;
  };
  JonswapNormalization n{0.2, 0, 0, 0};
  for (const bool below : {true, false}) {
    const double sigma = below ? sigma_a : sigma_b;
    // x = 1 + σd stays above 0.05, where p(x) = e^(−200000)/… is 0 in double anyway.
    const double a = below ? std::max(-12.0, -0.95 / sigma) : 0.0, b = below ? 0.0 : 12.0;
    auto p = [sigma](double d) { return pm_shape(1.0 + sigma * d); };
    auto excess = [&](double d) { return p(d) * std::expm1(std::exp(-0.5 * d * d) * log_gamma); };
    auto by_gamma = [&](double d) {
      const double r = std::exp(-0.5 * d * d);
      return p(d) * r * std::exp((r - 1.0) * log_gamma);
    };
    auto by_sigma = [&](double d) {
      const double r = std::exp(-0.5 * d * d);
      return p(d) * std::exp(r * log_gamma) * log_gamma * r * d * d;
    };
    n.value += sigma * integrate(excess, a, b, "F");
    n.d_gamma += sigma * integrate(by_gamma, a, b, "∂F/∂γ");
    if (sigma_derivatives) {
      (below ? n.d_sigma_a : n.d_sigma_b) += integrate(by_sigma, a, b, "∂F/∂σ");
    }
  }
  return n;
}

}  // namespace swell::validation::fit_detail
