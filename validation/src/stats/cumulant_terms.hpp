#pragma once
// The sums over coefficients that the saddlepoint laws of statistics.hpp make at every step of
// their Newton solves: K(s) = −Σ log(1 − c s) of S = Σ c E (E independent Exp(1)) and its
// derivatives.
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace swell::validation::stats::detail {

// Σ over the values of f(v), in four interleaved partial sums added at the end ((s0 + s1) +
// (s2 + s3)): the same double on any machine, and loops the compiler turns into vector code
// (one running sum chains every addition on the last: the saddlepoint laws' loops over 10⁶
// weights were bound by it). `f` returns the terms of two sums at once.
template <typename Terms>
std::array<double, 2> sum_pairs_of_terms(std::span<const double> values, const Terms& f) {
  double first[4] = {0, 0, 0, 0}, second[4] = {0, 0, 0, 0};
  const std::size_t n = values.size(), whole = n - n % 4;
  for (std::size_t i = 0; i < whole; i += 4) {
    for (int lane = 0; lane < 4; ++lane) {
      const auto [a, b] = f(values[i + std::size_t(lane)]);
      first[lane] += a;
      second[lane] += b;
    }
  }
  for (std::size_t i = whole; i < n; ++i) {
    const auto [a, b] = f(values[i]);
    first[i - whole] += a;
    second[i - whole] += b;
  }
  return {(first[0] + first[1]) + (first[2] + first[3]), (second[0] + second[1]) + (second[2] + second[3])};
}

// log(1 + x): its Taylor series where |x| ≤ 2⁻⁸ (eight terms: the ninth is below 10⁻²⁰ of the
// sum), std::log1p elsewhere: the series costs a fraction of the library call.
inline double log1p_near_zero(double x) {
  if (!(std::abs(x) <= 0x1p-8)) return std::log1p(x);
  return x * (1 + x * (-1.0 / 2 + x * (1.0 / 3 + x * (-1.0 / 4 + x * (1.0 / 5 + x * (-1.0 / 6 + x * (1.0 / 7 + x * (-1.0 / 8))))))));
}

// K(s) = −Σ log(1 − c s), K'(s) = Σ c/(1 − c s) and K''(s) = Σ c²/(1 − c s)² over nonzero finite
// coefficients c of either sign; with `pairs`, each value w > 0 stands for the two
// coefficients w and −w (S = Σ w (E − E')), whose terms are taken together.
//
// Each term is analytic in x = c s. Where |x| ≤ 2⁻⁹ its Taylor series to x⁸ leaves less than
// 2⁻⁷⁰ of the term (x⁸/(1 − x) against 1, in K''), far below a double's rounding, and summed
// over those c it is a polynomial in s whose coefficients are the power sums Σ c^k. So the
// coefficients are grouped by binary exponent, largest first, each group keeping its power
// sums; a sum at s takes term by term the groups where some |c s| may exceed 2⁻⁹, and the
// others through their power sums. The gate's laws run over a half plane (10⁵ to 10⁷
// coefficients across many decades, the spectrum's tail) and visit s of order 1/max |c|, where
// only the few thousand largest coefficients are summed one by one.
class CumulantTerms {
 public:
  CumulantTerms() = default;
  CumulantTerms(std::span<const double> values, bool pairs) { assign(values, pairs); }
  // These values in place of the last ones, in the arrays they held: a law rebuilt frame after
  // frame (statistics.hs_steady) costs no fresh pages.
  void assign(std::span<const double> values, bool pairs);
  std::size_t size() const { return values_.size(); }
  double largest() const { return largest_; }  // max |c|
  // {K'(s), K''(s)}
  std::array<double, 2> derivatives(double s) const;
  // {K(s), K''(s)}
  std::array<double, 2> cumulant_and_curvature(double s) const;

 private:
  static constexpr int kPowers = 8;
  struct Group {
    int exponent = 0;     // every |c| of the group is in [2^exponent, 2^(exponent + 1))
    std::size_t end = 0;  // its values are values_[previous group's end, end)
    std::array<double, kPowers> powers{};  // Σ (c / 2^(exponent + 1))^k, k = 1…8
  };
  // The number of leading groups summed term by term at s: those where |c s| may exceed 2⁻⁹.
  std::size_t exact_groups(double s) const;
  // {K, K', K''} over the groups from `exact` on, through their power sums.
  std::array<double, 3> series_sums(std::size_t exact, double s) const;
  std::vector<double> values_;  // by group, largest first; in their given order within one
  std::vector<Group> groups_;
  double largest_ = 0;
  bool pairs_ = false;
};

}  // namespace swell::validation::stats::detail
