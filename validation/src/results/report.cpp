#include "swell/validation/results/report.hpp"

#include "swell/reference/moments.hpp"

#include "swell/reference/errors.hpp"
#include "swell/validation/results/text.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>

namespace swell::validation {
namespace {

std::string number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return fmt::format("{:.10g}", x);
}

std::vector<std::vector<std::string>> rows_of(const std::vector<CheckResult>& results) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : results) {
    rows.push_back({r.check, r.subject, number(r.measured), number(r.expected), r.criterion,
                    r.passed ? "pass" : "FAIL"});
  }
  return rows;
}

const std::vector<std::string> kHeader = {"check", "subject", "measured", "expected", "tolerance",
                                          "verdict"};

}  // namespace

nlohmann::json json_number(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

nlohmann::json sea_state_json(const reference::SeaState& s) {
  const auto& m = s.moments;
  return {{"m_1", json_number(m.m_minus1)}, {"m0", json_number(m.m0)},
          {"m1", json_number(m.m1)},        {"m2", json_number(m.m2)},
          {"m4", json_number(m.m4)},        {"hs", json_number(s.hs)},
          {"tp", json_number(s.tp)},        {"tm01", json_number(s.tm01)},
          {"tm02", json_number(s.tm02)},    {"te", json_number(s.te)},
          {"epsilon4", json_number(s.epsilon4)}, {"nu", json_number(s.nu)},
          {"omega_p", json_number(s.omega_p)}};
}

std::string render_table(const std::vector<CheckResult>& results) {
  const auto rows = rows_of(results);
  std::vector<std::size_t> widths(kHeader.size());
  for (std::size_t c = 0; c < kHeader.size(); ++c) {
    widths[c] = display_width(kHeader[c]);
    for (const auto& row : rows) widths[c] = std::max(widths[c], display_width(row[c]));
  }
  std::string out;
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      out += c + 1 < cells.size() ? pad_to_width(cells[c], widths[c]) + "  " : cells[c];
    }
    out += '\n';
  };
  line(kHeader);
  for (const auto& row : rows) line(row);
  const auto failed = std::count_if(results.begin(), results.end(),
                                    [](const CheckResult& r) { return !r.passed; });
  out += fmt::format("{} passed, {} failed\n", results.size() - failed, failed);
  return out;
}

std::string render_markdown(const std::vector<CheckResult>& results, const std::string& title) {
  std::string out = "# " + title + "\n\n| check | subject | measured | expected | tolerance | "
                    "verdict | reason |\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : results) {
    out += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", r.check, r.subject,
                       number(r.measured), number(r.expected), r.criterion,
                       r.passed ? "pass" : "**FAIL**", r.reason);
  }
  const auto failed = std::count_if(results.begin(), results.end(),
                                    [](const CheckResult& r) { return !r.passed; });
  out += fmt::format("\n{} passed, {} failed\n", results.size() - failed, failed);
  return out;
}

nlohmann::json to_json(const std::vector<CheckResult>& results) {
  auto checks = nlohmann::json::array();
  int passed = 0;
  for (const auto& r : results) {
    passed += r.passed;
    checks.push_back({{"check", r.check},
                      {"subject", r.subject},
                      {"measured", json_number(r.measured)},
                      {"expected", json_number(r.expected)},
                      {"tolerance", json_number(r.tolerance)},
                      {"criterion", r.criterion},
                      {"p_value", json_number(r.p_value)},
                      {"alpha", json_number(r.alpha)},
                      {"pass", r.passed},
                      {"reason", r.reason}});
  }
  return {{"checks", checks},
          {"passed", passed},
          {"failed", static_cast<int>(results.size()) - passed}};
}

void write_report(const std::filesystem::path& dir, const std::string& stem,
                  const nlohmann::json& document, const std::string& markdown) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  auto write = [&](const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path);
    file << text;
    if (!file) throw InvalidInput("cannot write report " + path.string());
  };
  write(dir / (stem + ".json"), document.dump(2) + "\n");
  write(dir / (stem + ".md"), markdown);
}

}  // namespace swell::validation
