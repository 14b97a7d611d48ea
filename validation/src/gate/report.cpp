#include "swell/validation/gate/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gate/report_text.hpp"
#include "swell/validation/results/text.hpp"

namespace swell::validation {

bool GateReport::passed() const {
  return std::all_of(results.begin(), results.end(), [](const CheckResult& r) { return r.passed; });
}

namespace gate_text {

bool statistical_result(const CheckResult& r) { return !std::isnan(r.alpha); }

std::string judgement(const CheckResult& r) {
  if (r.check == "scale") return "reported";
  if (statistical_result(r)) {
    if (std::isnan(r.p_value)) {  // a set test (moments.tp): no p-value
      return fmt::format("{} at α {:.1e}", r.passed ? "in set" : "outside set", r.alpha);
    }
    return fmt::format("p {:.2g} {} α {:.1e}", r.p_value, r.p_value >= r.alpha ? "≥" : "<",
                       r.alpha);
  }
  return fmt::format("{} {:.2g}", r.passed ? "≤" : ">", r.tolerance);
}

std::string failure_message(const CheckResult& r) {
  std::string bound;
  if (statistical_result(r)) {
    bound = std::isnan(r.p_value) ? fmt::format("set test at α = {:.3g}", r.alpha)
                                  : fmt::format("p = {:.3g} < α = {:.3g}", r.p_value, r.alpha);
  } else {
    bound = fmt::format("bound {:.3g}", r.tolerance);
  }
  return fmt::format("{}: measured {}, expected {}, {}: {}", r.check, table_number(r.measured),
                     table_number(r.expected), bound, r.reason);
}

std::string failed_names(const GateReport& report) {
  std::string names;
  for (const auto& r : report.results) {
    if (!r.passed) names += (names.empty() ? "" : ", ") + r.check;
  }
  return names;
}

int failed_count(const GateReport& report) {
  return int(std::count_if(report.results.begin(), report.results.end(),
                           [](const CheckResult& r) { return !r.passed; }));
}

}  // namespace gate_text
}  // namespace swell::validation
