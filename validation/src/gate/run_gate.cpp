// The gate's path for one surface (gate.hpp): options, case, memory and sampling rule before any
// frame is read; then the frames, then the judgement.
#include <fmt/format.h>

#include <vector>

#include "gate/judge.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/checks/ocean_checks.hpp"

namespace swell::validation {

using namespace gate_path;

namespace {

GateReport read_and_judge(const CaseFile& case_file, const GateOptions& options,
                          Clock::time_point start) {
  options.validate();
  if (case_file.is_cascade_set()) return read_and_judge_cascades(case_file, options, start);
  if (case_file.is_probe_case()) return read_and_judge_probes(case_file, options, start);
  const int threads = options.resolved_threads();
  const auto& ocean = case_file.ocean;
  require_streamed_gate_memory(ocean, case_file.input.channels.size(), threads, options.power);
  // The rest of the sampling rule before any frame is read (a case no frames can satisfy is
  // refused as such, not as a missing file); the analysis applies it again in the frames'
  // stored format. τ(k) over the samples is evaluated once, on every thread, for this rule and
  // for the analysis.
  const auto sampling = ocean.sampling();
  std::vector<double> travelling = expected_travelling_power(ocean, threads);
  reference::require_valid_sampling(ocean, reference::kFloat64, 0, "", &travelling);
  options.report_progress(fmt::format("reading and judging {} frame{} on a {}, one at a time…",
                                      ocean.frames, ocean.frames == 1 ? "" : "s", sampling.describe()));
  // The frames stream through the analysis (io/frame_source.hpp): read ahead on a thread of
  // their own, frame by frame, never all at once, each file decoded on every thread (at 512² a
  // frame's six fields took one thread longer than the analysis took for them).
  const FileFrameSource frames(case_file, options.input_pattern, threads);
  GateReport report = judge(case_file, frames, std::move(travelling), options, start);
  report.case_path = case_file.origin.string();
  report.read_seconds = frames.reading_seconds();
  return report;
}

}  // namespace

GateReport run_gate(const std::filesystem::path& case_path, const GateOptions& options) {
  const auto start = Clock::now();
  options.validate();
  return read_and_judge(read_case_file(case_path), options, start);
}

GateReport run_gate(const CaseFile& case_file, const GateOptions& options) {
  return read_and_judge(case_file, options, Clock::now());
}

GateReport run_gate(const CaseFile& case_file, const reference::FrameSequence& frames,
                    const GateOptions& options) {
  options.validate();
  if (case_file.is_probe_case()) {
    throw InvalidInput(case_file.origin.string() + ": a probes case is judged on its series, not frames");
  }
  return judge(case_file, frames,
               expected_travelling_power(case_file.ocean, options.resolved_threads()), options,
               Clock::now());
}

GateReport run_probe_gate(const CaseFile& case_file, const ProbeSeries& series, const GateOptions& options) {
  options.validate();
  if (!case_file.is_probe_case()) {
    throw InvalidInput(case_file.origin.string() + ": not a probes case ([sampling] kind = \"probes\"): "
                       "it is judged on frames");
  }
  return judge_probes(case_file, series, options, Clock::now());
}

}  // namespace swell::validation
