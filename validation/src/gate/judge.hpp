#pragma once
// The steps of the gate's path that run_gate.cpp and cascade_gate.cpp share: the frames read,
// the memory they need, and one surface judged.
#include <chrono>
#include <limits>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/validation/gate/options.hpp"
#include "swell/validation/gate/report.hpp"
#include "swell/validation/io/probe_series.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_source.hpp"

namespace swell::validation::gate_path {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start);

// How many statistical checks run_ocean_checks runs on `frames` frames of a case of this scale,
// each at its share of α.
int statistical_check_count(SpectrumScale scale, std::size_t frames);

// Throws InvalidInput, naming the figure and what to reduce, when one surface streamed through
// the analysis (run_gate.cpp) needs more memory than the machine has available. What it needs
// does not depend on the frame count; called before anything of the grid's size is read.
// `power_table`: the gate's power table is made beside the passes (a single surface's gate).
void require_streamed_gate_memory(const reference::OceanCase& ocean, std::size_t fields, int threads,
                                  bool power_table = false);
// The same for a cascade set's set checks (cascade_checks.hpp): their sums per wave vector of
// every cascade at once, beside the largest surface's analysis.
void require_cascade_set_memory(const CaseFile& set, int threads);

// A cascade's (or the sum's) own case file: its case, its frames' input, the set's scale.
CaseFile surface_case_file(const CaseFile& set, const reference::OceanCase& ocean,
                           const InputSpec& input);

// Judges one surface's frames at
// `alpha_per_check` each (NaN: options.alpha shared by this surface's statistical checks alone;
// a cascade set shares α over all its surfaces). `travelling_power`: τ(k) of the case on its
// samples (expected_travelling_power in ocean_checks.hpp), evaluated once before reading.
GateReport judge(const CaseFile& case_file, const FrameSource& frames,
                 std::vector<double> travelling_power,
                 const GateOptions& options, Clock::time_point start,
                 double alpha_per_check = std::numeric_limits<double>::quiet_NaN());
GateReport judge(const CaseFile& case_file, const reference::FrameSequence& frames,
                 std::vector<double> travelling_power,
                 const GateOptions& options, Clock::time_point start,
                 double alpha_per_check = std::numeric_limits<double>::quiet_NaN());

// Reads the frames of every cascade and of the sum that a cascade set names, then judges them
// (cascade_gate.cpp).
GateReport read_and_judge_cascades(const CaseFile& case_file, const GateOptions& options,
                                   Clock::time_point start);
// A probes case (probe_gate.cpp): its series read, then judged by checks/probe_checks.hpp.
GateReport read_and_judge_probes(const CaseFile& case_file, const GateOptions& options,
                                 Clock::time_point start);
// Judges a probes case's series already read (or handed over in memory).
GateReport judge_probes(const CaseFile& case_file, const ProbeSeries& series, const GateOptions& options,
                        Clock::time_point start);

}  // namespace swell::validation::gate_path
