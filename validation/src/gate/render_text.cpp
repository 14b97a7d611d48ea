// The gate's report for the terminal: a table of checks and a verdict line (docs/gate.md §3).
#include "swell/validation/gate/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gate/report_text.hpp"
#include "swell/validation/gate/power.hpp"
#include "swell/validation/results/report.hpp"
#include "swell/validation/results/text.hpp"

namespace swell::validation {

using namespace gate_text;

std::string render_gate(const GateReport& report) {
  std::string out = fmt::format("swell gate: {}\n", report.subject);
  std::string fields;
  for (const auto& f : report.fields) fields += (fields.empty() ? "" : ", ") + f;
  const std::string case_name = report.case_path.empty() ? "" : "case " + report.case_path + "; ";
  if (report.frames == 0) {  // a probes case: series, not frames
    out += fmt::format("{}{}; fields: {}; unit roundoff {:.2g}\n", case_name, report.samples,
                       fields.empty() ? "none" : fields, report.unit_roundoff);
  } else {
    out += fmt::format("{}{} frame{} of {}; fields: {}; unit roundoff {:.2g}\n", case_name, report.frames,
                       report.frames == 1 ? "" : "s",
                       report.samples.empty() ? fmt::format("{}×{}", report.nx, report.ny) : report.samples,
                       fields.empty() ? "none" : fields, report.unit_roundoff);
  }
  out += fmt::format("family-wise α = {:.3g}, shared by {} statistical checks: each at α = {:.3g}\n",
                     report.alpha, report.statistical_checks, report.alpha_per_check);
  for (const auto& note : report.notes) out += "note: " + note + "\n";
  out += "\n";

  struct Row {
    std::string verdict, check, measured, expected, judged, reason;
  };
  std::vector<Row> rows;
  for (const auto& r : report.results) {
    rows.push_back({r.passed ? "PASS" : "FAIL", r.check, table_number(r.measured), table_number(r.expected),
                    judgement(r), r.reason});
  }
  for (const auto& entry : report.skipped) {
    const std::string &check = entry.check, &why = entry.why;
    rows.push_back({"SKIP", check, "", "", "", why});
  }
  std::size_t w_check = 5, w_measured = 8, w_expected = 8, w_judged = 6;
  for (const auto& row : rows) {
    w_check = std::max(w_check, display_width(row.check));
    w_measured = std::max(w_measured, display_width(row.measured));
    w_expected = std::max(w_expected, display_width(row.expected));
    w_judged = std::max(w_judged, display_width(row.judged));
  }
  out += fmt::format("{}  {}  {}  {}  {}  {}\n", pad_to_width("", 4), pad_to_width("check", w_check),
                     pad_to_width("measured", w_measured), pad_to_width("expected", w_expected),
                     pad_to_width("judged", w_judged), "reason");
  for (const auto& row : rows) {
    out += fmt::format("{}  {}  {}  {}  {}  {}\n", row.verdict, pad_to_width(row.check, w_check),
                       pad_to_width(row.measured, w_measured), pad_to_width(row.expected, w_expected),
                       pad_to_width(row.judged, w_judged), row.reason);
  }
  if (report.power) out += "\n" + render_power(*report.power);
  const int failed = failed_count(report);
  const int total = int(report.results.size());
  std::string skipped = report.skipped.empty()
                            ? std::string()
                            : fmt::format(", {} skipped", report.skipped.size());
  if (failed == 0) {
    out += fmt::format("\nverdict: PASS — {} check{} passed{}; family-wise α = {:.3g} ({:.2f} s)\n",
                       total, total == 1 ? "" : "s", skipped, report.alpha, report.seconds);
  } else {
    out += fmt::format("\nverdict: FAIL — {} of {} checks failed ({}){}; family-wise α = {:.3g} "
                       "({:.2f} s)\n",
                       failed, total, failed_names(report), skipped, report.alpha, report.seconds);
  }
  return out;
}

}  // namespace swell::validation
