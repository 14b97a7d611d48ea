#pragma once
// What the three renderings of a gate report share (render_text.cpp, render_json.cpp,
// render_junit.cpp).
#include <string>
#include <utility>

#include "swell/validation/gate/report.hpp"

namespace swell::validation::gate_text {

// Whether a result is statistical (judged by p against α) rather than against a bound.
bool statistical_result(const CheckResult& r);
// How the measurement is judged, in a few characters: "p 0.41 ≥ α 2.0e-04", "≤ 1.2e-13".
std::string judgement(const CheckResult& r);
// The failure message of a result: measured, expected and the bound (or p against α).
std::string failure_message(const CheckResult& r);
// The failed checks' names, comma-separated, and their number.
std::string failed_names(const GateReport& report);
int failed_count(const GateReport& report);

}  // namespace swell::validation::gate_text
