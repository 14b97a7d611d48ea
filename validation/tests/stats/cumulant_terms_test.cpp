// stats/cumulant_terms.hpp: the saddlepoint laws' sums K(s), K'(s), K''(s) over coefficients,
// taken term by term only where |c s| may exceed 2⁻⁹ and through power sums elsewhere, against
// the same sums taken term by term in long double at every s the laws visit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "stats/cumulant_terms.hpp"
#include "swell/reference/errors.hpp"

namespace {

using swell::validation::stats::detail::CumulantTerms;

struct Direct {
  long double cumulant = 0, first = 0, second = 0, first_magnitude = 0;
};

// The sums over the coefficients c (each w standing for ±w with `pairs`), term by term.
Direct direct_sums(const std::vector<double>& values, bool pairs, double s) {
  Direct out;
  auto add = [&](long double c) {
    const long double x = c * (long double)s, t = c / (1 - x);
    out.cumulant -= std::log1p(-x);
    out.first += t;
    out.first_magnitude += std::abs(t);
    out.second += t * t;
  };
  for (double v : values) {
    add(v);
    if (pairs) add(-(long double)v);
  }
  return out;
}

void expect_sums_match(const std::vector<double>& values, bool pairs, double s, const char* what) {
  const CumulantTerms terms(values, pairs);
  const Direct d = direct_sums(values, pairs, s);
  const auto [first, second] = terms.derivatives(s);
  const auto [cumulant, curvature] = terms.cumulant_and_curvature(s);
  // 1e-13 of the terms' magnitudes: the sums' own rounding over up to 10⁴ terms, far above the
  // series' truncation (2⁻⁷⁰) and far below a wrong series coefficient (a whole term's size).
  EXPECT_NEAR(first, double(d.first), 1e-13 * double(d.first_magnitude)) << what << ", s = " << s;
  EXPECT_NEAR(second / double(d.second), 1, 1e-13) << what << ", s = " << s;
  EXPECT_NEAR(curvature / double(d.second), 1, 1e-13) << what << ", s = " << s;
  EXPECT_NEAR(cumulant, double(d.cumulant), 1e-13 * std::max(1.0, std::abs(double(d.cumulant)))) << what << ", s = " << s;
}

TEST(CumulantTerms, GroupedSumsAreTheDirectSumsAcrossTheDomain) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  // A spectrum's half plane: a few large weights over many decades of small ones, a subnormal.
  std::vector<double> weights = {1.0, 0.75, 0.5, 4e-310};
  for (int i = 0; i < 6000; ++i) weights.push_back(std::pow(10.0, -14 * uniform(rng)));
  const double largest = 1.0;
  for (double f : {-1e8, -1e4, -30.0, -1.0, -1e-3, -1e-9, 0.0, 1e-9, 1e-3, 0.3, 0.9, 0.999, 0.999999}) {
    expect_sums_match(weights, false, f / largest, "positive weights");
    if (std::abs(f) < 1) expect_sums_match(weights, true, f / largest, "pairs ±w");
  }
  // Coefficients of both signs (a ratio's law): K is defined on (1/min c, 1/max c).
  std::vector<double> mixed;
  for (double w : weights) mixed.push_back(uniform(rng) < 0.3 ? -0.5 * w : w);
  for (double f : {-1.9, -0.5, -1e-4, 0.0, 1e-4, 0.5, 0.99}) expect_sums_match(mixed, false, f, "signed coefficients");
  // Equal weights (one group), and weights all far below 1 (the groups' scale is no longer 1).
  expect_sums_match(std::vector<double>(100, 3e-5), false, 0.9 / 3e-5, "equal weights");
  std::vector<double> small;
  for (int i = 0; i < 500; ++i) small.push_back(1e-150 * (1 + uniform(rng)));
  expect_sums_match(small, false, -1e3 / 2e-150, "weights of 1e-150");
  for (double f : {-0.99, -0.5, 0.2, 0.99}) expect_sums_match(small, true, f / 2e-150, "pairs of 1e-150");
}

// A law rebuilt in the arrays of the last one (hs_steady's, frame after frame) is the law built
// afresh: nothing of the earlier values (more groups, larger values) remains.
TEST(CumulantTerms, AssignedAgainIsTheLawBuiltAfresh) {
  std::vector<double> wide, narrow;
  for (int i = 0; i < 3000; ++i) wide.push_back(std::pow(10.0, -0.01 * i));
  for (int i = 0; i < 500; ++i) narrow.push_back(0.2 + 1e-4 * i);
  CumulantTerms reused(wide, false);
  reused.assign(narrow, true);
  const CumulantTerms fresh(narrow, true);
  EXPECT_EQ(reused.size(), fresh.size());
  EXPECT_EQ(reused.largest(), fresh.largest());
  for (double s : {-4.0, -0.3, 0.0, 1e-5, 2.0, 4.0}) {
    EXPECT_EQ(reused.derivatives(s), fresh.derivatives(s)) << "s = " << s;
    EXPECT_EQ(reused.cumulant_and_curvature(s), fresh.cumulant_and_curvature(s)) << "s = " << s;
  }
}

TEST(CumulantTerms, RefusesCoefficientsThatAreNotFinite) {
  const std::vector<double> not_a_number = {1.0, NAN}, infinite = {INFINITY}, with_zeros = {0.0, 2.0, 0.0};
  EXPECT_THROW(CumulantTerms(not_a_number, false), swell::NumericalError);
  EXPECT_THROW(CumulantTerms(infinite, true), swell::NumericalError);
  const CumulantTerms zeros(with_zeros, false);  // −log(1 − 0 s) = 0: dropped
  EXPECT_EQ(zeros.size(), 1u);
  EXPECT_EQ(zeros.largest(), 2.0);
}

}  // namespace
