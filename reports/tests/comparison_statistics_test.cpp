// swell::reports statistics against values computed independently with scipy and numpy.
//
// Source of every Mann–Whitney literal: scipy 1.10.1 (Debian python3-scipy 1.10.1-2, numpy
// 1.24.2), scipy.stats.mannwhitneyu(a, b, alternative='two-sided', method='asymptotic',
// use_continuity=True); its .statistic is U1 (U of a) and its .pvalue the p-value. scipy 1.10
// does not return z, so the expected z is scipy.stats.norm.isf(pvalue / 2): the z whose
// two-sided p is scipy's, which does not depend on how we compute z.
#include "swell/reports/comparison_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "swell/reference/errors.hpp"

namespace swell::reports {
namespace {

struct ScipyCase {
  const char* name;
  std::vector<double> a;
  std::vector<double> b;
  double u1;  // scipy .statistic
  double p;   // scipy .pvalue
  double z;   // scipy.stats.norm.isf(p / 2)
  bool ties;
};

// |actual − expected| ≤ rel·|expected| (absolute rel when expected is 0).
void expect_relative(double actual, double expected, double rel, const char* what) {
  const double scale = expected == 0.0 ? 1.0 : std::abs(expected);
  EXPECT_LE(std::abs(actual - expected), rel * scale)
      << what << ": got " << actual << ", expected " << expected;
}

const std::vector<ScipyCase>& scipy_cases() {
  static const std::vector<ScipyCase> cases = {
      {"no ties, 9 vs 9, b shifted up",
       {1.1, 2.3, 3.7, 4.2, 5.9, 6.4, 7.8, 8.5, 9.6},
       {3.2, 4.9, 5.1, 6.6, 7.3, 8.9, 9.9, 10.4, 11.7},
       24.0, 0.1577043874630777, 1.4128345142027126, false},
      {"ties within and across samples, 10 vs 9",
       {1, 2, 2, 3, 3, 3, 4, 5, 6, 7},
       {2, 3, 4, 4, 5, 5, 6, 8, 9},
       27.0, 0.14887829706945738, 1.443504886140518, true},
      {"unequal sizes, 5 vs 12",
       {0.52, 1.37, 2.91, 0.08, 1.84},
       {1.12, 2.44, 3.05, 3.71, 0.96, 2.87, 4.13, 3.39, 1.58, 2.20, 4.66, 3.93},
       11.0, 0.05116763051343237, 1.9500712237705005, false},
      {"identical samples, 5 vs 5",
       {1.5, 2.5, 3.5, 4.5, 5.5},
       {1.5, 2.5, 3.5, 4.5, 5.5},
       12.5, 1.0, 0.0, true},
      {"completely separated, 9 vs 9",
       {1, 2, 3, 4, 5, 6, 7, 8, 9},
       {10, 11, 12, 13, 14, 15, 16, 17, 18},
       0.0, 0.00041229480206169127, 3.5320862855067836, false},
  };
  return cases;
}

TEST(MannWhitneyU, MatchesScipyAsymptoticWithContinuity) {
  for (const ScipyCase& c : scipy_cases()) {
    SCOPED_TRACE(c.name);
    const MannWhitney r = mann_whitney_u(c.a, c.b);
    const double n1n2 = static_cast<double>(c.a.size() * c.b.size());
    EXPECT_EQ(r.n1, static_cast<int>(c.a.size()));
    EXPECT_EQ(r.n2, static_cast<int>(c.b.size()));
    EXPECT_EQ(r.ties, c.ties);
    expect_relative(r.u1, c.u1, 1e-12, "U1");
    expect_relative(r.u2, n1n2 - c.u1, 1e-12, "U2");
    expect_relative(r.p_value, c.p, 1e-9, "p");
    // Where p = 1 the p-value was clipped and z (≤ 0) is not recoverable from it.
    if (c.p < 1.0) expect_relative(r.z, c.z, 1e-9, "z");
  }
}

TEST(MannWhitneyU, SwappingTheSamplesSwapsUAndKeepsP) {
  // scipy gives U1 = n1·n2 − U1 and the same p for (b, a): e.g. 57 and 0.1577043874630777.
  for (const ScipyCase& c : scipy_cases()) {
    SCOPED_TRACE(c.name);
    const MannWhitney forward = mann_whitney_u(c.a, c.b);
    const MannWhitney reverse = mann_whitney_u(c.b, c.a);
    EXPECT_EQ(reverse.u1, forward.u2);
    EXPECT_EQ(reverse.u2, forward.u1);
    EXPECT_EQ(reverse.p_value, forward.p_value);
  }
}

TEST(MannWhitneyU, AllValuesEqualGivesPOne) {
  // σ = 0. scipy 1.10.1 on ([4, 4, 4], [4, 4]): statistic 3.0, pvalue 1.0.
  const std::vector<double> a = {4.0, 4.0, 4.0};
  const std::vector<double> b = {4.0, 4.0};
  const MannWhitney r = mann_whitney_u(a, b);
  EXPECT_EQ(r.u1, 3.0);
  EXPECT_EQ(r.u2, 3.0);
  EXPECT_EQ(r.p_value, 1.0);
  EXPECT_EQ(r.z, 0.0);
  EXPECT_TRUE(r.ties);
}

TEST(MannWhitneyU, RejectsEmptyAndNonFiniteSamples) {
  const std::vector<double> good = {1.0, 2.0, 3.0};
  const std::vector<double> empty;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> with_nan = {1.0, nan};
  const std::vector<double> with_inf = {-inf, 2.0};
  EXPECT_THROW(mann_whitney_u(empty, good), InvalidInput);
  EXPECT_THROW(mann_whitney_u(good, empty), InvalidInput);
  EXPECT_THROW(mann_whitney_u(with_nan, good), InvalidInput);
  EXPECT_THROW(mann_whitney_u(good, with_inf), InvalidInput);
  try {
    mann_whitney_u(good, with_nan);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("sample b[1] must be finite"), std::string::npos)
        << e.what();
  }
}

// numpy 1.24.2 numpy.percentile(x, [25, 50, 75]) (default method 'linear').
TEST(Quartiles, MatchNumpyPercentileLinear) {
  const Quartiles four = quartiles({1, 2, 3, 4});  // → [1.75, 2.5, 3.25]
  EXPECT_DOUBLE_EQ(four.q1, 1.75);
  EXPECT_DOUBLE_EQ(four.median, 2.5);
  EXPECT_DOUBLE_EQ(four.q3, 3.25);

  const Quartiles unsorted = quartiles({7.0, 1.0, 3.0, 10.0, 4.0});  // → [3, 4, 7]
  EXPECT_DOUBLE_EQ(unsorted.q1, 3.0);
  EXPECT_DOUBLE_EQ(unsorted.median, 4.0);
  EXPECT_DOUBLE_EQ(unsorted.q3, 7.0);

  const Quartiles two = quartiles({3.0, 1.0});  // → [1.5, 2, 2.5]
  EXPECT_DOUBLE_EQ(two.q1, 1.5);
  EXPECT_DOUBLE_EQ(two.median, 2.0);
  EXPECT_DOUBLE_EQ(two.q3, 2.5);

  const Quartiles one = quartiles({5.0});  // → [5, 5, 5]
  EXPECT_DOUBLE_EQ(one.q1, 5.0);
  EXPECT_DOUBLE_EQ(one.median, 5.0);
  EXPECT_DOUBLE_EQ(one.q3, 5.0);
}

TEST(Median, MatchesNumpyMedian) {
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(median({7.0, 1.0, 3.0, 10.0, 4.0}), 4.0);
}

TEST(Quartiles, RejectEmptyAndNonFinite) {
  EXPECT_THROW(median({}), InvalidInput);
  EXPECT_THROW(quartiles({}), InvalidInput);
  EXPECT_THROW(median({1.0, std::numeric_limits<double>::quiet_NaN()}), InvalidInput);
  EXPECT_THROW(quartiles({std::numeric_limits<double>::infinity()}), InvalidInput);
}

// scipy 1.10.1 scipy.stats.gmean: [2, 8] → 4.0; [1.5, 2.0, 7.25, 0.3] → 1.5982515305448513.
TEST(GeometricMean, MatchesScipyGmean) {
  const std::vector<double> two = {2.0, 8.0};
  EXPECT_DOUBLE_EQ(geometric_mean(two), 4.0);
  const std::vector<double> four = {1.5, 2.0, 7.25, 0.3};
  expect_relative(geometric_mean(four), 1.5982515305448513, 1e-14, "gmean");
}

TEST(GeometricMean, RejectsEmptyAndNonPositive) {
  const std::vector<double> empty;
  const std::vector<double> with_zero = {2.0, 0.0};
  const std::vector<double> with_negative = {-1.0, 4.0};
  const std::vector<double> with_nan = {std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(geometric_mean(empty), InvalidInput);
  EXPECT_THROW(geometric_mean(with_zero), InvalidInput);
  EXPECT_THROW(geometric_mean(with_negative), InvalidInput);
  EXPECT_THROW(geometric_mean(with_nan), InvalidInput);
}

}  // namespace
}  // namespace swell::reports
