#pragma once
// The gate: judge another engine's frames against its case file, with one family-wise
// false-alarm rate shared by all statistical checks (docs/gate.md).
//
// The statistical checks that run (energy, spectrum, moments, direction, randomness, statistics — those
// the given fields and frame count allow) share α by Bonferroni: each runs at α / (their
// number), so a right engine fails the gate with probability ≤ α. Exact checks (Hermitian,
// Parseval, dispersion, derived fields) are judged against rounding bounds.
//
// Its path, in one direction: the options validated (options.hpp); the case read once; the
// memory and the sampling rule checked before any frame is read; the frames read
// (io/frame_io.hpp); the checks run on one analysis of them (checks/ocean_checks.hpp); the
// report rendered (render.hpp).
#include <filesystem>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/validation/gate/options.hpp"
#include "swell/validation/gate/render.hpp"
#include "swell/validation/gate/report.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/probe_series.hpp"
#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

// Reads the case file, then judges the frames it names (the next overload).
GateReport run_gate(const std::filesystem::path& case_file, const GateOptions& options = {});
// Reads the frames the case names (frame_io.hpp) and judges them; the report names the case by
// case_file.origin. Bad input throws InvalidInput naming the file and the problem. Every field of
// every frame is read and checked; only what the checks use is kept: the height of every frame,
// and the other fields of the first and the last frame (the two the derived check compares).
GateReport run_gate(const CaseFile& case_file, const GateOptions& options);
// Judges frames already in memory.
GateReport run_gate(const CaseFile& case_file, const reference::FrameSequence& frames,
                    const GateOptions& options = {});
// Judges a probes case's series already in memory (io/probe_series.hpp).
GateReport run_probe_gate(const CaseFile& case_file, const ProbeSeries& series,
                          const GateOptions& options = {});
// Judges a cascade set (docs/gate.md §10) whose frames are in memory: `cascades[c]` holds
// cascade c's (no frames: not given), `sum` the summed surface's (null: not given). Every
// cascade passes the ordinary checks against its band of the spectrum (results named
// "cascade1.energy", …) and its band checks; the set passes cascade_checks.hpp's; the sum the
// ordinary checks ("sum.…") and its band checks. One family-wise α over all.
GateReport run_cascade_gate(const CaseFile& case_file,
                            const std::vector<reference::FrameSequence>& cascades,
                            const reference::FrameSequence* sum, const GateOptions& options = {});

}  // namespace swell::validation
