// Speed of probe series (docs/probes.md): the gate on a probes case, and the synthesis of its
// series.
//
//   probe_gate/<probes>/<samples>/real_time   run_gate(case.toml): reading the CSV series and
//                                             judging them (every series check), wall clock
//   probe_synth/<probes>/<samples>            probe_wave_lines + synthesize_probe_series
//   probe_moments/<probes>/<samples>          series.skewness and series.kurtosis alone (their
//                                             simulated null and the probes' moments), on
//                                             series held in memory
//
// The case is the OpenFAST sea: JONSWAP Hs 3 m, Tp 10 s, γ 3.3 in 30 m of water, cos-2s
// s = 10 toward 30°, Rayleigh amplitudes, 15 directions per frequency, uniform lines over
// [0, 6] rad/s repeating after the record, dt 0.25 s; the probes 10 m apart along x. The target:
// probe_gate/9/43200 (three hours at 4 Hz on nine probes) under 2 s on 2 cores. The series are
// written once per size into a temporary directory, removed at exit.
//
//   build/bench/swell_probe_bench --benchmark_filter=probe_gate/9/43200 --benchmark_repetitions=5
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "checks/probes/skewness_kurtosis.hpp"
#include "swell/impls/probe_synthesis.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/probe_series.hpp"

namespace {

namespace fs = std::filesystem;

swell::validation::CaseFile probe_case_file(int probes, int samples) {
  swell::validation::CaseFile c;
  c.ocean.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 10.0}, {"gamma", 3.3}}, {}};
  c.ocean.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.ocean.wind_dir_deg = 30;
  c.ocean.depth = 30;
  c.ocean.seed = 1;
  c.probes.emplace();
  auto& layout = c.probes->layout;
  for (int p = 0; p < probes; ++p) layout.positions.push_back({10.0 * p, 0.0});
  layout.dt = 0.25;
  layout.samples = std::size_t(samples);
  c.ocean.dt = layout.dt;
  auto& s = c.probes->synthesis;
  s.amplitudes = swell::reference::ProbeAmplitudes::rayleigh;
  s.frequencies = swell::reference::ProbeFrequencies::uniform;
  s.repeat_period = layout.duration();
  s.omega_low = 0;
  s.omega_high = 6;
  s.directions = swell::reference::ProbeDirections::double_summation;
  s.n_directions = 15;
  return c;
}

// The case written once per size: its directory.
struct Written {
  fs::path root = fs::temp_directory_path() / ("swell_probe_bench_" + std::to_string(::getpid()));
  std::map<std::string, fs::path> cases;
  ~Written() {
    std::error_code ignored;
    fs::remove_all(root, ignored);
  }
  fs::path get(int probes, int samples) {
    const std::string key = std::to_string(probes) + "_" + std::to_string(samples);
    if (auto it = cases.find(key); it != cases.end()) return it->second;
    const fs::path dir = root / key;
    fs::create_directories(dir);
    auto c = probe_case_file(probes, samples);
    const auto probe_case = c.probe_case();
    const auto series = swell::impls::synthesize_probe_series(
        probe_case, swell::reference::probe_wave_lines(probe_case, c.ocean.seed), 2);
    std::vector<std::string> names;
    for (int p = 0; p < probes; ++p) names.push_back("probe" + std::to_string(p));
    swell::validation::write_probe_series_csv(dir / "elevation.csv", probe_case.layout, series, names);
    c.probes->input = {"elevation.csv", "time", names};
    swell::validation::write_case_file(dir / "case.toml", c);
    return cases[key] = dir / "case.toml";
  }
};

Written& written() {
  static Written instance;
  return instance;
}

void probe_gate(benchmark::State& state) {
  const int probes = int(state.range(0)), samples = int(state.range(1));
  const fs::path case_path = written().get(probes, samples);
  for (auto _ : state) {
    const auto report = swell::validation::run_gate(case_path);
    if (!report.passed()) state.SkipWithError("the right series failed the gate");
    benchmark::DoNotOptimize(report.results.size());
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(probes) * samples, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(probe_gate)->Args({3, 4096})->Args({9, 43200})->UseRealTime()->Unit(benchmark::kMillisecond);

void probe_synth(benchmark::State& state) {
  const int probes = int(state.range(0)), samples = int(state.range(1));
  const auto c = probe_case_file(probes, samples);
  const auto probe_case = c.probe_case();
  for (auto _ : state) {
    const auto lines = swell::reference::probe_wave_lines(probe_case, c.ocean.seed);
    const auto series = swell::impls::synthesize_probe_series(probe_case, lines, 2);
    benchmark::DoNotOptimize(series.data());
  }
}
BENCHMARK(probe_synth)->Args({3, 4096})->Args({9, 43200})->UseRealTime()->Unit(benchmark::kMillisecond);

void probe_moments(benchmark::State& state) {
  const int probes = int(state.range(0)), samples = int(state.range(1));
  const auto c = probe_case_file(probes, samples);
  const auto probe_case = c.probe_case();
  const auto series = swell::impls::synthesize_probe_series(
      probe_case, swell::reference::probe_wave_lines(probe_case, c.ocean.seed), 2);
  for (auto _ : state) {
    swell::validation::ProbeCheckReport report;
    swell::validation::skewness_and_kurtosis(probe_case, series, 0.01, report);
    if (!swell::validation::all_passed(report.results)) state.SkipWithError("the right series failed its moments");
    benchmark::DoNotOptimize(report.results.size());
  }
}
BENCHMARK(probe_moments)->Args({3, 4096})->Args({9, 43200})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
