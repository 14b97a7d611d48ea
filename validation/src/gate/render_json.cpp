// The gate's report as JSON (docs/gate.md §3).
#include "swell/validation/gate/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gate/report_text.hpp"
#include "swell/validation/results/report.hpp"
#include "swell/validation/results/text.hpp"

namespace swell::validation {

using namespace gate_text;

nlohmann::json gate_json(const GateReport& report) {
  // Strings as valid UTF-8: a case path may hold any bytes, and JSON cannot.
  auto checks = to_json(report.results);
  for (auto& check : checks["checks"]) {
    for (auto& [key, value] : check.items()) {
      if (value.is_string()) value = valid_utf8(value.get<std::string>());
    }
  }
  auto skipped = nlohmann::json::array();
  for (const auto& entry : report.skipped) {
    const std::string &check = entry.check, &why = entry.why;
    skipped.push_back({{"check", valid_utf8(check)}, {"reason", valid_utf8(why)}});
  }
  nlohmann::json document = {{"case", valid_utf8(report.case_path)},
          {"subject", valid_utf8(report.subject)},
          {"frames", report.frames},
          {"nx", report.nx},
          {"ny", report.ny},
          {"samples", report.samples},
          {"fields", report.fields},
          {"alpha", json_number(report.alpha)},
          {"alpha_per_check", json_number(report.alpha_per_check)},
          {"statistical_checks", report.statistical_checks},
          {"fitted_scale", json_number(report.fitted_scale)},
          {"unit_roundoff", json_number(report.unit_roundoff)},
          {"storage_roundoff", json_number(report.storage_roundoff)},
          {"power", report.power ? power_json(*report.power) : nlohmann::json(nullptr)},
          {"checks", checks["checks"]},
          {"skipped", skipped},
          {"passed", checks["passed"]},
          {"failed", checks["failed"]},
          {"seconds", json_number(report.seconds)},
          {"pass", report.passed()}};
  if (!report.notes.empty()) {
    nlohmann::json notes = nlohmann::json::array();
    for (const auto& note : report.notes) notes.push_back(valid_utf8(note));
    document["notes"] = notes;
  }
  return document;
}

}  // namespace swell::validation
