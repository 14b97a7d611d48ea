#pragma once
// (key, position) pairs of positions 0 … n − 1 in ascending order: exactly what std::sort of the
// pairs gives (a stable sort by key, as the pairs are distinct), in about linear time. The
// keys are spread into n/4 buckets by their value — a monotone map, so a bucket holds a range
// of keys and equal keys share one — with a counting sort that keeps the positions ascending,
// and each bucket is then sorted on its own, a few pairs in cache. At 4096² a std::sort of the
// 8.4 × 10⁶ pairs of the analysis' half plane took over a second (docs/performance.md §6).
// The half plane's ω (checks/ocean/analysis.hpp), the power table's |k| (gate/power.cpp) and
// Anderson–Darling's sample (stats/statistics.cpp) are sorted here. Keys that are not all
// finite, or too few to gain from buckets, go through std::sort itself.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace swell::validation::detail {

template <typename KeyOf>
std::vector<std::pair<double, std::size_t>> sorted_by_key(std::size_t n, const KeyOf& key_of) {
  std::vector<std::pair<double, std::size_t>> sorted;
  double low = INFINITY, high = -INFINITY;
  bool finite = true;
  for (std::size_t i = 0; i < n; ++i) {
    const double key = key_of(i);
    finite = finite && std::isfinite(key);
    low = std::min(low, key);
    high = std::max(high, key);
  }
  const std::size_t buckets = n / 4;
  const double scale = double(buckets) / (high - low);
  // Below 2¹⁶ pairs std::sort is a few milliseconds; a range that overflows the scale (keys
  // spanning more than the doubles' range over n/4) sorts there too, and so many pairs that a
  // bucket's start outgrows 32 bits.
  if (n < (std::size_t(1) << 16) || n > UINT32_MAX || !finite || !(high > low) || !std::isfinite(scale)) {
    sorted.resize(n);
    for (std::size_t i = 0; i < n; ++i) sorted[i] = {key_of(i), i};
    std::sort(sorted.begin(), sorted.end());
    return sorted;
  }
  // (key − low) × scale is non-decreasing in the key (each operation rounds monotonically), so
  // a lower bucket never holds a greater key.
  const auto bucket_of = [&](double key) {
    return std::min(buckets - 1, std::size_t((key - low) * scale));
  };
  std::vector<std::uint32_t> first(buckets + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++first[bucket_of(key_of(i)) + 1];
  for (std::size_t b = 0; b < buckets; ++b) first[b + 1] += first[b];
  sorted.resize(n);
  {
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const double key = key_of(i);
      sorted[next[bucket_of(key)]++] = {key, i};
    }
  }
  for (std::size_t b = 0; b < buckets; ++b) {
    if (first[b + 1] - first[b] > 1) std::sort(sorted.begin() + first[b], sorted.begin() + first[b + 1]);
  }
  return sorted;
}

}  // namespace swell::validation::detail
