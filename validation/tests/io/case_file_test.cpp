// Case files (docs/case_files.md): the issue's example parses to the case it describes, defaults
// are the documented ones, case_toml() round-trips every kind of case exactly (including awkward
// doubles and the largest seeds), and every malformed file is rejected with a message that starts
// with the file (and line) and names the section and key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/validation/io/case_file.hpp"

namespace {

namespace fs = std::filesystem;
using swell::InvalidInput;
using swell::reference::Field;
using swell::reference::ModelSpec;
using swell::reference::OceanCase;
using swell::validation::CaseFile;
using swell::validation::case_toml;
using swell::validation::parse_case_toml;
using swell::validation::read_case_file;
using swell::validation::SpectrumScale;
using swell::validation::write_case_file;

constexpr double kInf = std::numeric_limits<double>::infinity();

const char* const kIssueExample = R"(
[grid]
n = [256, 256]            # samples along x, y (integers ≥ 1)
length = [200.0, 200.0]   # metres
[time]
t0 = 0.0
dt = 0.25                 # seconds between frames
frames = 16
[physics]
gravity = 9.81
depth = "inf"             # or metres (number)
[spectrum]
model = "jonswap"
scale = "absolute"        # or "free"
hs = 3.0
tp = 8.0
gamma = 3.3
[spreading]
model = "cos2s"
s = 10.0
wind_dir_deg = 30.0
[synthesis]
choppiness = 1.0
loop_period = 0.0         # 0 = none
seed = 1
[input]
files = "frame_%04d.exr"
height = "h"
disp_x = "dx"
disp_y = "dy"
raw_type = "float32"
)";

// Exact equality of everything a case file holds (doubles bit for bit: +0 and −0 differ).
void expect_same(const CaseFile& a, const CaseFile& b) {
  auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  const OceanCase &x = a.ocean, &y = b.ocean;
  EXPECT_EQ(x.grid.nx, y.grid.nx);
  EXPECT_EQ(x.grid.ny, y.grid.ny);
  EXPECT_EQ(bits(x.grid.lx), bits(y.grid.lx)) << x.grid.lx << " vs " << y.grid.lx;
  EXPECT_EQ(bits(x.grid.ly), bits(y.grid.ly)) << x.grid.ly << " vs " << y.grid.ly;
  EXPECT_EQ(bits(x.t0), bits(y.t0)) << x.t0 << " vs " << y.t0;
  EXPECT_EQ(bits(x.dt), bits(y.dt)) << x.dt << " vs " << y.dt;
  EXPECT_EQ(x.frames, y.frames);
  EXPECT_EQ(bits(x.gravity), bits(y.gravity));
  EXPECT_EQ(bits(x.depth), bits(y.depth)) << x.depth << " vs " << y.depth;
  const auto xs = x.components(), ys = y.components();
  ASSERT_EQ(xs.size(), ys.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (const auto& [p, q] : {std::pair{&xs[i].spectrum, &ys[i].spectrum},
                               std::pair{&xs[i].spreading, &ys[i].spreading}}) {
      EXPECT_EQ(p->model, q->model);
      EXPECT_EQ(p->choices, q->choices);
      ASSERT_EQ(p->numbers.size(), q->numbers.size()) << p->model;
      for (const auto& [name, value] : p->numbers) {
        ASSERT_TRUE(q->numbers.count(name)) << name;
        EXPECT_EQ(bits(value), bits(q->numbers.at(name))) << name << ": " << value << " vs "
                                                          << q->numbers.at(name);
      }
    }
    EXPECT_EQ(bits(xs[i].wind_dir_deg), bits(ys[i].wind_dir_deg))
        << xs[i].wind_dir_deg << " vs " << ys[i].wind_dir_deg;
    EXPECT_EQ(bits(xs[i].energy_factor), bits(ys[i].energy_factor));
    EXPECT_EQ(bits(xs[i].short_wave_fade), bits(ys[i].short_wave_fade));
  }
  EXPECT_EQ(bits(x.choppiness), bits(y.choppiness)) << x.choppiness << " vs " << y.choppiness;
  EXPECT_EQ(bits(x.loop_period), bits(y.loop_period));
  EXPECT_EQ(x.seed, y.seed);
  EXPECT_EQ(a.scale, b.scale);
  EXPECT_EQ(a.input.files, b.input.files);
  EXPECT_EQ(a.input.channels, b.input.channels);
  EXPECT_EQ(a.input.raw_type, b.input.raw_type);
  EXPECT_EQ(a.input.value_ranges, b.input.value_ranges);
}

TEST(CaseFile, IssueExampleParsesToTheCaseItDescribes) {
  const CaseFile c = parse_case_toml(kIssueExample, "cases/example.toml");
  const OceanCase& o = c.ocean;
  EXPECT_EQ(o.grid.nx, 256);
  EXPECT_EQ(o.grid.ny, 256);
  EXPECT_EQ(o.grid.lx, 200.0);
  EXPECT_EQ(o.grid.ly, 200.0);
  EXPECT_EQ(o.t0, 0.0);
  EXPECT_EQ(o.dt, 0.25);
  EXPECT_EQ(o.frames, 16);
  EXPECT_EQ(o.time(3), 0.75);
  EXPECT_EQ(o.gravity, 9.81);
  EXPECT_EQ(o.depth, kInf);
  EXPECT_EQ(o.spectrum.model, "jonswap");
  EXPECT_EQ(o.spectrum.numbers, (std::map<std::string, double>{{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}));
  EXPECT_TRUE(o.spectrum.choices.empty());
  EXPECT_EQ(o.spreading.model, "cos2s");
  EXPECT_EQ(o.spreading.numbers, (std::map<std::string, double>{{"s", 10.0}}));
  EXPECT_EQ(o.wind_dir_deg, 30.0);
  EXPECT_EQ(o.choppiness, 1.0);
  EXPECT_EQ(o.loop_period, 0.0);
  EXPECT_EQ(o.seed, 1u);
  EXPECT_EQ(c.scale, SpectrumScale::absolute);
  EXPECT_EQ(c.input.files, "frame_%04d.exr");
  EXPECT_EQ(c.input.channels, (std::map<Field, std::string>{
                                  {Field::height, "h"}, {Field::disp_x, "dx"}, {Field::disp_y, "dy"}}));
  EXPECT_EQ(c.input.raw_type, "float32");
  EXPECT_EQ(c.directory, fs::path("cases"));
  // The spectrum it names is the one the model factory builds (Hs = 3 m by exact normalization).
  EXPECT_NO_THROW((void)o.directional_spectrum());
}

TEST(CaseFile, DefaultsAreTheDocumentedOnes) {
  const CaseFile c = parse_case_toml(R"(
[grid]
n = [64, 32]
length = [100, 50]
[spectrum]
model = "bretschneider"
hs = 2
tp = 7
[spreading]
model = "donelan-banner"
)", "defaults.toml");
  const OceanCase& o = c.ocean;
  EXPECT_EQ(o.grid.nx, 64);
  EXPECT_EQ(o.grid.ny, 32);
  EXPECT_EQ(o.grid.lx, 100.0);  // integers are accepted where numbers are expected
  EXPECT_EQ(o.grid.ly, 50.0);
  EXPECT_EQ(o.t0, 0.0);
  EXPECT_EQ(o.dt, 0.0);
  EXPECT_EQ(o.frames, 1);
  EXPECT_EQ(o.gravity, 9.81);
  EXPECT_EQ(o.depth, kInf);
  EXPECT_EQ(o.wind_dir_deg, 0.0);
  EXPECT_EQ(o.choppiness, 1.0);
  EXPECT_EQ(o.loop_period, 0.0);
  EXPECT_EQ(o.seed, 0u);
  EXPECT_EQ(c.scale, SpectrumScale::absolute);
  EXPECT_TRUE(c.input.files.empty());
  EXPECT_TRUE(c.input.channels.empty());
  EXPECT_EQ(c.directory, fs::path(""));
}

TEST(CaseFile, ScalarGridSizeMeansSquareAndDepthMayBeANumberOrTomlInf) {
  const CaseFile c = parse_case_toml(R"(
[grid]
n = 128
length = 300.5
[physics]
depth = 12.5
[spectrum]
model = "tma"
hs = 1.5
tp = 6
[spreading]
model = "cos2s"
s = 4
)", "square.toml");
  EXPECT_EQ(c.ocean.grid.nx, 128);
  EXPECT_EQ(c.ocean.grid.ny, 128);
  EXPECT_EQ(c.ocean.grid.lx, 300.5);
  EXPECT_EQ(c.ocean.grid.ly, 300.5);
  EXPECT_EQ(c.ocean.depth, 12.5);
  // TMA takes its depth from [physics]: the full spec carries it.
  EXPECT_EQ(c.ocean.full_spectrum_spec().numbers.at("depth"), 12.5);

  const CaseFile d = parse_case_toml(R"(
[grid]
n = [8, 8]
length = [10, 10]
[physics]
depth = inf
[spectrum]
model = "phillips"
amplitude = 1e-3
wind_speed = 10
wind_dir_deg = 45
)", "toml_inf.toml");
  EXPECT_EQ(d.ocean.depth, kInf);
  EXPECT_EQ(d.ocean.wind_dir_deg, 45.0);  // phillips: the direction may sit in [spectrum]
  EXPECT_TRUE(d.ocean.spreading.model.empty());
}

// Every ```toml block of docs/case_files.md is a valid case file.
TEST(CaseFile, EveryExampleInTheDocsParses) {
  const fs::path doc = fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path() / "docs" / "case_files.md";
  if (!fs::exists(doc)) GTEST_SKIP() << doc << " not found (tests run outside the source tree)";
  std::ifstream file(doc);
  std::string line, block;
  bool inside = false;
  int blocks = 0;
  for (int number = 1; std::getline(file, line); ++number) {
    if (!inside && line == "```toml") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      ++blocks;
      SCOPED_TRACE("block ending at docs/case_files.md:" + std::to_string(number));
      // Read as if written in docs/: a table's file is relative to it.
      EXPECT_NO_THROW((void)parse_case_toml(block, doc)) << block;
    } else if (inside) {
      block += line + "\n";
    }
  }
  EXPECT_GE(blocks, 4);
}

// ------------------------------------------------------------------ round trips

CaseFile base_case() {
  CaseFile c;
  c.ocean.grid = {256, 128, 200.0, 100.0};
  c.ocean.t0 = 0.5;
  c.ocean.dt = 0.25;
  c.ocean.frames = 16;
  return c;
}

std::vector<std::pair<std::string, CaseFile>> round_trip_cases() {
  std::vector<std::pair<std::string, CaseFile>> cases;
  {
    CaseFile c = base_case();
    c.ocean.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
    c.ocean.spreading = {"cos2s", {{"s", 10.0}}, {}};
    c.ocean.wind_dir_deg = 30;
    c.ocean.seed = 1;
    c.input.files = "frame_%04d.exr";
    c.input.channels = {{Field::height, "h"}, {Field::disp_x, "dx"}, {Field::disp_y, "dy"}};
    cases.emplace_back("jonswap_cos2s", c);
  }
  {
    CaseFile c = base_case();
    c.ocean.depth = 20;
    c.ocean.spectrum = {"tma",
                        {{"hs", 1.25}, {"tp", 6.5}, {"gamma", 2.0}, {"sigma_a", 0.06}, {"sigma_b", 0.1}},
                        {{"normalization", "dnv"}, {"depth_factor", "thompson-vincent"}}};
    c.ocean.spreading = {"cos-power", {{"p", 4}}, {{"one_sided", "yes"}}};
    c.ocean.gravity = 9.80665;
    c.ocean.choppiness = -0.7;
    c.ocean.loop_period = 60;
    c.ocean.seed = 123456789;
    c.input.files = "out/frame_%03d.npy";
    c.input.channels = {{Field::height, "h"}, {Field::jacobian, "J"}};
    cases.emplace_back("tma_depth_choices", c);
  }
  {
    CaseFile c = base_case();
    c.ocean.spectrum = {"phillips",
                        {{"amplitude", 3e-4}, {"wind_speed", 31.0}, {"exponent", 6}, {"small_wave_cutoff", 0.01}},
                        {}};
    c.ocean.wind_dir_deg = -135.25;
    c.scale = SpectrumScale::free;
    c.ocean.seed = std::numeric_limits<std::uint64_t>::max();  // beyond TOML's int64
    c.input.files = "frames/%d.raw";
    c.input.channels = {{Field::height, "height"}, {Field::slope_x, "sx"}, {Field::slope_y, "sy"}};
    c.input.raw_type = "float64";
    cases.emplace_back("phillips_free_largest_seed", c);
  }
  {
    CaseFile c = base_case();
    c.ocean.spectrum = {"pierson-moskowitz", {{"u19_5", 15.0}}, {}};
    c.ocean.spreading = {"mitsuyasu", {{"s_max", 25}}, {}};
    c.ocean.wind_dir_deg = 90;
    c.ocean.seed = (std::uint64_t{1} << 63);  // the first seed that needs the string form
    cases.emplace_back("pierson_moskowitz_mitsuyasu", c);
  }
  {
    // PNG frames: one value range for every field, written as [low, high] ...
    CaseFile c = base_case();
    c.ocean.spectrum = {"jonswap", {{"hs", 2.0}, {"tp", 7.0}}, {}};
    c.ocean.spreading = {"cos2s", {{"s", 10.0}}, {}};
    c.input.files = "png/frame_%04d.png";
    c.input.channels = {{Field::height, "R"}, {Field::disp_x, "G"}, {Field::disp_y, "B"}};
    c.input.value_ranges = {{Field::height, {-4.0, 4.0}}, {Field::disp_x, {-4.0, 4.0}},
                            {Field::disp_y, {-4.0, 4.0}}};
    cases.emplace_back("png_one_range", c);
    // ... and one per field, as a table.
    c.input.value_ranges = {{Field::height, {-4.5, 4.5}}, {Field::disp_x, {-2.0, 2.25}},
                            {Field::disp_y, {-2.0, 2.25}}};
    cases.emplace_back("png_ranges_by_field", c);
  }
  {
    // Doubles whose shortest decimal form is long, tiny or huge.
    CaseFile c = base_case();
    c.ocean.grid = {5, 3, 1.0 / 3.0, 0.1 + 0.2};
    c.ocean.t0 = -1e-300;
    c.ocean.dt = 5e-324;  // the smallest subnormal
    c.ocean.frames = 2;
    c.ocean.gravity = 9.81 * (1 + 1e-15);
    c.ocean.depth = 1e300;
    c.ocean.spectrum = {"jonswap", {{"u10", 12.345678901234567}, {"fetch", 1e5}}, {}};
    c.ocean.spreading = {"hasselmann", {{"wave_age", 0.83}}, {}};
    c.ocean.wind_dir_deg = -0.0;
    c.ocean.choppiness = 1.7976931348623157e308;
    cases.emplace_back("awkward_doubles", c);
  }
  {
    // A composite sea: a wind sea with an energy factor and a fade, a swell, and a phillips
    // component (its direction in its own table).
    CaseFile c = base_case();
    swell::reference::SeaComponent wind, swell_part, phillips;
    wind.spectrum = {"jonswap", {{"hs", 2.5}, {"tp", 7.0}, {"gamma", 3.3}}, {}};
    wind.spreading = {"cos2s", {{"s", 10.0}}, {}};
    wind.wind_dir_deg = 30;
    wind.energy_factor = 8;
    wind.short_wave_fade = 0.05;
    swell_part.spectrum = {"bretschneider", {{"hs", 1.5}, {"tp", 14.0}}, {}};
    swell_part.spreading = {"cos2s", {{"s", 40.0}}, {}};
    swell_part.wind_dir_deg = 75;
    phillips.spectrum = {"phillips", {{"amplitude", 3e-4}, {"wind_speed", 12.0}}, {}};
    phillips.wind_dir_deg = -20;
    c.ocean.set_components({wind, swell_part, phillips});
    c.scale = SpectrumScale::free;
    cases.emplace_back("composite_three_components", c);
  }
  return cases;
}

TEST(CaseFile, CaseTomlRoundTripsExactly) {
  for (const auto& [name, original] : round_trip_cases()) {
    SCOPED_TRACE(name);
    ASSERT_NO_THROW(original.ocean.validate());
    const std::string text = case_toml(original);
    CaseFile back;
    ASSERT_NO_THROW(back = parse_case_toml(text, name + ".toml")) << text;
    expect_same(original, back);
    EXPECT_EQ(case_toml(back), text);  // a fixed point
  }
}

TEST(CaseFile, CaseTomlWritesInfiniteDepthAsTheStringInf) {
  CaseFile c = round_trip_cases().front().second;
  const std::string text = case_toml(c);
  EXPECT_NE(text.find("depth = \"inf\""), std::string::npos) << text;
  EXPECT_NE(text.find("n = [256, 128]"), std::string::npos) << text;
  EXPECT_NE(text.find("[input]\nfiles = \"frame_%04d.exr\""), std::string::npos) << text;
}

TEST(CaseFile, RandomDoublesRoundTripBitForBit) {
  // t0, wind_dir_deg and choppiness accept any finite double: random bit patterns exercise the
  // shortest-form printing and toml++'s parsing over the whole exponent range.
  std::mt19937_64 random(20240611);
  CaseFile c = round_trip_cases().front().second;
  for (int trial = 0; trial < 2000; ++trial) {
    auto finite = [&] {
      while (true) {
        const double x = std::bit_cast<double>(random());
        if (std::isfinite(x)) return x;
      }
    };
    c.ocean.t0 = finite();
    c.ocean.wind_dir_deg = std::ldexp(finite(), -40);  // θw in radians must stay finite
    c.ocean.choppiness = finite();
    c.ocean.grid.lx = std::abs(finite()) + 1e-300;
    const CaseFile back = parse_case_toml(case_toml(c), "random.toml");
    ASSERT_EQ(std::bit_cast<std::uint64_t>(back.ocean.t0), std::bit_cast<std::uint64_t>(c.ocean.t0))
        << c.ocean.t0;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(back.ocean.wind_dir_deg),
              std::bit_cast<std::uint64_t>(c.ocean.wind_dir_deg));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(back.ocean.choppiness),
              std::bit_cast<std::uint64_t>(c.ocean.choppiness));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(back.ocean.grid.lx),
              std::bit_cast<std::uint64_t>(c.ocean.grid.lx));
  }
}

TEST(CaseFile, WriteAndReadBackThroughTheFileSystem) {
  const fs::path dir = fs::temp_directory_path() / ("swell_case_file_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const CaseFile original = round_trip_cases()[1].second;
  write_case_file(dir / "case.toml", original);
  const CaseFile back = read_case_file(dir / "case.toml");
  expect_same(original, back);
  EXPECT_EQ(back.directory, dir);  // the base of [input] files
  fs::remove_all(dir);
}

TEST(CaseFile, MissingOrUnreadableFileIsNamed) {
  try {
    (void)read_case_file("/nonexistent/dir/case.toml");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/case.toml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such"), std::string::npos) << e.what();
  }
  try {
    (void)read_case_file(fs::temp_directory_path());
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------ malformed files

struct Malformed {
  std::string name;
  std::string toml;
  std::vector<std::string> fragments;  // each must appear in the message
};

// A valid case with one line replaced: `replace` is the line to change (exact), `with` the new
// text ("" drops it).
std::string edit(const std::string& from, const std::string& with) {
  std::string text = R"([grid]
n = [64, 64]
length = [100.0, 100.0]
[time]
dt = 0.5
frames = 4
[physics]
depth = "inf"
[spectrum]
model = "jonswap"
hs = 2.0
tp = 7.0
[spreading]
model = "cos2s"
s = 10.0
wind_dir_deg = 0.0
[synthesis]
seed = 3
[input]
files = "f_%04d.exr"
height = "h"
)";
  const auto at = text.find(from + "\n");
  if (at == std::string::npos) throw std::logic_error("edit: no line '" + from + "'");
  text.replace(at, from.size() + 1, with.empty() ? "" : with + "\n");
  return text;
}

std::vector<Malformed> malformed_cases() {
  return {
      {"unknown_section", edit("[synthesis]", "[synthesys]"),
       {"bad.toml:17:", "unknown section [synthesys]", "valid sections: grid, time, physics"}},
      {"unknown_grid_key", edit("length = [100.0, 100.0]", "length = [100.0, 100.0]\nsize = 3"),
       {"bad.toml:4:", "unknown key 'size' in [grid]", "valid keys: n, length"}},
      {"unknown_time_key", edit("frames = 4", "frame = 4"),
       {"bad.toml:6:", "unknown key 'frame' in [time]", "valid keys: t0, dt, frames"}},
      {"parameter_of_another_model", edit("tp = 7.0", "tp = 7.0\nu19_5 = 10.0"),
       {"unknown key 'u19_5' in [spectrum] for model 'jonswap'", "hs", "sigma_a"}},
      {"unknown_spreading_key", edit("s = 10.0", "s_max = 10.0"),
       {"unknown key 's_max' in [spreading] for model 'cos2s'", "valid keys: model, wind_dir_deg, s"}},
      {"unknown_input_key", edit("height = \"h\"", "heigth = \"h\""),
       {"bad.toml:21:", "unknown key 'heigth' in [input]", "height", "jacobian"}},
      {"unknown_synthesis_key", edit("seed = 3", "sead = 3"), {"unknown key 'sead' in [synthesis]"}},
      {"spreading_parameter_without_model", edit("model = \"cos2s\"", ""),
       {"unknown key 's' in [spreading]", "need a model"}},
      {"n_string", edit("n = [64, 64]", "n = \"256\""),
       {"bad.toml:2:", "[grid] n", "array of 2 integers", "the string \"256\""}},
      {"n_float", edit("n = [64, 64]", "n = [64.0, 64]"), {"[grid] n", "integers"}},
      {"n_three", edit("n = [64, 64]", "n = [64, 64, 64]"), {"[grid] n", "array of 2"}},
      {"length_string", edit("length = [100.0, 100.0]", "length = [\"100\", 100.0]"),
       {"[grid] length", "numbers"}},
      {"frames_float", edit("frames = 4", "frames = 2.5"), {"[time] frames", "an integer", "2.5"}},
      {"frames_zero", edit("frames = 4", "frames = 0"), {"[time] frames", "1…"}},
      {"frames_huge", edit("frames = 4", "frames = 99999999999"), {"[time] frames", "99999999999"}},
      {"hs_string", edit("hs = 2.0", "hs = \"2.0\""), {"bad.toml:11:", "[spectrum] hs", "a number"}},
      {"choice_number", edit("hs = 2.0", "hs = 2.0\nnormalization = 1"),
       {"[spectrum] normalization", "a string"}},
      {"model_number", edit("model = \"jonswap\"", "model = 3"), {"[spectrum] model", "a string"}},
      {"scale_unknown", edit("model = \"jonswap\"", "model = \"jonswap\"\nscale = \"relative\""),
       {"[spectrum] scale", "\"absolute\" or \"free\"", "relative"}},
      {"gravity_bool", edit("depth = \"inf\"", "gravity = true"), {"[physics] gravity", "a number", "true"}},
      {"depth_word", edit("depth = \"inf\"", "depth = \"deep\""), {"[physics] depth", "\"inf\"", "deep"}},
      {"seed_negative", edit("seed = 3", "seed = -3"), {"[synthesis] seed", "≥ 0", "-3"}},
      {"seed_float", edit("seed = 3", "seed = 3.5"), {"[synthesis] seed", "integer"}},
      {"seed_bad_string", edit("seed = 3", "seed = \"12abc\""), {"[synthesis] seed", "12abc"}},
      {"raw_type", edit("height = \"h\"", "height = \"h\"\nraw_type = \"int16\""),
       {"[input] raw_type", "float32", "int16"}},
      {"channel_twice", edit("height = \"h\"", "height = \"h\"\ndisp_x = \"h\""),
       {"[input] disp_x", "already given to height"}},
      {"files_bad_conversion", edit("files = \"f_%04d.exr\"", "files = \"f_%s.exr\""),
       {"bad.toml:20:", "[input] files", "unsupported conversion '%s'"}},
      {"files_two_conversions", edit("files = \"f_%04d.exr\"", "files = \"f_%d_%d.exr\""),
       {"[input] files", "more than one conversion"}},
      {"files_extension", edit("files = \"f_%04d.exr\"", "files = \"f_%04d.jpg\""),
       {"[input] files", "'.jpg'", ".png"}},
      {"value_range_one_number", edit("height = \"h\"", "height = \"h\"\nvalue_range = 4.0"),
       {"bad.toml:22:", "[input] value_range", "[low, high]"}},
      {"value_range_three", edit("height = \"h\"", "height = \"h\"\nvalue_range = [1, 2, 3]"),
       {"[input] value_range", "[low, high]"}},
      {"value_range_string", edit("height = \"h\"", "height = \"h\"\nvalue_range = [\"-4\", 4]"),
       {"[input] value_range", "[low, high]"}},
      {"value_range_reversed", edit("height = \"h\"", "height = \"h\"\nvalue_range = [4.0, -4.0]"),
       {"[input] value_range", "[4, -4]", "low < high"}},
      {"value_range_empty_interval", edit("height = \"h\"", "height = \"h\"\nvalue_range = [1, 1]"),
       {"[input] value_range", "low < high"}},
      {"value_range_nan", edit("height = \"h\"", "height = \"h\"\nvalue_range = [nan, 4.0]"),
       {"[input] value_range", "finite"}},
      {"value_range_unknown_field",
       edit("height = \"h\"", "height = \"h\"\nvalue_range = { heigth = [-4.0, 4.0] }"),
       {"[input] value_range", "unknown field 'heigth'", "disp_x"}},
      {"value_range_field_not_given",
       edit("height = \"h\"", "height = \"h\"\nvalue_range = { disp_x = [-4.0, 4.0] }"),
       {"[input] value_range", "disp_x", "does not provide"}},
      {"value_range_field_bad_pair",
       edit("height = \"h\"", "height = \"h\"\nvalue_range = { height = [4.0] }"),
       {"[input] value_range", "height: must be"}},
      {"value_range_empty_table", edit("height = \"h\"", "height = \"h\"\nvalue_range = {}"),
       {"[input] value_range", "empty table"}},
      {"files_number", edit("files = \"f_%04d.exr\"", "files = 3"), {"[input] files", "a string"}},
      {"channel_empty", edit("height = \"h\"", "height = \"\""), {"[input] height", "must name"}},
      {"input_without_fields", edit("height = \"h\"", ""), {"[input] names no field"}},
      {"missing_n", edit("n = [64, 64]", ""), {"[grid] needs 'n'"}},
      {"missing_length", edit("length = [100.0, 100.0]", ""), {"[grid] needs 'length'"}},
      {"missing_grid", edit("[grid]\nn = [64, 64]\nlength = [100.0, 100.0]", ""), {"missing section [grid]"}},
      {"missing_model", edit("model = \"jonswap\"", ""), {"[spectrum] needs 'model'", "jonswap"}},
      {"missing_spectrum",
       edit("[spectrum]\nmodel = \"jonswap\"\nhs = 2.0\ntp = 7.0", ""), {"missing section [spectrum]"}},
      {"unknown_model", edit("model = \"jonswap\"", "model = \"jonswop\""),
       {"bad.toml:10:", "unknown spectrum model 'jonswop'", "jonswap", "phillips"}},
      {"unknown_spreading_model", edit("model = \"cos2s\"", "model = \"cos3s\""),
       {"unknown spreading model 'cos3s'", "mitsuyasu"}},
      {"depth_in_spectrum", edit("hs = 2.0", "hs = 2.0\ndepth = 10.0"), {"[spectrum] depth", "[physics]"}},
      {"wind_dir_in_spectrum", edit("hs = 2.0", "hs = 2.0\nwind_dir = 10.0"), {"[spectrum] wind_dir", "wind_dir_deg"}},
      {"wind_dir_twice", edit("hs = 2.0", "hs = 2.0\nwind_dir_deg = 10.0"), {"wind_dir_deg", "both"}},
      {"negative_depth", edit("depth = \"inf\"", "depth = -5.0"), {"bad.toml: ", "depth", "> 0", "-5"}},
      {"zero_gravity", edit("depth = \"inf\"", "gravity = 0.0"), {"bad.toml: ", "gravity", "0"}},
      {"negative_hs", edit("hs = 2.0", "hs = -1.0"), {"bad.toml: ", "hs", "-1"}},
      {"negative_length", edit("length = [100.0, 100.0]", "length = [-100.0, 100.0]"),
       {"bad.toml: ", "-100"}},
      {"frames_without_dt", edit("dt = 0.5", ""), {"bad.toml: ", "dt", "more than one frame"}},
      {"negative_loop_period", edit("seed = 3", "seed = 3\nloop_period = -1.0"), {"loop_period", "-1"}},
      {"nan_choppiness", edit("seed = 3", "seed = 3\nchoppiness = nan"), {"choppiness", "finite"}},
      {"jonswap_without_spreading", edit("[spreading]\nmodel = \"cos2s\"\ns = 10.0", "[spreading]"),
       {"bad.toml: ", "needs a spreading model"}},
      {"jonswap_missing_tp", edit("tp = 7.0", ""), {"bad.toml: ", "tp"}},
      {"top_level_value", "grid = 3\n" + edit("[grid]\nn = [64, 64]\nlength = [100.0, 100.0]", ""),
       {"bad.toml:1:", "'grid' must be a section"}},
      {"not_toml", edit("hs = 2.0", "hs = = 2.0"), {"bad.toml:11:", "not valid TOML"}},
      {"duplicate_key", edit("hs = 2.0", "hs = 2.0\nhs = 3.0"), {"bad.toml:12:", "not valid TOML"}},
  };
}

TEST(CaseFile, TheTemplateOfTheMalformedCasesIsValid) {
  const CaseFile c = parse_case_toml(edit("seed = 3", "seed = 3"), "bad.toml");
  EXPECT_EQ(c.ocean.frames, 4);
  EXPECT_EQ(c.ocean.seed, 3u);
}

TEST(CaseFile, EveryMalformedCaseIsRejectedWithFileSectionAndKey) {
  for (const auto& m : malformed_cases()) {
    SCOPED_TRACE(m.name);
    try {
      (void)parse_case_toml(m.toml, "bad.toml");
      ADD_FAILURE() << m.name << ": accepted\n" << m.toml;
    } catch (const InvalidInput& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("bad.toml:", 0), 0u) << message;  // starts with the file
      for (const auto& fragment : m.fragments) {
        EXPECT_NE(message.find(fragment), std::string::npos)
            << m.name << ": '" << fragment << "' not in: " << message;
      }
    }
  }
}

TEST(CaseFile, PhillipsTakesNoSpreadingModel) {
  try {
    (void)parse_case_toml(R"(
[grid]
n = [8, 8]
length = [10, 10]
[spectrum]
model = "phillips"
amplitude = 1e-3
wind_speed = 10
[spreading]
model = "cos2s"
s = 3
)", "phillips.toml");
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("phillips.toml: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("spreading"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------ found by the fuzzer
// Inputs validation/fuzz/case_file_fuzzer found escaping as something other than InvalidInput
// (each is also a seed in validation/fuzz/corpus/case_file/).

// tp = 4.4e65 s: validate() normalizes the JONSWAP (TMA) spectrum by quadrature, which threw
// NumericalError — `swell fit --case` exited 1 (a failed check) instead of 2 (bad input).
TEST(CaseFileFuzzFindings, SpectrumThatCannotBeNormalizedIsBadInputNamingTheFile) {
  try {
    (void)parse_case_toml(R"(
[grid]
n = 256
length = 300.0
[physics]
depth = 8.0
[spectrum]
model = "tma"
hs = 1.2
tp = 444444444444444444444444444444444444444444444444444444444444444444.0
gamma = 2.0
)", "huge_tp.toml");
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("huge_tp.toml: ", 0), 0u) << message;
    EXPECT_NE(message.find("spectrum"), std::string::npos) << message;
  }
}

}  // namespace

// ------------------------------------------------------------------ composite seas

const char* const kCompositeExample = R"(
[grid]
n = [64, 64]
length = [200.0, 200.0]
[time]
dt = 0.5
frames = 4
[[spectrum]]              # component 0: wind sea
model = "jonswap"
hs = 2.5
tp = 7.0
gamma = 3.3
[spectrum.spreading]
model = "cos2s"
s = 10.0
wind_dir_deg = 30.0
[[spectrum]]              # component 1: swell
model = "bretschneider"
hs = 1.5
tp = 14.0
energy_factor = 2.0
[spectrum.spreading]
model = "cos2s"
s = 40.0
wind_dir_deg = 75.0
[synthesis]
seed = 3
)";

TEST(CaseFileComposite, ComponentsAreReadInOrderWithTheirOwnSpreadingAndDirection) {
  const CaseFile c = parse_case_toml(kCompositeExample, "composite.toml");
  const auto parts = c.ocean.components();
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].spectrum.model, "jonswap");
  EXPECT_EQ(parts[0].spectrum.numbers.at("gamma"), 3.3);
  EXPECT_EQ(parts[0].spreading.numbers.at("s"), 10.0);
  EXPECT_EQ(parts[0].wind_dir_deg, 30.0);
  EXPECT_EQ(parts[0].energy_factor, 1.0);
  EXPECT_EQ(parts[1].spectrum.model, "bretschneider");
  EXPECT_EQ(parts[1].spreading.numbers.at("s"), 40.0);
  EXPECT_EQ(parts[1].wind_dir_deg, 75.0);
  EXPECT_EQ(parts[1].energy_factor, 2.0);
  EXPECT_TRUE(c.ocean.is_composite());
  // The sea's m0 is the wind sea's Hs²/16 plus twice the swell's.
  const double m0 = swell::reference::spectral_moment(c.ocean.sea_spectrum()->omnidirectional(), 0);
  EXPECT_NEAR(m0, (2.5 * 2.5 + 2 * 1.5 * 1.5) / 16, 2e-9 * m0);
}

TEST(CaseFileComposite, OneComponentInBracketsIsTheOneComponentCase) {
  std::string one = kCompositeExample;
  one = one.substr(0, one.find("[[spectrum]]              # component 1"));
  one += "[synthesis]\nseed = 3\n";
  const CaseFile c = parse_case_toml(one, "one.toml");
  EXPECT_FALSE(c.ocean.is_composite());
  EXPECT_EQ(c.ocean.spectrum.model, "jonswap");
  EXPECT_EQ(c.ocean.wind_dir_deg, 30.0);
}

TEST(CaseFileComposite, MistakesAreNamedWithTheComponent) {
  const std::string base = kCompositeExample;
  auto expect_refused = [](const std::string& text, std::vector<std::string> fragments) {
    try {
      (void)parse_case_toml(text, "bad.toml");
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const InvalidInput& e) {
      for (const auto& f : fragments) {
        EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what() << "\nmissing: " << f;
      }
    }
  };
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string t = base;
    const auto at = t.find(from);
    if (at == std::string::npos) throw std::logic_error(from);
    return t.replace(at, from.size(), to);
  };
  // A top-level [spreading] beside [[spectrum]] tables.
  expect_refused(base + "[spreading]\nmodel = \"cos2s\"\ns = 5.0\n", {"bad.toml", "[spreading]", "[spectrum.spreading]"});
  // scale belongs to the whole sea: only in the first component.
  expect_refused(replace("energy_factor = 2.0", "scale = \"free\""), {"bad.toml", "spectrum 1", "scale", "first"});
  // An unknown key in a component's spreading names that component.
  expect_refused(replace("s = 40.0", "s = 40.0\nspread = 3.0"), {"bad.toml", "spectrum 1.spreading", "spread"});
  // A bad energy factor.
  expect_refused(replace("energy_factor = 2.0", "energy_factor = 0.0"), {"bad.toml", "spectrum 1", "energy_factor"});
  // A component without a model.
  expect_refused(replace("model = \"bretschneider\"\n", ""), {"bad.toml", "spectrum 1", "model"});
  // A component's parameters are its model's.
  expect_refused(replace("tp = 14.0", "tp = 14.0\ngamma = 2.0"), {"bad.toml", "spectrum 1", "gamma"});
  // spreading must be a table.
  expect_refused(replace("[spectrum.spreading]\nmodel = \"cos2s\"\ns = 40.0\nwind_dir_deg = 75.0",
                         "spreading = 3.0"),
                 {"bad.toml", "spectrum 1", "spreading"});
}
