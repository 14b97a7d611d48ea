#include "swell/reports/comparison_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <utility>

#include "swell/reference/errors.hpp"

namespace swell::reports {
namespace {

// Throws InvalidInput unless `values` is non-empty and every value finite. `what` names the
// argument in the message ("mann_whitney_u: sample a").
void require_finite_sample(std::span<const double> values, const std::string& what) {
  require(!values.empty(), what + " size", "at least 1", 0.0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      fail_requirement(what + "[" + std::to_string(i) + "]", "finite", values[i]);
    }
  }
}

// The quantile at probability p of sorted values by numpy's 'linear' method: the virtual index
// h = (n − 1)p, interpolated between x[⌊h⌋] and x[⌊h⌋ + 1]. The interpolation is written as
// numpy's _lerp writes it (from the nearer end: a + (b − a)t for t < 0.5, b − (b − a)(1 − t)
// otherwise), so the results agree with numpy.percentile to the last bit.
double linear_quantile(const std::vector<double>& sorted, double p) {
  const double h = static_cast<double>(sorted.size() - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  if (lo + 1 >= sorted.size()) return sorted.back();
  const double t = h - static_cast<double>(lo);
  const double a = sorted[lo];
  const double b = sorted[lo + 1];
  const double diff = b - a;
  return t < 0.5 ? a + diff * t : b - diff * (1.0 - t);
}

std::vector<double> sorted_finite(std::vector<double> values, const std::string& what) {
  require_finite_sample(values, what);
  std::sort(values.begin(), values.end());
  return values;
}

}  // namespace

MannWhitney mann_whitney_u(std::span<const double> a, std::span<const double> b) {
  require_finite_sample(a, "mann_whitney_u: sample a");
  require_finite_sample(b, "mann_whitney_u: sample b");

  // Pool the samples, remembering which came from a, and sort by value.
  std::vector<std::pair<double, bool>> pooled;  // (value, from a)
  pooled.reserve(a.size() + b.size());
  for (double x : a) pooled.emplace_back(x, true);
  for (double x : b) pooled.emplace_back(x, false);
  std::sort(pooled.begin(), pooled.end(),
            [](const auto& l, const auto& r) { return l.first < r.first; });

  // Midranks (scipy.stats.rankdata's default 'average'): a run of t equal values at 1-based
  // positions i+1 … i+t all get rank i + (t + 1)/2. The same runs give the tie term Σ(t³ − t).
  double rank_sum_a = 0.0;
  double tie_term = 0.0;
  bool ties = false;
  for (std::size_t i = 0; i < pooled.size();) {
    std::size_t j = i;
    while (j < pooled.size() && pooled[j].first == pooled[i].first) ++j;
    const double t = static_cast<double>(j - i);
    const double midrank = static_cast<double>(i) + (t + 1.0) / 2.0;
    for (std::size_t k = i; k < j; ++k) {
      if (pooled[k].second) rank_sum_a += midrank;
    }
    tie_term += t * t * t - t;
    ties = ties || t > 1.0;
    i = j;
  }

  const double n1 = static_cast<double>(a.size());
  const double n2 = static_cast<double>(b.size());
  const double n = n1 + n2;
  MannWhitney result{};
  result.n1 = static_cast<int>(a.size());
  result.n2 = static_cast<int>(b.size());
  result.ties = ties;
  result.u1 = rank_sum_a - n1 * (n1 + 1.0) / 2.0;
  result.u2 = n1 * n2 - result.u1;

  // scipy 1.10 _mannwhitneyu._get_mwu_z: the two-sided test takes U = max(U1, U2), whose upper
  // tail is the smaller one, and doubles it. The variance is the tie-corrected one scipy takes
  // from its reference [2] (Wikipedia, "Mann–Whitney U test"),
  // σ² = n1 n2/12 · ((n + 1) − Σ(t³ − t)/(n(n − 1))), and the continuity correction always
  // subtracts 0.5 because only the upper tail is used.
  const double u = std::max(result.u1, result.u2);
  const double mu = n1 * n2 / 2.0;
  const double variance = n1 * n2 / 12.0 * ((n + 1.0) - tie_term / (n * (n - 1.0)));
  if (!(variance > 0.0)) {
    // Every pooled value equal (or n = 1, where σ² = 0 too): no evidence either way. scipy
    // reaches p = 1 through z = −∞; we report z = 0 rather than an infinity.
    result.z = 0.0;
    result.p_value = 1.0;
    return result;
  }
  result.z = (u - mu - 0.5) / std::sqrt(variance);
  // 2·(1 − Φ(z)) = erfc(z/√2), which keeps precision in the upper tail; z < 0 (U within 0.5
  // of its mean) gives more than 1, clipped as scipy clips it.
  result.p_value = std::clamp(std::erfc(result.z / std::numbers::sqrt2), 0.0, 1.0);
  return result;
}

double median(std::vector<double> values) {
  return linear_quantile(sorted_finite(std::move(values), "median: values"), 0.5);
}

Quartiles quartiles(std::vector<double> values) {
  const std::vector<double> sorted = sorted_finite(std::move(values), "quartiles: values");
  return {linear_quantile(sorted, 0.25), linear_quantile(sorted, 0.5),
          linear_quantile(sorted, 0.75)};
}

double geometric_mean(std::span<const double> positive_values) {
  require(!positive_values.empty(), "geometric_mean: values size", "at least 1", 0.0);
  // The mean of the logs (scipy.stats.gmean), which neither overflows nor underflows the way
  // the n-th root of a product does.
  double log_sum = 0.0;
  for (std::size_t i = 0; i < positive_values.size(); ++i) {
    const double x = positive_values[i];
    if (!(std::isfinite(x) && x > 0.0)) {
      fail_requirement("geometric_mean: values[" + std::to_string(i) + "]",
                       "finite and positive", x);
    }
    log_sum += std::log(x);
  }
  return std::exp(log_sum / static_cast<double>(positive_values.size()));
}

}  // namespace swell::reports
