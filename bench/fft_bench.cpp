// 2-D transform speed of every backend: fft2d/<kind>/<impl>/<precision>/<N>/real_time for
// N = 64 … 4096 (vulkan from 16), fp32 and fp64, c2c inverse ("c2c") and c2r, and the anchor
// fft2d/c2c/vkfft/fp32/<N> (vkfft_anchor.cpp). Wall-clock time (real_time, which Google
// Benchmark appends to the name): a device backend's host thread sleeps on a fence, and a
// threaded backend's CPU time adds its threads'. Planning (FFTW_MEASURE: about 1 s at 2048²; a
// vulkan plan compiles its pipelines) is done before timing and reported as plan_seconds.
// Counters: GFLOP/s by benchFFT's convention (5 N² log2 N² per complex transform, half for
// c2r) and bytes/s (input + output); floor_fraction, the roofline: the time of the copy
// benchmark below for the same arrays (measured in the same process right after, the best of
// 5) over the transform's time — 1 would be a transform as fast as moving its data twice;
// kernel_floor_fraction (radix2 c2c, one thread), the arithmetic roof: the time its butterflies
// would take at the rate of radix2's fastest kernel alone in L1 (radix2_kernel.hpp, measured
// right after too) over the transform's time; for vulkan, gearshifft's phases: device_seconds
// (the transform's timestamps on the device, mean per iteration) and upload_seconds and
// download_seconds (host ↔ device copies of the input and output, mean of 3 host executions).
//
//
// The roofline, fft2d/<kind>/copy/<precision>/<N>: the bytes a 2-D transform's two passes (one
// per axis) move, without arithmetic — the input copied to the output, then the output copied
// back to the input (memcpy, one thread): read and write of the array once per axis. Its
// GFLOP/s is not a flop rate; it is registered whatever SWELL_BENCH_IMPLS says.
//
//   build/bench/swell_fft_bench --benchmark_format=json --benchmark_out=fft.json
//   SWELL_BENCH_IMPLS=radix2,fftw build/bench/swell_fft_bench --benchmark_filter=c2c/.*/fp32
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "swell/impls/radix2_kernel.hpp"
#include "swell/impls/transform.hpp"
#ifdef SWELL_HAVE_VULKAN
#include "swell/impls/vulkan.hpp"
#endif
#include "vkfft_anchor.hpp"

namespace {

using namespace swell::impls;

std::vector<std::string> implementations() {
  return swell::bench::backends_from_environment(backend_names());
}

std::string cpu_flags() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, found;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    for (const char* flag : {" sse2", " avx ", " avx2", " fma", " avx512f", " avx512dq"}) {
      if (line.find(flag) != std::string::npos) found += std::string(flag).substr(1) + " ";
    }
    break;
  }
  return found;
}

// The two passes of the roofline on arrays of the transform's input and output sizes.
void copy_passes(void* in, void* out, std::size_t in_bytes, std::size_t out_bytes) {
  const std::size_t bytes = std::min(in_bytes, out_bytes);
  std::memcpy(out, in, bytes);
  std::memcpy(in, out, bytes);
  benchmark::ClobberMemory();
}

// Seconds of the roofline's two passes for `spec`'s arrays: the best of 5.
double copy_seconds(const TransformSpec& spec) {
  std::vector<unsigned char> in(spec.input_bytes(), 1), out(spec.output_bytes(), 2);
  double best = 1e300;
  for (int repeat = 0; repeat < 5; ++repeat) {
    const auto start = std::chrono::steady_clock::now();
    copy_passes(in.data(), out.data(), in.size(), out.size());
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// radix2's arithmetic roof for a c2c `spec` (one thread): its n² log2(n²)/2 butterflies at the
// rate of its fastest kernel alone (radix2_kernel.hpp), measured now, in this process.
double radix2_kernel_seconds(const TransformSpec& spec) {
  const auto rate = measure_radix2_kernel_rate(spec.precision);
  const double points = double(spec.nx) * spec.ny;
  return points * std::log2(points) / 2 / rate.lanes * rate.seconds_per_vector_butterfly;
}

void run_copy(benchmark::State& state, TransformSpec spec) {
  std::vector<unsigned char> in(spec.input_bytes(), 1), out(spec.output_bytes(), 2);
  for (auto _ : state) copy_passes(in.data(), out.data(), in.size(), out.size());
  state.counters["floor_fraction"] = 1.0;
  state.SetBytesProcessed(state.iterations() * int64_t(spec.input_bytes() + spec.output_bytes()));
}

void run(benchmark::State& state, const std::string& impl, TransformSpec spec) {
  const auto backend = make_backend(impl);
  const auto plan_start = std::chrono::steady_clock::now();
  std::unique_ptr<Plan> plan;
  try {
    plan = backend->plan(spec);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const double plan_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - plan_start).count();
  auto in = backend->allocate(spec.input_bytes());
  auto out = backend->allocate(spec.output_bytes());
  {
    std::vector<unsigned char> bytes(spec.input_bytes());
    std::mt19937 engine(7);
    const std::size_t reals = spec.input_bytes() / real_size(spec.precision);
    if (spec.precision == Precision::f32) {
      auto* x = reinterpret_cast<float*>(bytes.data());
      for (std::size_t i = 0; i < reals; ++i) x[i] = float(engine()) / 4294967296.0f - 0.5f;
    } else {
      auto* x = reinterpret_cast<double*>(bytes.data());
      for (std::size_t i = 0; i < reals; ++i) x[i] = double(engine()) / 4294967296.0 - 0.5;
    }
    in->upload(bytes.data(), bytes.size());
  }
#ifdef SWELL_HAVE_VULKAN
  if (backend->name() == "vulkan") {
    double device_seconds = 0;
    for (auto _ : state) {
      device_seconds += vulkan_execute_timed(*plan, *in, *out).compute_seconds;
    }
    state.counters["device_seconds"] = device_seconds / double(state.iterations());
    std::vector<unsigned char> host_in(spec.input_bytes()), host_out(spec.output_bytes());
    double upload = 0, download = 0;
    for (int repeat = 0; repeat < 3; ++repeat) {
      const auto t = vulkan_execute_timed(*plan, host_in.data(), host_out.data());
      upload += t.upload_seconds / 3;
      download += t.download_seconds / 3;
    }
    state.counters["upload_seconds"] = upload;
    state.counters["download_seconds"] = download;
  } else
#endif
  {
    const auto start = std::chrono::steady_clock::now();
    for (auto _ : state) {
      plan->execute(*in, *out);
      benchmark::ClobberMemory();
    }
    const double per_transform =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
        double(std::max<std::int64_t>(1, state.iterations()));
    state.counters["floor_fraction"] = copy_seconds(spec) / per_transform;
    if (impl == "radix2" && spec.kind == Kind::c2c) {
      state.counters["kernel_floor_fraction"] = radix2_kernel_seconds(spec) / per_transform;
    }
  }
  const double n2 = double(spec.nx) * spec.ny;
  const double flops = (spec.kind == Kind::c2c ? 5.0 : 2.5) * n2 * std::log2(n2);
  state.counters["GFLOP/s"] = benchmark::Counter(flops * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["plan_seconds"] = plan_seconds;
  state.SetBytesProcessed(state.iterations() * int64_t(spec.input_bytes() + spec.output_bytes()));
}

void register_all() {
  for (const auto& impl : implementations()) {
    if (impl == "copy") continue;  // the roofline, registered below
    for (Kind kind : {Kind::c2c, Kind::c2r}) {
      for (Precision precision : {Precision::f32, Precision::f64}) {
        for (int n = impl.rfind("vulkan", 0) == 0 ? 16 : 64; n <= 4096; n *= 2) {
          if (impl == "naive" && n > 128) continue;  // O(N³) per 2-D transform: minutes beyond
          TransformSpec spec;
          spec.nx = spec.ny = n;
          spec.kind = kind;
          spec.direction = Direction::inverse;
          spec.precision = precision;
          const std::string name = "fft2d/" + to_string(kind) + "/" + impl + "/" +
                                   to_string(precision) + "/" + std::to_string(n);
          benchmark::RegisterBenchmark(name.c_str(), run, impl, spec)
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime()
              // Warm-up (untimed) before each: the first benchmarks of a run were up to 2× slower
              // than the same ones later (lavapipe's threads and the CPU's clocks waking up).
              ->MinWarmUpTime(0.05);
        }
      }
    }
  }
  for (Kind kind : {Kind::c2c, Kind::c2r}) {
    for (Precision precision : {Precision::f32, Precision::f64}) {
      for (int n = 64; n <= 4096; n *= 2) {
        TransformSpec spec;
        spec.nx = spec.ny = n;
        spec.kind = kind;
        spec.direction = Direction::inverse;
        spec.precision = precision;
        const std::string name = "fft2d/" + to_string(kind) + "/copy/" + to_string(precision) +
                                 "/" + std::to_string(n);
        benchmark::RegisterBenchmark(name.c_str(), run_copy, spec)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinWarmUpTime(0.05);
      }
    }
  }
  swell::bench::register_vkfft_benchmarks();
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("fftw_version", fftw_version);
  benchmark::AddCustomContext("cpu_flags", cpu_flags());
  benchmark::AddCustomContext("compiler", __VERSION__);
  benchmark::AddCustomContext("threads", "1 (one thread per transform unless an impl says threads=N)");
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
