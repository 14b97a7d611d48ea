// `swell fft` end to end: .npy in, transform, .npy out — checked against what a DFT must give
// (an impulse's spectrum, inverse ∘ forward = N, r2c = the first nx/2+1 columns of c2c, c2r ∘ r2c
// = N), across backends, and exit code 2 with a named problem for bad input (docs/conventions.md §8).
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "swell/validation/io/npy.hpp"
#include "vulkan_test_support.hpp"

namespace {

namespace fs = std::filesystem;
using swell::validation::NpyArray;
using swell::validation::read_npy;
using swell::validation::write_npy;
using Dtype = NpyArray::Dtype;
using cd = std::complex<double>;
using cf = std::complex<float>;

using swell::test::Run;
using swell::test::swell;

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

template <typename T>
std::vector<T> random_values(std::size_t n, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<T> v(n);
  for (auto& x : v) {
    if constexpr (std::is_floating_point_v<T>) {
      x = T(u(random));
    } else {
      using R = typename T::value_type;
      const R re = R(u(random));
      x = T(re, R(u(random)));
    }
  }
  return v;
}

// max |a − b| / max |b|
template <typename T>
double relative_max_error(const std::vector<T>& a, const std::vector<T>& b) {
  EXPECT_EQ(a.size(), b.size());
  double error = 0, scale = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    error = std::max(error, double(std::abs(a[i] - b[i])));
    scale = std::max(scale, double(std::abs(b[i])));
  }
  return scale > 0 ? error / scale : error;
}

constexpr double kEps64 = std::numeric_limits<double>::epsilon();
constexpr double kEps32 = std::numeric_limits<float>::epsilon();

class FftCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("swell_fft_cli_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  template <typename T>
  std::string save(const std::string& name, std::vector<std::size_t> shape, const std::vector<T>& values) {
    write_npy(path(name), NpyArray::from_values(std::move(shape), values));
    return path(name);
  }

  // Runs `swell fft` and expects success.
  void fft(const std::string& arguments) {
    const auto run = swell("fft " + arguments);
    ASSERT_EQ(run.exit_code, 0) << arguments << "\n" << run.output;
  }

  fs::path dir_;
};

// ------------------------------------------------------------------ what a DFT must give

TEST_F(FftCli, ForwardC2cOfAnImpulseIsAllOnes) {
  for (const std::string impl : {"naive", "radix2", "fftw"}) {
    SCOPED_TRACE(impl);
    std::vector<cd> impulse(16, 0.0);
    impulse[0] = 1.0;
    const auto in = save("impulse.npy", {16}, impulse);
    fft("--impl " + impl + " --in " + in + " --out " + path("ones.npy"));
    const auto out = read_npy(path("ones.npy"));
    EXPECT_EQ(out.dtype, Dtype::c16);
    EXPECT_EQ(out.shape, (std::vector<std::size_t>{16}));
    for (const auto& x : out.values<cd>()) EXPECT_NEAR(std::abs(x - cd(1.0)), 0.0, 4 * kEps64);

    // The same in 2-D and in single precision.
    std::vector<cf> impulse2(4 * 8, 0.0f);
    impulse2[0] = 1.0f;
    const auto in2 = save("impulse2.npy", {4, 8}, impulse2);
    fft("--impl " + impl + " --in " + in2 + " --out " + path("ones2.npy"));
    const auto out2 = read_npy(path("ones2.npy"));
    EXPECT_EQ(out2.dtype, Dtype::c8);
    EXPECT_EQ(out2.shape, (std::vector<std::size_t>{4, 8}));
    for (const auto& x : out2.values<cf>()) EXPECT_NEAR(std::abs(x - cf(1.0f)), 0.0, 4 * kEps32);
  }
}

TEST_F(FftCli, ShiftedImpulseGivesTheForwardSign) {
  // x = δ(i − 1): X[n] = e^(−2πi n/N) for the forward transform, e^(+2πi n/N) for the inverse.
  const int n = 6;
  std::vector<cd> shifted(n, 0.0);
  shifted[1] = 1.0;
  const auto in = save("shifted.npy", {std::size_t(n)}, shifted);
  fft("--impl naive --in " + in + " --out " + path("fwd.npy"));
  fft("--impl naive --inverse --in " + in + " --out " + path("inv.npy"));
  const auto forward = read_npy(path("fwd.npy")).values<cd>();
  const auto inverse = read_npy(path("inv.npy")).values<cd>();
  for (int k = 0; k < n; ++k) {
    const cd twiddle = std::polar(1.0, -2 * M_PI * k / n);
    EXPECT_LT(std::abs(forward[k] - twiddle), 8 * kEps64) << k;
    EXPECT_LT(std::abs(inverse[k] - std::conj(twiddle)), 8 * kEps64) << k;
  }
}

TEST_F(FftCli, ForwardThenInverseReturnsNTimesTheInput) {
  const std::size_t ny = 6, nx = 10;
  const auto x = random_values<cd>(ny * nx, 1);
  const auto in = save("x.npy", {ny, nx}, x);
  for (const std::string impl : {"naive", "fftw"}) {
    SCOPED_TRACE(impl);
    fft("--impl " + impl + " --in " + in + " --out " + path("X.npy"));
    fft("--impl " + impl + " --inverse --in " + path("X.npy") + " --out " + path("back.npy"));
    const auto back = read_npy(path("back.npy"));
    EXPECT_EQ(back.shape, (std::vector<std::size_t>{ny, nx}));
    auto scaled = x;
    for (auto& v : scaled) v *= double(nx * ny);
    EXPECT_LT(relative_max_error(back.values<cd>(), scaled), 16 * kEps64 * std::log2(nx * ny));
  }
}

TEST_F(FftCli, R2cIsTheFirstHalfOfC2cAndC2rInvertsIt) {
  const std::size_t ny = 6, nx = 10;
  const auto x = random_values<double>(ny * nx, 2);
  const auto real_in = save("x.npy", {ny, nx}, x);
  std::vector<cd> as_complex(x.begin(), x.end());
  const auto complex_in = save("xc.npy", {ny, nx}, as_complex);

  fft("--impl fftw --in " + real_in + " --out " + path("half.npy"));
  fft("--impl fftw --in " + complex_in + " --out " + path("full.npy"));
  const auto half = read_npy(path("half.npy"));
  ASSERT_EQ(half.dtype, Dtype::c16);
  ASSERT_EQ(half.shape, (std::vector<std::size_t>{ny, nx / 2 + 1}));
  const auto full = read_npy(path("full.npy")).values<cd>();
  std::vector<cd> first_columns;
  for (std::size_t j = 0; j < ny; ++j) {
    for (std::size_t i = 0; i < nx / 2 + 1; ++i) first_columns.push_back(full[j * nx + i]);
  }
  EXPECT_LT(relative_max_error(half.values<cd>(), first_columns), 16 * kEps64);

  // c2r of the half spectrum: nx = 2(m − 1) by default, and nx·ny·x comes back.
  fft("--impl fftw --c2r --in " + path("half.npy") + " --out " + path("back.npy"));
  const auto back = read_npy(path("back.npy"));
  ASSERT_EQ(back.dtype, Dtype::f8);
  ASSERT_EQ(back.shape, (std::vector<std::size_t>{ny, nx}));
  auto scaled = x;
  for (auto& v : scaled) v *= double(nx * ny);
  EXPECT_LT(relative_max_error(back.values<double>(), scaled), 16 * kEps64 * std::log2(nx * ny));

  // --inverse alongside --c2r is redundant (c2r is an inverse), not a conflict.
  fft("--impl naive --c2r --inverse --in " + path("half.npy") + " --out " + path("back2.npy"));
  EXPECT_LT(relative_max_error(read_npy(path("back2.npy")).values<double>(), scaled),
            16 * kEps64 * std::log2(nx * ny));
}

TEST_F(FftCli, OddLengthsNeedNxForC2r) {
  // nx = 9 and nx = 8 share m = 5 columns; --nx 9 selects the odd one.
  const std::size_t nx = 9;
  const auto x = random_values<float>(nx, 3);
  const auto in = save("x9.npy", {nx}, x);
  fft("--impl naive --in " + in + " --out " + path("half9.npy"));
  const auto half = read_npy(path("half9.npy"));
  ASSERT_EQ(half.dtype, Dtype::c8);
  ASSERT_EQ(half.shape, (std::vector<std::size_t>{5}));
  fft("--impl naive --c2r --nx 9 --in " + path("half9.npy") + " --out " + path("back9.npy"));
  const auto back = read_npy(path("back9.npy"));
  ASSERT_EQ(back.dtype, Dtype::f4);
  ASSERT_EQ(back.shape, (std::vector<std::size_t>{9}));
  auto scaled = x;
  for (auto& v : scaled) v *= float(nx);
  EXPECT_LT(relative_max_error(back.values<float>(), scaled), 16 * kEps32 * std::log2(nx));

  fft("--impl naive --c2r --in " + path("half9.npy") + " --out " + path("back8.npy"));
  EXPECT_EQ(read_npy(path("back8.npy")).shape, (std::vector<std::size_t>{8}));

  const auto wrong = swell("fft --impl naive --c2r --nx 7 --in " + path("half9.npy") + " --out " +
                           path("bad.npy"));
  EXPECT_EQ(wrong.exit_code, 2) << wrong.output;
  EXPECT_TRUE(contains(wrong.output, "--nx 7")) << wrong.output;
}

TEST_F(FftCli, BackendsAgree) {
  // One input through every exact backend; outputs agree to a few ε · log2 N.
  const std::size_t ny = 16, nx = 32;
  const double bound64 = 8 * kEps64 * std::log2(nx * ny), bound32 = 8 * kEps32 * std::log2(nx * ny);
  const auto c16 = save("c16.npy", {ny, nx}, random_values<cd>(nx * ny, 4));
  const auto c8 = save("c8.npy", {ny, nx}, random_values<cf>(nx * ny, 5));
  const auto f8 = save("f8.npy", {ny, nx}, random_values<double>(nx * ny, 6));
  const auto f4 = save("f4.npy", {ny, nx}, random_values<float>(nx * ny, 7));
  for (const std::string flags : {"", "--inverse"}) {
    for (const std::string impl : {"naive", "radix2", "fftw"}) {
      fft("--impl " + impl + " " + flags + " --in " + c16 + " --out " + path(impl + "_c16.npy"));
      fft("--impl " + impl + " " + flags + " --in " + c8 + " --out " + path(impl + "_c8.npy"));
      if (flags.empty()) {
        fft("--impl " + impl + " --in " + f8 + " --out " + path(impl + "_f8.npy"));
        fft("--impl " + impl + " --in " + f4 + " --out " + path(impl + "_f4.npy"));
      }
    }
    const auto reference64 = read_npy(path("fftw_c16.npy")).values<cd>();
    const auto reference32 = read_npy(path("fftw_c8.npy")).values<cf>();
    const auto reference_r64 = read_npy(path("fftw_f8.npy")).values<cd>();
    const auto reference_r32 = read_npy(path("fftw_f4.npy")).values<cf>();
    for (const std::string impl : {"naive", "radix2"}) {
      SCOPED_TRACE(impl + " " + flags);
      EXPECT_LT(relative_max_error(read_npy(path(impl + "_c16.npy")).values<cd>(), reference64), bound64);
      EXPECT_LT(relative_max_error(read_npy(path(impl + "_c8.npy")).values<cf>(), reference32), bound32);
      EXPECT_LT(relative_max_error(read_npy(path(impl + "_f8.npy")).values<cd>(), reference_r64), bound64);
      EXPECT_LT(relative_max_error(read_npy(path(impl + "_f4.npy")).values<cf>(), reference_r32), bound32);
    }
  }
}

// `swell fft --impl vulkan` on .npy files, every kind and precision, against fftw (the bound of
// BackendsAgree: two transforms' errors of a few ε log2 N each).
TEST_F(FftCli, VulkanAgreesWithFftwOnNpyFiles) {
  const std::size_t ny = 16, nx = 32;
  const double bound64 = 8 * kEps64 * std::log2(nx * ny), bound32 = 8 * kEps32 * std::log2(nx * ny);
  const auto c16 = save("c16.npy", {ny, nx}, random_values<cd>(nx * ny, 4));
  const auto c8 = save("c8.npy", {ny, nx}, random_values<cf>(nx * ny, 5));
  const auto f4 = save("f4.npy", {ny, nx}, random_values<float>(nx * ny, 7));
  const auto probe = swell("fft --impl vulkan --in " + c8 + " --out " + path("probe.npy"));
  if (probe.exit_code == 2 && contains(probe.output, "vulkan: ")) SWELL_SKIP_WITHOUT_VULKAN(probe.output);
  for (const std::string impl : {"vulkan", "fftw"}) {
    fft("--impl " + impl + " --in " + c16 + " --out " + path(impl + "_c16.npy"));
    fft("--impl " + impl + " --inverse --in " + c8 + " --out " + path(impl + "_c8.npy"));
    fft("--impl " + impl + " --in " + f4 + " --out " + path(impl + "_f4.npy"));
    fft("--impl " + impl + " --c2r --in " + path(impl + "_f4.npy") + " --out " + path(impl + "_back.npy"));
  }
  EXPECT_LT(relative_max_error(read_npy(path("vulkan_c16.npy")).values<cd>(),
                               read_npy(path("fftw_c16.npy")).values<cd>()), bound64);
  EXPECT_LT(relative_max_error(read_npy(path("vulkan_c8.npy")).values<cf>(),
                               read_npy(path("fftw_c8.npy")).values<cf>()), bound32);
  EXPECT_LT(relative_max_error(read_npy(path("vulkan_f4.npy")).values<cf>(),
                               read_npy(path("fftw_f4.npy")).values<cf>()), bound32);
  EXPECT_LT(relative_max_error(read_npy(path("vulkan_back.npy")).values<float>(),
                               read_npy(path("fftw_back.npy")).values<float>()), 2 * bound32);
}

TEST_F(FftCli, JsonReportsTheTransform) {
  const auto in = save("x.npy", {4, 6}, random_values<cd>(24, 8));
  const auto run = swell("fft --impl naive --inverse --in " + in + " --out " + path("y.npy") + " --json -");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto doc = nlohmann::json::parse(run.output);
  EXPECT_EQ(doc.at("impl"), "naive");
  EXPECT_EQ(doc.at("kind"), "c2c");
  EXPECT_EQ(doc.at("direction"), "inverse");
  EXPECT_EQ(doc.at("precision"), "fp64");
  EXPECT_EQ(doc.at("n"), nlohmann::json::array({6, 4}));  // [nx, ny]
  EXPECT_EQ(doc.at("in"), in);
  EXPECT_EQ(doc.at("out"), path("y.npy"));
  EXPECT_GE(doc.at("seconds").get<double>(), 0.0);

  const auto real = save("r.npy", {10}, random_values<float>(10, 9));
  const auto json_file = path("report.json");
  const auto run2 = swell("fft --impl fftw --in " + real + " --out " + path("z.npy") + " --json " + json_file);
  ASSERT_EQ(run2.exit_code, 0) << run2.output;
  std::ifstream file(json_file);
  const auto doc2 = nlohmann::json::parse(file);
  EXPECT_EQ(doc2.at("kind"), "r2c");
  EXPECT_EQ(doc2.at("direction"), "forward");
  EXPECT_EQ(doc2.at("precision"), "fp32");
  EXPECT_EQ(doc2.at("n"), nlohmann::json::array({10, 1}));
}

// ------------------------------------------------------------------ bad input: exit 2

TEST_F(FftCli, Radix2RefusesTwelve) {
  const auto in = save("x12.npy", {12}, random_values<cd>(12, 10));
  const auto run = swell("fft --impl radix2 --in " + in + " --out " + path("y.npy"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "power")) << run.output;
  EXPECT_TRUE(contains(run.output, "12")) << run.output;
  EXPECT_FALSE(fs::exists(path("y.npy")));
}

TEST_F(FftCli, NonFiniteInputNamesTheFileAndElement) {
  auto x = random_values<cd>(6, 11);
  x[5] = cd(0.0, std::nan(""));
  const auto in = save("nan.npy", {2, 3}, x);
  const auto run = swell("fft --impl fftw --in " + in + " --out " + path("y.npy"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, in)) << run.output;
  EXPECT_TRUE(contains(run.output, "[1, 2]")) << run.output;
  EXPECT_TRUE(contains(run.output, "NaN")) << run.output;

  auto r = random_values<float>(8, 12);
  r[3] = -std::numeric_limits<float>::infinity();
  const auto rin = save("inf.npy", {8}, r);
  const auto run2 = swell("fft --impl naive --in " + rin + " --out " + path("y.npy"));
  EXPECT_EQ(run2.exit_code, 2) << run2.output;
  EXPECT_TRUE(contains(run2.output, "[3]")) << run2.output;
  EXPECT_TRUE(contains(run2.output, "Inf")) << run2.output;
}

TEST_F(FftCli, MalformedOrMissingFilesNameTheFile) {
  const auto in = save("x.npy", {8}, random_values<cd>(8, 13));
  fs::resize_file(in, fs::file_size(in) - 5);
  const auto run = swell("fft --impl fftw --in " + in + " --out " + path("y.npy"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, in)) << run.output;
  EXPECT_TRUE(contains(run.output, "truncated")) << run.output;

  const auto missing = swell("fft --impl fftw --in " + path("absent.npy") + " --out " + path("y.npy"));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_TRUE(contains(missing.output, path("absent.npy"))) << missing.output;

  const auto good = save("good.npy", {4}, random_values<cd>(4, 14));
  const auto unwritable = swell("fft --impl fftw --in " + good + " --out " + path("no/dir/y.npy"));
  EXPECT_EQ(unwritable.exit_code, 2) << unwritable.output;
  EXPECT_TRUE(contains(unwritable.output, path("no/dir/y.npy"))) << unwritable.output;
}

TEST_F(FftCli, MissingOrUnknownOptions) {
  const auto in = save("x.npy", {4}, random_values<cd>(4, 15));
  const auto no_in = swell("fft --impl fftw --out " + path("y.npy"));
  EXPECT_EQ(no_in.exit_code, 2) << no_in.output;
  EXPECT_TRUE(contains(no_in.output, "--in")) << no_in.output;
  EXPECT_EQ(swell("fft --impl fftw --in " + in).exit_code, 2);
  EXPECT_EQ(swell("fft --in " + in + " --out " + path("y.npy")).exit_code, 2);

  const auto unknown = swell("fft --impl fastest --in " + in + " --out " + path("y.npy"));
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  for (const char* name : {"fastest", "naive", "radix2", "fftw"}) {
    EXPECT_TRUE(contains(unknown.output, name)) << name << ": " << unknown.output;
  }
}

TEST_F(FftCli, InconsistentRequestsExit2) {
  const auto real = save("r.npy", {8}, random_values<double>(8, 16));
  const auto complex = save("c.npy", {8}, random_values<cd>(8, 17));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--inverse --in " + real, "--inverse needs complex input"},
      {"--c2r --in " + real, "--c2r needs a complex half spectrum"},
      {"--nx 8 --in " + complex, "--nx applies only to --c2r"},
  };
  for (const auto& [arguments, message] : cases) {
    const auto run = swell("fft --impl naive " + arguments + " --out " + path("y.npy"));
    EXPECT_EQ(run.exit_code, 2) << arguments << ": " << run.output;
    EXPECT_TRUE(contains(run.output, message)) << arguments << ": " << run.output;
  }
  // Rank 3 (and rank 0) arrays are not transforms swell fft offers.
  const auto cube = save("cube.npy", {2, 2, 2}, random_values<cd>(8, 18));
  const auto run = swell("fft --impl naive --in " + cube + " --out " + path("y.npy"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "rank 3")) << run.output;
  const auto scalar = save("scalar.npy", {}, random_values<cd>(1, 19));
  EXPECT_EQ(swell("fft --impl naive --in " + scalar + " --out " + path("y.npy")).exit_code, 2);
  // An empty array has nothing to transform.
  const auto empty = save("empty.npy", {0}, std::vector<cd>{});
  const auto run_empty = swell("fft --impl naive --in " + empty + " --out " + path("y.npy"));
  EXPECT_EQ(run_empty.exit_code, 2) << run_empty.output;
  // A one-column half spectrum is nx = 1 and must say so.
  const auto one = save("one.npy", {1}, std::vector<cd>{cd(2.0)});
  EXPECT_EQ(swell("fft --impl naive --c2r --in " + one + " --out " + path("y.npy")).exit_code, 2);
  fft("--impl naive --c2r --nx 1 --in " + one + " --out " + path("y1.npy"));
  EXPECT_EQ(read_npy(path("y1.npy")).values<double>(), (std::vector<double>{2.0}));
}

TEST_F(FftCli, UnknownSubcommandHintListsFft) {
  const auto run = swell("fourier");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_TRUE(contains(run.output, "fft")) << run.output;
}

}  // namespace
