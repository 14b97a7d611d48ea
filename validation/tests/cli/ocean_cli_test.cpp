// The ocean commands end to end through the built `swell` binary: `swell synth` (frames and
// case.toml that read back to the synthesizer's own frames), then `swell fit` and `swell check
// ocean`. Bad input exits 2 with the problem named (docs/conventions.md §8).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "vulkan_test_support.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/io/npy.hpp"

namespace {

namespace fs = std::filesystem;
using swell::reference::Field;
using swell::reference::FrameSequence;
using CliRun = swell::test::Run;  // (inside a fixture, Run is testing::Test::Run)
using swell::test::swell;

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

// Bad input: exit 2, and the message carries every fragment that names the problem.
void expect_refusal(const CliRun& run, const std::vector<std::string>& fragments) {
  EXPECT_EQ(run.exit_code, 2) << run.output;
  for (const auto& fragment : fragments) {
    EXPECT_TRUE(contains(run.output, fragment)) << "'" << fragment << "' not in: " << run.output;
  }
}

// A fresh directory per test, removed afterwards.
class OceanCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (auto& c : name) c = (c == '/') ? '_' : c;
    dir_ = fs::temp_directory_path() / ("swell_ocean_cli_test_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// ==================================================================== swell synth

// The frames `swell synth` wrote equal, bit for bit, those the synthesizer makes of the case it
// wrote (stored as float32 unless fp64 went to .npy).
void expect_frames_of_the_case(const fs::path& out, const std::string& impl,
                               swell::impls::Precision precision, bool stored_float32) {
  const auto case_file = swell::validation::read_case_file(out / "case.toml");
  const FrameSequence read = swell::validation::read_frames(case_file);
  swell::impls::SynthesizerOptions options;
  options.backend = impl;
  options.precision = precision;
  const FrameSequence want = swell::impls::Synthesizer(case_file.ocean, options).frames();
  ASSERT_EQ(read.frames.size(), want.frames.size());
  EXPECT_EQ(read.unit_roundoff, stored_float32 ? 0x1p-24 : 0x1p-53);
  for (std::size_t f = 0; f < want.frames.size(); ++f) {
    EXPECT_EQ(read.frames[f].time, want.frames[f].time);
    ASSERT_EQ(read.frames[f].fields.size(), 6u) << "frame " << f;
    for (const auto& [field, values] : want.frames[f].fields) {
      const auto& got = read.frames[f].fields.at(field);
      ASSERT_EQ(got.size(), values.size());
      std::size_t differ = 0;
      for (std::size_t k = 0; k < values.size(); ++k) {
        const double expected = stored_float32 ? static_cast<double>(static_cast<float>(values[k])) : values[k];
        differ += std::bit_cast<std::uint64_t>(got[k]) != std::bit_cast<std::uint64_t>(expected);
      }
      EXPECT_EQ(differ, 0u) << swell::reference::field_name(field) << " frame " << f;
    }
  }
}

struct SynthFormat {
  std::string format, precision;
};

void PrintTo(const SynthFormat& p, std::ostream* os) { *os << p.format << " " << p.precision; }

class SynthFormats : public OceanCli, public ::testing::WithParamInterface<SynthFormat> {};

TEST_P(SynthFormats, WritesFramesAndACaseThatReadsThemBack) {
  const auto& p = GetParam();
  const CliRun run = swell("synth --model jonswap --hs 2.5 --tp 7 --gamma 2 --spreading mitsuyasu "
                        "--s-max 12 --impl fftw --n 32 --ny 16 --length 120 --length-y 70 "
                        "--frames 3 --dt 0.5 --t0 2 --seed 11 --wind-dir 20 --choppiness 0.8 "
                        "--precision " + p.precision + " --format " + p.format + " --out " + path("out"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "frame    2")) << run.output;  // one line per frame
  EXPECT_TRUE(fs::exists(dir_ / "out" / "case.toml"));
  if (p.format == "npy") {
    EXPECT_TRUE(fs::exists(dir_ / "out" / "frame_0002_J.npy"));
    EXPECT_EQ(swell::validation::read_npy(dir_ / "out" / "frame_0000_h.npy").dtype,
              p.precision == "fp64" ? swell::validation::NpyArray::Dtype::f8
                                    : swell::validation::NpyArray::Dtype::f4);
  } else {
    EXPECT_TRUE(fs::exists(dir_ / "out" / (p.format == "exr" ? "frame_0002.exr" : "frame_0002.tif")));
  }

  // The case holds what the flags said.
  const auto c = swell::validation::read_case_file(dir_ / "out" / "case.toml");
  EXPECT_EQ(c.ocean.grid.nx, 32);
  EXPECT_EQ(c.ocean.grid.ny, 16);
  EXPECT_EQ(c.ocean.grid.lx, 120.0);
  EXPECT_EQ(c.ocean.grid.ly, 70.0);
  EXPECT_EQ(c.ocean.frames, 3);
  EXPECT_EQ(c.ocean.dt, 0.5);
  EXPECT_EQ(c.ocean.t0, 2.0);
  EXPECT_EQ(c.ocean.seed, 11u);
  EXPECT_EQ(c.ocean.wind_dir_deg, 20.0);
  EXPECT_EQ(c.ocean.choppiness, 0.8);
  EXPECT_EQ(c.ocean.spectrum.model, "jonswap");
  EXPECT_EQ(c.ocean.spectrum.numbers,
            (std::map<std::string, double>{{"hs", 2.5}, {"tp", 7.0}, {"gamma", 2.0}}));
  EXPECT_EQ(c.ocean.spreading.model, "mitsuyasu");
  EXPECT_EQ(c.ocean.spreading.numbers, (std::map<std::string, double>{{"s_max", 12.0}}));
  EXPECT_EQ(c.input.channels.size(), 6u);

  const auto precision = p.precision == "fp64" ? swell::impls::Precision::f64 : swell::impls::Precision::f32;
  expect_frames_of_the_case(dir_ / "out", "fftw", precision, !(p.precision == "fp64" && p.format == "npy"));
}

INSTANTIATE_TEST_SUITE_P(Synth, SynthFormats,
                         ::testing::Values(SynthFormat{"exr", "fp32"}, SynthFormat{"npy", "fp32"},
                                           SynthFormat{"tiff", "fp32"}, SynthFormat{"npy", "fp64"},
                                           SynthFormat{"exr", "fp64"}),
                         [](const auto& info) { return info.param.format + "_" + info.param.precision; });

// 16-bit PNG: height, disp_x, disp_y as R, G, B through --value-range, read back within half a
// quantization step of the synthesizer's own frames, and passed by the gate.
TEST_F(OceanCli, SynthWritesSixteenBitPngThatTheGatePasses) {
  const CliRun run = swell("synth --model jonswap --hs 2.5 --tp 7 --impl fftw --n 64 --length 300 "
                           "--frames 4 --dt 0.5 --seed 5 --format png --value-range=-4,4 --out " +
                           path("png"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_TRUE(fs::exists(dir_ / "png" / "frame_0003.png"));
  const auto c = swell::validation::read_case_file(dir_ / "png" / "case.toml");
  EXPECT_EQ(c.input.channels, (std::map<Field, std::string>{
                                  {Field::height, "R"}, {Field::disp_x, "G"}, {Field::disp_y, "B"}}));
  EXPECT_EQ(c.input.value_ranges.at(Field::disp_y), (swell::validation::IntegerRange{-4.0, 4.0}));
  const auto read = swell::validation::read_frames(c);
  swell::impls::SynthesizerOptions options;
  options.backend = "fftw";
  options.precision = swell::impls::Precision::f32;  // synth's default
  const FrameSequence want = swell::impls::Synthesizer(c.ocean, options).frames();
  // Half a quantization step, plus the pixel's pass through float as p/65535 (OpenImageIO's
  // normalized value, 2⁻²⁴ relative) scaled by the range's width.
  const double bound = 0.5 * 8.0 / 65535 + 8.0 * 0x1p-24;
  for (std::size_t f = 0; f < want.frames.size(); ++f) {
    ASSERT_EQ(read.frames[f].fields.size(), 3u);
    for (const auto& [field, got] : read.frames[f].fields) {
      const auto& values = want.frames[f].fields.at(field);
      double worst = 0;
      for (std::size_t k = 0; k < values.size(); ++k) worst = std::max(worst, std::abs(got[k] - values[k]));
      EXPECT_LE(worst, bound) << swell::reference::field_name(field) << " frame " << f;
    }
  }
  const CliRun gate = swell("gate --case " + path("png/case.toml"));
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
}

// --fields stores the fields named (a film pipeline's h, dx, dy), in swell's order whatever
// order they are named in; the case reads them back and the gate passes them. Without the
// height, or with an unknown name, it is bad input.
TEST_F(OceanCli, SynthStoresTheFieldsNamed) {
  const CliRun run = swell("synth --model jonswap --hs 2.5 --tp 7 --impl fftw --n 64 --length 300 "
                           "--frames 4 --dt 0.5 --seed 5 --format npy --fields disp_y,h,dx --out " +
                           path("three"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir_ / "three" / "frame_0003_dy.npy"));
  EXPECT_FALSE(fs::exists(dir_ / "three" / "frame_0000_sx.npy"));
  EXPECT_FALSE(fs::exists(dir_ / "three" / "frame_0000_J.npy"));
  const auto c = swell::validation::read_case_file(dir_ / "three" / "case.toml");
  EXPECT_EQ(c.input.channels, (std::map<Field, std::string>{
                                  {Field::height, "h"}, {Field::disp_x, "dx"}, {Field::disp_y, "dy"}}));
  const CliRun gate = swell("gate --case " + path("three/case.toml"));
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
  EXPECT_TRUE(contains(gate.output, "derived.disp_y")) << gate.output;

  const CliRun no_height = swell("synth --model jonswap --hs 2.5 --tp 7 --impl fftw --n 16 "
                                 "--length 300 --fields dx,dy --out " + path("none"));
  EXPECT_EQ(no_height.exit_code, 2);
  EXPECT_TRUE(contains(no_height.output, "--fields must include height (h)")) << no_height.output;
  const CliRun unknown = swell("synth --model jonswap --hs 2.5 --tp 7 --impl fftw --n 16 "
                               "--length 300 --fields h,dz --out " + path("none"));
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(contains(unknown.output, "unknown field 'dz'; valid: height (h)")) << unknown.output;
  const CliRun twice = swell("synth --model jonswap --hs 2.5 --tp 7 --impl fftw --n 16 "
                             "--length 300 --fields h,height --out " + path("none"));
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_TRUE(contains(twice.output, "--fields names height twice")) << twice.output;
  EXPECT_FALSE(fs::exists(dir_ / "none"));
}

TEST_F(OceanCli, SynthFromACaseFileWithOverrides) {
  {
    std::ofstream(path("phillips.toml")) << R"([grid]
n = [64, 64]
length = [500.0, 500.0]
[time]
dt = 1.0
frames = 5
[spectrum]
model = "phillips"
scale = "free"
amplitude = 2e-4
wind_speed = 12.0
wind_dir_deg = 135.0
[synthesis]
seed = 99
choppiness = 1.2
)";
  }
  const CliRun run = swell("synth --case " + path("phillips.toml") +
                        " --impl radix2 --n 16 --frames 2 --seed 5 --wind-speed 9 --out " + path("out"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto c = swell::validation::read_case_file(dir_ / "out" / "case.toml");
  EXPECT_EQ(c.ocean.grid.nx, 16);  // --n sets both axes
  EXPECT_EQ(c.ocean.grid.ny, 16);
  EXPECT_EQ(c.ocean.grid.lx, 500.0);  // from the file
  EXPECT_EQ(c.ocean.frames, 2);
  EXPECT_EQ(c.ocean.dt, 1.0);
  EXPECT_EQ(c.ocean.seed, 5u);
  EXPECT_EQ(c.ocean.choppiness, 1.2);
  EXPECT_EQ(c.ocean.wind_dir_deg, 135.0);
  EXPECT_EQ(c.scale, swell::validation::SpectrumScale::free);
  EXPECT_EQ(c.ocean.spectrum.model, "phillips");
  EXPECT_EQ(c.ocean.spectrum.numbers.at("wind_speed"), 9.0);
  EXPECT_EQ(c.ocean.spectrum.numbers.at("amplitude"), 2e-4);
  EXPECT_TRUE(c.ocean.spreading.model.empty());
  expect_frames_of_the_case(dir_ / "out", "radix2", swell::impls::Precision::f32, true);
}

TEST_F(OceanCli, SynthModelOverrideKeepsOrDropsTheSpreading) {
  {
    std::ofstream(path("case.toml")) << R"([grid]
n = [16, 16]
length = [100.0, 100.0]
[spectrum]
model = "phillips"
amplitude = 1e-3
wind_speed = 10.0
)";
  }
  // Phillips → jonswap: there is no spreading to keep, so the default cos2s s = 10 applies.
  CliRun run = swell("synth --case " + path("case.toml") + " --model jonswap --hs 1 --tp 5 --impl fftw --out " +
                  path("a"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto c = swell::validation::read_case_file(dir_ / "a" / "case.toml");
  EXPECT_EQ(c.ocean.spectrum.numbers, (std::map<std::string, double>{{"hs", 1.0}, {"tp", 5.0}}));
  EXPECT_EQ(c.ocean.spreading.model, "cos2s");
  EXPECT_EQ(c.ocean.spreading.numbers, (std::map<std::string, double>{{"s", 10.0}}));

  // jonswap + cos2s → phillips without --spreading: the spreading goes.
  run = swell("synth --case " + path("a/case.toml") + " --model phillips --amplitude 1e-3 --wind-speed 8 "
              "--impl fftw --out " + path("b"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  c = swell::validation::read_case_file(dir_ / "b" / "case.toml");
  EXPECT_EQ(c.ocean.spectrum.model, "phillips");
  EXPECT_TRUE(c.ocean.spreading.model.empty());

  // A spreading parameter flag alone changes that parameter of the case's spreading.
  run = swell("synth --case " + path("a/case.toml") + " --s 3.5 --impl fftw --out " + path("c"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  c = swell::validation::read_case_file(dir_ / "c" / "case.toml");
  EXPECT_EQ(c.ocean.spreading.numbers.at("s"), 3.5);
  EXPECT_EQ(c.ocean.spectrum.numbers.at("hs"), 1.0);
}

TEST_F(OceanCli, SynthJson) {
  const CliRun run = swell("synth --model bretschneider --hs 2 --tp 6 --impl naive --n 8 --length 50 "
                        "--frames 2 --dt 0.25 --out " + path("out") + " --json " + path("synth.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ifstream file(path("synth.json"));
  const auto document = nlohmann::json::parse(file);
  EXPECT_EQ(document.at("frames"), 2);
  EXPECT_EQ(document.at("case"), path("out") + "/case.toml");
  ASSERT_EQ(document.at("files").size(), 2u);
  EXPECT_EQ(document.at("files")[1], path("out") + "/frame_0001.exr");
  EXPECT_GE(document.at("seconds").get<double>(), 0.0);
  EXPECT_EQ(document.at("impl"), "naive");

  // --json -: standard output is the JSON document alone.
  const CliRun quiet = swell("synth --model bretschneider --hs 2 --tp 6 --impl naive --n 8 --length 50 "
                          "--format npy --out " + path("out2") + " --json -");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  const auto parsed = nlohmann::json::parse(quiet.output);
  EXPECT_EQ(parsed.at("files").size(), 6u);  // six fields, one .npy each
  EXPECT_EQ(parsed.at("format"), "npy");
}

// The vulkan backend end to end: `swell synth --impl vulkan` writes frames (synthesized on the
// device, docs/synthesis.md §vulkan) that the gate passes and that equal the host synthesizer's
// within the fp32 bound of the synthesizer tests, and `swell check ocean --impl vulkan` passes
// every check on every built-in case in fp32 and fp64.
TEST_F(OceanCli, VulkanSynthAndCheckOceanPass) {
  SWELL_VULKAN_OR_SKIP();
  const CliRun synth = swell("synth --model jonswap --hs 2.5 --tp 7 --impl vulkan --n 64 --length 300 "
                             "--frames 3 --dt 0.5 --seed 5 --format npy --out " + path("vulkan"));
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const auto c = swell::validation::read_case_file(dir_ / "vulkan" / "case.toml");
  const FrameSequence read = swell::validation::read_frames(c);
  swell::impls::SynthesizerOptions options;
  options.backend = "fftw";
  options.precision = swell::impls::Precision::f64;
  const FrameSequence want = swell::impls::Synthesizer(c.ocean, options).frames();
  ASSERT_EQ(read.frames.size(), want.frames.size());
  for (std::size_t f = 0; f < want.frames.size(); ++f) {
    const auto& got = read.frames[f].fields.at(Field::height);
    const auto& reference = want.frames[f].fields.at(Field::height);
    double difference = 0, norm = 0;
    for (std::size_t k = 0; k < reference.size(); ++k) {
      difference += (got[k] - reference[k]) * (got[k] - reference[k]);
      norm += reference[k] * reference[k];
    }
    EXPECT_LE(std::sqrt(difference / norm), 2e-6) << "frame " << f;  // fp32: synth's default
  }
  const CliRun gate = swell("gate --case " + path("vulkan/case.toml"));
  EXPECT_EQ(gate.exit_code, 0) << gate.output;

  const CliRun check = swell("check ocean --impl vulkan --n 64 --json - --report-dir " + path("report"));
  ASSERT_EQ(check.exit_code, 0) << check.output;
  const auto doc = nlohmann::json::parse(check.output.substr(check.output.find('{')));
  ASSERT_EQ(doc.at("ocean").size(), 8u);  // 4 built-in cases × fp32, fp64
  for (const auto& row : doc.at("ocean")) {
    EXPECT_EQ(row.at("backend"), "vulkan");
    EXPECT_TRUE(row.at("pass").get<bool>()) << row.dump();
  }
}

TEST_F(OceanCli, SynthBadInputExitsTwoNamingTheProblem) {
  {
    std::ofstream(path("bad.toml")) << "[grid]\nn = \"64\"\nlength = [1.0, 1.0]\n";
  }
  const std::string base = "synth --impl fftw --out " + path("out") + " ";
  const std::string jonswap = "--model jonswap --hs 3 --tp 8 ";
  const std::string grid = "--n 16 --length 100 ";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"--model jonswap --hs 3 --tp 8 --length 100", {"--n", "required without --case"}},
      {"--hs 3 --tp 8 --n 16 --length 100", {"--model", "required without --case"}},
      {"--model jonswop --n 16 --length 100", {"--model", "jonswop"}},
      {"--model jonswap --n 16 --length 100", {"jonswap", "missing parameters"}},
      {jonswap + grid + "--s-max 3", {"--s-max", "not a parameter", "cos2s"}},
      {"--model phillips --amplitude 1e-3 --wind-speed 10 --n 16 --length 100 --spreading cos2s",
       {"phillips", "no spreading model"}},
      {jonswap + "--n 0 --length 100", {"nx", "≥ 1", "0"}},
      {jonswap + "--n 16 --length -5", {"-5"}},
      {jonswap + grid + "--depth -3", {"depth", "-3"}},
      {jonswap + grid + "--depth shallow", {"--depth", "shallow"}},
      {jonswap + grid + "--frames 4", {"dt", "more than one frame"}},
      {jonswap + grid + "--seed -1", {"--seed", "-1"}},
      {jonswap + grid + "--format bmp", {"--format", "bmp"}},
      {jonswap + grid + "--precision fp16", {"--precision", "fp16"}},
      {jonswap + grid + "--format png", {"--format png needs --value-range"}},
      {jonswap + grid + "--value-range=-4,4", {"--value-range applies to --format png only"}},
      {jonswap + grid + "--format png --value-range=-4,4,5", {"--value-range", "two numbers"}},
      {jonswap + grid + "--format png --value-range=4,-4", {"low < high"}},
      {jonswap + grid + "--format png --value-range=-0.01,0.01", {"frame_0000.png", "outside the PNG value range"}},
      {"--model jonswap --hs -1 --tp 8 " + grid, {"hs", "-1"}},
      {"--case " + path("missing.toml"), {"missing.toml", "no such case file"}},
      {"--case " + path("bad.toml"), {"bad.toml:2:", "[grid] n"}},
  };
  for (const auto& [args, fragments] : cases) {
    SCOPED_TRACE(args);
    const CliRun run = swell(base + args);
    expect_refusal(run, fragments);
    EXPECT_FALSE(fs::exists(dir_ / "out" / "case.toml")) << "a case was written for bad input";
    EXPECT_TRUE(!fs::exists(dir_ / "out") || fs::is_empty(dir_ / "out"))
        << "files were left behind for bad input";
  }
  // A value outside the PNG range in a later frame removes the frames already written.
  const CliRun late = swell(base + jonswap + grid + "--frames 60 --dt 1 --format png --value-range=-3,3");
  EXPECT_EQ(late.exit_code, 2) << late.output;
  EXPECT_TRUE(contains(late.output, "frame_0003.png")) << late.output;  // frames 0–2 were written
  EXPECT_TRUE(contains(late.output, "outside the PNG value range")) << late.output;
  EXPECT_TRUE(!fs::exists(dir_ / "out") || fs::is_empty(dir_ / "out")) << "frames were left behind";
  // Unknown backend and a size the backend cannot do.
  CliRun run = swell("synth --impl nope --out " + path("out") + " " + jonswap + grid);
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "nope")) << run.output;
  run = swell("synth --impl radix2 --out " + path("out") + " --model jonswap --hs 3 --tp 8 --n 12 --length 100");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "radix2")) << run.output;
  EXPECT_TRUE(contains(run.output, "12")) << run.output;
  // Without --out.
  run = swell("synth --impl fftw " + jonswap + grid);
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "--out")) << run.output;
}

// Issue 10's table: each case swell synth once accepted and made nonsense of (NaN, zeros, a
// meaningless phase, std::bad_alloc) is refused with exit 2, naming the parameter and the
// limit, and nothing is written.
TEST_F(OceanCli, SynthRefusesCasesItCannotMakeNamingTheParameterAndTheLimit) {
  const std::string base = "synth --model jonswap --tp 8 --impl fftw --out " + path("out") + " ";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"--hs 3 --n 64 --length 1e-300", {"1e-300 m grid", "of the spectrum's m0", "at least 1e-06", "rad/m", "[grid] length"}},
      {"--hs 3 --n 64 --length 1e300", {"1e+300 m grid", "carries 0 of the spectrum's m0", "0.0344 … 0.567 rad/m"}},
      {"--hs 3 --n 64 --length 100 --choppiness 1e300", {"choppiness", "1e+300", "fp32"}},
      {"--hs 3 --n 64 --length 100 --depth 1e-300 --frames 4 --dt 0.5", {"of the spectrum's m0", "depth 1e-300 m"}},
      {"--hs 3 --n 64 --length 100 --t0 1e300", {"t0 = 1e+300", "2⁵⁰", "|t| ≤"}},
      {"--hs 3 --n 64 --length 100 --t0 2e14 --frames 1000 --dt 1e12", {"[time]", "frames = 1000"}},
      {"--hs 3 --n 1048576 --length 100", {"needs about", "bytes", "available", "[grid] n"}},
      {"--n 64 --length 100 --hs 1e-35", {"height", "below", "underflow", "fp64"}},
      {"--hs 3 --n 64 --length 100 --choppiness 1e-40", {"displacements", "underflow", "choppiness"}},
      {"--hs 3 --n 2 --length 100", {"2² over 100 m grid", "no wave vector that carries energy", "at least 3"}},
  };
  for (const auto& [args, fragments] : cases) {
    SCOPED_TRACE(args);
    const CliRun run = swell(base + args);
    expect_refusal(run, fragments);
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "files were written for a refused case";
  }
  // What fp32 cannot carry, fp64 stored as .npy can: the rule is the storage format's.
  const CliRun tiny = swell(base + "--n 64 --length 100 --hs 1e-35 --precision fp64 --format npy");
  EXPECT_EQ(tiny.exit_code, 0) << tiny.output;
}

// The same rule in every command: frames of a valid case, with the case's patch changed to one
// whose grid holds none of the spectrum, are refused by the gate and the fit (exit 2), naming
// the grid's band; and a gate at a late t0 (1e6 s) passes swell's own fp64 frames, phases
// reduced exactly.
TEST_F(OceanCli, GateAndFitShareTheValidityRule) {
  CliRun run = swell("synth --model jonswap --hs 3 --tp 8 --impl fftw --n 32 --length 200 "
                     "--frames 3 --dt 0.5 --t0 1e6 --precision fp64 --format npy --out " + path("sea"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  run = swell("gate --case " + path("sea/case.toml"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  std::string text;
  {
    std::ifstream in(path("sea/case.toml"));
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = text.find("length = [");
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, text.find('\n', at) - at, "length = [0.001, 0.001]");
  {
    std::ofstream(path("sea/case.toml")) << text;
  }
  for (const std::string& command : {"gate --case " + path("sea/case.toml"),
                                    "fit --input " + path("sea") + " --case " + path("sea/case.toml")}) {
    SCOPED_TRACE(command);
    run = swell(command);
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_TRUE(contains(run.output, "of the spectrum's m0")) << run.output;
    EXPECT_TRUE(contains(run.output, "0.001 m grid")) << run.output;
  }
}

// The gate refuses a case no frames can satisfy before it looks for any frame.
TEST_F(OceanCli, GateRefusesAnInvalidCaseBeforeReadingFrames) {
  {
    std::ofstream(path("case.toml"))
        << "[grid]\nn = [64, 64]\nlength = [1e-3, 1e-3]\n[spectrum]\nmodel = \"jonswap\"\n"
           "hs = 3.0\ntp = 8.0\n[spreading]\nmodel = \"cos2s\"\ns = 10.0\n[input]\n"
           "files = \"nowhere_%04d.exr\"\nheight = \"h\"\n";
  }
  const CliRun run = swell("gate --case " + path("case.toml"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "of the spectrum's m0")) << run.output;
  EXPECT_FALSE(contains(run.output, "missing frame")) << run.output;
}

// Refusals that teach: what to do instead, not only what was wrong.
TEST_F(OceanCli, RefusalsSayWhatToDoInstead) {
  const std::string out = " --impl fftw --n 16 --length 100 --out " + path("out");
  {
    std::ofstream(path("phillips_spreading.toml"))
        << "[grid]\nn = [16, 16]\nlength = [100.0, 100.0]\n[spectrum]\nmodel = \"jonswap\"\n"
           "hs = 3.0\ntp = 8.0\n[spreading]\nmodel = \"phillips\"\n";
  }
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"synth --model jonswap --hs 3 --tp 8 --spreading phillips" + out,
       {"its own directionality", "[spectrum]", "wind direction", "no [spreading]"}},
      {"synth --case " + path("phillips_spreading.toml") + out,
       {"phillips_spreading.toml:", "its own directionality", "--model phillips"}},
      {"synth --model cos2s" + out, {"'cos2s' is a spreading model", "--spreading cos2s"}},
      {"synth --model jonswop --hs 3 --tp 8" + out, {"did you mean 'jonswap'?"}},
      {"synth --model phillips --hs 3" + out, {"--hs", "amplitude", "--model jonswap"}},
      {"synth --model jonswap --hs 3 --tp 8 --impl radix2 --n 24 --length 100 --out " + path("out"),
       {"powers of two", "for other sizes use --impl", "fftw"}},
  };
  for (const auto& [args, fragments] : cases) {
    SCOPED_TRACE(args);
    const CliRun run = swell(args);
    expect_refusal(run, fragments);
  }
}

// ==================================================================== end of swell synth

}  // namespace

// ==================================================================== swell fit
// (appended by the JONSWAP-fit work; swell fit is documented in docs/fit.md)

namespace {

// JONSWAP Hs 3 m, Tp 8 s, γ 3.3 + cos-2s s = 10 on 256² over 800 m: the peak at |k| = 8 Δk
// (coarser grids leave σa, σb unidentifiable from one surface) and the axes reaching ω = 4 ωp.
// No [input]: frames come from --input.
constexpr const char* kFitCase = R"([grid]
n = [256, 256]
length = [800.0, 800.0]
[spectrum]
model = "jonswap"
hs = 3.0
tp = 8.0
gamma = 3.3
[spreading]
model = "cos2s"
s = 10.0
wind_dir_deg = 30.0
)";

TEST_F(OceanCli, FitSynthDirectoriesAndPatterns) {
  std::ofstream(path("case.toml")) << kFitCase;
  for (const char* seed : {"1", "2"}) {
    const CliRun run = swell("synth --case " + path("case.toml") + " --impl fftw --precision fp64 "
                             "--format npy --seed " + seed + " --out " + path(std::string("r") + seed));
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  // Two realizations: a synth directory and a pattern read with the case (height "h").
  const CliRun run = swell("fit --input " + path("r1") + " --input '" + path("r2") +
                           "/frame_%04d.npy' --case " + path("case.toml") + " --json -");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto document = nlohmann::json::parse(run.output);
  EXPECT_EQ(document.at("converged"), true);
  EXPECT_EQ(document.at("realizations"), 2);
  EXPECT_GT(document.at("wave_vectors").get<int>(), 20000);
  EXPECT_EQ(document.at("interval"), "profile-likelihood");
  EXPECT_NEAR(document.at("peak_wavelengths").get<double>(), 800 / 99.92, 0.01);
  const std::map<std::string, double> truth = {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}};
  ASSERT_EQ(document.at("fit").size(), 3u);
  for (const auto& [name, value] : truth) {
    SCOPED_TRACE(name);
    const auto& e = document.at("fit").at(name);
    const double v = e.at("value"), se = e.at("se"), lo = e.at("ci95")[0], hi = e.at("ci95")[1];
    EXPECT_GT(se, 0);
    // Profile-likelihood ends (checked exactly against a brute-force profile in
    // swell_fit_tests; here the plumbing): around the estimate, not symmetric — these seeds
    // measured γ −0.21/+0.24 se and Tp −0.32 se from the Wald ends — but each half-width within
    // a factor 2 of the Wald one, which a wrong χ² level or a wrong sign would break.
    EXPECT_EQ(e.at("method"), "profile-likelihood");
    EXPECT_EQ(e.at("calibrated"), true);
    EXPECT_FALSE(e.contains("reason"));
    EXPECT_LT(lo, v);
    EXPECT_GT(hi, v);
    for (const double half : {hi - v, v - lo}) {
      EXPECT_GT(half, 0.5 * 1.959964 * se);
      EXPECT_LT(half, 2.0 * 1.959964 * se);
    }
    EXPECT_NEAR(v, value, 5 * se);  // fixed seeds: deterministic
    EXPECT_EQ(document.at("truth").at(name), value);
  }

  // The table, and --sigma adds σa and σb.
  const CliRun table = swell("fit --input " + path("r1") + " --case " + path("case.toml") +
                             " --sigma --json " + path("fit.json"));
  ASSERT_EQ(table.exit_code, 0) << table.output;
  for (const char* fragment : {"95 % interval", "profile-likelihood", "hs [m]", "tp [s]", "gamma", "sigma_a",
                               "sigma_b", "converged: yes", "1 realization"}) {
    EXPECT_TRUE(contains(table.output, fragment)) << fragment << " not in: " << table.output;
  }
  std::ifstream file(path("fit.json"));
  const auto with_sigma = nlohmann::json::parse(file);
  EXPECT_TRUE(with_sigma.at("fit").contains("sigma_a"));
  EXPECT_TRUE(with_sigma.at("fit").contains("sigma_b"));
  EXPECT_EQ(with_sigma.at("truth").at("sigma_b"), 0.09);

  // --interval wald: estimate ± 1.959964 se, and the method says so.
  const CliRun wald = swell("fit --input " + path("r1") + " --case " + path("case.toml") +
                            " --interval wald --json -");
  ASSERT_EQ(wald.exit_code, 0) << wald.output;
  const auto w = nlohmann::json::parse(wald.output);
  EXPECT_EQ(w.at("interval"), "wald");
  for (const char* name : {"hs", "tp", "gamma"}) {
    const auto& e = w.at("fit").at(name);
    const double v = e.at("value"), se = e.at("se"), lo = e.at("ci95")[0], hi = e.at("ci95")[1];
    EXPECT_EQ(e.at("method"), "wald");
    EXPECT_NEAR(hi - v, 1.959964 * se, 1e-6 * se);
    EXPECT_NEAR(v - lo, 1.959964 * se, 1e-6 * se);
  }
}

// A patch of 1.5 peak wavelengths (64² over 150 m, Tp 8 s): the fit runs, but prints "cannot"
// and why instead of an interval, and the JSON has no ci95 (null) but the reason.
TEST_F(OceanCli, FitSaysCannotWhenThePeakIsNotResolved) {
  std::string small = kFitCase;
  small.replace(small.find("256, 256"), 8, "64, 64");
  small.replace(small.find("800.0, 800.0"), 12, "150.0, 150.0");
  std::ofstream(path("small.toml")) << small;
  ASSERT_EQ(swell("synth --case " + path("small.toml") + " --impl fftw --seed 3 --out " +
                  path("s")).exit_code, 0);
  const CliRun table = swell("fit --input " + path("s") + " --case " + path("small.toml"));
  ASSERT_EQ(table.exit_code, 0) << table.output;
  for (const char* fragment : {"cannot (note 1)", "1.50 peak wavelengths", "no calibrated 95 %"}) {
    EXPECT_TRUE(contains(table.output, fragment)) << fragment << " not in: " << table.output;
  }
  EXPECT_FALSE(contains(table.output, "inside")) << table.output;
  const CliRun json = swell("fit --input " + path("s") + " --case " + path("small.toml") +
                            " --json -");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto document = nlohmann::json::parse(json.output);
  for (const char* name : {"hs", "tp", "gamma"}) {
    const auto& e = document.at("fit").at(name);
    EXPECT_EQ(e.at("calibrated"), false);
    EXPECT_TRUE(e.at("ci95").is_null());
    EXPECT_EQ(e.at("ci95_uncalibrated").size(), 2u);
    EXPECT_TRUE(contains(e.at("reason").get<std::string>(), "peak wavelengths"));
  }
}

TEST_F(OceanCli, FitBadInputExitsTwoNamingTheProblem) {
  std::ofstream(path("case.toml")) << kFitCase;
  ASSERT_EQ(swell("synth --case " + path("case.toml") + " --impl fftw --out " + path("r")).exit_code, 0);
  std::ofstream(path("phillips.toml")) << R"([grid]
n = [256, 256]
length = [800.0, 800.0]
[spectrum]
model = "phillips"
amplitude = 1e-3
wind_speed = 10.0
)";
  std::string other = kFitCase;
  other.replace(other.find("800.0, 800.0"), 12, "300.0, 300.0");
  std::ofstream(path("other.toml")) << other;
  fs::create_directories(dir_ / "empty");
  const std::string c = " --case " + path("case.toml");
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"--input " + path("r") + " --case " + path("phillips.toml"), {"phillips", "JONSWAP family"}},
      {"--input " + path("r") + " --case " + path("other.toml"), {"grid", "300"}},
      {"--input " + path("empty") + c, {"without case.toml"}},
      {"--input " + path("r/nothing_%04d.exr") + c, {"nothing_0000.exr"}},
      {"--input " + path("r") + c + " --frame 2", {"frame 2"}},
      {c.substr(1), {"--input"}},
      {"--input " + path("r"), {"--case"}},
      {"--input " + path("r") + " --case " + path("missing.toml"), {"missing.toml"}},
  };
  for (const auto& [args, fragments] : cases) {
    SCOPED_TRACE(args);
    const CliRun run = swell("fit " + args);
    expect_refusal(run, fragments);
  }
}

}  // namespace

// ==================================================================== end of swell fit

// ---------------------------------------------------------------- any sea an engine is asked for

namespace {

const fs::path kCases = fs::path(SWELL_TEST_DATA_DIR) / "cases";

// swell synth then swell gate, from the command line, on every form of sea a case can declare:
// a composite wind sea plus swell, Torsethaugen, Horvath with swell and blend, a netCDF table and
// an NDBC hour (data/cases/). Eight frames each: what the gate needs for every check.
TEST_F(OceanCli, SynthThenGatePassOnEveryFormOfSea) {
  for (const char* name : {"wind_sea_and_swell", "torsethaugen", "horvath_swell_blend",
                           "twopeak_table", "ndbc_41010_hour"}) {
    SCOPED_TRACE(name);
    const std::string out = path(name);
    const CliRun synth = swell("synth --case " + (kCases / (std::string(name) + ".toml")).string() +
                               " --impl fftw --frames 8 --out " + out);
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    const CliRun gate = swell("gate --case " + out + "/case.toml");
    EXPECT_EQ(gate.exit_code, 0) << gate.output;
    EXPECT_TRUE(contains(gate.output, "verdict: PASS")) << gate.output;
  }
}

// A tabulated sea on a rank-1 lattice: swell synth makes it, the gate passes it, and the report
// notes the share of the table's m0 the lattice's wave vectors carry, as it does for a grid.
TEST_F(OceanCli, ATabulatedSeaOnALatticeIsJudgedWithItsShareNoted) {
  const std::string out = path("lattice");
  const CliRun synth = swell("synth --case " + (kCases / "twopeak_table.toml").string() +
                             " --impl lattice --points 16384 --frames 8 --out " + out);
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const CliRun gate = swell("gate --case " + out + "/case.toml");
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
  EXPECT_TRUE(contains(gate.output, "note: the lattice's wave vectors carry")) << gate.output;
}

// swell spectrum --case prints each component and the sum, whose m0 is theirs added.
TEST_F(OceanCli, SpectrumOfACaseShowsEachComponentAndTheSum) {
  const CliRun run = swell("spectrum --case " + (kCases / "wind_sea_and_swell.toml").string() +
                           " --json -");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto document = nlohmann::json::parse(run.output);
  ASSERT_EQ(document["components"].size(), 2u);
  EXPECT_EQ(document["components"][0]["model"], "jonswap");
  EXPECT_EQ(document["components"][1]["model"], "gaussian");
  const double m0 = document["moments"]["m0"].get<double>();
  const double parts = document["components"][0]["moments"]["m0"].get<double>() +
                       document["components"][1]["moments"]["m0"].get<double>();
  EXPECT_NEAR(m0, parts, 2e-9 * m0);
  // Each component's m0 is its Hs²/16 (the Gaussian's cut at ω = 0 is Φ(ωp/σ) = 1 − 1e-70 here).
  EXPECT_NEAR(document["components"][0]["moments"]["m0"].get<double>(), 2.5 * 2.5 / 16, 1e-8);
  EXPECT_NEAR(document["components"][1]["moments"]["m0"].get<double>(), 1.5 * 1.5 / 16, 1e-8);
  const CliRun text = swell("spectrum --case " + (kCases / "wind_sea_and_swell.toml").string());
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_TRUE(contains(text.output, "component 1: gaussian")) << text.output;
  EXPECT_TRUE(contains(text.output, "moments of the sea, the sum of its components")) << text.output;
  expect_refusal(swell("spectrum --case " + (kCases / "wind_sea_and_swell.toml").string() + " --hs 2"),
                 {"--hs with --case"});
}

// A missing energy factor is named as the product of convention factors it is: frames made at
// 8 × the declared energy (energy_factor = 8 in the synthesized case) judged against the case
// without it.
TEST_F(OceanCli, AnUndeclaredEnergyFactorIsNamedAsItsProduct) {
  std::string text;
  {
    std::ifstream in(kCases / "jonswap_deep.toml");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = text.find("gamma = 3.3");
  ASSERT_NE(at, std::string::npos);
  std::string declared = text;
  declared.insert(at, "energy_factor = 8.0\n");
  std::ofstream(path("eight.toml")) << declared;
  const CliRun synth = swell("synth --case " + path("eight.toml") + " --impl fftw --frames 4 --n 128 --out " + path("out"));
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  // Judged as declared: passes.
  EXPECT_EQ(swell("gate --case " + path("out") + "/case.toml").exit_code, 0);
  // Judged without the factor: the energy check names × 8 = 2 × 2 × 2 and the key to declare.
  auto plain = swell::validation::read_case_file(dir_ / "out" / "case.toml");
  plain.ocean.energy_factor = 1;
  swell::validation::write_case_file(dir_ / "out" / "plain.toml", plain);  // beside its frames
  const CliRun gate = swell("gate --case " + path("out/plain.toml"));
  EXPECT_EQ(gate.exit_code, 1) << gate.output;
  EXPECT_TRUE(contains(gate.output, "× 8 = 2 × 2 × 2")) << gate.output;
  EXPECT_TRUE(contains(gate.output, "energy_factor = 8")) << gate.output;
}

// Each declaration a table's file depends on, declared wrong, fails with a message naming the
// key and the reading the frames follow: frames made from the two-peak netCDF table as it is
// (Hz, nautical "from", per Hz per degree), judged against the same case with one key changed.
// Degrees for radians is refused on reading (exit 2): the values contradict it.
TEST_F(OceanCli, EachMisdeclaredTableConventionIsNamed) {
  const CliRun synth = swell("synth --case " + (kCases / "twopeak_table.toml").string() +
                             " --impl fftw --frames 8 --out " + path("out"));
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  std::string text;
  {
    std::ifstream in(dir_ / "out" / "case.toml");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto with = [&](const std::string& line, const std::string& replacement) {
    std::string changed = text;
    const auto at = changed.find(line);
    EXPECT_NE(at, std::string::npos) << line;
    if (at != std::string::npos) changed.replace(at, line.size(), replacement);
    return changed;
  };
  auto gate = [&](const std::string& name, const std::string& contents) {
    std::ofstream(dir_ / "out" / name) << contents;  // beside its frames
    return swell("gate --case " + path("out/" + name));
  };
  struct Slip {
    const char* line;
    const char* replacement;
    std::vector<std::string> named;
  };
  const Slip slips[] = {
      {"frequency_unit = \"Hz\"", "frequency_unit = \"rad/s\"",
       {"frequencies in Hz, not rad/s as declared (frequency_unit)"}},
      {"direction_convention = \"nautical_from\"", "direction_convention = \"toward_ccw_from_x\"",
       {"directions as nautical_from, not toward_ccw_from_x as declared (direction_convention)",
        "the mean direction is the case's mirrored"}},
      {"density_unit = \"m2/Hz/deg\"", "density_unit = \"m2/Hz/rad\"",
       {"(density_unit): energy × 57.3 = 180/π (per degree read as per radian)"}},
  };
  for (const Slip& slip : slips) {
    SCOPED_TRACE(slip.replacement);
    const CliRun run = gate("slip.toml", with(slip.line, slip.replacement));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    for (const auto& named : slip.named) EXPECT_TRUE(contains(run.output, named)) << run.output;
  }
  expect_refusal(gate("radians.toml", with("direction_unit = \"deg\"", "direction_unit = \"rad\"")),
                 {"direction_unit = \"rad\"", "deg"});
  // The engine's slip, the case right: frames made with the directions read in the other
  // convention, judged as the file declares them.
  std::ofstream(dir_ / "out" / "slip_source.toml")
      << with("direction_convention = \"nautical_from\"", "direction_convention = \"toward_ccw_from_x\"");
  const CliRun engine = swell("synth --case " + path("out/slip_source.toml") +
                              " --impl fftw --frames 8 --out " + path("mirrored"));
  ASSERT_EQ(engine.exit_code, 0) << engine.output;
  std::ofstream(dir_ / "mirrored" / "right.toml") << text;
  const CliRun judged = swell("gate --case " + path("mirrored/right.toml"));
  EXPECT_EQ(judged.exit_code, 1) << judged.output;
  EXPECT_TRUE(contains(judged.output, "directions as toward_ccw_from_x, not nautical_from as declared"))
      << judged.output;
  // A factor no unit explains is not blamed on the table: frames at twice the energy
  // (energy_factor = 2 in the synthesized case) are "twice the energy", not a density unit.
  ASSERT_NE(text.find("[spectrum]\n"), std::string::npos);
  std::string doubled = text;
  doubled.insert(doubled.find("[spectrum]\n") + std::string("[spectrum]\n").size(), "energy_factor = 2.0\n");
  std::ofstream(dir_ / "out" / "doubled_source.toml") << doubled;
  const CliRun twice = swell("synth --case " + path("out/doubled_source.toml") + " --impl fftw --frames 8 --out " +
                             path("doubled"));
  ASSERT_EQ(twice.exit_code, 0) << twice.output;
  std::ofstream(dir_ / "doubled" / "right.toml") << text;
  const CliRun judged_twice = swell("gate --case " + path("doubled/right.toml"));
  EXPECT_EQ(judged_twice.exit_code, 1) << judged_twice.output;
  EXPECT_TRUE(contains(judged_twice.output, "twice the energy")) << judged_twice.output;
  EXPECT_FALSE(contains(judged_twice.output, "the frames follow the table")) << judged_twice.output;
}

}  // namespace
