// common/sorted_by_key.hpp: its bucketed sort gives exactly std::sort's order of the (key,
// position) pairs, on keys as the gate meets them (ω and |k| of a grid, many equal) and on
// keys that defeat its buckets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/sorted_by_key.hpp"

namespace {

using swell::validation::detail::sorted_by_key;

std::vector<std::pair<double, std::size_t>> sorted_by_std_sort(const std::vector<double>& keys) {
  std::vector<std::pair<double, std::size_t>> pairs(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) pairs[i] = {keys[i], i};
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

void expect_std_sort_order(const std::vector<double>& keys, const std::string& what) {
  const auto got = sorted_by_key(keys.size(), [&](std::size_t i) { return keys[i]; });
  const auto want = sorted_by_std_sort(keys);
  ASSERT_EQ(got.size(), want.size()) << what;
  std::size_t first_difference = got.size();
  for (std::size_t i = 0; i < got.size() && first_difference == got.size(); ++i) {
    // Bit for bit: the key carried is the one given (−0 and +0 included).
    if (got[i].second != want[i].second || std::signbit(got[i].first) != std::signbit(want[i].first) ||
        !(got[i].first == want[i].first)) {
      first_difference = i;
    }
  }
  EXPECT_EQ(first_difference, got.size()) << what << ": the orders part at this rank";
}

TEST(SortedByKey, IsStdSortsOrderOnAGridsFrequencies) {
  // ω = √(g|k|) over a 512² grid's half plane in FFT order: equal |k| on every (±n, ±m) and
  // (m, n), ties broken by position.
  const int n = 512;
  std::vector<double> omegas;
  for (int row = 0; row < n; ++row) {
    for (int column = 0; column < n; ++column) {
      const int kx = column < n / 2 ? column : column - n, ky = row < n / 2 ? row : row - n;
      if (ky < 0 || (ky == 0 && kx <= 0)) continue;
      omegas.push_back(std::sqrt(9.81 * std::hypot(kx * 0.01, ky * 0.01)));
    }
  }
  expect_std_sort_order(omegas, "grid ω");
}

TEST(SortedByKey, IsStdSortsOrderOnKeysThatCrowdItsBuckets) {
  std::mt19937_64 rng(7);
  const std::size_t n = 200000;
  std::vector<double> keys(n);
  std::uniform_real_distribution<double> uniform(-3.0, 5.0);
  for (double& k : keys) k = uniform(rng);
  expect_std_sort_order(keys, "uniform, negative and positive");
  std::uniform_int_distribution<int> level(0, 30);
  for (double& k : keys) k = 0.25 * level(rng);
  expect_std_sort_order(keys, "31 levels");
  std::exponential_distribution<double> heavy(1.0);
  for (double& k : keys) k = std::exp(20 * heavy(rng));
  expect_std_sort_order(keys, "spread over hundreds of decades");
  for (double& k : keys) k = 1.0;
  keys[n / 3] = 1e300;
  expect_std_sort_order(keys, "one outlier: every other key in one bucket");
  keys.assign(n, 0.0);
  for (std::size_t i = 0; i < n; i += 2) keys[i] = -0.0;
  keys[5] = std::numeric_limits<double>::denorm_min(), keys[6] = 1.0;
  expect_std_sort_order(keys, "−0 and +0 equal, a subnormal beside them");
  for (double& k : keys) k = uniform(rng);
  keys[17] = -std::numeric_limits<double>::max(), keys[18] = std::numeric_limits<double>::max();
  expect_std_sort_order(keys, "a range past the doubles' (the scale overflows)");
  keys[18] = std::numeric_limits<double>::infinity();
  expect_std_sort_order(keys, "an infinite key");
}

TEST(SortedByKey, IsStdSortsOrderBelowTheBuckets) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> level(0, 9);
  for (std::size_t n : {0u, 1u, 2u, 1000u}) {
    std::vector<double> keys(n);
    for (double& k : keys) k = level(rng);
    expect_std_sort_order(keys, std::to_string(n) + " keys");
  }
}

}  // namespace
