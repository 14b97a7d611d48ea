#pragma once
// A gate's report for a terminal, as JSON and as JUnit XML for CI systems (docs/gate.md).
#include <nlohmann/json.hpp>
#include <string>

#include "swell/validation/gate/report.hpp"

namespace swell::validation {

// One line per check and a verdict line, for the terminal.
std::string render_gate(const GateReport& report);
// {"case", "subject", "frames", "nx", "ny", "fields", "alpha", "alpha_per_check",
//  "statistical_checks", "fitted_scale", "unit_roundoff", "storage_roundoff", "checks": [report.hpp's to_json entries],
//  "skipped": [{"check", "reason"}], "passed", "failed", "seconds", "pass"}; strings as valid
// UTF-8 (malformed bytes become U+FFFD), non-finite numbers null.
nlohmann::json gate_json(const GateReport& report);
// JUnit XML: one <testsuite name="swell gate"> (inside <testsuites>) with one <testcase> per
// check result; a failed check carries <failure message="…"> with measured, expected and bound;
// skipped checks are <skipped/> test cases. Valid XML 1.0 whatever the strings hold: markup
// escaped, control characters dropped, malformed UTF-8 replaced by U+FFFD.
std::string gate_junit(const GateReport& report);
// JUnit XML for a gate that could not judge (bad input, exit code 2): one <testcase name="input">
// with an <error> carrying the message, so the CI job's test report says why.
std::string gate_junit_error(const std::string& case_path, const std::string& message);

}  // namespace swell::validation
