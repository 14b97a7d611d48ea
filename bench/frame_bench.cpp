// Whole-frame speed of the grid synthesizer (docs/synthesis.md): Synthesizer::evaluate — the
// spectrum assembly, the inverse transforms and the unpack into all six fields — into a
// preallocated buffer, for N² = 256² … 2048², fp32 and fp64, through the exact backends.
//
//   frame/<impl>/<precision>/<N>                     packing automatic (what a user gets)
//   frame_packing/<impl>/<precision>/<packing>/<N>   complex_pairs (4 c2c) against real (8 c2r)
//   frame_transforms/<impl>/<precision>/<N>          the transforms of an automatic frame alone
//                                                    (Synthesizer::transforms_per_frame())
//
// The frame benchmarks time evaluate() alone and, in the same iteration with the benchmark timer
// paused, the bare transforms of that frame on buffers of their own; so each frame result
// carries, measured side by side under the same machine load, the counters (CPU time of the
// benchmark thread, like the cpu_time column)
//   transforms_ms        bare transforms of one frame
//   transform_fraction   bare transforms / frame
//   rest_ms              frame − bare transforms: assembly and unpack (the non-transform part)
// and setup_s, the construction (amplitudes, ω, plans) before timing, in wall-clock seconds.
// On a shared machine compare cpu_time: real_time also holds the time slices other processes
// took. With threads = 1 everything runs on the benchmark thread and the two agree on an idle
// machine; for threads=N variants read real_time (cpu_time then misses the other threads).
//
// A device-resident backend (vulkan) works on its device, and the benchmark thread only waits
// for it (on lavapipe the work runs on the driver's own threads): its benchmarks use real time
// (UseRealTime, which Google Benchmark marks in the name: frame/vulkan/fp32/512/real_time; by
// CPU time a 23 ms frame showed 0.2 ms and ran a thousand iterations), and transforms_ms,
// rest_ms and transform_fraction are wall-clock too, the bare transforms run on device
// Buffers as the frame's do. Its frames also carry the device's own
// timestamps (Synthesizer::evaluate_timed, vulkan_execute_timed):
//   device_seconds             evolution + the frame's passes, before the fields reach the host
//   evolve_seconds             the evolution kernel alone (h̃ at t)
//   frame_transforms_seconds   the frame's passes alone: the transforms, whose first pass makes
//                              the packed spectra and whose last writes the six fields
//   transforms_device_seconds  the bare transforms alone
// (seconds per frame, as fft_bench's device_seconds; frame real time − device_seconds is the
// submission, the wait, any copy of the fields through staging and the copy into the caller's
// memory).
//
// The case: JONSWAP Hs 3 m, Tp 8 s, γ 3.3, cos2s s = 10, over a 1000 m patch, one thread.
// Implementations: every backend whose capabilities().exact is true except naive, or
// SWELL_BENCH_IMPLS (comma separated, options allowed: "fftw:threads=2" also runs the assembly
// on 2 threads; "null" measures everything but the transform). naive, the long-double oracle,
// costs about a second per frame at 256² (O(N³) transforms, minutes at 1024²) and tells nothing
// about frame cost, so it runs only when named, and then at 256² only; left in the default
// list it would make the smoke test 40 s instead of a few.
//
//   build/bench/swell_frame_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//   SWELL_BENCH_IMPLS=fftw,radix2 build/bench/swell_frame_bench --benchmark_filter='/1024$'
//   SWELL_BENCH_IMPLS=vulkan build/bench/swell_frame_bench --benchmark_repetitions=5
//       --benchmark_filter='frame(_transforms)?/vulkan/fp32/(512|1024)/real_time$'
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "frame_support.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/ocean_case.hpp"
#ifdef SWELL_HAVE_VULKAN
#include "swell/impls/vulkan.hpp"
#endif

namespace {

using namespace swell::impls;
using swell::reference::OceanCase;
using Clock = std::chrono::steady_clock;

using swell::bench::thread_cpu_seconds;
using swell::bench::wall_seconds;

constexpr double kFrameStep = 1.0 / 60;  // s between timed frames (any value would do)

// Set when a benchmark could not run: the exit status is then 1, so the smoke test fails.
bool any_failed = false;

void fail(benchmark::State& state, const std::exception& e) {
  any_failed = true;
  state.SkipWithError(e.what());
}

std::vector<std::string> implementations() {
  std::vector<std::string> exact;
  for (const auto& name : backend_names()) {
    if (name == "naive") continue;
    try {
      if (make_backend(name)->capabilities().exact) exact.push_back(name);
    } catch (const UnsupportedTransform&) {
      // A backend that cannot start here (vulkan without a device) is exact; its benchmarks
      // register and skip with the reason (register_all).
      exact.push_back(name);
    }
  }
  return swell::bench::backends_from_environment(exact);
}

// "fftw:threads=2" → 2: the assembly then runs on as many threads as the transform.
int threads_of(const std::string& impl) {
  const auto at = impl.find("threads=");
  return at == std::string::npos ? 1 : std::atoi(impl.c_str() + at + 8);
}

OceanCase bench_case(int n) { return swell::bench::jonswap_bench_case(n, 1, kFrameStep); }

using swell::bench::BareTransforms;

// A synthesizer with its output buffer and its bare transforms. Construction costs seconds at
// 2048² (amplitudes, FFTW_MEASURE planning) and Google Benchmark calls a benchmark function
// several times per repetition, so the last one built is kept for the next call.
struct Fixture {
  std::string key;
  std::unique_ptr<Synthesizer> synthesizer;
  std::vector<std::byte> fields;
  std::optional<BareTransforms> bare;
  double setup_seconds = 0;
  double t = 0;
};

Fixture& fixture(const std::string& impl, Precision precision, Packing packing, int n) {
  static std::unique_ptr<Fixture> current;
  const std::string key =
      impl + "/" + to_string(precision) + "/" + to_string(packing) + "/" + std::to_string(n);
  if (current && current->key == key) return *current;
  current.reset();  // free the previous one (up to a gigabyte at 2048² fp64) before building
  auto f = std::make_unique<Fixture>();
  f->key = key;
  const auto start = Clock::now();
  SynthesizerOptions options;
  options.backend = impl;
  options.precision = precision;
  options.packing = packing;
  options.threads = threads_of(impl);
  f->synthesizer = std::make_unique<Synthesizer>(bench_case(n), options);
  f->fields.resize(f->synthesizer->frame_bytes());
  f->synthesizer->evaluate(0.0, f->fields);  // first touch, outside the timing
  f->bare.emplace(impl, f->synthesizer->transforms_per_frame());
  f->setup_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  current = std::move(f);
  return *current;
}

void run_frame(benchmark::State& state, const std::string& impl, Precision precision,
               Packing packing, int n) {
  Fixture* f = nullptr;
  try {
    f = &fixture(impl, precision, packing, n);
  } catch (const std::exception& e) {
    fail(state, e);
    return;
  }
  const bool on_device = f->bare->backend->capabilities().device_resident;
  const auto clock = on_device ? wall_seconds : thread_cpu_seconds;
  double frame_seconds = 0, transform_seconds = 0;
  double device_seconds = 0, evolve_seconds = 0, passes_seconds = 0, transform_device_seconds = 0;
  for (auto _ : state) {
    const double start = clock();
    const FrameTimings timings = f->synthesizer->evaluate_timed(f->t, f->fields);
    benchmark::ClobberMemory();
    const double middle = clock();
    state.PauseTiming();  // about a microsecond, against a millisecond or more per frame
    transform_device_seconds += f->bare->run();
    benchmark::ClobberMemory();
    const double end = clock();
    frame_seconds += middle - start;
    transform_seconds += end - middle;
    device_seconds += timings.device_seconds;
    evolve_seconds += timings.evolve_seconds;
    passes_seconds += timings.transforms_seconds;
    f->t += kFrameStep;
    state.ResumeTiming();
  }
  const double iterations = double(state.iterations());
  state.counters["transforms_ms"] = 1e3 * transform_seconds / iterations;
  state.counters["rest_ms"] = 1e3 * (frame_seconds - transform_seconds) / iterations;
  state.counters["transform_fraction"] = transform_seconds / frame_seconds;
  if (on_device) {
    state.counters["device_seconds"] = device_seconds / iterations;
    state.counters["evolve_seconds"] = evolve_seconds / iterations;
    state.counters["frame_transforms_seconds"] = passes_seconds / iterations;
    state.counters["transforms_device_seconds"] = transform_device_seconds / iterations;
  }
  state.counters["setup_s"] = f->setup_seconds;
  state.SetLabel(to_string(f->synthesizer->packing()));
}

void run_transforms(benchmark::State& state, const std::string& impl, Precision precision,
                    int n) {
  Fixture* f = nullptr;
  try {
    f = &fixture(impl, precision, Packing::automatic, n);
  } catch (const std::exception& e) {
    fail(state, e);
    return;
  }
  for (auto _ : state) {
    f->bare->run();
    benchmark::ClobberMemory();
  }
  std::string label;
  for (const auto& spec : f->synthesizer->transforms_per_frame()) {
    label += (label.empty() ? "" : "; ") + spec.describe();
  }
  state.SetLabel(label);
}

void register_all() {
  for (const auto& impl : implementations()) {
    Capabilities capabilities;
    try {
      capabilities = make_backend(impl)->capabilities();
    } catch (const UnsupportedTransform& e) {
      // It cannot start here (no Vulkan device): not registered, and not a failure.
      std::fprintf(stderr, "swell_frame_bench: %s (not run)\n", e.what());
      continue;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "swell_frame_bench: %s\n", e.what());
      any_failed = true;
      continue;
    }
    for (Precision precision : {Precision::f32, Precision::f64}) {
      if (std::find(capabilities.precisions.begin(), capabilities.precisions.end(), precision) ==
          capabilities.precisions.end()) {
        continue;
      }
      for (int n = 256; n <= 2048; n *= 2) {
        if (impl.rfind("naive", 0) == 0 && n > 256) continue;  // see the header
        const std::string tail = "/" + impl + "/" + to_string(precision) + "/";
        const std::string size = std::to_string(n);
        // frame and frame_transforms share one fixture (registered next to each other).
        // A device-resident backend's benchmark thread only waits: real time (see the header).
        const auto unit = [&](benchmark::internal::Benchmark* b) {
          b->Unit(benchmark::kMillisecond);
          if (capabilities.device_resident) b->UseRealTime();
        };
        unit(benchmark::RegisterBenchmark(("frame" + tail + size).c_str(), run_frame, impl,
                                          precision, Packing::automatic, n));
        unit(benchmark::RegisterBenchmark(("frame_transforms" + tail + size).c_str(),
                                          run_transforms, impl, precision, n));
        for (Packing packing : {Packing::complex_pairs, Packing::real}) {
          if (packing == Packing::real && !capabilities.real_transforms) continue;
          unit(benchmark::RegisterBenchmark(
              ("frame_packing" + tail + to_string(packing) + "/" + size).c_str(), run_frame, impl,
              precision, packing, n));
        }
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("fftw_version", fftw_version);
  benchmark::AddCustomContext("compiler", __VERSION__);
  benchmark::AddCustomContext(
      "case", bench_case(256).describe() + " (N² varies), choppiness 0.8, seed 2024");
  benchmark::AddCustomContext("threads", "1 unless an impl says threads=N");
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return any_failed ? 1 : 0;
}
