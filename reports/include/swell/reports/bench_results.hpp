#pragma once
// Google Benchmark results as swell's reports read them: one BenchmarkRun per benchmark, with
// the time of every repetition, parsed from the JSON that --benchmark_out writes, and the name
// taken apart by swell's naming scheme (bench/*.cpp):
//
//   fft2d/<kind>/<impl>/<precision>/<N>[/real_time]     kind c2c (inverse) or c2r; N² points
//   frame/<impl>/<precision>/<n>[/real_time]             (and frame_packing, frame_transforms)
//   lattice/<impl>/<precision>/<N>                       N points (and lattice_one_pass, …)
//   gate/<N>/<frames>/real_time                          frames of N² samples
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace swell::reports {

struct BenchmarkName {
  std::string family;     // fft2d, frame, frame_packing, lattice, lattice_one_pass, gate, …
  std::string suite;      // fft, frame, lattice, gate (the binary that ran it)
  std::string kind;       // fft2d: c2c | c2r; frame_packing: the packing; else empty
  std::string impl;       // backend with its options ("fftw:threads=2"); empty for gate
  std::string precision;  // fp32 | fp64 | fp80; empty for gate
  long size = 0;          // N of an N² transform or frame, N points of a lattice, gate's N
  long frames = 0;        // gate only
  bool real_time = false; // the name ends in /real_time: wall-clock time is its measure
  // Samples one timed operation covers: N² for 2-D transforms and frames, N for lattices,
  // N²·frames for the gate.
  double points() const;
};

// Throws swell::InvalidInput naming the benchmark when the name follows none of the schemes.
BenchmarkName parse_benchmark_name(const std::string& run_name);

struct BenchmarkRun {
  std::string run_name;  // as Google Benchmark reports it, /real_time included
  BenchmarkName name;
  // Seconds per iteration of every repetition: real_time for /real_time benchmarks, cpu_time
  // (the benchmark thread's CPU time) otherwise — the time each suite documents as its measure.
  std::vector<double> seconds;
  // Each counter's value per repetition (plan_seconds, transforms_ms, GFLOP/s, …).
  std::map<std::string, std::vector<double>> counters;
  std::string label;
  std::string error;  // the skip or error message; seconds is then empty
};

struct BenchmarkFile {
  nlohmann::json context;  // Google Benchmark's "context" block
  std::vector<BenchmarkRun> runs;
};

// Reads one --benchmark_out JSON file. Aggregate rows (mean, median, …) are ignored: the
// statistics are recomputed from the repetitions. Throws InvalidInput naming the file on
// unreadable or malformed JSON.
BenchmarkFile load_benchmark_file(const std::filesystem::path& file);

// The runs of several files of the same suite run in turns (interleaved A B A B…: one
// repetition per file), merged by run name, repetitions in file order.
std::vector<BenchmarkRun> merge_runs(const std::vector<BenchmarkFile>& files);

}  // namespace swell::reports
