#pragma once
// The gate: judge another engine's frames against its case file, with one family-wise
// false-alarm rate shared by all statistical checks (docs/gate.md).
//
// The statistical checks that run (energy, spectrum, moments, direction, randomness, statistics — those
// the given fields and frame count allow) share α by Bonferroni: each runs at α / (their
// number), so a right engine fails the gate with probability ≤ α. Exact checks (Hermitian,
// Parseval, dispersion, derived fields) are judged against rounding bounds.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/validation/case_file.hpp"
#include "swell/validation/check_result.hpp"

namespace swell::validation {

struct GateOptions {
  double alpha = 1e-3;        // family-wise false-alarm rate of the whole gate
  std::string input_pattern;  // replaces the case's [input] files when not empty
  // Threads that read frames and run the checks (0: every hardware thread); the verdict does
  // not depend on it.
  int threads = 0;
  // Called with a one-line message ("reading 64 frames of 512×512…") as the gate goes; unset:
  // silent. The CLI prints them on standard error.
  std::function<void(const std::string&)> progress;
};

struct GateReport {
  std::string case_path;               // the case file judged ("" when given in memory)
  std::string subject;                 // the case's one-line description
  int frames = 0, nx = 0, ny = 0;  // a lattice: nx = N points, ny = 1
  std::string samples;             // "512×512", or the lattice ("korobov N=4096 g=(1,671) over …")
  std::vector<std::string> fields;     // field names present
  double alpha = 0;                    // family-wise
  double alpha_per_check = 0;          // what each statistical check ran at
  int statistical_checks = 0;          // how many share α
  std::vector<CheckResult> results;
  std::vector<std::string> skipped;    // checks that could not run, with the reason
  double fitted_scale = 1;             // free-scale cases: the engine's spectrum over the case's
  double unit_roundoff = 0;            // of the values read (FrameSequence::unit_roundoff)
  double seconds = 0;                  // wall time of reading and judging
  double read_seconds = 0;             // of which reading the case and its frames
  bool passed() const;
};

// Judges frames already in memory.
GateReport run_gate(const CaseFile& case_file, const reference::FrameSequence& frames,
                    const GateOptions& options = {});
// Judges a cascade set (DESIGN.md §1 "Cascades"; docs/gate.md §Cascades) whose frames are in
// memory: `cascades[c]` holds cascade c's (no frames: not given), `sum` the summed surface's
// (null: not given). Every cascade passes the ordinary checks against its band of the spectrum
// (results named "cascade1.energy", …) and its band checks; the set passes cascade_checks.hpp's;
// the sum the ordinary checks ("sum.…") and its band checks. One family-wise α over all.
GateReport run_cascade_gate(const CaseFile& case_file,
                            const std::vector<reference::FrameSequence>& cascades,
                            const reference::FrameSequence* sum, const GateOptions& options = {});
// Reads the case file and its frames (frame_io.hpp), then judges them. Bad input throws
// InvalidInput naming the file and the problem. Every field of every frame is read and checked;
// only what the checks use is kept: the height of every frame, and the other fields of the
// first and the last frame (the two the derived check compares).
GateReport run_gate(const std::filesystem::path& case_file, const GateOptions& options = {});

// One line per check and a verdict line, for the terminal.
std::string render_gate(const GateReport& report);
// {"case", "subject", "frames", "nx", "ny", "fields", "alpha", "alpha_per_check",
//  "statistical_checks", "fitted_scale", "unit_roundoff", "checks": [report.hpp's to_json entries],
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
