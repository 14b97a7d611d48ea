#pragma once
// Tuning experiments (docs/sweeps.md): a base case, the cartesian product of varied case keys
// ("points") × S replicates ("seeds"). Each run synthesizes the point's case with its own seed
// and measures the surface's statistics (and, on request, fits JONSWAP to it). The library is
// the science; `swell sweep` (cli/sweep_command.cpp) adds threads, MPI, shards, progress and
// resumption around it.
//
// Reproducible whatever the split: a run's seed is a function of (the sweep's seed, the point's
// index, the replicate) alone (run_seed), and a row is a function of its run alone, so any
// division of the runs over threads, ranks or shards gives the same rows.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "swell/impls/transform.hpp"
#include "swell/validation/io/case_file.hpp"

namespace swell::validation::sweep {

// One varied case key and its values, in the order given.
struct Variation {
  std::string name;          // as the user wrote it: "gamma" or "spectrum.gamma"
  std::string section, key;  // where it goes in the case file: [spectrum] gamma
  std::vector<std::string> labels;  // each value as written to the outputs
  // Each value's number (NaN for a non-numeric value such as depth = "inf" or a model name):
  // what the plots put on their x axis.
  std::vector<double> numbers;
  // TOML text of each value as it goes into the case file ("3.5", "256", "\"inf\"").
  std::vector<std::string> toml_values;
  bool numeric() const;  // every value a finite number
};

struct SweepSpec {
  std::filesystem::path case_path;  // where the base case came from (relative paths, messages)
  std::string case_text;            // the base case's TOML text, as read
  std::vector<Variation> variations;
  int seeds = 1;                    // replicates per point
  std::uint64_t sweep_seed = 0;     // the base of every run's seed
  bool fit = false;                 // also fit JONSWAP to every run
  std::string impl = "radix2";      // transform backend of the synthesis
  impls::Precision precision = impls::Precision::f64;

  std::size_t point_count() const;  // Π values per variation (1 without variations)
  std::size_t run_count() const { return point_count() * std::size_t(seeds); }
  // The sweep as JSON (sweep.json): everything that determines its rows, so that --resume and
  // --merge can refuse work from a different sweep.
  nlohmann::json to_json() const;
  static SweepSpec from_json(const nlohmann::json& document);
};

// Parses one --vary spec, NAME=a:b:n (n values evenly from a to b inclusive) or NAME=v1,v2,…,
// against the base case's text. NAME is a case key: "section.key", or a bare key that names one
// key of the case's sections (the base case's own keys first, then the keys its models accept).
// Throws InvalidInput naming the spec for an unknown or ambiguous key, an empty or malformed
// range, or a key a sweep cannot vary (the seed: replicates are --seeds).
Variation parse_variation(const std::string& spec, const std::string& case_text,
                          const std::filesystem::path& case_path);

// A point of the product: its index (the last variation varies fastest), the value index of
// each variation, and its case (validated by the case file rules).
struct Point {
  std::size_t index = 0;
  std::vector<std::size_t> value_index;  // one per variation
  CaseFile case_file;
};
// Throws InvalidInput naming the --vary key(s) and value(s) when the case rules refuse the point.
Point make_point(const SweepSpec& spec, std::size_t index);
// Builds every point and checks what a run needs (a grid sampling, a backend that takes the
// grid, with --fit a JONSWAP-family spectrum), so that bad specs fail before any work starts.
void validate(const SweepSpec& spec);

// The seed of run (point, replicate): SplitMix64 (Steele, Lea & Flood 2014) over the three
// numbers, so that seeds of neighbouring runs are unrelated and no thread or rank enters it.
std::uint64_t run_seed(std::uint64_t sweep_seed, std::size_t point, int replicate);

// One fitted parameter: the estimate and its 95 % interval (calibrated: an interval swell vouches
// for, docs/fit.md §4).
struct FittedValue {
  double value = 0, ci95_low = 0, ci95_high = 0;
  bool calibrated = false;
};

// What one run produced. Statistics over all samples of all the case's frames (docs/sweeps.md
// §Statistics): hs = 4 √(variance of h); tp, tm01, tm02 from the surface's periodogram mapped
// to ω by the case's dispersion; skewness and excess kurtosis of h; foam_fraction, the share
// of samples with J < 0, and min_jacobian.
struct RunRow {
  std::size_t point = 0;
  int replicate = 0;
  std::uint64_t seed = 0;
  std::map<std::string, double> statistics;
  bool fitted = false;
  std::map<std::string, FittedValue> fit;  // "hs", "tp", "gamma"
  bool fit_converged = false;
  double seconds = 0;  // wall time of the run: the only column that differs between runs
};

// The statistics' names, in output order.
const std::vector<std::string>& statistic_names();

// Synthesizes and measures run (point, replicate).
RunRow run(const SweepSpec& spec, const Point& point, int replicate);

// A row as one JSON object (the journal's lines, runs.json's entries) and back.
nlohmann::json row_json(const SweepSpec& spec, const RunRow& row);
RunRow row_from_json(const nlohmann::json& object);

// Writes DIR/runs.csv, DIR/runs.json, DIR/points.csv, DIR/points.json and the plots
// (DIR/plots/<statistic>_vs_<key>.png with .dat/.gp) from the rows (any order; sorted by point
// and replicate before writing). `gnuplot`: the program, "" for none. Returns notes (figures
// not rendered and why).
std::vector<std::string> write_outputs(const SweepSpec& spec, std::vector<RunRow> rows,
                                       const std::filesystem::path& dir,
                                       const std::string& gnuplot = "gnuplot");

}  // namespace swell::validation::sweep
