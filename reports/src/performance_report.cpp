#include "swell/reports/performance_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "swell/reference/errors.hpp"
#include "swell/reports/bench_results.hpp"
#include "swell/reports/comparison_statistics.hpp"
#include "swell/reports/figures.hpp"

namespace swell::reports {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The drift between runs of the same build (reports/README.md §Comparisons, measured on the
// 2-core development VM, fft suite, fftw and radix2, fp32, 64²–512², 9 repetitions): run back to
// back, 10 of 16 medians differed "significantly" (p < 0.05) by up to 34.5 % (ratios 0.85–1.35);
// interleaved A B A B…, none did (p ≥ 0.16, ratios 0.90–1.14). A smaller effect than the drift
// of the way the runs were made is no evidence of a change.
constexpr double kSeparateRunsThreshold = 0.35;
constexpr double kInterleavedThreshold = 0.10;

// Whether two bench folders are the two halves of one interleaved run.
bool interleaved_pair(const json& run, const json& other_run) {
  return run.value("interleaved_with", std::string()) != "" &&
         other_run.value("interleaved_with", std::string()) != "";
}

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json read_json(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InvalidInput("cannot read " + file.string());
  try {
    return json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput(file.string() + " is not JSON: " + e.what());
  }
}

// Every benchmark of a bench folder: the runs of each suite's file(s), merged.
struct Folder {
  fs::path path;
  json run, context, accuracy;
  std::vector<BenchmarkRun> runs;
};

Folder load_folder(const fs::path& dir) {
  Folder folder;
  folder.path = dir;
  if (!fs::is_directory(dir)) {
    throw InvalidInput("bench folder " + dir.string() + " does not exist (write one with `swell bench --out DIR`)");
  }
  const fs::path bench = dir / "bench";
  if (!fs::is_directory(bench)) {
    throw InvalidInput("bench folder " + dir.string() + " has no bench/ results (expected " +
                       kBenchFolderLayout + ")");
  }
  folder.run = fs::exists(dir / "run.json") ? read_json(dir / "run.json") : json::object();
  folder.context = fs::exists(dir / "context.json") ? read_json(dir / "context.json") : json::object();
  folder.accuracy = fs::exists(dir / "accuracy.json") ? read_json(dir / "accuracy.json") : json::object();
  std::map<std::string, std::vector<fs::path>> by_suite;
  for (const auto& entry : fs::directory_iterator(bench)) {
    if (entry.path().extension() != ".json") continue;
    const std::string stem = entry.path().stem().string();
    by_suite[stem.substr(0, stem.find('.'))].push_back(entry.path());
  }
  if (by_suite.empty()) throw InvalidInput("bench folder " + bench.string() + " holds no .json results");
  for (auto& [suite, files] : by_suite) {
    std::sort(files.begin(), files.end());  // <suite>.round0001.json … in turn order
    std::vector<BenchmarkFile> loaded;
    for (const auto& file : files) loaded.push_back(load_benchmark_file(file));
    auto merged = merge_runs(loaded);
    // The suite is the binary that ran it: the lattice suite also times grid frames
    // (frame/<impl>/<precision>/<n>, its equal-count partners), named as the frame suite's.
    for (auto& run : merged) run.name.suite = suite;
    folder.runs.insert(folder.runs.end(), merged.begin(), merged.end());
  }
  return folder;
}

double counter_median(const BenchmarkRun& run, const std::string& key) {
  const auto found = run.counters.find(key);
  if (found == run.counters.end() || found->second.empty()) return NAN;
  return median(found->second);
}

std::string ms(double seconds) {
  if (!std::isfinite(seconds)) return "—";
  const double v = seconds * 1e3;
  return v >= 100 ? fmt::format("{:.1f}", v) : v >= 1 ? fmt::format("{:.3f}", v) : fmt::format("{:.4f}", v);
}
std::string fixed(double x, int digits) { return std::isfinite(x) ? fmt::format("{:.{}f}", x, digits) : "—"; }
std::string sci(double x) { return std::isfinite(x) ? fmt::format("{:.2e}", x) : "—"; }

// One row of a table: a benchmark's statistics and what its suite adds.
struct Row {
  const BenchmarkRun* run = nullptr;
  Quartiles q{};
};

// The fields every table's JSON row has; each suite adds its own.
json row_json(const Row& r) {
  const auto& n = r.run->name;
  json row = {{"name", r.run->run_name}, {"repetitions", r.run->seconds.size()},
              {"median_s", r.q.median}, {"q1_s", r.q.q1}, {"q3_s", r.q.q3},
              {"iqr_s", r.q.q3 - r.q.q1}};
  if (!n.impl.empty()) {
    row["impl"] = n.impl;
    row["precision"] = n.precision;
  }
  return row;
}

std::string series_key(const BenchmarkName& n) {
  std::string key = n.impl + " " + n.precision;
  if (!n.kind.empty()) key += " " + n.kind;
  return key;
}

void add_point(std::map<std::string, Series>& series, const std::string& title, double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y) || (y <= 0)) return;
  auto& s = series[title];
  s.title = title;
  s.points.emplace_back(x, y);
}

std::vector<Series> sorted_series(std::map<std::string, Series> series) {
  std::vector<Series> out;
  for (auto& [key, s] : series) {
    std::sort(s.points.begin(), s.points.end());
    out.push_back(std::move(s));
  }
  return out;
}

// ------------------------------------------------------------------ accuracy

struct AccuracyKey {
  std::string impl, precision, kind;
  long n;
  auto operator<=>(const AccuracyKey&) const = default;
};

std::map<AccuracyKey, json> accuracy_index(const json& accuracy) {
  std::map<AccuracyKey, json> index;
  if (!accuracy.contains("transforms")) return index;
  for (const auto& row : accuracy["transforms"]) {
    index[{row.value("impl", ""), row.value("precision", ""), row.value("kind", ""), row.value("n", 0L)}] = row;
  }
  return index;
}

double json_double(const json& object, const char* key) {
  return object.contains(key) && object[key].is_number() ? object[key].get<double>() : NAN;
}

}  // namespace

double benchfft_flops(double points, bool real) {
  return (real ? 2.5 : 5.0) * points * std::log2(points);
}

json write_performance_report(const ReportOptions& options) {
  const Folder folder = load_folder(options.bench_dir);
  double threshold = options.threshold;  // set below for a comparison when not given
  if (!(options.alpha > 0 && options.alpha < 1)) {
    throw InvalidInput(fmt::format("significance level {} must lie in (0, 1)", options.alpha));
  }
  std::error_code error;
  fs::create_directories(options.out / "figures", error);
  if (error) throw InvalidInput("cannot create report folder " + options.out.string() + ": " + error.message());

  const bool gnuplot_found = program_found(options.gnuplot);
  std::vector<std::string> notes, problems;
  if (!gnuplot_found) {
    notes.push_back(fmt::format(
        "gnuplot ({}) was not found: the figures' data (.dat) and scripts (.gp) are written, "
        "their PNGs are not (install gnuplot-nox and run `gnuplot NAME.gp` in figures/, or run "
        "`swell report` again)", options.gnuplot.empty() ? "none given" : options.gnuplot));
  }

  json report;
  report["source"] = fs::absolute(options.bench_dir).string();
  report["run"] = folder.run;
  report["context"] = folder.context;
  report["time_convention"] =
      "seconds per operation; real time for benchmarks named …/real_time, else the benchmark "
      "thread's CPU time (bench/*.cpp say which each suite uses); statistics over repetitions";
  report["gflops_convention"] =
      "benchFFT's: 5 N log2 N / t for complex transforms, 2.5 N log2 N / t for real ones (N = "
      "points of the transform; http://www.fftw.org/speed/method.html)";

  // ---- rows per suite
  std::map<std::string, std::vector<Row>> rows;
  json skipped = json::array();
  int fewest_repetitions = 1 << 30;
  for (const auto& run : folder.runs) {
    if (run.seconds.empty()) {
      skipped.push_back({{"name", run.run_name}, {"reason", run.error.empty() ? "no repetitions" : run.error}});
      continue;
    }
    fewest_repetitions = std::min<int>(fewest_repetitions, int(run.seconds.size()));
    Row row;
    row.run = &run;
    row.q = quartiles(run.seconds);
    rows[run.name.suite].push_back(row);
  }
  for (auto& [suite, list] : rows) {
    std::sort(list.begin(), list.end(), [](const Row& a, const Row& b) {
      const auto& x = a.run->name;
      const auto& y = b.run->name;
      return std::tie(x.family, x.kind, x.precision, x.size, x.frames, x.impl) <
             std::tie(y.family, y.kind, y.precision, y.size, y.frames, y.impl);
    });
  }
  if (fewest_repetitions < kRecommendedRepetitions && fewest_repetitions != (1 << 30)) {
    notes.push_back(fmt::format(
        "some benchmarks have only {} repetitions: Google Benchmark's compare.py trusts its U "
        "test from {} on, and the interquartile ranges of so few are rough", fewest_repetitions,
        kRecommendedRepetitions));
  }

  std::ostringstream md;
  md << "# swell performance report\n\n";
  const json& ctx = folder.context;
  const auto ctx_str = [&](const char* a, const char* b) {
    return ctx.contains(a) && ctx[a].contains(b) ? (ctx[a][b].is_string() ? ctx[a][b].get<std::string>() : ctx[a][b].dump()) : std::string("unknown");
  };
  md << "From `" << options.bench_dir.string() << "`";
  if (folder.run.contains("started")) md << ", run " << folder.run["started"].get<std::string>();
  md << ".\n\n| | |\n|---|---|\n";
  md << "| CPU | " << ctx_str("cpu", "model") << " (" << ctx_str("cpu", "logical_cores") << " logical cores; SIMD: " << ctx_str("cpu", "simd") << ") |\n";
  if (ctx.contains("cpu") && ctx["cpu"].contains("caches")) {
    std::string caches;
    for (const auto& c : ctx["cpu"]["caches"]) {
      caches += (caches.empty() ? "" : ", ") + std::string("L") + c.value("level", "?") + " " +
                c.value("type", "") + " " + c.value("size", "");
    }
    md << "| caches | " << caches << " |\n";
  }
  md << "| frequency scaling | governor " << (ctx.contains("cpu") ? ctx["cpu"].value("frequency_scaling", json::object()).value("governor", std::string("unknown")) : "unknown") << " |\n";
  md << "| memory | " << (ctx.contains("memory") ? fmt::format("{:.1f} GiB", ctx["memory"].value("total_bytes", 0.0) / (1 << 30)) : "unknown") << " |\n";
  std::string load = "unknown";
  if (ctx.contains("load_average") && ctx["load_average"].is_array() && ctx["load_average"].size() == 3) {
    load = fmt::format("{:.2f}, {:.2f}, {:.2f} (1, 5, 15 min)", ctx["load_average"][0].get<double>(),
                       ctx["load_average"][1].get<double>(), ctx["load_average"][2].get<double>());
  }
  md << "| load average at start | " << load << " |\n";
  md << "| compiler | " << ctx_str("build", "compiler") << ", " << ctx_str("build", "build_type") << ", flags `" << ctx_str("build", "flags") << "` |\n";
  md << "| swell | commit " << ctx_str("build", "git_commit") << (ctx.contains("build") && ctx["build"].value("git_dirty", false) ? " (with uncommitted changes)" : "") << " |\n";
  md << "| libraries | FFTW " << ctx_str("libraries", "fftw") << "; OpenImageIO " << ctx_str("libraries", "openimageio") << "; Ceres " << ctx_str("libraries", "ceres") << "; Google Benchmark " << ctx_str("libraries", "google_benchmark") << "; Vulkan loader " << ctx_str("libraries", "vulkan_loader") << " |\n";
  md << "| Vulkan device | " << ctx_str("libraries", "vulkan_device") << " |\n\n";
  md << "Times are medians over the repetitions with their interquartile range (IQR = q3 − q1); "
     << report["time_convention"].get<std::string>() << ". GFLOP/s follow "
     << report["gflops_convention"].get<std::string>() << ".\n\n";

  const fs::path figures = options.out / "figures";
  json figure_entries = json::array();
  const auto figure = [&](const Figure& f) {
    figure_entries.push_back(write_figure(f, figures, options.gnuplot, gnuplot_found, problems));
  };

  // ---- fft
  const auto accuracy = accuracy_index(folder.accuracy);
  if (rows.count("fft")) {
    auto& list = rows["fft"];
    std::map<std::tuple<std::string, std::string, long>, double> fftw_median;
    for (const auto& r : list) {
      if (r.run->name.impl == "fftw") fftw_median[{r.run->name.kind, r.run->name.precision, r.run->name.size}] = r.q.median;
    }
    json table = json::array();
    md << "## 2-D transforms (swell_fft_bench)\n\n"
       << "| N | backend | precision | kind | median ms | IQR ms | GFLOP/s | ratio to FFTW | floor fraction | kernel fraction | rel. L2 error | bound | plan s | reps |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::map<std::string, Series> time_series, gflops_series, ratio_series, error_series, bound_series;
    for (auto& r : list) {
      const auto& n = r.run->name;
      const bool real = n.kind == "c2r" || n.kind == "r2c";
      // null copies and transforms nothing: a flop rate would be meaningless.
      const bool copies = n.impl.substr(0, n.impl.find(':')) == "null" || n.impl == "copy";
      // The roofline: the copy of the same bytes over this transform's time (1 = bandwidth-bound).
      const double floor_fraction = counter_median(*r.run, "floor_fraction");
      // The arithmetic roof (radix2 c2c only): its butterflies at its best kernel's rate, over
      // this transform's time (docs/performance.md §1).
      const double kernel_fraction = counter_median(*r.run, "kernel_floor_fraction");
      const double gflops = copies ? NAN : benchfft_flops(n.points(), real) / r.q.median * 1e-9;
      const auto base = fftw_median.find({n.kind, n.precision, n.size});
      const double ratio = base != fftw_median.end() ? r.q.median / base->second : NAN;
      const auto acc = accuracy.find({n.impl, n.precision, n.kind, n.size});
      const double rel_l2 = acc != accuracy.end() ? json_double(acc->second, "rel_l2") : NAN;
      const double rel_linf = acc != accuracy.end() ? json_double(acc->second, "rel_linf") : NAN;
      const double bound = acc != accuracy.end() ? json_double(acc->second, "bound") : NAN;
      const double plan = counter_median(*r.run, "plan_seconds");
      md << fmt::format("| {}² | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", n.size,
                        n.impl, n.precision, n.kind, ms(r.q.median), ms(r.q.q3 - r.q.q1),
                        fixed(gflops, 2), fixed(ratio, 2), fixed(floor_fraction, 3), fixed(kernel_fraction, 3), sci(rel_l2), sci(bound),
                        std::isfinite(plan) ? fmt::format("{:.3g}", plan) : "—", r.run->seconds.size());
      json row = row_json(r);
      row.update({{"kind", n.kind}, {"n", n.size}, {"points", n.points()},
                  {"gflops", number(gflops)}, {"ratio_to_fftw", number(ratio)},
                  {"floor_fraction", number(floor_fraction)},
                  {"kernel_floor_fraction", number(kernel_fraction)},
                  {"rel_l2", number(rel_l2)}, {"rel_linf", number(rel_linf)},
                  {"bound", number(bound)}, {"plan_s", number(plan)}});
      table.push_back(row);
      const std::string key = series_key(n);
      add_point(time_series, key, double(n.size), r.q.median * 1e3);
      add_point(gflops_series, key, double(n.size), gflops);
      if (n.impl != "fftw") add_point(ratio_series, key, double(n.size), ratio);
      add_point(error_series, key, double(n.size), rel_l2);
      if (std::isfinite(bound)) add_point(bound_series, "bound " + n.precision, double(n.size), bound);
    }
    md << "\n";
    report["fft"] = table;
    figure({"fft_time", "2-D transform time against size", "n (n × n transform)", "median time (ms)",
            "Median time of one transform against n, log–log, one line per backend, precision and kind: "
            "an O(n² log n) transform climbs a little faster than 4× per doubling of n.",
            true, true, false, sorted_series(time_series)});
    figure({"fft_gflops", "2-D transform speed (benchFFT GFLOP/s)", "n (n × n transform)", "GFLOP/s",
            "benchFFT's GFLOP/s (5 N log2 N / t, half for c2r): flat lines are transforms whose speed "
            "does not depend on size; drops mark sizes that leave a cache.",
            true, false, false, sorted_series(gflops_series)});
    figure({"fft_ratio_to_fftw", "Time relative to FFTW (same kind, precision and size)",
            "n (n × n transform)", "time / FFTW time",
            "Each backend's median over FFTW's at the same n: below 1 is faster than FFTW.", true,
            true, false, sorted_series(ratio_series)});
    auto errors = sorted_series(error_series);
    for (auto& s : sorted_series(bound_series)) {
      s.dashed = true;
      errors.push_back(std::move(s));
    }
    figure({"fft_error", "Accuracy against the long-double oracle", "n (n × n transform)",
            "relative L2 error",
            "Relative L2 error of each backend's transform of seeded random input against the "
            "long-double oracle (swell check transforms), with the bound c·ε·log2 N it is held to "
            "(dashed).",
            true, true, true, errors});
  }

  // ---- frames
  if (rows.count("frame")) {
    json table = json::array();
    md << "## Frames (swell_frame_bench)\n\n"
       << "| N | benchmark | backend | precision | median ms | IQR ms | bare transforms ms | frame / transforms | reps |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    std::map<std::string, Series> cost_series;
    for (auto& r : rows["frame"]) {
      const auto& n = r.run->name;
      const double transforms = counter_median(*r.run, "transforms_ms") * 1e-3;
      const double over = transforms > 0 ? r.q.median / transforms : NAN;
      md << fmt::format("| {}² | {} | {} | {} | {} | {} | {} | {} | {} |\n", n.size, n.family + (n.kind.empty() ? "" : " " + n.kind),
                        n.impl, n.precision, ms(r.q.median), ms(r.q.q3 - r.q.q1), ms(transforms),
                        fixed(over, 2), r.run->seconds.size());
      json row = row_json(r);
      row.update({{"family", n.family}, {"n", n.size}, {"transforms_s", number(transforms)},
                  {"frame_over_transforms", number(over)}});
      table.push_back(row);
      if (n.family == "frame") add_point(cost_series, series_key(n), double(n.size), over);
    }
    md << "\n";
    report["frame"] = table;
    figure({"frame_cost", "Frame time over its bare transforms", "n (n × n grid)", "frame / bare transforms",
            "A whole frame (spectrum at t, the transforms, the six fields) over the same frame's "
            "bare transforms timed beside it: 1 would be a frame that costs only its transforms.",
            true, false, false, sorted_series(cost_series)});
  }

  // ---- lattices
  if (rows.count("lattice")) {
    json table = json::array();
    md << "## Lattice frames (swell_lattice_bench)\n\n"
       << "| points | benchmark | backend | precision | median ms | IQR ms | ns per point | alias-free fraction | reps |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    for (auto& r : rows["lattice"]) {
      const auto& n = r.run->name;
      const double per_point = r.q.median / n.points() * 1e9;
      const double fraction = counter_median(*r.run, "alias_free_fraction");
      md << fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", long(n.points()), n.family,
                        n.impl, n.precision, ms(r.q.median), ms(r.q.q3 - r.q.q1), fixed(per_point, 1),
                        fixed(fraction, 3), r.run->seconds.size());
      json row = row_json(r);
      row.update({{"family", n.family}, {"points", n.points()}, {"ns_per_point", per_point},
                  {"alias_free_fraction", number(fraction)}});
      table.push_back(row);
    }
    md << "\n";
    report["lattice"] = table;
  }

  // ---- gate
  if (rows.count("gate")) {
    json table = json::array();
    md << "## The gate (swell_gate_bench)\n\n"
       << "| benchmark | N | frames | median s | IQR s | reading s | judging s | reps |\n"
          "|---|---|---|---|---|---|---|---|\n";
    for (auto& r : rows["gate"]) {
      const auto& n = r.run->name;
      const double read = counter_median(*r.run, "read_s"), judge = counter_median(*r.run, "judge_s");
      md << fmt::format("| {} | {}² | {} | {:.3f} | {:.3f} | {} | {} | {} |\n",
                        n.family == "gate" ? "one surface" : "three cascades", n.size, n.frames,
                        r.q.median,
                        r.q.q3 - r.q.q1, fixed(read, 3), fixed(judge, 3), r.run->seconds.size());
      json row = row_json(r);
      row.update({{"benchmark", n.family}, {"n", n.size}, {"frames", n.frames}, {"read_s", number(read)},
                  {"judge_s", number(judge)}});
      table.push_back(row);
    }
    md << "\n";
    report["gate"] = table;
  }

  // ---- comparison
  if (!options.against.empty()) {
    const Folder other = load_folder(options.against);
    std::string threshold_reason = "given with --threshold";
    if (!(options.threshold > 0)) {
      const bool pair = interleaved_pair(folder.run, other.run);
      threshold = pair ? kInterleavedThreshold : kSeparateRunsThreshold;
      threshold_reason = pair ? "the default for the two halves of one interleaved run"
                              : "the default for separately made runs (run them interleaved, "
                                "swell bench --interleave, to resolve smaller changes)";
    }
    std::map<std::string, const BenchmarkRun*> theirs;
    for (const auto& run : other.runs) {
      if (!run.seconds.empty()) theirs[run.name.suite + " " + run.run_name] = &run;
    }
    json comparison;
    comparison["against"] = fs::absolute(options.against).string();
    comparison["threshold"] = threshold;
    comparison["threshold_reason"] = threshold_reason;
    comparison["alpha"] = options.alpha;
    comparison["rule"] = fmt::format(
        "faster: p < {} and ratio < 1/(1 + {}); slower: p < {} and ratio > 1 + {}; otherwise no "
        "significant change (ratio = this run's median / the other's)",
        options.alpha, threshold, options.alpha, threshold);
    json compared = json::array();
    std::vector<double> ratios;
    int faster = 0, slower = 0, unchanged = 0;
    md << "## Compared with `" << options.against.string() << "`\n\n"
       << "Ratio = this run's median / the other run's (below 1: faster now). p: two-sided "
          "Mann–Whitney U over the repetitions (normal approximation with tie and continuity "
          "corrections, as Google Benchmark's compare.py via scipy). A verdict of faster or slower "
          "needs p < "
       << options.alpha << " **and** a ratio beyond 1 + " << threshold << " or below 1/(1 + "
       << threshold << "); threshold " << threshold << ": " << threshold_reason
       << " (the drift between identical runs on a shared machine, reports/README.md).\n\n"
       << "| benchmark | median ms | other median ms | ratio | p | verdict |\n|---|---|---|---|---|---|\n";
    std::map<std::string, Series> ratio_points;
    int position = 0;
    for (const auto& run : folder.runs) {
      if (run.seconds.empty()) continue;
      const auto found = theirs.find(run.name.suite + " " + run.run_name);
      if (found == theirs.end()) continue;
      const BenchmarkRun& old = *found->second;
      const double mine = median(run.seconds), before = median(old.seconds);
      const double ratio = mine / before;
      const MannWhitney test = mann_whitney_u(run.seconds, old.seconds);
      std::string verdict = "no significant change";
      if (test.p_value < options.alpha && ratio > 1 + threshold) verdict = "slower";
      if (test.p_value < options.alpha && ratio < 1 / (1 + threshold)) verdict = "faster";
      std::string warning;
      if (int(std::min(run.seconds.size(), old.seconds.size())) < kRecommendedRepetitions) {
        warning = fmt::format("{} and {} repetitions: fewer than the {} the U test needs to be trusted",
                              run.seconds.size(), old.seconds.size(), kRecommendedRepetitions);
      }
      (verdict == "faster" ? faster : verdict == "slower" ? slower : unchanged)++;
      ratios.push_back(ratio);
      md << fmt::format("| {} | {} | {} | {:.3f} | {:.2g} | {}{} |\n", run.run_name, ms(mine), ms(before),
                        ratio, test.p_value, verdict, warning.empty() ? "" : " ⚠");
      compared.push_back({{"name", run.run_name}, {"median_s", mine}, {"other_median_s", before},
                          {"ratio", ratio}, {"p_value", test.p_value}, {"u", std::min(test.u1, test.u2)},
                          {"repetitions", run.seconds.size()}, {"other_repetitions", old.seconds.size()},
                          {"verdict", verdict}, {"warning", warning}});
      add_point(ratio_points, verdict, double(++position), ratio);
    }
    const double geomean = ratios.empty() ? NAN : geometric_mean(ratios);
    comparison["rows"] = compared;
    comparison["faster"] = faster;
    comparison["slower"] = slower;
    comparison["unchanged"] = unchanged;
    comparison["geometric_mean_ratio"] = number(geomean);
    report["comparison"] = comparison;
    md << fmt::format("\n**{} faster, {} slower, {} without significant change; geometric mean of the "
                      "ratios {}** (as rocFFT's performance scripts summarize).\n\n",
                      faster, slower, unchanged, fixed(geomean, 3));
    if (compared.empty()) notes.push_back("the two runs share no benchmark: nothing was compared");
    Figure f{"comparison_ratios", "This run over the other, per benchmark", "benchmark (in the table's order)",
             "median ratio (this / other)",
             "Ratio of medians per benchmark, in the order of the comparison table, coloured by verdict; "
             "the dashed lines are 1 ± the threshold.",
             false, true, true, sorted_series(ratio_points)};
    if (position > 0) {
      f.series.push_back({fmt::format("1 + {}", threshold), {{1, 1 + threshold}, {double(position), 1 + threshold}}, true, {}});
      f.series.push_back({fmt::format("1 / (1 + {})", threshold), {{1, 1 / (1 + threshold)}, {double(position), 1 / (1 + threshold)}}, true, {}});
    }
    figure(f);
  }

  // ---- figures, skipped, notes
  md << "## Figures\n\n";
  for (const auto& f : figure_entries) {
    md << "### " << f["title"].get<std::string>() << "\n\n" << f["description"].get<std::string>() << "\n\n";
    if (f["rendered"].get<bool>()) {
      md << "![" << f["title"].get<std::string>() << "](figures/" << f["png"].get<std::string>() << ")\n\n";
    } else {
      md << "(not rendered: figures/" << f["data"].get<std::string>() << " and figures/"
         << f["script"].get<std::string>() << " are written)\n\n";
    }
  }
  if (!skipped.empty()) {
    md << "## Skipped\n\n";
    for (const auto& s : skipped) md << "- `" << s["name"].get<std::string>() << "`: " << s["reason"].get<std::string>() << "\n";
    md << "\n";
  }
  for (const auto& p : problems) notes.push_back("gnuplot failed on " + p);
  if (!notes.empty()) {
    md << "## Notes\n\n";
    for (const auto& n : notes) md << "- " << n << "\n";
  }
  report["figures"] = figure_entries;
  report["skipped"] = skipped;
  report["notes"] = notes;
  report["gnuplot"] = gnuplot_found ? "found: " + options.gnuplot : "not found: " + options.gnuplot;

  std::ofstream(options.out / "README.md") << md.str();
  std::ofstream(options.out / "report.json") << report.dump(2) << "\n";
  if (!fs::exists(options.out / "report.json")) {
    throw InvalidInput("cannot write the report into " + options.out.string());
  }
  return report;
}

}  // namespace swell::reports
