// Speed of `swell gate` (docs/gate.md): run_gate(case.toml) — reading the case and its EXR
// frames and judging them with every check — on F frames of N² written once per size.
//
//   gate/<N>/<F>/real_time    F frames of N², fp32 EXR with all six fields (as `swell synth`
//                             writes them), timed by the wall clock
//   gate_cascades/<N>/<F>/real_time
//                             a set of three additive cascades of N² each, patches 1600, 400
//                             and 100 m, bands [0, 0.2), [0.2, 0.8), [0.8, 6.4) rad/m
//                             (data/cases/three_cascades.toml), F frames each, judged per
//                             cascade and as a set (target: gate_cascades/256/16 under 1 s
//                             with 2 threads)
//
// Setup, not timed: the frames of a JONSWAP case (Hs 3 m, Tp 8 s, γ 3.3, cos2s s = 10, 1000 m
// patch, dt 0.1 s) are synthesized once in fp32 through FFTW and written as EXR with their
// case.toml into a temporary directory, removed at exit. The target: gate/512/64 under 1.0 s
// with 2 threads on the 2-core reference machine, with the reports GateGolden in
// swell_gate_catalogue_tests holds.
//
// Counters per run: read_s (case and frames) and judge_s (the checks), wall clock; cpu_s, the
// CPU time of every thread (on a shared machine real_time grows with the others' load, cpu_s
// much less: on an idle machine real_time approaches cpu_s / threads); threads.
// SWELL_GATE_THREADS sets GateOptions::threads (default 2; 0 = every hardware thread). Read
// real_time: the gate runs on several threads, which cpu_time misses. FFTW wisdom on disk does
// not change these figures: the gate's analysis plans with FFTW's estimate planner, which no
// longer loads it (before 83ae62c it did, and runs on a machine with cached wisdom were faster
// than a fresh machine's: docs/performance.md §6).
//
//   gate_floor/<N>/<F>/real_time
//                             the floor a gate cannot beat: the same frames read one at a time
//                             and every field of each transformed once (the analysis
//                             transform, fp64 FFTW), nothing kept
//
// Both carry peak_MB, the run's peak resident memory, and rise_MB, its rise over what the
// process held before (peak_memory.hpp); frames_MB, the frames' fields as stored (float32). From
// 2048² on, the frames hold h, dx and dy only (a film pipeline's displacement maps).
//
//   build/bench/swell_gate_bench --benchmark_filter=gate/512/64 --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "bench_support.hpp"
#include "peak_memory.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/gate/gate.hpp"

namespace {

namespace fs = std::filesystem;
using swell::reference::OceanCase;

bool any_failed = false;

// CPU seconds of the whole process, every thread, user and system.
double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

int gate_threads() {
  const char* value = std::getenv("SWELL_GATE_THREADS");
  return value && *value ? std::atoi(value) : 2;
}

OceanCase bench_case(int n, int frames) { return swell::bench::jonswap_bench_case(n, frames, 0.1); }

// All six fields up to 1024²; h, dx and dy from 2048² on.
std::vector<swell::reference::Field> bench_fields(int n) {
  using swell::reference::Field;
  if (n >= 2048) return {Field::height, Field::disp_x, Field::disp_y};
  return {swell::reference::kAllFields.begin(), swell::reference::kAllFields.end()};
}

void set_memory_counters(benchmark::State& state, const swell::bench::PeakMemory& memory, int n, int frames) {
  constexpr double kMB = 1e6;
  state.counters["peak_MB"] = memory.peak_bytes() / kMB;
  state.counters["rise_MB"] = memory.rise_bytes() / kMB;
  state.counters["frames_MB"] = double(n) * n * 4.0 * double(bench_fields(n).size()) * frames / kMB;
}

// One directory of frames per (N, F), made on first use and removed at exit.
class FrameDirectories {
 public:
  ~FrameDirectories() {
    std::error_code error;
    for (const auto& [key, directory] : made_) fs::remove_all(directory, error);
  }
  fs::path case_file(int n, int frames) {
    const std::string key = std::to_string(n) + "/" + std::to_string(frames);
    const auto fields = bench_fields(n);
    if (auto it = made_.find(key); it != made_.end()) return it->second / "case.toml";
    const fs::path directory = fs::temp_directory_path() /
                               ("swell_gate_bench_" + std::to_string(getpid()) + "_" +
                                std::to_string(n) + "_" + std::to_string(frames));
    made_[key] = directory;
    swell::validation::CaseFile case_file;
    case_file.ocean = bench_case(n, frames);
    swell::impls::SynthesizerOptions options;
    options.precision = swell::impls::Precision::f32;
    const swell::impls::Synthesizer synthesizer(case_file.ocean, options);
    swell::validation::FrameWriteOptions write;
    write.format = swell::validation::FrameFormat::exr;
    for (int f = 0; f < frames; ++f) {
      auto frame = synthesizer.frame(case_file.ocean.time(f));
      std::erase_if(frame.fields, [&](const auto& entry) {
        return std::find(fields.begin(), fields.end(), entry.first) == fields.end();
      });
      swell::validation::write_frame(directory, case_file.ocean.grid, frame, f, write);
    }
    case_file.input = swell::validation::frame_input_spec(fields, write);
    swell::validation::write_case_file(directory / "case.toml", case_file);
    return directory / "case.toml";
  }

 private:
  std::map<std::string, fs::path> made_;
};

// The three-cascade set of data/cases/three_cascades.toml at N² per cascade, F frames, its
// frames written as `swell synth` writes a set (cascade0/, cascade1/, cascade2/).
fs::path cascade_case_file(int n, int frames) {
  static std::map<std::string, fs::path> made;
  static struct Cleanup {
    ~Cleanup() {
      std::error_code error;
      for (const auto& [key, directory] : made) fs::remove_all(directory, error);
    }
  } cleanup;
  const std::string key = std::to_string(n) + "/" + std::to_string(frames);
  if (auto it = made.find(key); it != made.end()) return it->second / "case.toml";
  const fs::path directory = fs::temp_directory_path() /
                             ("swell_gate_cascades_bench_" + std::to_string(getpid()) + "_" + std::to_string(n) +
                              "_" + std::to_string(frames));
  made[key] = directory;
  std::string text =
      "[time]\ndt = 0.25\nframes = " + std::to_string(frames) +
      "\n[spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 8.0\ngamma = 3.3\n"
      "[spreading]\nmodel = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n"
      "[synthesis]\nchoppiness = 0.8\nseed = 3\n[cascades]\nrelation = \"additive\"\n";
  const double lengths[3] = {1600, 400, 100}, edges[4] = {0, 0.2, 0.8, 6.4};
  for (int c = 0; c < 3; ++c) {
    text += "[[cascade]]\nn = " + std::to_string(n) + "\nlength = " + std::to_string(lengths[c]) +
            "\nband = [" + std::to_string(edges[c]) + ", " + std::to_string(edges[c + 1]) + "]\n";
  }
  auto case_file = swell::validation::parse_case_toml(text, directory / "case.toml");
  swell::impls::SynthesizerOptions options;
  options.precision = swell::impls::Precision::f32;
  swell::validation::FrameWriteOptions write;
  write.format = swell::validation::FrameFormat::exr;
  std::vector<swell::reference::Field> fields(swell::reference::kAllFields.begin(),
                                              swell::reference::kAllFields.end());
  for (std::size_t c = 0; c < case_file.cascades.size(); ++c) {
    const auto ocean = case_file.cascade_case(c);
    const swell::impls::Synthesizer synthesizer(ocean, options);
    const fs::path folder = directory / ("cascade" + std::to_string(c));
    fs::create_directories(folder);
    for (int f = 0; f < frames; ++f) {
      swell::validation::write_frame(folder, ocean.grid, synthesizer.frame(ocean.time(f)), f, write);
    }
    auto input = swell::validation::frame_input_spec(fields, write);
    input.files = "cascade" + std::to_string(c) + "/" + input.files;
    case_file.cascades[c].input = input;
  }
  swell::validation::write_case_file(directory / "case.toml", case_file);
  return directory / "case.toml";
}

FrameDirectories& directories() {
  static FrameDirectories instance;
  return instance;
}

void run_gate_bench(benchmark::State& state, int n, int frames, bool cascades) {
  fs::path case_path;
  try {
    case_path = cascades ? cascade_case_file(n, frames) : directories().case_file(n, frames);
  } catch (const std::exception& e) {
    any_failed = true;
    state.SkipWithError(e.what());
    return;
  }
  swell::validation::GateOptions options;
  options.threads = gate_threads();
  double read = 0, total = 0, cpu = 0;
  bool passed = true;
  const swell::bench::PeakMemory memory;
  for (auto _ : state) {
    try {
      const double cpu_start = process_cpu_seconds();
      const auto report = swell::validation::run_gate(case_path, options);
      cpu += process_cpu_seconds() - cpu_start;
      read += report.read_seconds;
      total += report.seconds;
      passed = passed && report.passed();
    } catch (const std::exception& e) {
      any_failed = true;
      state.SkipWithError(e.what());
      return;
    }
  }
  const double iterations = double(state.iterations());
  state.counters["read_s"] = read / iterations;
  state.counters["judge_s"] = (total - read) / iterations;
  state.counters["cpu_s"] = cpu / iterations;
  state.counters["threads"] = options.threads;
  if (!cascades) set_memory_counters(state, memory, n, frames);
  // A right surface fails the gate with probability ≤ α = 1e-3; this seed passes.
  state.SetLabel(passed ? "pass" : "FAIL");
}

// The floor: each frame read alone (a one-frame case naming its file) and every field
// transformed, nothing kept.
void run_floor_bench(benchmark::State& state, int n, int frames) {
  fs::path case_path;
  try {
    case_path = directories().case_file(n, frames);
  } catch (const std::exception& e) {
    any_failed = true;
    state.SkipWithError(e.what());
    return;
  }
  const auto whole = swell::validation::read_case_file(case_path);
  const int threads = gate_threads();
  const swell::bench::PeakMemory memory;
  std::vector<std::complex<double>> spectrum;
  for (auto _ : state) {
    for (int f = 0; f < frames; ++f) {
      auto one = whole;
      one.ocean.frames = 1;
      one.ocean.t0 = whole.ocean.time(f);
      one.input.files = swell::validation::frame_file_name(whole.input.files, f);
      const auto frame = swell::validation::read_frames(one, "", {}, threads);
      for (const auto& [field, values] : frame.frames.front().fields) {
        swell::validation::field_spectrum(values, frame.sampling(), spectrum);
        benchmark::DoNotOptimize(spectrum.data());
      }
    }
  }
  set_memory_counters(state, memory, n, frames);
  state.counters["threads"] = threads;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("case", bench_case(512, 64).describe() +
                                          ", dt 0.1 s, choppiness 0.8, seed 2024, fp32 EXR");
  benchmark::AddCustomContext("threads", std::to_string(gate_threads()) +
                                             " (SWELL_GATE_THREADS; 0 = every hardware thread)");
  for (const auto& [n, frames] : {std::pair{128, 8}, std::pair{512, 64}}) {
    benchmark::RegisterBenchmark(
        ("gate/" + std::to_string(n) + "/" + std::to_string(frames)).c_str(), run_gate_bench, n,
        frames, false)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  // Gate beside floor, N from 256² to 4096² and 16 to 256 frames (the frames of 4096² take
  // 3.2 GB of disk at 16 frames and 12.9 GB at 64, written once per run).
  for (const auto& [n, frames] :
       {std::pair{256, 16}, std::pair{256, 64}, std::pair{256, 256}, std::pair{512, 16},
        std::pair{512, 64}, std::pair{512, 256}, std::pair{1024, 16}, std::pair{1024, 64},
        std::pair{2048, 16}, std::pair{2048, 64}, std::pair{4096, 16}, std::pair{4096, 64}}) {
    const std::string size = std::to_string(n) + "/" + std::to_string(frames);
    benchmark::RegisterBenchmark(("gate_floor/" + size).c_str(), run_floor_bench, n, frames)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    if (!(n == 512 && frames == 64)) {
      benchmark::RegisterBenchmark(("gate/" + size).c_str(), run_gate_bench, n, frames, false)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  for (const auto& [n, frames] : {std::pair{64, 8}, std::pair{256, 16}}) {
    benchmark::RegisterBenchmark(
        ("gate_cascades/" + std::to_string(n) + "/" + std::to_string(frames)).c_str(),
        run_gate_bench, n, frames, true)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return any_failed ? 1 : 0;
}
