#pragma once
// The sample skewness m3/m2^(3/2) and excess kurtosis m4/m2² − 3 of values about a given centre,
// accumulated over one or more spans. Real is the accumulator: double for one frame (the
// statistics check), long double over every sample of many frames (a sweep's row), where
// double sums of 10⁷ and more terms would lose digits the rows print.
#include <cmath>
#include <cstddef>
#include <span>

namespace swell::validation::stats {

template <typename Real>
class SampleMoments {
 public:
  // Adds x − centre for every x (the difference taken in double, then widened).
  void add(std::span<const double> values, double centre) {
    for (const double x : values) {
      const Real d = x - centre, d2 = d * d;
      m2_ += d2;
      m3_ += d2 * d;
      m4_ += d2 * d2;
    }
    count_ += values.size();
  }
  std::size_t count() const { return count_; }
  Real variance() const { return m2_ / Real(count_); }  // about the centre
  Real skewness() const { return (m3_ / Real(count_)) / std::pow(variance(), Real(1.5)); }
  Real excess_kurtosis() const {
    const Real m2 = variance();
    return (m4_ / Real(count_)) / (m2 * m2) - 3;
  }

 private:
  Real m2_ = 0, m3_ = 0, m4_ = 0;
  std::size_t count_ = 0;
};

}  // namespace swell::validation::stats
