// The vulkan backend beyond the conformance suite (docs/vulkan.md): the accuracy target at
// 2048², the two-pass split beyond shared memory, batches beyond one storage-buffer binding,
// chains of plans on device buffers, device choice, and the device's timings. Every test skips
// with the reason where there is no Vulkan device (vulkan_test_support.hpp).
#include <gtest/gtest.h>

#include <complex>
#include <cstdlib>
#include <random>

#include "swell/impls/transform.hpp"
#include "swell/impls/vulkan.hpp"
#include "swell/validation/checks/transform_checks.hpp"
#include "vulkan_test_support.hpp"

namespace {

using namespace swell::impls;
using swell::validation::measure_transform_accuracy;

// `backend`: the vulkan backend, or the test returns (skipped or, required, failed).
#define VULKAN_OR_SKIP(backend)                             \
  const auto backend = swell::test::vulkan_or_skip();       \
  if (!backend) return

std::vector<std::complex<float>> random_complex(std::size_t n, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<std::complex<float>> v(n);
  for (auto& x : v) x = {u(engine), u(engine)};
  return v;
}

// The four kinds of transform, for the sweeps below.
constexpr std::pair<Kind, Direction> kKinds[] = {{Kind::c2c, Direction::forward},
                                                 {Kind::c2c, Direction::inverse},
                                                 {Kind::r2c, Direction::forward},
                                                 {Kind::c2r, Direction::inverse}};

// Relative L2 and L∞ error against the long-double oracle within the transform's bound.
void expect_within_bound(const Backend& backend, int nx, int ny, Kind kind, Direction direction,
                         Precision precision, unsigned seed) {
  TransformSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.kind = kind;
  spec.direction = direction;
  spec.precision = precision;
  const auto r = measure_transform_accuracy(backend, spec, seed);
  EXPECT_LE(r.rel_l2, r.bound) << spec.describe() << " against " << r.oracle;
  EXPECT_LE(r.rel_linf, r.bound) << spec.describe() << " against " << r.oracle;
}

TEST(Vulkan, Fp32At2048SquaredWithinFiveTimesTenToTheMinusSeven) {
  VULKAN_OR_SKIP(backend);
  TransformSpec spec;
  spec.nx = spec.ny = 2048;
  spec.direction = Direction::inverse;
  spec.precision = Precision::f32;
  const auto r = measure_transform_accuracy(*backend, spec, 42);
  // The target for the ocean's transform, and the general bound c·ε·log2 N.
  EXPECT_LE(r.rel_l2, 5e-7) << r.oracle;
  EXPECT_LE(r.rel_l2, r.bound) << r.oracle;
  EXPECT_LE(r.rel_linf, r.bound) << r.oracle;
}

// Every length whose kernel differs (docs/vulkan.md §Kernels), on either axis, through both
// line kernels — the subgroup kernel where the device has it (16 … 2048 points, 4096 as two
// 64-point passes; shorter lines take the portable one) and the portable Stockham kernel
// (subgroups=off): the portable kernel's first stages of radix 2, 4, 8 and 16 alone, radix 4, 8
// and 16 followed by a radix-8 stage, one and two radix-16 stages after it (4096 = 16·16·16
// fills lavapipe's shared memory: one copy, two barriers a stage); the subgroup kernel's lane
// counts L = 1, 2, 4, 8 (16 … 128 points) and exchange groups G = 2, 4, 16 (256, 512, 2048).
// Kind (c2c forward, c2r) and precision alternate over the lengths, so that each kernel meets
// each of them on short and long lines alike. The soak tier runs every length in every
// combination (VulkanSoak below).
TEST(Vulkan, EveryKernelPathOnEitherAxis) {
  VULKAN_OR_SKIP(backend);
  const auto portable = make_backend("vulkan:subgroups=off");
  const int lengths[] = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 2048, 4096};
  for (const Backend* b : {backend.get(), portable.get()}) {
    const auto& precisions = b->capabilities().precisions;
    for (std::size_t i = 0; i < std::size(lengths); ++i) {
      const int n = lengths[i];
      const Precision precision = precisions[i % precisions.size()];
      const auto [kind, direction] = (i / 2) % 2 ? std::pair{Kind::c2r, Direction::inverse}
                                                 : std::pair{Kind::c2c, Direction::forward};
      for (auto [nx, ny] : {std::pair{n, 16}, std::pair{16, n}}) {
        expect_within_bound(*b, nx, ny, kind, direction, precision, 13);
      }
    }
  }
}

// Every length 1 … 4096 on either axis, both precisions, c2c and c2r (r2c shares c2c's passes
// with other flags; the accuracy suite has it): each length selects its own first radix (2, 4,
// 8, 16) and number of radix-16 stages.
TEST(VulkanSoak, EveryPowerOfTwoLengthOnEitherAxis) {
  VULKAN_OR_SKIP(backend);
  for (Precision precision : backend->capabilities().precisions) {
    for (int n = 1; n <= 4096; n *= 2) {
      for (auto [nx, ny] : {std::pair{n, 2}, std::pair{4, n}}) {
        expect_within_bound(*backend, nx, ny, Kind::c2c, Direction::forward, precision, 11);
        expect_within_bound(*backend, nx, ny, Kind::c2r, Direction::inverse, precision, 11);
      }
    }
  }
}

// The two line kernels (docs/vulkan.md §Kernels) on every length from 16 to 4096:
// fft_lines_shuffle (registers, one shared-memory exchange, subgroup shuffles; 16 … 2048
// points, 4096 as two 64-point passes; 16 lines give every length a workgroup of 16 threads
// or more, whole subgroups on lavapipe) and, with subgroups=off, the portable Stockham kernel
// (4096 in one pass) — the one devices without subgroup shuffles run.
TEST(VulkanSoak, BothLineKernelsOnEveryLengthOnEitherAxis) {
  VULKAN_OR_SKIP(backend);
  const auto portable = make_backend("vulkan:subgroups=off");
  // The portable kernel's fp64 is its fp32 code on doubles (and runs beside the shuffle kernel
  // in EveryPowerOfTwoLength); r2c and c2c inverse take the same passes with other flags.
  for (const Backend* b : {backend.get(), portable.get()}) {
    for (Precision precision : b->capabilities().precisions) {
      if (b == portable.get() && precision == Precision::f64) continue;
      for (int n = 16; n <= 4096; n *= 2) {
        for (auto [nx, ny] : {std::pair{n, 16}, std::pair{16, n}}) {
          expect_within_bound(*b, nx, ny, Kind::c2c, Direction::forward, precision, 5);
          expect_within_bound(*b, nx, ny, Kind::c2r, Direction::inverse, precision, 5);
        }
      }
    }
  }
}

TEST(Vulkan, SubgroupsOptionIsOnOrOffAndVulkanOnly) {
  VULKAN_OR_SKIP(backend);
  EXPECT_NO_THROW(make_backend("vulkan:subgroups=on"));
  EXPECT_THROW(make_backend("vulkan:subgroups=maybe"), swell::InvalidInput);
  EXPECT_THROW(make_backend("fftw:subgroups=off"), swell::InvalidInput);
  EXPECT_THROW(make_backend("radix2:device=0"), swell::InvalidInput);
}

// Lines longer than any device's shared memory (256 KiB: 32768 fp32 or 16384 fp64 points) run
// as two passes (four-step), on either axis and for every kind.
TEST(Vulkan, LinesBeyondSharedMemoryRunAsTwoPassesOnEitherAxis) {
  VULKAN_OR_SKIP(backend);
  for (Precision precision : backend->capabilities().precisions) {
    const int long_side = precision == Precision::f32 ? 32768 : 16384;
    for (auto [nx, ny] : {std::pair{long_side, 2}, std::pair{4, long_side}}) {
      for (auto [kind, direction] : kKinds) expect_within_bound(*backend, nx, ny, kind, direction, precision, 7);
    }
  }
}

// A batch larger than one storage-buffer binding (lavapipe: 128 MiB) is dispatched one
// transform at a time; each must equal the transform done alone.
TEST(Vulkan, BatchBeyondOneBindingEqualsOneByOne) {
  VULKAN_OR_SKIP(backend);
  TransformSpec spec;
  spec.nx = spec.ny = 2048;
  spec.howmany = 5;  // 160 MiB of fp32 complex
  spec.precision = Precision::f32;
  spec.direction = Direction::inverse;
  spec.placement = Placement::in_place;
  const auto batch = backend->plan(spec);
  spec.howmany = 1;
  spec.placement = Placement::out_of_place;
  const auto single = backend->plan(spec);
  const std::size_t n = std::size_t(2048) * 2048;
  auto data = random_complex(5 * n, 3);
  const auto input = data;
  batch->execute(static_cast<const void*>(data.data()), static_cast<void*>(data.data()));
  std::vector<std::complex<float>> one(n);
  for (int b = 0; b < 5; b += 2) {
    single->execute(static_cast<const void*>(input.data() + b * n), static_cast<void*>(one.data()));
    for (std::size_t i = 0; i < n; i += 997) {
      ASSERT_EQ(data[b * n + i], one[i]) << "batch member " << b << ", element " << i;
    }
  }
}

// Plans on the backend's Buffers stay on the device: forward then inverse, never through the
// host, gives N times the input, and equals what host execution gives.
TEST(Vulkan, ChainOfPlansOnDeviceBuffers) {
  VULKAN_OR_SKIP(backend);
  TransformSpec spec;
  spec.nx = 256;
  spec.ny = 128;
  spec.precision = Precision::f32;
  const auto forward = backend->plan(spec);
  spec.direction = Direction::inverse;
  spec.placement = Placement::in_place;
  const auto inverse = backend->plan(spec);
  const std::size_t n = std::size_t(256) * 128;
  const auto input = random_complex(n, 5);
  auto a = backend->allocate(spec.input_bytes());
  auto b = backend->allocate(spec.output_bytes());
  EXPECT_EQ(a->host_data(), nullptr);  // device memory
  a->upload(input.data(), spec.input_bytes());
  forward->execute(*a, *b);
  std::vector<std::complex<float>> spectrum(n), host_spectrum(n), round_trip(n);
  b->download(spectrum.data(), spec.output_bytes());
  forward->execute(static_cast<const void*>(input.data()), static_cast<void*>(host_spectrum.data()));
  EXPECT_EQ(spectrum, host_spectrum);
  inverse->execute(*b, *b);
  b->download(round_trip.data(), spec.output_bytes());
  double error = 0, norm = 0;
  for (std::size_t i = 0; i < n; ++i) {
    error += std::norm(round_trip[i] / float(n) - input[i]);
    norm += std::norm(input[i]);
  }
  EXPECT_LE(std::sqrt(error / norm), 2 * swell::validation::transform_error_bound(spec));
  // Buffers of another backend, or an in-place plan given two buffers, are refused.
  auto host = make_backend("radix2")->allocate(spec.input_bytes());
  EXPECT_THROW(forward->execute(*host, *b), swell::InvalidInput);
  EXPECT_THROW(inverse->execute(*a, *b), swell::InvalidInput);
}

TEST(Vulkan, TimingsComeFromTheDevice) {
  VULKAN_OR_SKIP(backend);
  TransformSpec spec;
  spec.nx = spec.ny = 512;
  spec.precision = Precision::f32;
  const auto plan = backend->plan(spec);
  const auto input = random_complex(512 * 512, 9);
  std::vector<std::complex<float>> out(input.size());
  const auto t = vulkan_execute_timed(*plan, input.data(), out.data());
  EXPECT_GT(t.upload_seconds, 0);
  EXPECT_GT(t.compute_seconds, 0);
  EXPECT_GT(t.download_seconds, 0);
  EXPECT_LT(t.compute_seconds, 10);
  EXPECT_THROW(vulkan_execute_timed(*make_backend("radix2")->plan(spec), input.data(), out.data()),
               swell::InvalidInput);
}

TEST(Vulkan, DeviceChoiceByOptionAndEnvironment) {
  VULKAN_OR_SKIP(backend);
  const std::string chosen = vulkan_device_description("vulkan");
  EXPECT_NE(chosen.find("Vulkan 1."), std::string::npos) << chosen;
  EXPECT_NE(chosen.find("device "), std::string::npos) << chosen;
  EXPECT_NO_THROW(make_backend("vulkan:device=0"));
  try {
    make_backend("vulkan:device=200");
    ADD_FAILURE() << "device 200 accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("device 200"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_backend("vulkan:device=x"), swell::InvalidInput);
  EXPECT_THROW(make_backend("vulkan:threads=2"), swell::InvalidInput);
  const char* previous = std::getenv("SWELL_VULKAN_DEVICE");
  const std::string saved = previous ? previous : "";
  setenv("SWELL_VULKAN_DEVICE", "gpu", 1);
  EXPECT_THROW(make_backend("vulkan"), swell::InvalidInput);
  setenv("SWELL_VULKAN_DEVICE", "0", 1);
  EXPECT_NE(vulkan_device_description("vulkan").find("device 0 of"), std::string::npos);
  if (previous) setenv("SWELL_VULKAN_DEVICE", saved.c_str(), 1); else unsetenv("SWELL_VULKAN_DEVICE");
}

TEST(Vulkan, RefusesWhatNoBindingHoldsNamingTheLimit) {
  VULKAN_OR_SKIP(backend);
  TransformSpec spec;
  spec.nx = spec.ny = 32768;  // 8 GiB of fp32 complex: beyond any maxStorageBufferRange (< 4 GiB)
  spec.precision = Precision::f32;
  try {
    backend->plan(spec);
    ADD_FAILURE() << "no refusal";
  } catch (const UnsupportedTransform& e) {
    EXPECT_NE(std::string(e.what()).find("maxStorageBufferRange"), std::string::npos) << e.what();
  }
}

}  // namespace
