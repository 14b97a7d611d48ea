#pragma once
// A check returns a value, not a printout: what was checked, on what, the measured and expected
// numbers, the criterion, the verdict and a one-line reason. Text, JSON and Markdown are
// renderings of it (report.hpp).
#include <limits>
#include <string>
#include <vector>

namespace swell::validation {

struct CheckResult {
  std::string check;      // dotted name: "dispersion.round_trip"
  std::string subject;    // what it was applied to: "finite depth h = 10 m"
  double measured = 0;
  double expected = 0;
  double tolerance = 0;   // the bound in the criterion
  std::string criterion;  // how measured is judged: "|rel err| ≤ 1e-12"
  bool passed = false;
  std::string reason;     // one line: why it passed or failed, in the user's terms
  // Statistical checks: the p-value of the measurement under the hypothesis that the surface is
  // right, and the false-alarm rate α it was judged at (passed ⇔ p ≥ α). NaN for exact checks.
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha = std::numeric_limits<double>::quiet_NaN();
};

// |measured − expected| ≤ tolerance · |expected|.
CheckResult relative_check(std::string check, std::string subject, double measured,
                           double expected, double tolerance, std::string what);
// |measured − expected| ≤ tolerance.
CheckResult absolute_check(std::string check, std::string subject, double measured,
                           double expected, double tolerance, std::string what);
// A measured error (already relative or absolute) that must not exceed a bound.
CheckResult error_bound_check(std::string check, std::string subject, double error, double bound,
                              std::string what);
// lower ≤ measured ≤ upper.
CheckResult range_check(std::string check, std::string subject, double measured, double lower,
                        double upper, std::string what);

// A statistical result with its own reason: passed ⇔ p ≥ α (false for a NaN p), tolerance = α.
CheckResult statistical_check(std::string check, std::string subject, double measured,
                              double expected, double p_value, double alpha,
                              std::string criterion, std::string reason);

bool all_passed(const std::vector<CheckResult>& results);

}  // namespace swell::validation
