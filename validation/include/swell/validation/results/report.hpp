#pragma once
// Renderings of check results: a compact text table for the terminal, JSON and Markdown files.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "swell/validation/results/check_result.hpp"

namespace swell::reference {
struct SeaState;
}

namespace swell::validation {

std::string render_table(const std::vector<CheckResult>& results);
std::string render_markdown(const std::vector<CheckResult>& results, const std::string& title);
// {"checks": [{"check", "subject", "measured", "expected", "tolerance", "criterion", "pass",
//  "reason"}], "passed": n, "failed": n}. Non-finite numbers become null.
nlohmann::json to_json(const std::vector<CheckResult>& results);

// Writes <dir>/<stem>.json and <dir>/<stem>.md, creating dir; throws swell::InvalidInput
// naming the path when it cannot.
void write_report(const std::filesystem::path& dir, const std::string& stem,
                  const nlohmann::json& document, const std::string& markdown);

// A JSON number, or null when x is NaN or ±∞ (JSON has no such numbers).
nlohmann::json json_number(double x);
// A sea state's moments and periods as `swell spectrum --json` writes them: {"m_1", "m0", "m1",
// "m2", "m4", "hs", "tp", "tm01", "tm02", "te", "epsilon4", "nu", "omega_p"}; a moment that
// diverges is null.
nlohmann::json sea_state_json(const reference::SeaState& state);

}  // namespace swell::validation
