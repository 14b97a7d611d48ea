#pragma once
// The sampling distributions the ocean checks judge by (docs/checks.md). A right surface's
// periodogram ordinates over a half plane are independent exponentials, so most statistics
// are weighted sums of exponentials or functions of them.
#include <memory>
#include <vector>

namespace swell::validation::stats {

namespace detail {
class CumulantTerms;  // stats/cumulant_terms.hpp
}

// Standard normal: P(|Z| ≥ |z|).
double normal_two_sided_p(double z);
// χ² with `dof` degrees of freedom: P(X ≥ x).
double chi_squared_upper_p(double x, double dof);
// Gamma(shape, scale 1): P(X ≤ x), P(X ≥ x).
double gamma_lower_p(double shape, double x);
double gamma_upper_p(double shape, double x);

// X = Σ w_i E_i with E_i ~ Exp(1) independent and w_i > 0 (a generalized χ²). Its CDF by the
// Lugannani–Rice saddlepoint approximation (Butler 2007, §1.2), whose relative error in the
// tails is O(1/n) and which is exact in the tails' exponential rate: far better than the normal
// approximation for the few dominant waves of a small grid.
class WeightedExponentialSum {
 public:
  explicit WeightedExponentialSum(std::vector<double> weights);  // zero weights are dropped
  double mean() const { return mean_; }
  double variance() const { return variance_; }
  double cdf(double x) const;       // P(X ≤ x)
  double survival(double x) const;  // P(X ≥ x)
  double two_sided_p(double x) const;  // 2 min(P(X ≤ x), P(X ≥ x)), capped at 1
  double quantile(double p) const;  // x with P(X ≤ x) = p

 private:
  // The lower (upper = false) or upper tail; Lugannani–Rice away from the mean.
  // `hint`, where given, is a saddlepoint to start Newton from (a neighbouring x's: a quantile's
  // root search evaluates the tail at x close together), and receives this x's.
  double tail(double x, bool upper, double* hint = nullptr) const;
  double lugannani_rice(double x, bool upper, double* hint = nullptr) const;
  double saddlepoint(double x, double* hint = nullptr) const;  // s with K'(s) = x
  std::shared_ptr<const detail::CumulantTerms> terms_;  // K(s) = −Σ log(1 − w s) and its derivatives
  double mean_ = 0, variance_ = 0, max_weight_ = 0;
};

// P(Σ c_i E_i ≤ 0) for E_i ~ Exp(1) independent and coefficients c_i of both signs (zero ones
// dropped): the law of a ratio of two weighted exponential sums, P(A/B ≤ r) = P(A − rB ≤ 0)
// for B > 0. Lugannani–Rice at x = 0 with K(s) = −Σ log(1 − c s) on (1/min c, 1/max c)
// (Butler 2007, §1.2; Daniels 1987 for ratios); 0 when every c > 0, 1 when every c < 0, the
// normal law within 1e-3 sd of the mean, where Lugannani–Rice is 0/0.
double mixed_exponential_sum_cdf_at_zero(const std::vector<double>& coefficients);
// P(Σ c_i E_i ≤ x): the same at any threshold x (K'(s) = x).
double mixed_exponential_sum_cdf(const std::vector<double>& coefficients, double x);
// P(Σ w_i (E_i − E'_i) ≤ x) for weights w_i > 0 (finite), E and E' independent Exp(1): the
// law above of the coefficients w_1, −w_1, w_2, −w_2, …, each pair's terms taken together
// (one division and one logarithm per pair; equal to it to rounding, ~10⁻¹⁴ relative).
double exponential_difference_sum_cdf(const std::vector<double>& weights, double x);

// Anderson–Darling statistic A² of a sample against a fully specified continuous distribution,
// given the sample's CDF values u_i = F(x_i) (any order) and their logs of survival
// log(1 − u_i) (passed separately to keep precision in the upper tail).
double anderson_darling_statistic(const std::vector<double>& cdf_values,
                                  const std::vector<double>& log_survival_values);
// P(A² ≥ a) for a sample of n under the null, by Marsaglia & Marsaglia (2004), "Evaluating the
// Anderson–Darling distribution", J. Stat. Softw. 9(2): the asymptotic CDF plus their
// finite-n correction (absolute error < 2e-6 in the CDF).
double anderson_darling_p(double a2, int n);

// P(A² ≥ a) for a sample of n tested against an exponential law whose scale was estimated
// from the sample (its mean): D'Agostino & Stephens (1986), Goodness-of-Fit Techniques,
// Table 4.14, with the modified statistic A²(1 + 0.6/n).
double anderson_darling_exponential_p(double a2, int n);

// Fisher's method: −2 Σ log p_i ~ χ²(2k) for k independent uniform p-values; its p-value.
double fisher_combined_p(const std::vector<double>& p_values);

}  // namespace swell::validation::stats
