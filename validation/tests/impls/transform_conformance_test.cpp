// Conformance of every registered transform backend, written once and instantiated over
// backend × precision × kind × size (docs/transforms.md):
//  - accuracy against the long-double oracle within c·ε·log2 N (transform_checks.hpp says why),
//  - FFTW's randomized self-test (Ergün) and the other invariants (fft_invariants.hpp),
//  - in-place and batched execution, thread safety, and one kind of error for what a backend
//    cannot do.
// The long-double FFTW oracle used beyond 256² is itself checked here against the naive DFT.
#include <fftw3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <random>
#include <thread>

#include "swell/impls/radix2_kernel.hpp"
#include "swell/impls/transform.hpp"
#include "swell/validation/testing/fft_invariants.hpp"
#include "swell/validation/checks/transform_checks.hpp"
#include "vulkan_test_support.hpp"

namespace {

using namespace swell::impls;
namespace fi = swell::fft_invariants;
using swell::validation::measure_transform_accuracy;
using swell::validation::transform_error_bound;

// Test backends with fast planning; the MEASURE planner gets its own test below.
std::string configured(const std::string& name) {
  return name == "fftw" ? "fftw:planner=estimate" : name;
}

// A backend that cannot start here (vulkan without a device) says why; its name is left out of
// the parameterized suites and Registry.EveryBackendStartsOrSaysWhy reports it.
std::string why_unavailable(const std::string& name) {
  try {
    make_backend(configured(name));
    return "";
  } catch (const UnsupportedTransform& e) {
    return e.what();
  }
}

// Asked once per process: the three instantiations below share it (starting vulkan loads the
// Vulkan loader's drivers, ~0.1 s each time).
const std::vector<std::string>& available_backends() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& name : backend_names()) {
      if (why_unavailable(name).empty()) out.push_back(name);
    }
    return out;
  }();
  return names;
}

struct Case {
  std::string backend;
  Precision precision;
  Kind kind;
  Direction direction;
  int nx, ny;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.backend << " " << to_string(c.precision) << " " << to_string(c.kind) << " "
      << to_string(c.direction) << " " << c.nx << "×" << c.ny;
}

std::string case_name(const testing::TestParamInfo<Case>& info) {
  const auto& c = info.param;
  return c.backend + "_" + to_string(c.precision) + "_" + to_string(c.kind) +
         (c.kind == Kind::c2c ? (c.direction == Direction::forward ? "fwd" : "inv") : "") + "_" +
         std::to_string(c.nx) + "x" + std::to_string(c.ny);
}

std::vector<std::pair<int, int>> sizes_for(const Capabilities& caps) {
  // 1-D: 1, 2 and (where allowed) small primes and odd sizes; 2-D up to 1024².
  // The powers of two from 128 to 16384 in 1-D and the long thin shapes reach every path of
  // radix2's fused passes (gathers of 4 and 8, scatters of 4, 8 and 16, middle stages in chunks
  // and over the whole scratch).
  std::vector<std::pair<int, int>> sizes = {{1, 1},    {2, 1},     {8, 1},      {64, 1},
                                            {128, 1},  {512, 1},   {1024, 1},   {4096, 1},
                                            {16384, 1}, {2, 2},    {4, 8},      {16, 16},
                                            {64, 32},  {4096, 8},  {8, 4096},   {256, 256},
                                            {1024, 1024}};
  if (caps.any_size) {
    for (auto s : std::vector<std::pair<int, int>>{{3, 1}, {5, 1}, {7, 1}, {12, 1}, {15, 1},
                                                   {5, 3}, {12, 7}, {15, 9}}) {
      sizes.push_back(s);
    }
  }
  return sizes;
}

std::vector<Case> accuracy_cases() {
  std::vector<Case> cases;
  for (const auto& name : available_backends()) {
    const auto backend = make_backend(configured(name));
    const auto caps = backend->capabilities();
    if (!caps.exact) continue;
    for (Precision p : caps.precisions) {
      for (auto [nx, ny] : sizes_for(caps)) {
        const double cost = double(nx) * ny * (nx + ny);
        // fp80 results are compared with a long-double oracle: informative only where the oracle
        // is the naive DFT (checking FFTW's long-double build against it), and naive-vs-naive is
        // no test at all.
        if (p == Precision::f80 && (name == "naive" || cost > 256.0 * 256 * 512)) continue;
        if (name == "naive" && cost > 256.0 * 256 * 512) continue;  // O(N²): the oracle's range
        for (auto [kind, direction] : {std::pair{Kind::c2c, Direction::forward},
                                       std::pair{Kind::c2c, Direction::inverse},
                                       std::pair{Kind::r2c, Direction::forward},
                                       std::pair{Kind::c2r, Direction::inverse}}) {
          cases.push_back({name, p, kind, direction, nx, ny});
        }
      }
    }
  }
  return cases;
}

class Accuracy : public testing::TestWithParam<Case> {};

// Issue 17's accuracy floor for the fast radix2: fp32 2048² relative L2 ≤ 5e-7 (the general
// bound above is looser, ~ε·log2 N² with a margin); an error of one misplaced twiddle or a
// stage done in the wrong order is orders of magnitude larger.
TEST(Radix2, Fp32At2048SquaredWithinFiveTimesTenToTheMinusSeven) {
  const auto backend = make_backend("radix2");
  for (Direction direction : {Direction::forward, Direction::inverse}) {
    TransformSpec spec;
    spec.nx = spec.ny = 2048;
    spec.kind = Kind::c2c;
    spec.direction = direction;
    spec.precision = Precision::f32;
    const auto r = measure_transform_accuracy(*backend, spec, 17);
    EXPECT_LE(r.rel_l2, 5e-7) << spec.describe() << " against " << r.oracle;
    RecordProperty(to_string(direction) + "_rel_l2", std::to_string(r.rel_l2));
    std::printf("radix2 %s: relative L2 %.3g against %s\n", spec.describe().c_str(), r.rel_l2,
                r.oracle.c_str());
    EXPECT_GT(r.rel_l2, 1e-8) << "no rounding at all: was anything compared?";
  }
}

// The benchmarks' arithmetic roof for radix2 (radix2_kernel.hpp): a rate per vector of one
// register's width (16, 32 or 64 bytes, the same for both precisions), a positive time below a
// microsecond per vector butterfly (thousands of cycles: a broken count, not a slow machine), and
// a clear refusal for a precision radix2 does not compute.
TEST(Radix2, KernelRateIsPerRegisterWideVectorAndRefusesFp80) {
  const auto f32 = measure_radix2_kernel_rate(Precision::f32, 3);
  const auto f64 = measure_radix2_kernel_rate(Precision::f64, 3);
  const int register_bytes = f32.lanes * int(sizeof(float));
  std::printf("radix2 kernel: %d-byte vectors, fp32 %.3g ns, fp64 %.3g ns per vector butterfly\n",
              register_bytes, f32.seconds_per_vector_butterfly * 1e9,
              f64.seconds_per_vector_butterfly * 1e9);
  EXPECT_TRUE(register_bytes == 16 || register_bytes == 32 || register_bytes == 64) << f32.lanes;
  EXPECT_EQ(f64.lanes * int(sizeof(double)), register_bytes);
  for (const auto& rate : {f32, f64}) {
    EXPECT_TRUE(std::isfinite(rate.seconds_per_vector_butterfly));
    EXPECT_GT(rate.seconds_per_vector_butterfly, 0.0);
    EXPECT_LT(rate.seconds_per_vector_butterfly, 1e-6);
  }
  try {
    measure_radix2_kernel_rate(Precision::f80);
    ADD_FAILURE() << "fp80 accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("fp80"), std::string::npos) << e.what();
  }
}

TEST_P(Accuracy, WithinBoundOfLongDoubleOracle) {
  const auto& c = GetParam();
  const auto backend = make_backend(configured(c.backend));
  TransformSpec spec;
  spec.nx = c.nx;
  spec.ny = c.ny;
  spec.kind = c.kind;
  spec.direction = c.direction;
  spec.precision = c.precision;
  const auto r = measure_transform_accuracy(*backend, spec, 42);
  EXPECT_LE(r.rel_l2, r.bound) << spec.describe() << " against " << r.oracle;
  EXPECT_LE(r.rel_linf, r.bound) << spec.describe() << " against " << r.oracle;
  // A result exactly equal to the oracle in fp32/fp64 would mean the comparison compared
  // nothing (the output was the oracle's); beyond tiny sizes, rounding is unavoidable.
  if (c.precision != Precision::f80 && c.nx * c.ny >= 16) {
    EXPECT_GT(r.rel_l2, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, Accuracy, testing::ValuesIn(accuracy_cases()), case_name);

// ------------------------------------------------------------------ invariants

struct InvariantCase {
  std::string backend;
  Precision precision;
  int nx, ny;
};

std::vector<InvariantCase> invariant_cases() {
  std::vector<InvariantCase> cases;
  for (const auto& name : available_backends()) {
    const auto caps = make_backend(configured(name))->capabilities();
    if (!caps.exact) continue;
    for (Precision p : {Precision::f32, Precision::f64}) {
      std::vector<std::pair<int, int>> sizes = {{1, 1}, {2, 1}, {16, 1}, {8, 4}, {32, 64}, {128, 128}};
      if (caps.any_size) sizes.insert(sizes.end(), {{7, 1}, {12, 5}});
      for (auto [nx, ny] : sizes) cases.push_back({name, p, nx, ny});
    }
  }
  return cases;
}

void PrintTo(const InvariantCase& c, std::ostream* os) {
  *os << c.backend << " " << to_string(c.precision) << " " << c.nx << "×" << c.ny;
}

std::string invariant_name(const testing::TestParamInfo<InvariantCase>& info) {
  return info.param.backend + "_" + to_string(info.param.precision) + "_" +
         std::to_string(info.param.nx) + "x" + std::to_string(info.param.ny);
}

template <typename T>
fi::Transform<T> as_transform(const Plan& plan) {
  return [&plan](const std::complex<T>* in, std::complex<T>* out) {
    plan.execute(static_cast<const void*>(in), static_cast<void*>(out));
  };
}

template <typename T>
void expect_invariants(const Backend& backend, int nx, int ny, Precision p) {
  TransformSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.precision = p;
  const auto forward = backend.plan(spec);
  spec.direction = Direction::inverse;
  const auto inverse = backend.plan(spec);
  fi::Setup setup;
  setup.nx = nx;
  setup.ny = ny;
  // Each side of an invariant carries up to one transform's error bound, some sides two or
  // three transforms (linearity: three); 3 × the single-transform bound.
  setup.tolerance = 3 * transform_error_bound(spec);
  setup.seed = 7;
  EXPECT_FFT_INVARIANTS_HOLD(T, as_transform<T>(*forward), as_transform<T>(*inverse), setup);

  TransformSpec c2r_spec = spec;
  c2r_spec.kind = Kind::c2r;
  if (nx * ny <= 64 * 64) {  // the invariant builds its Hermitian spectrum by an O(N²) DFT
    const auto c2r = backend.plan(c2r_spec);
    fi::HalfToReal<T> half_to_real = [&](const std::complex<T>* in, T* out) {
      c2r->execute(static_cast<const void*>(in), static_cast<void*>(out));
    };
    auto inv = setup;
    inv.sign = +1;
    EXPECT_TRUE(fi::c2r_matches_c2c<T>(half_to_real, as_transform<T>(*inverse), inv));
  }
}

class Invariants : public testing::TestWithParam<InvariantCase> {};

TEST_P(Invariants, ErgunSelfTestRoundTripParsevalHermitian) {
  const auto& c = GetParam();
  const auto backend = make_backend(configured(c.backend));
  if (c.precision == Precision::f32) {
    expect_invariants<float>(*backend, c.nx, c.ny, c.precision);
  } else {
    expect_invariants<double>(*backend, c.nx, c.ny, c.precision);
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, Invariants, testing::ValuesIn(invariant_cases()), invariant_name);

// ------------------------------------------------------------------ placement, batches, threads

class EveryBackend : public testing::TestWithParam<std::string> {};

std::vector<double> random_reals(std::size_t n, unsigned seed) {
  std::mt19937_64 engine(seed);
  std::vector<double> v(n);
  for (auto& x : v) x = 2.0 * ((engine() >> 11) * 0x1.0p-53) - 1.0;
  return v;
}

TEST_P(EveryBackend, InPlaceEqualsOutOfPlace) {
  const auto backend = make_backend(configured(GetParam()));
  TransformSpec spec;
  spec.nx = 32;
  spec.ny = 16;
  spec.direction = Direction::inverse;
  const auto out_of_place = backend->plan(spec);
  spec.placement = Placement::in_place;
  const auto in_place = backend->plan(spec);
  const auto input = random_reals(2 * 32 * 16, 3);
  std::vector<double> a(input.size()), b = input;
  out_of_place->execute(static_cast<const void*>(input.data()), static_cast<void*>(a.data()));
  in_place->execute(static_cast<const void*>(b.data()), static_cast<void*>(b.data()));
  EXPECT_EQ(a, b);  // same algorithm on the same numbers
}

TEST_P(EveryBackend, BatchEqualsOneByOne) {
  const auto backend = make_backend(configured(GetParam()));
  for (auto [nx, ny, howmany] : {std::tuple{64, 1, 19}, std::tuple{16, 8, 3}}) {
    TransformSpec spec;
    spec.nx = nx;
    spec.ny = ny;
    spec.howmany = howmany;
    spec.precision = Precision::f32;
    const auto batch = backend->plan(spec);
    spec.howmany = 1;
    const auto single = backend->plan(spec);
    const std::size_t n = std::size_t(nx) * ny;
    const auto reals = random_reals(2 * n * howmany, 5);
    std::vector<std::complex<float>> in(n * howmany), all(n * howmany), one(n);
    for (std::size_t i = 0; i < in.size(); ++i) in[i] = {float(reals[2 * i]), float(reals[2 * i + 1])};
    batch->execute(std::span<const std::complex<float>>(in), std::span<std::complex<float>>(all));
    for (int b = 0; b < howmany; ++b) {
      single->execute(std::span<const std::complex<float>>(in.data() + b * n, n),
                      std::span<std::complex<float>>(one));
      for (std::size_t i = 0; i < n; ++i) {
        // Batched and single may vectorize differently: equal to a few ulps of the data.
        ASSERT_LE(std::abs(all[b * n + i] - one[i]), 1e-5f) << "batch member " << b << ", " << i;
      }
    }
  }
}

TEST_P(EveryBackend, PlansAreSafeToShareBetweenThreads) {
  const auto backend = make_backend(configured(GetParam()));
  TransformSpec spec;
  spec.nx = spec.ny = 128;
  const auto plan = backend->plan(spec);
  const auto input = random_reals(2 * 128 * 128, 9);
  std::vector<double> expected(input.size());
  plan->execute(static_cast<const void*>(input.data()), static_cast<void*>(expected.data()));
  std::vector<std::vector<double>> outputs(4, std::vector<double>(input.size()));
  std::vector<std::thread> threads;
  for (auto& out : outputs) {
    threads.emplace_back([&, o = out.data()] {
      for (int repeat = 0; repeat < 5; ++repeat) {
        plan->execute(static_cast<const void*>(input.data()), static_cast<void*>(o));
      }
    });
  }
  for (auto& t : threads) t.join();
  for (const auto& out : outputs) EXPECT_EQ(out, expected);
}

// `spec` (precision T) run by both backends on the same random input: with `bit_for_bit` the
// outputs must be identical, otherwise within twice the transform's error bound of each other.
template <typename T>
void expect_same_output(const Backend& first, const Backend& second, const TransformSpec& spec,
                        bool bit_for_bit) {
  const auto values = random_reals(spec.input_bytes() / sizeof(T), 17);
  const std::vector<T> input(values.begin(), values.end());
  std::vector<T> a(spec.output_bytes() / sizeof(T)), b(a.size());
  first.plan(spec)->execute(static_cast<const void*>(input.data()), static_cast<void*>(a.data()));
  second.plan(spec)->execute(static_cast<const void*>(input.data()), static_cast<void*>(b.data()));
  if (bit_for_bit) {
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(T)), 0)
        << spec.describe() << ": the outputs differ";
    return;
  }
  double err = 0, ref = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    err += (double(a[i]) - double(b[i])) * (double(a[i]) - double(b[i]));
    ref += double(a[i]) * double(a[i]);
  }
  EXPECT_LE(std::sqrt(err / ref), 2 * transform_error_bound(spec)) << spec.describe();
}

// A backend that claims multi_threaded computes with 2 threads what it computes with 1. The
// shapes are above every threading threshold (radix2: ≥ 2¹⁵ points, ≥ 2 row blocks and ≥ 4
// column blocks a thread at 16 lanes; fftw: 4 MiB of complex data), so the threaded code runs —
// at 64², say, both would fall back to one thread and this could not fail. Square, wide, tall,
// a batch of rows, and r2c/c2r, in both precisions. radix2 splits its passes by blocks of
// signals, each transformed by the same code whichever thread runs it: bit for bit. FFTW's
// threaded plans may factor differently: within the transform's error bound.
TEST_P(EveryBackend, TwoThreadsComputeWhatOneDoes) {
  const std::string name = configured(GetParam());
  const auto one_thread = make_backend(name);
  if (!one_thread->capabilities().multi_threaded) GTEST_SKIP() << GetParam() << " runs one thread";
  const auto two_threads =
      make_backend(name + (name.find(':') == std::string::npos ? ":" : ",") + "threads=2");
  const bool bit_for_bit = GetParam() == "radix2";
  using enum Kind;
  using enum Direction;
  for (TransformSpec spec : {TransformSpec{.nx = 1024, .ny = 512, .kind = c2c, .direction = forward},
                             TransformSpec{.nx = 512, .ny = 1024, .kind = c2c, .direction = inverse},
                             TransformSpec{.nx = 4096, .ny = 128, .kind = c2c, .direction = inverse},
                             TransformSpec{.nx = 128, .ny = 4096, .kind = c2c, .direction = forward},
                             TransformSpec{.nx = 8192, .howmany = 64, .kind = c2c, .direction = inverse},
                             TransformSpec{.nx = 1024, .ny = 1024, .kind = r2c, .direction = forward},
                             TransformSpec{.nx = 1024, .ny = 1024, .kind = c2r, .direction = inverse}}) {
    spec.precision = Precision::f32;
    expect_same_output<float>(*one_thread, *two_threads, spec, bit_for_bit);
    spec.precision = Precision::f64;
    expect_same_output<double>(*one_thread, *two_threads, spec, bit_for_bit);
  }
}

TEST_P(EveryBackend, RejectsWhatItCannotDoNamingBackendSizeAndRule) {
  const auto backend = make_backend(configured(GetParam()));
  auto expect_refusal = [&](TransformSpec spec, const std::string& words) {
    try {
      backend->plan(spec);
      ADD_FAILURE() << "no error for " << spec.describe();
    } catch (const UnsupportedTransform& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(backend->name()), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  TransformSpec zero;
  zero.nx = 0;
  expect_refusal(zero, "≥ 1");
  TransformSpec real_inverse;
  real_inverse.nx = 8;
  real_inverse.kind = Kind::r2c;
  real_inverse.direction = Direction::inverse;
  expect_refusal(real_inverse, "forward only");
  TransformSpec in_place_real;
  in_place_real.nx = 8;
  in_place_real.kind = Kind::c2r;
  in_place_real.direction = Direction::inverse;
  in_place_real.placement = Placement::in_place;
  expect_refusal(in_place_real, "in-place");
  if (!backend->capabilities().any_size) {
    TransformSpec twelve;
    twelve.nx = 12;
    expect_refusal(twelve, "powers of two");
    TransformSpec tall;
    tall.nx = 16;
    tall.ny = 24;
    expect_refusal(tall, "24");
  }
}

TEST_P(EveryBackend, TypedExecuteChecksSizesAndTypes) {
  const auto backend = make_backend(configured(GetParam()));
  TransformSpec spec;
  spec.nx = 8;
  spec.precision = Precision::f32;
  const auto plan = backend->plan(spec);
  std::vector<std::complex<float>> in(8), out(8), short_out(7);
  std::vector<std::complex<double>> wrong_type(8);
  EXPECT_NO_THROW(plan->execute(std::span<const std::complex<float>>(in), std::span<std::complex<float>>(out)));
  EXPECT_THROW(plan->execute(std::span<const std::complex<float>>(in), std::span<std::complex<float>>(short_out)),
               swell::InvalidInput);
  EXPECT_THROW(plan->execute(std::span<const std::complex<double>>(wrong_type), std::span<std::complex<float>>(out)),
               swell::InvalidInput);
  EXPECT_THROW(plan->execute(std::span<const std::complex<float>>(in), std::span<std::complex<float>>(in)),
               swell::InvalidInput);  // aliased buffers for an out-of-place plan
}

TEST_P(EveryBackend, OutOfPlaceLeavesInputBitIdenticalForEveryKind) {
  const auto backend = make_backend(configured(GetParam()));
  for (Kind kind : {Kind::c2c, Kind::r2c, Kind::c2r}) {
    TransformSpec spec;
    spec.nx = 16;
    spec.ny = 8;
    spec.kind = kind;
    spec.direction = kind == Kind::r2c ? Direction::forward : Direction::inverse;
    const auto plan = backend->plan(spec);
    const auto input = random_reals(spec.input_bytes() / sizeof(double), 11);
    auto copy = input;
    std::vector<double> out(spec.output_bytes() / sizeof(double));
    plan->execute(static_cast<const void*>(copy.data()), static_cast<void*>(out.data()));
    EXPECT_EQ(copy, input) << to_string(kind);
  }
}

// One input mode lands in exactly one output bin: e^(+2πi(a n/nx + b m/ny)) transforms forward
// to nx·ny at (a, b) and inverse to nx·ny at (−a, −b) (e^(−…) the other way round), zero
// elsewhere. A transposed output (nx ≠ ny), a conjugated one (a ≠ −a mod n) or a wrong sign
// convention puts the peak in another bin; round trips and Parseval cannot see these.
TEST_P(EveryBackend, PlaneWaveLandsInItsBinPerAxisAndSign) {
  const auto backend = make_backend(configured(GetParam()));
  if (!backend->capabilities().exact) GTEST_SKIP() << GetParam() << " copies instead of transforming";
  for (auto [nx, ny] : {std::pair{16, 8}, std::pair{64, 1}}) {
    for (Precision precision : backend->capabilities().precisions) {
      if (precision == Precision::f80) continue;
      for (Direction direction : {Direction::forward, Direction::inverse}) {
        for (int sign : {+1, -1}) {
          for (auto [a, b] : {std::pair{3, 0}, std::pair{0, ny > 1 ? 3 : 0}}) {
            if (a == 0 && b == 0) continue;
            TransformSpec spec;
            spec.nx = nx;
            spec.ny = ny;
            spec.direction = direction;
            spec.precision = Precision::f64;
            std::vector<std::complex<double>> in(std::size_t(nx) * ny), out(in.size());
            const long double two_pi = 6.283185307179586476925286766559005768L;
            for (int m = 0; m < ny; ++m) {
              for (int n = 0; n < nx; ++n) {
                const long double angle = sign * two_pi * ((long double)(a * n) / nx + (long double)(b * m) / ny);
                in[std::size_t(m) * nx + n] = {double(std::cos(angle)), double(std::sin(angle))};
              }
            }
            // Run in the precision under test, compare in double.
            spec.precision = precision;
            const auto plan = backend->plan(spec);
            if (precision == Precision::f32) {
              std::vector<std::complex<float>> in32(in.begin(), in.end()), out32(in.size());
              plan->execute(static_cast<const void*>(in32.data()), static_cast<void*>(out32.data()));
              out.assign(out32.begin(), out32.end());
            } else {
              plan->execute(static_cast<const void*>(in.data()), static_cast<void*>(out.data()));
            }
            const int s = direction == Direction::forward ? sign : -sign;
            const int peak_n = ((s * a) % nx + nx) % nx, peak_m = ((s * b) % ny + ny) % ny;
            const double total = double(nx) * ny;
            // The bound is on the error's L2 norm relative to the output's, N here; no bin's
            // error exceeds the norm.
            const double tolerance = total * transform_error_bound(spec);
            for (int m = 0; m < ny; ++m) {
              for (int n = 0; n < nx; ++n) {
                const std::complex<double> want = (n == peak_n && m == peak_m) ? total : 0.0;
                ASSERT_LE(std::abs(out[std::size_t(m) * nx + n] - want), tolerance)
                    << spec.describe() << ", mode (" << a << ", " << b << ") sign " << sign
                    << ": bin (" << n << ", " << m << ") holds " << out[std::size_t(m) * nx + n]
                    << ", the mode belongs at (" << peak_n << ", " << peak_m << ")";
              }
            }
          }
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryBackend, testing::ValuesIn(available_backends()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

// Every registered backend starts here, or (vulkan without a device, which is not an error)
// says why — and SWELL_REQUIRE_VULKAN=1 makes that a failure too.
TEST(Registry, EveryBackendStartsOrSaysWhy) {
  for (const auto& name : backend_names()) {
    const std::string why = why_unavailable(name);
    if (why.empty()) continue;
    EXPECT_NE(why.find(name), std::string::npos) << why;
    if (name != "vulkan") ADD_FAILURE() << why;
    else SWELL_SKIP_WITHOUT_VULKAN(why);
  }
}

// ------------------------------------------------------------------ registry and FFTW options

TEST(Registry, UnknownNamesAndOptionsListWhatIsValid) {
  try {
    make_backend("fftx");
    FAIL();
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("radix2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_backend("fftw:planner=fast"), swell::InvalidInput);
  EXPECT_THROW(make_backend("radix2:threads=0"), swell::InvalidInput);
  EXPECT_THROW(make_backend("radix2:color=blue"), swell::InvalidInput);
  EXPECT_NO_THROW(make_backend("fftw:planner=estimate,threads=2"));
}

TEST(Fftw, MeasurePlannerAndThreadsAgreeWithEstimate) {
  // MEASURE may pick other algorithms: equal to within the error bound, not bit for bit.
  TransformSpec spec;
  spec.nx = spec.ny = 64;
  const auto input = random_reals(2 * 64 * 64, 13);
  std::vector<double> a(input.size()), b(input.size());
  make_backend("fftw:planner=estimate")->plan(spec)->execute(input.data(), a.data());
  make_backend("fftw:planner=measure,threads=2")->plan(spec)->execute(input.data(), b.data());
  double err = 0, ref = 0;
  for (std::size_t i = 0; i < a.size(); ++i) err += (a[i] - b[i]) * (a[i] - b[i]), ref += a[i] * a[i];
  EXPECT_LE(std::sqrt(err / ref), 2 * transform_error_bound(spec));
}

TEST(Fftw, MisalignedArraysGoThroughAlignedCopies) {
  TransformSpec spec;
  spec.nx = 64;
  spec.precision = Precision::f32;
  const auto plan = make_backend("fftw:planner=estimate")->plan(spec);
  // Offset by one float: misaligned for FFTW's SIMD codelets.
  std::vector<float> storage_in(2 * 64 + 1), storage_out(2 * 64 + 1), aligned_out(2 * 64);
  const auto reals = random_reals(2 * 64, 17);
  for (int i = 0; i < 128; ++i) storage_in[i + 1] = float(reals[i]);
  plan->execute(storage_in.data() + 1, storage_out.data() + 1);
  std::vector<float> aligned_in(storage_in.begin() + 1, storage_in.end());
  auto buffer_in = make_backend("fftw")->allocate(128 * sizeof(float));
  auto buffer_out = make_backend("fftw")->allocate(128 * sizeof(float));
  buffer_in->upload(aligned_in.data(), 128 * sizeof(float));
  plan->execute(*buffer_in, *buffer_out);
  buffer_out->download(aligned_out.data(), 128 * sizeof(float));
  EXPECT_TRUE(std::equal(aligned_out.begin(), aligned_out.end(), storage_out.begin() + 1));
}

TEST(Null, CopiesAndIsNotExact) {
  const auto backend = make_backend("null");
  EXPECT_FALSE(backend->capabilities().exact);
  TransformSpec spec;
  spec.nx = 8;
  const auto input = random_reals(16, 19);
  std::vector<double> out(16);
  backend->plan(spec)->execute(input.data(), out.data());
  EXPECT_EQ(out, input);
}

// The fftw backend runs an estimate-planned 2-D c2c on rows padded by one element where the
// rows' length in bytes is a multiple of 1 KiB (impls/src/backends/fftw.cpp, pads_rows: the column pass
// on the unpadded array thrashes the cache, 12.5 against 1.8 ms at 512² fp64). The gate's reports
// depend on its last bits, so it must round exactly as FFTW's own estimate plan of the unpadded
// array: compared here bit for bit, padded sizes and unpadded ones, both directions, all three
// precisions (fp80 is never padded). Wisdom is forgotten first: an estimate plan takes any
// wisdom the process holds.
template <typename Real, typename FftwComplex, typename FftwPlan, typename PlanFn, typename ExecFn,
          typename DestroyFn, typename ForgetFn>
void expect_same_bits_as_fftw(Precision precision, PlanFn plan_2d, ExecFn execute, DestroyFn destroy,
                              ForgetFn forget) {
  forget();
  const auto backend = make_backend("fftw:planner=estimate");
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{16, 16}, {64, 64}, {128, 128}, {256, 256},
                                                                {512, 512}, {64, 256}, {256, 64}, {1024, 16},
                                                                {512, 96}, {96, 512}, {100, 100}, {768, 768},
                                                                {1024, 1024}, {2048, 32}}) {
    for (Direction direction : {Direction::forward, Direction::inverse}) {
      const std::size_t count = std::size_t(nx) * ny;
      auto* in = static_cast<FftwComplex*>(fftw_malloc(count * sizeof(FftwComplex)));
      auto* expected = static_cast<FftwComplex*>(fftw_malloc(count * sizeof(FftwComplex)));
      std::vector<std::complex<Real>> data(count), got(count);
      for (auto& z : data) z = {Real(normal(rng)), Real(normal(rng))};
      FftwPlan reference = plan_2d(ny, nx, in, expected, direction == Direction::forward ? FFTW_FORWARD : FFTW_BACKWARD,
                                   FFTW_ESTIMATE);
      ASSERT_NE(reference, nullptr);
      std::memcpy(in, data.data(), count * sizeof(FftwComplex));
      execute(reference);
      TransformSpec spec;
      spec.nx = nx;
      spec.ny = ny;
      spec.direction = direction;
      spec.precision = precision;
      backend->plan(spec)->execute(data.data(), got.data());
      // By value: fp80's 16-byte storage holds 6 bytes of padding that memcmp would compare.
      std::size_t differing = 0;
      for (std::size_t e = 0; e < count; ++e) {
        differing += got[e].real() != expected[e][0] || got[e].imag() != expected[e][1];
      }
      EXPECT_EQ(differing, 0u)
          << nx << "×" << ny << (direction == Direction::forward ? " forward" : " inverse") << " bytes/real "
          << sizeof(Real);
      // Again from an input one element off its allocation (8 bytes off FFTW's alignment in
      // fp32: the plan then runs on an aligned copy).
      std::vector<std::complex<Real>> shifted(count + 1);
      std::copy(data.begin(), data.end(), shifted.begin() + 1);
      backend->plan(spec)->execute(shifted.data() + 1, got.data());
      differing = 0;
      for (std::size_t e = 0; e < count; ++e) {
        differing += got[e].real() != expected[e][0] || got[e].imag() != expected[e][1];
      }
      EXPECT_EQ(differing, 0u) << nx << "×" << ny << " from a shifted input, bytes/real " << sizeof(Real);
      destroy(reference);
      fftw_free(in);
      fftw_free(expected);
    }
  }
}

TEST(TransformConformance, FftwEstimateOnPaddedRowsIsBitForBitFftwsOwnPlan) {
  expect_same_bits_as_fftw<float, fftwf_complex, fftwf_plan>(
      Precision::f32, fftwf_plan_dft_2d, fftwf_execute, fftwf_destroy_plan, fftwf_forget_wisdom);
  expect_same_bits_as_fftw<double, fftw_complex, fftw_plan>(
      Precision::f64, fftw_plan_dft_2d, fftw_execute, fftw_destroy_plan, fftw_forget_wisdom);
  expect_same_bits_as_fftw<long double, fftwl_complex, fftwl_plan>(
      Precision::f80, fftwl_plan_dft_2d, fftwl_execute, fftwl_destroy_plan, fftwl_forget_wisdom);
}


// execute_over_input writes back over its input exactly what execute writes into another
// array: through FFTW's padded rows (64 fp64 complex rows are 1 KiB), its pool's array (48×20,
// a 1-D 100, fp32), an input off FFTW's alignment, an in-place plan, and the default of a
// backend without its own (naive, radix2). Fails if the write-back takes the wrong array or
// misses rows, or if the padded rows are copied back at the wrong pitch.
template <typename Real>
void expect_over_input_is_execute(const std::string& backend_name, int nx, int ny, Precision precision,
                                  Direction direction, Placement placement, bool shifted) {
  const auto backend = make_backend(backend_name);
  const TransformSpec spec{
      .nx = nx, .ny = ny, .direction = direction, .precision = precision, .placement = placement};
  const auto plan = backend->plan(spec);
  const std::size_t count = std::size_t(nx) * ny;
  std::mt19937_64 rng(std::uint64_t(nx) * 1000 + ny);
  std::normal_distribution<double> normal;
  std::vector<std::complex<Real>> input(count + 1);
  for (auto& z : input) z = {Real(normal(rng)), Real(normal(rng))};
  std::complex<Real>* data = input.data() + (shifted ? 1 : 0);
  std::vector<std::complex<Real>> expected(count), over(data, data + count);
  if (placement == Placement::in_place) {
    expected.assign(data, data + count);
    plan->execute(expected.data(), expected.data());
  } else {
    plan->execute(data, expected.data());
  }
  std::vector<std::complex<Real>> holder(count + 1);
  std::complex<Real>* target = holder.data() + (shifted ? 1 : 0);
  std::copy(data, data + count, target);
  plan->execute_over_input(target);
  std::size_t differing = 0;
  for (std::size_t e = 0; e < count; ++e) {
    differing += target[e].real() != expected[e].real() || target[e].imag() != expected[e].imag();
  }
  EXPECT_EQ(differing, 0u) << backend_name << " " << spec.describe() << (shifted ? " shifted" : "");
  // Not the input back: the transform happened.
  EXPECT_NE(target[1], data[1]) << backend_name << " " << spec.describe();
}

TEST(TransformConformance, ExecuteOverInputIsBitForBitExecuteIntoAnotherArray) {
  for (auto direction : {Direction::forward, Direction::inverse}) {
    for (bool shifted : {false, true}) {
      expect_over_input_is_execute<double>("fftw:planner=estimate", 64, 32, Precision::f64, direction,
                                           Placement::out_of_place, shifted);
      expect_over_input_is_execute<double>("fftw:planner=estimate", 48, 20, Precision::f64, direction,
                                           Placement::out_of_place, shifted);
      expect_over_input_is_execute<double>("fftw:planner=estimate", 100, 1, Precision::f64, direction,
                                           Placement::out_of_place, shifted);
      expect_over_input_is_execute<float>("fftw:planner=estimate", 128, 32, Precision::f32, direction,
                                          Placement::out_of_place, shifted);
    }
    expect_over_input_is_execute<double>("fftw:planner=estimate", 64, 32, Precision::f64, direction,
                                         Placement::in_place, false);
    expect_over_input_is_execute<double>("naive", 12, 10, Precision::f64, direction, Placement::out_of_place,
                                         false);
    expect_over_input_is_execute<double>("radix2", 64, 32, Precision::f64, direction, Placement::out_of_place,
                                         false);
  }
}

TEST(TransformConformance, ExecuteOverInputRefusesRealTransforms) {
  TransformSpec spec;
  spec.nx = 16;
  spec.ny = 8;
  spec.kind = Kind::r2c;
  for (const char* name : {"fftw:planner=estimate", "naive"}) {
    const auto plan = make_backend(name)->plan(spec);
    std::vector<double> data(16 * 8 * 2);
    EXPECT_THROW(plan->execute_over_input(data.data()), UnsupportedTransform) << name;
  }
}

}  // namespace
