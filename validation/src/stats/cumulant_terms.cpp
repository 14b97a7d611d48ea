#include "cumulant_terms.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <string>

#include "swell/reference/errors.hpp"

namespace swell::validation::stats::detail {

namespace {
// A double's binary exponents, subnormals included (std::ilogb's range for finite x ≠ 0).
constexpr int kLowestExponent = std::numeric_limits<double>::min_exponent - std::numeric_limits<double>::digits;
constexpr int kHighestExponent = std::numeric_limits<double>::max_exponent - 1;

// std::ilogb(x) for finite x ≠ 0: read from the bits where x is normal (it is taken twice per
// value), by the library for subnormals.
inline int binary_exponent(double x) {
  const int biased = int((std::bit_cast<std::uint64_t>(x) >> 52) & 0x7ff);
  return biased != 0 ? biased - 1023 : std::ilogb(x);
}
}  // namespace

void CumulantTerms::assign(std::span<const double> values, bool pairs) {
  pairs_ = pairs;
  largest_ = 0;
  groups_.clear();
  std::vector<std::size_t> count(std::size_t(kHighestExponent - kLowestExponent + 1), 0);
  std::size_t nonzero = 0;
  for (double v : values) {
    if (!std::isfinite(v)) throw NumericalError("saddlepoint law: a coefficient is not finite");
    if (v == 0) continue;  // −log(1 − 0 s) = 0
    ++count[std::size_t(binary_exponent(v) - kLowestExponent)];
    ++nonzero;
    largest_ = std::max(largest_, std::abs(v));
  }
  // Groups by exponent, largest first; each value at its group's next place.
  std::vector<std::size_t> next(count.size(), 0);
  std::size_t end = 0;
  for (int e = kHighestExponent; e >= kLowestExponent; --e) {
    const std::size_t i = std::size_t(e - kLowestExponent);
    if (count[i] == 0) continue;
    next[i] = end;
    end += count[i];
    Group group;
    group.exponent = e;
    group.end = end;
    groups_.push_back(group);
  }
  values_.resize(nonzero);
  for (double v : values) {
    if (v != 0) values_[next[std::size_t(binary_exponent(v) - kLowestExponent)]++] = v;
  }
  std::size_t begin = 0;
  for (Group& group : groups_) {
    // c / 2^(e + 1) in [1/2, 1) in magnitude: exact, by a power of two (ldexp where 2^−(e+1)
    // itself is out of range).
    const double factor = std::ldexp(1.0, -(group.exponent + 1));
    const bool exact_factor = std::isfinite(factor) && factor >= std::numeric_limits<double>::min();
    for (std::size_t i = begin; i < group.end; ++i) {
      const double x = exact_factor ? values_[i] * factor : std::ldexp(values_[i], -(group.exponent + 1));
      double power = x;
      for (int k = 0; k < kPowers; ++k, power *= x) {
        // w and −w together: the odd powers cancel, the even ones count twice.
        if (pairs_) group.powers[std::size_t(k)] += k % 2 == 1 ? 2 * power : 0.0;
        else group.powers[std::size_t(k)] += power;
      }
    }
    begin = group.end;
  }
}

std::size_t CumulantTerms::exact_groups(double s) const {
  const double magnitude = std::abs(s);
  std::size_t g = 0;
  while (g < groups_.size() && !(std::ldexp(magnitude, groups_[g].exponent + 1) <= 0x1p-9)) ++g;
  return g;
}

// {K, K', K''} over the groups from `exact` on, by their series, smallest group first: with
// t = s 2^(e+1) and r_k the group's power sums, K = Σ t^k r_k / k, K' = 2^(e+1) Σ t^(k−1) r_k and
// K'' = 2^(2e+2) Σ (k − 1) t^(k−2) r_k.
std::array<double, 3> CumulantTerms::series_sums(std::size_t exact, double s) const {
  double cumulant = 0, first = 0, second = 0;
  for (std::size_t g = groups_.size(); g-- > exact;) {
    const auto& r = groups_[g].powers;
    const double scale = std::ldexp(1.0, groups_[g].exponent + 1), t = s == 0 ? 0.0 : s * scale;
    double k0 = r[kPowers - 1] / kPowers, d1 = r[kPowers - 1], d2 = double(kPowers - 1) * r[kPowers - 1];
    for (int k = kPowers - 1; k >= 1; --k) {
      k0 = r[std::size_t(k - 1)] / k + t * k0;
      d1 = r[std::size_t(k - 1)] + t * d1;
      if (k >= 2) d2 = double(k - 1) * r[std::size_t(k - 1)] + t * d2;
    }
    cumulant += t * k0;
    first += scale * d1;
    second += scale * scale * d2;
  }
  return {cumulant, first, second};
}

std::array<double, 2> CumulantTerms::derivatives(double s) const {
  const std::size_t exact = exact_groups(s);
  const std::span<const double> terms(values_.data(), exact == 0 ? 0 : groups_[exact - 1].end);
  std::array<double, 2> sums;
  if (pairs_) {
    // w/(1 − a) − w/(1 + a) = 2 w a/(1 − a²) and w²/(1 − a)² + w²/(1 + a)² = 2 w² (1 + a²)/(1 − a²)²,
    // a = w s: one division per pair.
    sums = sum_pairs_of_terms(terms, [s](double w) {
      const double a = w * s, q = 1 / ((1 - a) * (1 + a));
      return std::array<double, 2>{w * a * q, w * w * (1 + a * a) * q * q};
    });
    sums[0] *= 2, sums[1] *= 2;
  } else {
    sums = sum_pairs_of_terms(terms, [s](double c) {
      const double t = c / (1 - c * s);
      return std::array<double, 2>{t, t * t};
    });
  }
  const auto series = series_sums(exact, s);
  return {sums[0] + series[1], sums[1] + series[2]};
}

std::array<double, 2> CumulantTerms::cumulant_and_curvature(double s) const {
  const std::size_t exact = exact_groups(s);
  const std::span<const double> terms(values_.data(), exact == 0 ? 0 : groups_[exact - 1].end);
  std::array<double, 2> sums;
  if (pairs_) {
    sums = sum_pairs_of_terms(terms, [s](double w) {
      // log(1 − a²), as (1 − a)(1 + a) where a² is near 1 (1 − a is exact there).
      const double a = w * s, q = 1 / ((1 - a) * (1 + a));
      return std::array<double, 2>{std::abs(a) < 0.5 ? -log1p_near_zero(-a * a) : -std::log((1 - a) * (1 + a)),
                                   2 * w * w * (1 + a * a) * q * q};
    });
  } else {
    sums = sum_pairs_of_terms(terms, [s](double c) {
      const double t = c / (1 - c * s);
      return std::array<double, 2>{-log1p_near_zero(-c * s), t * t};
    });
  }
  const auto series = series_sums(exact, s);
  return {sums[0] + series[0], sums[1] + series[2]};
}

}  // namespace swell::validation::stats::detail
