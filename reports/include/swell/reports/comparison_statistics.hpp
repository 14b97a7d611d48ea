#pragma once
// Statistics for comparing two sets of measurements (e.g. run times of two engines): a rank test
// of whether one tends to be larger, and the robust summaries a report prints beside it. Each
// follows a named reference implementation so that a report's numbers can be checked with it.
#include <span>
#include <vector>

namespace swell::reports {

// The result of a two-sided Mann–Whitney U test of samples a (size n1) and b (size n2).
struct MannWhitney {
  double u1;       // U of a: R1 − n1(n1+1)/2, R1 the sum of a's midranks in the pooled sample
  double u2;       // U of b: n1·n2 − u1
  double z;        // (max(u1, u2) − n1·n2/2 − 0.5) / σ, σ tie-corrected; 0 when σ = 0
  double p_value;  // two-sided, in [0, 1]; 1 when σ = 0 (every value equal)
  int n1;
  int n2;
  bool ties;  // whether any value occurs more than once in the pooled sample
};

// Two-sided Mann–Whitney U test by the normal approximation with tie and continuity
// corrections: the same numbers as scipy.stats.mannwhitneyu(a, b, alternative='two-sided',
// method='asymptotic', use_continuity=True) (scipy 1.10). Throws InvalidInput when a sample is
// empty or holds a non-finite value.
MannWhitney mann_whitney_u(std::span<const double> a, std::span<const double> b);

// Quartiles by linear interpolation between order statistics: numpy.percentile's default
// method ('linear', Hyndman & Fan type 7), the quantile at p being x[(n−1)p] interpolated.
struct Quartiles {
  double q1;
  double median;
  double q3;
};

// The median (numpy.median). Throws InvalidInput when empty or holding a non-finite value.
double median(std::vector<double> values);
// numpy.percentile(values, [25, 50, 75]). Throws InvalidInput when empty or non-finite.
Quartiles quartiles(std::vector<double> values);

// exp(mean(log x)), as scipy.stats.gmean: the mean of ratios such as speed-ups. Throws
// InvalidInput when empty or when a value is not finite and positive.
double geometric_mean(std::span<const double> positive_values);

}  // namespace swell::reports
