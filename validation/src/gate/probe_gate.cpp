// The gate's path for a probes case (gate.hpp, docs/probes.md): the case's series read, then
// judged against its sea and synthesis scheme (checks/probe_checks.hpp), one family-wise α
// shared by the statistical checks.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gate/judge.hpp"
#include "swell/validation/checks/probe_checks.hpp"
#include "swell/validation/io/probe_series.hpp"

namespace swell::validation::gate_path {

GateReport read_and_judge_probes(const CaseFile& case_file, const GateOptions& options, Clock::time_point start) {
  const auto& layout = case_file.probes->layout;
  options.report_progress(fmt::format("reading {} samples of {} probes…", layout.samples, layout.positions.size()));
  return judge_probes(case_file, read_probe_series(case_file), options, start);
}

GateReport judge_probes(const CaseFile& case_file, const ProbeSeries& series, const GateOptions& options,
                        Clock::time_point start) {
  const auto probe_case = case_file.probe_case();
  const auto& layout = probe_case.layout;
  GateReport report;
  report.case_path = case_file.origin.string();
  report.subject = probe_case.describe();
  report.read_seconds = seconds_since(start);
  report.frames = 0;
  report.samples = fmt::format("{} probe{} × {} samples at {:g} s", layout.positions.size(),
                               layout.positions.size() == 1 ? "" : "s", layout.samples, layout.dt);
  report.fields = {"elevation"};
  report.alpha = options.alpha;
  report.statistical_checks = probe_statistical_check_count(probe_case);
  report.alpha_per_check = options.alpha / double(std::max(1, report.statistical_checks));
  for (std::size_t p = 0; p < series.elevation.size(); ++p) {
    double sum = 0;
    for (double v : series.elevation[p]) sum += v * v;
    const double rms = std::sqrt(sum / double(series.elevation[p].size()));
    if (rms > 0) report.unit_roundoff = std::max(report.unit_roundoff, series.rounding[p] / rms);
  }
  auto checks = run_probe_checks(probe_case, series.elevation, series.rounding, report.alpha_per_check);
  report.results = std::move(checks.results);
  report.skipped = std::move(checks.skipped);
  report.notes = series.notes;
  for (auto& note : checks.notes) report.notes.push_back(std::move(note));
  report.seconds = seconds_since(start);
  return report;
}

}  // namespace swell::validation::gate_path
