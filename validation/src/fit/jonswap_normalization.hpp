#pragma once
// JONSWAP's normalization F(γ, σa, σb) = ∫₀^∞ x⁻⁵ e^(−5/4 x⁻⁴) γ^r(x) dx, r = e^(−(x − 1)²/(2σ²)),
// and its gradient: what both JONSWAP fits divide by (jonswap_fit.cpp on surfaces, buoy_fit.cpp
// on buoy spectra; docs/fit.md §1).
namespace swell::validation::fit_detail {

struct JonswapNormalization {
  double value = 0, d_gamma = 0, d_sigma_a = 0, d_sigma_b = 0;  // F and its partial derivatives
};

// F and ∂F/∂γ, and ∂F/∂σa, ∂F/∂σb when `sigma_derivatives` (the buoy fit holds σ fixed). A
// quadrature that does not reach its tolerance throws NumericalError, which the optimizers treat
// as an infeasible point.
JonswapNormalization jonswap_normalization(double gamma, double sigma_a, double sigma_b,
                                           bool sigma_derivatives = true);

}  // namespace swell::validation::fit_detail
