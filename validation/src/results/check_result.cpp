#include "swell/validation/results/check_result.hpp"

#include <cmath>
#include <fmt/format.h>

namespace swell::validation {
namespace {
CheckResult make(std::string check, std::string subject, double measured, double expected,
                 double tolerance, std::string criterion, bool passed, std::string what) {
  const std::string reason =
      fmt::format("{} {}", what, passed ? "within bound" : "OUT OF BOUND");
  return {std::move(check), std::move(subject), measured, expected, tolerance,
          std::move(criterion), passed, reason};
}
}  // namespace

CheckResult relative_check(std::string check, std::string subject, double measured,
                           double expected, double tolerance, std::string what) {
  const double error = std::abs(measured - expected) / std::abs(expected);
  const bool passed = error <= tolerance;  // false for NaN
  return make(std::move(check), std::move(subject), measured, expected, tolerance,
              fmt::format("|rel err| ≤ {:.0e}", tolerance), passed,
              fmt::format("{}: rel err {:.2e}", what, error));
}

CheckResult exact_check(std::string check, std::string subject, double measured, double bound,
                        bool passed, std::string criterion, std::string reason) {
  CheckResult r;
  r.check = std::move(check);
  r.subject = std::move(subject);
  r.measured = measured;
  r.expected = 0;
  r.tolerance = bound;
  r.criterion = std::move(criterion);
  r.passed = passed;
  r.reason = std::move(reason);
  return r;
}

CheckResult bounded_check(std::string check, std::string subject, double error, double bound,
                          std::string criterion, std::string reason) {
  const bool passed = error <= bound;
  return exact_check(std::move(check), std::move(subject), error, bound, passed,
                     std::move(criterion), std::move(reason));
}

CheckResult error_bound_check(std::string check, std::string subject, double error, double bound,
                              std::string what) {
  return make(std::move(check), std::move(subject), error, 0.0, bound,
              fmt::format("err ≤ {:.0e}", bound), error <= bound, std::move(what));
}

CheckResult range_check(std::string check, std::string subject, double measured, double lower,
                        double upper, std::string what) {
  return make(std::move(check), std::move(subject), measured, 0.5 * (lower + upper),
              0.5 * (upper - lower), fmt::format("{} ≤ x ≤ {}", lower, upper),
              measured >= lower && measured <= upper, std::move(what));
}

CheckResult statistical_check(std::string check, std::string subject, double measured,
                              double expected, double p_value, double alpha,
                              std::string criterion, std::string reason) {
  CheckResult r;
  r.check = std::move(check);
  r.subject = std::move(subject);
  r.measured = measured;
  r.expected = expected;
  r.tolerance = alpha;
  r.criterion = std::move(criterion);
  r.p_value = p_value;
  r.alpha = alpha;
  r.passed = p_value >= alpha;  // false for NaN
  r.reason = std::move(reason);
  return r;
}

bool all_passed(const std::vector<CheckResult>& results) {
  for (const auto& r : results) {
    if (!r.passed) return false;
  }
  return true;
}

}  // namespace swell::validation
