#pragma once
// A probes case's elevation series on disk (docs/probes.md): CSV (a header line of column names,
// then rows of numbers separated by commas), OpenFAST's .out tables (a free preamble, a line of
// names, a line of units in parentheses, then whitespace-separated rows) and .npy (float32 or
// float64, samples × probes in the positions' order, or one column for one probe).
#include <filesystem>
#include <string>
#include <vector>

#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/npy.hpp"

namespace swell::validation {

struct ProbeSeries {
  // elevation[p][n]: probe p at t_n = t0 + n dt, m.
  std::vector<std::vector<double>> elevation;
  // The rounding of the stored numbers per probe, as an absolute bound in m: half the last
  // printed digit's place (CSV, .out; the largest over the probe's values) or half an ulp of the
  // largest value (.npy). An exact check cannot see errors below it.
  std::vector<double> rounding;
  std::string source;               // the file, for messages
  std::vector<std::string> notes;   // what the reader found worth saying
};

// Reads the series of `case_file` (a probes case) from its [input] files, relative to the case
// file. Throws InvalidInput naming the file, line and column for: a missing file, column or
// value; a value that is not a finite number; a row of another width; a time column whose
// values are not t0 + n dt of the case (to their printed precision and 1e-9 relative); a
// number of samples other than the case's.
ProbeSeries read_probe_series(const CaseFile& case_file);

// The same from `input`'s file at `path` against `layout`.
ProbeSeries read_probe_series(const std::filesystem::path& path, const ProbeInput& input,
                              const reference::ProbeLayout& layout);

// The series of an array handed over in memory (the Python module), as a .npy file of it is
// read: (samples, probes), or (samples,) for one probe, float32 or float64; `source` names it
// in messages.
ProbeSeries probe_series_from_array(const NpyArray& array, const std::string& source,
                                    const reference::ProbeLayout& layout);

// Writes `series` (elevation[p][n]) as CSV: a header "time,<names…>", then one row per sample
// with the time and each probe's value, in shortest round-trip form (exact for float64).
void write_probe_series_csv(const std::filesystem::path& path, const reference::ProbeLayout& layout,
                            const std::vector<std::vector<double>>& elevation,
                            const std::vector<std::string>& names, const std::string& time_column = "time");

}  // namespace swell::validation
