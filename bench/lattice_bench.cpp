// Lattice frames against grid frames at equal point count (docs/lattice.md; docs/conventions.md
// §2.1): Synthesizer::evaluate — the spectrum assembly, the inverse transforms and the
// unpack into all six fields — into a preallocated buffer, on a rank-1 lattice of N points (one
// row of N classes, 1-D transforms of size N) and on the n × n grid with n² = N.
//
//   lattice/<impl>/<precision>/<N>            Korobov lattice, generator by the spectral test
//                                             (korobov_lattice), N = 2^12 … 2^22
//   frame/<impl>/<precision>/<n>              the n × n grid, n = √N for N an even power of two
//                                             (n = 64 … 2048), registered right after its lattice
//   lattice_one_pass/<impl>/<precision>/<N>   the same lattice with each of the synthesizer's
//   lattice_four_step/<impl>/<precision>/<N>  two lattice transforms forced (N ≥ 2^16, host
//                                             backends): lattice/… is the automatic choice,
//                                             one of them; four_step_n1 and four_step_n2 give
//                                             N = n1·n2 (0 for one pass)
//   lattice_fibonacci/<impl>/<precision>/<N>  Fibonacci lattices N = F_j, j = 19 … 33 (4181 …
//                                             3524578 points): backends of any size only
//
// so that one filter runs a lattice and its grid side by side in one process:
//
//   build/bench/swell_lattice_bench --benchmark_filter='^(lattice|frame)/fftw/fp32/'
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//       --benchmark_format=json --benchmark_out=lattice_fftw_fp32.json
//   SWELL_BENCH_IMPLS=radix2 build/bench/swell_lattice_bench
//       --benchmark_filter='^(lattice|frame)/radix2/fp32/(4096|64|1048576|1024)$'
//   build/bench/swell_lattice_bench --benchmark_filter='^lattice_fibonacci/fftw/fp64/'
//
// Every frame result carries
//   points               samples per field (N, or n²)
//   ns_per_point         frame time / points (the thread's CPU time, as cpu_time; wall-clock
//                        for a device-resident backend, as real_time)
//   alias_free_fraction  the sampling's band geometry in the patch metric (lattice_band for a
//   inscribed_radius     lattice, grid_band below for a grid): the share of the Voronoi cell
//   covering_radius      of the dual lattice filled by its inscribed disc, that disc's radius
//                        and the cell's circumradius, rad/m
//   transforms_ms        bare transforms of one frame, measured in the same iteration with
//   rest_ms              the benchmark timer paused, as frame_bench does: frame − transforms
//   transform_fraction   is the assembly and the unpack (the non-transform part)
//   setup_s              construction before timing (the lattice's search and wave table, the
//                        amplitudes, plans), wall-clock seconds
// and a lattice result also grid_alias_free_fraction, grid_inscribed_radius and
// grid_covering_radius: those of a square grid of the same point count over the same patch
// (n = √N samples a side, a real number when N is not a square: the square grid of the same
// density), and lattice_s, the part of setup_s spent building the lattice (the spectral-test
// search and the wave-vector table). Its label is the lattice (korobov N=4096 g=(1,…) over
// 200×200 m).
//
// The case: frame_bench's sea (JONSWAP Hs 3 m, Tp 8 s, γ 3.3, cos2s s = 10 toward 30°,
// λ = 0.8, seed 2024) over a 200 × 200 m patch, for lattices and grids alike, one thread.
// Implementations: fftw and radix2 (and vulkan in a build with it), or SWELL_BENCH_IMPLS (comma
// separated, options allowed: "fftw:threads=2" runs the transforms and a grid's assembly on 2
// threads, a lattice's assembly stays on one (synthesizer.cpp: one row); "null" measures
// everything but the transform; "naive" runs only the smallest of each series, its transforms
// being O(N²) and O(n³)). What a backend refuses (UnsupportedTransform: no Vulkan device, a size
// beyond its limits) skips with the reason; any other error skips and makes the exit status 1,
// so the smoke test fails. Fibonacci sizes are registered only for backends of any size.
//
// A device-resident backend (vulkan) works on its device and its benchmarks use real time
// (/real_time, see frame_bench). Its grid frame is the fused device frame; its lattice frame is
// assembled and unpacked on the host with the 1-D transforms run on the device through host
// memory (synthesizer.hpp), so the lattice's transforms_ms (bare transforms on device buffers)
// misses the copies that its frame pays.
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "frame_support.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/grid.hpp"
#include "swell/reference/lattice.hpp"
#include "swell/reference/ocean_case.hpp"
#ifdef SWELL_HAVE_VULKAN
#include "swell/impls/vulkan.hpp"
#endif

namespace {

using namespace swell::impls;
using swell::reference::Grid;
using swell::reference::LatticeBand;
using swell::reference::OceanCase;
using swell::reference::RankOneLattice;
using Clock = std::chrono::steady_clock;

using swell::bench::thread_cpu_seconds;
using swell::bench::wall_seconds;

constexpr double kFrameStep = 1.0 / 60;  // s between timed frames (any value would do)
constexpr double kPatch = 200.0;         // m, both sides
constexpr int kLog2First = 12, kLog2Last = 22;        // lattice points 2^12 … 2^22
constexpr int kFibonacciFirst = 19, kFibonacciLast = 33;  // F_19 = 4181 … F_33 = 3524578
// From 2^16 points on, lattice_one_pass and lattice_four_step run both of the synthesizer's
// lattice transforms beside the automatic choice (synthesizer.hpp).
constexpr int kLog2Alternatives = 16;

// Set when a benchmark could not run for a reason other than the backend's refusal: the exit
// status is then 1, so the smoke test fails.
bool any_failed = false;

// A backend's refusal (no device, a size beyond its limits) is a skip with its reason; any
// other error is a failure.
void skip(benchmark::State& state, const std::exception& e) {
  if (!dynamic_cast<const UnsupportedTransform*>(&e)) any_failed = true;
  state.SkipWithError(e.what());
}

std::vector<std::string> implementations() {
  std::vector<std::string> fallback = {"fftw", "radix2"};
#ifdef SWELL_HAVE_VULKAN
  fallback.push_back("vulkan");
#endif
  return swell::bench::backends_from_environment(fallback);
}

// "fftw:threads=2" → 2: the assembly then runs on as many threads as the transform.
int threads_of(const std::string& impl) {
  const auto at = impl.find("threads=");
  return at == std::string::npos ? 1 : std::atoi(impl.c_str() + at + 8);
}

// frame_bench's sea over the benchmark's patch, sampled by an n × n grid.
OceanCase grid_case(int n) {
  OceanCase c = swell::bench::jonswap_bench_case(n, 1, kFrameStep);
  c.grid = Grid::create(n, n, kPatch, kPatch);
  return c;
}

// The band geometry of an nx × ny grid over lx × ly, as lattice_band gives a lattice's: the
// grid cannot tell K from K + (nx·2π/lx) e_x or K + (ny·2π/ly) e_y, so its dual lattice is
// rectangular with those sides; its Voronoi cell is the rectangle of half-sides
// a = (nx/2)·2π/lx and b = (ny/2)·2π/ly, the inscribed radius min(a, b), the covering radius
// the half-diagonal √(a² + b²), and the alias-free fraction π min(a, b)² / (4ab) (π/4 when
// square). Counts are doubles: a square grid of N points has √N a side, which need not be whole.
LatticeBand grid_band(double nx, double ny, double lx, double ly) {
  const double a = nx / 2 * (2 * std::numbers::pi / lx);
  const double b = ny / 2 * (2 * std::numbers::pi / ly);
  LatticeBand band;
  band.inscribed_radius = std::min(a, b);
  band.covering_radius = std::hypot(a, b);
  band.alias_free_fraction =
      std::numbers::pi * band.inscribed_radius * band.inscribed_radius / (4 * a * b);
  return band;
}

// The square grid of N points over the patch (the grid of equal point count).
LatticeBand equal_count_grid_band(std::int64_t points) {
  const double side = std::sqrt(double(points));
  return grid_band(side, side, kPatch, kPatch);
}

enum class Sampled { korobov, fibonacci, grid };

// What one benchmark samples: `size` is N (korobov), j (fibonacci) or n (grid).
struct Subject {
  Sampled kind;
  int size;
  LatticeTransform transform = LatticeTransform::automatic;
  std::string key() const {
    const char* names[] = {"korobov", "fibonacci", "grid"};
    return std::string(names[int(kind)]) + "/" + std::to_string(size) + "/" + to_string(transform);
  }
};

using swell::bench::BareTransforms;

// A synthesizer with its output buffer, its bare transforms and its sampling's band. The
// lattice's search and table (up to 0.3 s at 2^22 points), the amplitudes and FFTW_MEASURE
// planning all happen here, outside the timing; Google Benchmark calls a benchmark function
// several times per repetition, so the last one built is kept for the next call.
struct Fixture {
  std::string key;
  std::unique_ptr<Synthesizer> synthesizer;
  std::vector<std::byte> fields;
  std::optional<BareTransforms> bare;
  std::int64_t points = 0;
  LatticeBand band;                 // of what is sampled
  std::optional<LatticeBand> grid;  // a lattice's: the square grid of equal point count
  std::string label;
  double setup_seconds = 0, lattice_seconds = 0;
  double t = 0;
};

Fixture& fixture(const std::string& impl, Precision precision, Subject subject) {
  static std::unique_ptr<Fixture> current;
  const std::string key = impl + "/" + to_string(precision) + "/" + subject.key();
  if (current && current->key == key) return *current;
  current.reset();  // free the previous one (over a gigabyte at 2^22 points, fp64) first
  auto f = std::make_unique<Fixture>();
  f->key = key;
  const auto start = Clock::now();
  OceanCase c;
  if (subject.kind == Sampled::grid) {
    c = grid_case(subject.size);
    f->points = std::int64_t(subject.size) * subject.size;
    f->band = grid_band(subject.size, subject.size, kPatch, kPatch);
    f->label = c.sampling().describe();
  } else {
    c = grid_case(64);  // the sea; the lattice replaces the grid
    auto lattice = std::make_shared<const RankOneLattice>(
        subject.kind == Sampled::korobov
            ? swell::reference::korobov_lattice(subject.size, {kPatch, kPatch})
            : swell::reference::fibonacci_lattice(subject.size, kPatch, kPatch));
    f->lattice_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    f->points = lattice->points();
    f->band = swell::reference::lattice_band(*lattice);
    f->grid = equal_count_grid_band(f->points);
    f->label = lattice->describe();
    if (subject.kind == Sampled::fibonacci) f->label += " j=" + std::to_string(subject.size);
    c.set_lattice(std::move(lattice));
  }
  SynthesizerOptions options;
  options.backend = impl;
  options.precision = precision;
  options.threads = threads_of(impl);
  options.lattice_transform = subject.transform;
  f->synthesizer = std::make_unique<Synthesizer>(c, options);
  f->fields.resize(f->synthesizer->frame_bytes());
  f->synthesizer->evaluate(0.0, f->fields);  // first touch, outside the timing
  f->bare.emplace(impl, f->synthesizer->transforms_per_frame());
  f->setup_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  current = std::move(f);
  return *current;
}

void run_frame(benchmark::State& state, const std::string& impl, Precision precision,
               Subject subject) {
  Fixture* f = nullptr;
  try {
    f = &fixture(impl, precision, subject);
  } catch (const std::exception& e) {
    skip(state, e);
    return;
  }
  const bool on_device = f->bare->backend->capabilities().device_resident;
  const auto clock = on_device ? wall_seconds : thread_cpu_seconds;
  double frame_seconds = 0, transform_seconds = 0;
  double device_seconds = 0, evolve_seconds = 0, passes_seconds = 0, transform_device_seconds = 0;
  try {
    for (auto _ : state) {
      const double start = clock();
      const FrameTimings timings = f->synthesizer->evaluate_timed(f->t, f->fields);
      benchmark::ClobberMemory();
      const double middle = clock();
      state.PauseTiming();  // about a microsecond, against 0.1 ms or more per frame
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
  } catch (const std::exception& e) {
    skip(state, e);
    return;
  }
  const double iterations = double(state.iterations());
  state.counters["points"] = double(f->points);
  state.counters["ns_per_point"] = 1e9 * frame_seconds / iterations / double(f->points);
  state.counters["alias_free_fraction"] = f->band.alias_free_fraction;
  state.counters["inscribed_radius"] = f->band.inscribed_radius;
  state.counters["covering_radius"] = f->band.covering_radius;
  if (f->grid) {
    state.counters["grid_alias_free_fraction"] = f->grid->alias_free_fraction;
    state.counters["grid_inscribed_radius"] = f->grid->inscribed_radius;
    state.counters["grid_covering_radius"] = f->grid->covering_radius;
    state.counters["lattice_s"] = f->lattice_seconds;
    const auto [n1, n2] = f->synthesizer->four_step_factors();
    state.counters["four_step_n1"] = n1;
    state.counters["four_step_n2"] = n2;
  }
  state.counters["transforms_ms"] = 1e3 * transform_seconds / iterations;
  state.counters["rest_ms"] = 1e3 * (frame_seconds - transform_seconds) / iterations;
  state.counters["transform_fraction"] = transform_seconds / frame_seconds;
  if (on_device) {
    state.counters["transforms_device_seconds"] = transform_device_seconds / iterations;
    if (subject.kind == Sampled::grid) {  // the fused device frame's timestamps (frame_bench)
      state.counters["device_seconds"] = device_seconds / iterations;
      state.counters["evolve_seconds"] = evolve_seconds / iterations;
      state.counters["frame_transforms_seconds"] = passes_seconds / iterations;
    }
  }
  state.counters["setup_s"] = f->setup_seconds;
  state.SetLabel(f->label);
}

void register_all() {
  for (const auto& impl : implementations()) {
    // A backend that cannot start here (no Vulkan device) still registers its benchmarks,
    // which skip with the reason; with no capabilities to go by, both precisions.
    Capabilities capabilities;
    capabilities.precisions = {Precision::f32, Precision::f64};
    capabilities.any_size = false;
    try {
      capabilities = make_backend(impl)->capabilities();
    } catch (const UnsupportedTransform& e) {
      std::fprintf(stderr, "swell_lattice_bench: %s (its benchmarks skip)\n", e.what());
      capabilities.device_resident = impl.rfind("vulkan", 0) == 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "swell_lattice_bench: %s\n", e.what());
      any_failed = true;
      continue;
    }
    const bool naive = impl.rfind("naive", 0) == 0;  // 4096 points only (see the header)
    const auto unit = [&](benchmark::internal::Benchmark* b) {
      b->Unit(benchmark::kMillisecond);
      if (capabilities.device_resident) b->UseRealTime();
    };
    for (Precision precision : {Precision::f32, Precision::f64}) {
      if (std::find(capabilities.precisions.begin(), capabilities.precisions.end(), precision) ==
          capabilities.precisions.end()) {
        continue;
      }
      const std::string tail = "/" + impl + "/" + to_string(precision) + "/";
      for (int log2 = kLog2First; log2 <= kLog2Last; ++log2) {
        if (naive && log2 > kLog2First) continue;
        const int points = 1 << log2;
        unit(benchmark::RegisterBenchmark(("lattice" + tail + std::to_string(points)).c_str(),
                                          run_frame, impl, precision,
                                          Subject{Sampled::korobov, points}));
        if (log2 >= kLog2Alternatives && !capabilities.device_resident) {
          for (const auto transform : {LatticeTransform::one_pass, LatticeTransform::four_step}) {
            unit(benchmark::RegisterBenchmark(
                ("lattice_" + to_string(transform) + tail + std::to_string(points)).c_str(),
                run_frame, impl, precision, Subject{Sampled::korobov, points, transform}));
          }
        }
        if (log2 % 2 == 0) {  // the grid of equal point count, next to its lattice
          const int n = 1 << (log2 / 2);
          unit(benchmark::RegisterBenchmark(("frame" + tail + std::to_string(n)).c_str(),
                                            run_frame, impl, precision,
                                            Subject{Sampled::grid, n}));
        }
      }
      if (!capabilities.any_size) continue;  // Fibonacci numbers are not powers of two
      for (int j = kFibonacciFirst; j <= kFibonacciLast; ++j) {
        if (naive && j > kFibonacciFirst) continue;
        const auto points = swell::reference::fibonacci_number(j);
        unit(benchmark::RegisterBenchmark(
            ("lattice_fibonacci" + tail + std::to_string(points)).c_str(), run_frame, impl,
            precision, Subject{Sampled::fibonacci, j}));
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
      "case", grid_case(64).describe() + " (the sampling varies), choppiness 0.8, seed 2024");
  benchmark::AddCustomContext("threads", "1 unless an impl says threads=N");
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return any_failed ? 1 : 0;
}
