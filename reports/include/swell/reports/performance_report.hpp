#pragma once
// `swell report`: a folder of `swell bench` results (docs: reports/README.md) made into a
// report — README.md and report.json with the same numbers, and gnuplot figures (PNG, with the
// .dat and .gp beside each so a person can restyle it) — optionally compared with another
// run: ratio of medians, two-sided Mann–Whitney U p-value, and a verdict that needs both
// significance and an effect beyond a stated threshold.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace swell::reports {

// Layout of a bench folder (what `swell bench --out DIR` writes):
//   DIR/run.json        what was asked (suites, implementations, sizes, repetitions) and when
//   DIR/context.json    machine_context()
//   DIR/bench/<suite>.json, or <suite>.round<k>.json for interleaved runs: Google Benchmark's
//                       --benchmark_out of swell_<suite>_bench
//   DIR/accuracy.json   {"transforms": [{impl, precision, kind, n, rel_l2, rel_linf, bound,
//                       oracle}]} for the fft suite's backends and sizes
inline constexpr const char* kBenchFolderLayout =
    "run.json, context.json, bench/<suite>.json, accuracy.json";

struct ReportOptions {
  std::filesystem::path bench_dir;
  std::filesystem::path against;     // empty: no comparison
  std::filesystem::path out;         // the report folder
  // A change counts as faster or slower only when p < alpha and the ratio of medians is
  // beyond 1 ± threshold (docs in reports/README.md §Comparisons: the default comes from the
  // drift measured between identical runs on this machine).
  double threshold = 0.0;            // 0: 0.35 for separate runs, 0.10 for an interleaved pair
  double alpha = 0.05;
  std::string gnuplot = "gnuplot";   // the program; "" never renders
};

// The fewest repetitions Google Benchmark's compare.py trusts for its U test.
inline constexpr int kRecommendedRepetitions = 9;

// Writes out/README.md, out/report.json and out/figures/; returns report.json's document.
// Throws swell::InvalidInput naming the file or folder when a bench folder is missing or
// malformed.
nlohmann::json write_performance_report(const ReportOptions& options);

// benchFFT's flop count convention: 5 N log2 N for a complex transform of N points, half that
// for a real one (http://www.fftw.org/speed/method.html).
double benchfft_flops(double points, bool real);

}  // namespace swell::reports
