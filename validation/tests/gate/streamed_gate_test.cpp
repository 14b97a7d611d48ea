// The gate on a case's files streams them (io/frame_source.hpp): one frame at a time, read ahead
// on a thread of its own. What it says must be what the gate says on the same frames read whole
// into memory, number for number; its reading must check what read_frames checks, name the frame
// that fails, and learn the frames' precision from all of them; and the memory it asks for must
// not depend on the frame count.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/gate/render.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/io/frame_source.hpp"
#include "swell/validation/io/half.hpp"
#include "half_rounding.hpp"
#include "gate_cases.hpp"
#include "test_engine.hpp"

namespace {

namespace fs = std::filesystem;
using swell::InvalidInput;
using swell::reference::Field;
using swell::reference::FrameSequence;
using swell::reference::Grid;
using swell::reference::OceanCase;
using swell::validation::CaseFile;
using swell::validation::FileFrameSource;
using swell::validation::FrameFormat;
using swell::validation::GateOptions;

OceanCase small_case(int frames = 8) { return swell::test::small_gate_case(frames); }

// A report's JSON without what differs from run to run (times) and the case's path.
nlohmann::json comparable(const swell::validation::GateReport& report) {
  nlohmann::json json = swell::validation::gate_json(report);
  for (const char* key : {"seconds", "read_seconds", "case"}) json.erase(key);
  return json;
}

class StreamedGate : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("swell_streamed_gate_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `frames` of `c` written into dir_/name with its case.toml; returns the case file's path.
  fs::path write(const std::string& name, const CaseFile& case_file, const FrameSequence& frames,
                 FrameFormat format, bool float64 = false) {
    swell::validation::FrameWriteOptions options;
    options.format = format;
    options.float64 = float64;
    CaseFile out = case_file;
    out.input = swell::validation::write_frames(dir_ / name, frames, options);
    swell::validation::write_case_file(dir_ / name / "case.toml", out);
    return dir_ / name / "case.toml";
  }

  // The gate streaming the files against the gate on the same files read whole.
  void expect_same_reports(const fs::path& case_path) {
    const CaseFile read_back = swell::validation::read_case_file(case_path);
    for (int threads : {1, 2}) {
      SCOPED_TRACE(threads);
      GateOptions options;
      options.threads = threads;
      const auto in_memory =
          swell::validation::run_gate(read_back, swell::validation::read_frames(read_back), options);
      const auto streamed = swell::validation::run_gate(case_path, options);
      EXPECT_EQ(comparable(streamed).dump(1), comparable(in_memory).dump(1));
      EXPECT_GT(streamed.read_seconds, 0);
    }
  }

  fs::path dir_;
};

// Number for number (JSON renders every double to the last bit), on float32 EXR with six
// fields, float64 .npy, a lattice's .npy and half EXR: each sum over the frames is added to in
// frame order, as the whole series was summed.
TEST_F(StreamedGate, ReportsEqualTheInMemoryGateNumberForNumber) {
  const OceanCase grid = small_case(6);
  CaseFile grid_case;
  grid_case.ocean = grid;
  const FrameSequence frames = swell::test::render_surface(grid);
  expect_same_reports(write("exr", grid_case, frames, FrameFormat::exr));
  expect_same_reports(write("npy64", grid_case, frames, FrameFormat::npy, true));

  const CaseFile lattice_case = swell::validation::parse_case_toml(R"(
[sampling]
kind = "lattice"
points = 4181
generator = [1, 2584]
[grid]
length = 400.0
[time]
dt = 0.5
frames = 5
[spectrum]
model = "jonswap"
hs = 3.0
tp = 8.0
[spreading]
model = "cos2s"
s = 10.0
wind_dir_deg = 30.0
[synthesis]
choppiness = 0.8
seed = 7
)", dir_ / "lattice.toml");
  expect_same_reports(write("lattice", lattice_case, swell::test::render_surface(lattice_case.ocean),
                            FrameFormat::npy));
}

// Frame 0 says "half" (every value a half, in a float file); frame 2 does not. The gate then
// judges every frame as float32 — as read_frames, which sees all frames first, does — and no
// note says half.
TEST_F(StreamedGate, PrecisionIsThatOfEveryFrameNotFrameZeros) {
  const OceanCase c = small_case(4);
  CaseFile case_file;
  case_file.ocean = c;
  FrameSequence frames = swell::test::render_surface(c);
  for (auto& [field, values] : frames.frames[0].fields) {
    for (double& v : values) v = swell::test::to_half(v, false);
  }
  const fs::path path = write("halves_then_floats", case_file, frames, FrameFormat::npy);
  const CaseFile read_back = swell::validation::read_case_file(path);
  const FileFrameSource source(read_back);
  EXPECT_EQ(source.precision().storage_roundoff, swell::validation::kHalfUlp);  // frame 0 alone
  EXPECT_FALSE(source.precision_final());
  const auto report = swell::validation::run_gate(path, GateOptions{});
  EXPECT_EQ(report.storage_roundoff, 0);
  EXPECT_EQ(report.unit_roundoff, 0x1p-24);
  for (const auto& note : report.notes) EXPECT_EQ(note.find("half"), std::string::npos) << note;
  expect_same_reports(path);
}

// The dispersion pass reads each frame's transform back from a temporary file; where none can
// be made (TMPDIR missing), it reads and transforms the frames again, with the same report.
TEST_F(StreamedGate, WithoutATemporaryFileTheFramesAreReadAgain) {
  const OceanCase c = small_case(6);
  CaseFile case_file;
  case_file.ocean = c;
  const fs::path path = write("exr", case_file, swell::test::render_surface(c), FrameFormat::exr);
  const CaseFile read_back = swell::validation::read_case_file(path);
  const auto in_memory = swell::validation::run_gate(read_back, swell::validation::read_frames(read_back),
                                                     GateOptions{});
  const char* previous = std::getenv("TMPDIR");
  const std::string kept = previous ? previous : "";
  ::setenv("TMPDIR", (dir_ / "no_such_directory").c_str(), 1);
  const auto streamed = swell::validation::run_gate(path, GateOptions{});
  if (previous) ::setenv("TMPDIR", kept.c_str(), 1); else ::unsetenv("TMPDIR");
  EXPECT_EQ(comparable(streamed).dump(1), comparable(in_memory).dump(1));
}

// Each frame as read_frames reads it (values, times, precision), in order, and any one again.
TEST_F(StreamedGate, TheSourceHandsOverEveryFrameAsReadFramesReadsIt) {
  const OceanCase c = small_case(5);
  CaseFile case_file;
  case_file.ocean = c;
  const fs::path path = write("exr", case_file, swell::test::render_surface(c), FrameFormat::exr);
  const CaseFile read_back = swell::validation::read_case_file(path);
  const FrameSequence whole = swell::validation::read_frames(read_back);
  const FileFrameSource source(read_back);
  ASSERT_EQ(source.size(), 5u);
  std::vector<std::size_t> order;
  source.stream({}, [&](std::size_t f, const swell::reference::FieldFrame& frame) {
    order.push_back(f);
    EXPECT_EQ(frame.time, whole.frames[f].time);
    EXPECT_EQ(frame.fields, whole.frames[f].fields) << "frame " << f;
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(source.precision_final());
  EXPECT_EQ(source.precision().unit_roundoff, whole.unit_roundoff);
  EXPECT_EQ(source.precision().storage_roundoff, whole.storage_roundoff);
  // Heights only, and frame 3 alone.
  int streamed = 0;
  source.stream([](int, Field field) { return field == Field::height; },
                [&](std::size_t f, const swell::reference::FieldFrame& frame) {
                  ++streamed;
                  ASSERT_EQ(frame.fields.size(), 1u);
                  EXPECT_EQ(frame.fields.at(Field::height), whole.frames[f].fields.at(Field::height));
                });
  EXPECT_EQ(streamed, 5);
  EXPECT_EQ(source.frame(3)->fields, whole.frames[3].fields);
}

// A frame that cannot be read stops the stream at that frame, with read_frames' message; the
// frames before it were visited, none after, and the reading thread is gone.
TEST_F(StreamedGate, AFrameThatCannotBeReadStopsTheStreamWithItsName) {
  const OceanCase c = small_case(6);
  CaseFile case_file;
  case_file.ocean = c;
  const fs::path path = write("npy", case_file, swell::test::render_surface(c), FrameFormat::npy);
  fs::remove(path.parent_path() / "frame_0003_h.npy");
  const CaseFile read_back = swell::validation::read_case_file(path);
  const FileFrameSource source(read_back);
  std::vector<std::size_t> visited;
  try {
    source.stream({}, [&](std::size_t f, const swell::reference::FieldFrame&) { visited.push_back(f); });
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("frame_0003_h.npy: missing frame file (frame 3 of 6, height)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(visited, (std::vector<std::size_t>{0, 1, 2}));
  // The gate says the same.
  try {
    (void)swell::validation::run_gate(path, GateOptions{});
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("frame_0003_h.npy: missing frame file"), std::string::npos)
        << e.what();
  }
  // A visitor's own error stops the reading thread too.
  EXPECT_THROW(source.stream({}, [](std::size_t f, const swell::reference::FieldFrame&) {
                 if (f == 1) throw InvalidInput("stop");
               }),
               InvalidInput);
}

// A cascade set's surfaces stream too, each from its own files: the set checks keep sums per
// wave vector (the patch check's residuals in a second pass, the nested check's coarse frames
// read beside the broad band's), and say what the gate on the frames read whole says, number
// for number. An additive set of two cascades with their sum, and a nested pair, fp32 EXR
// written by the synthesizer as `swell synth` writes a set.
TEST_F(StreamedGate, CascadeSetsStreamAndReportAsInMemory) {
  const std::string sea =
      "[time]\ndt = 0.5\nframes = 5\n[spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 8.0\n"
      "gamma = 3.3\n[spreading]\nmodel = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n"
      "[synthesis]\nchoppiness = 0.8\nseed = 11\n";
  const std::vector<std::pair<std::string, std::string>> sets = {
      {"additive", "[cascades]\nrelation = \"additive\"\n"
                   "[[cascade]]\nn = 64\nlength = 1000.0\nband = [0.0, 0.1]\n"
                   "[[cascade]]\nn = 64\nlength = 250.0\nband = [0.1, 0.8]\n"},
      {"nested", "[cascades]\nrelation = \"nested\"\n[[cascade]]\nn = 32\nlength = 1000.0\n"
                 "[[cascade]]\nn = 128\nlength = 1000.0\n"}};
  swell::impls::SynthesizerOptions synthesis;
  synthesis.precision = swell::impls::Precision::f32;
  swell::validation::FrameWriteOptions write;
  write.format = FrameFormat::exr;
  const std::vector<Field> fields = {Field::height, Field::disp_x, Field::disp_y};
  for (const auto& [name, cascades] : sets) {
    SCOPED_TRACE(name);
    const fs::path directory = dir_ / name;
    CaseFile set = swell::validation::parse_case_toml(sea + cascades, directory / "case.toml");
    // Each surface's frames, into its folder: cascadeN/, and sum/ for the additive set.
    auto write_surface = [&](const OceanCase& ocean, const std::string& folder) {
      const swell::impls::Synthesizer synthesizer(ocean, synthesis);
      fs::create_directories(directory / folder);
      for (int f = 0; f < ocean.frames; ++f) {
        auto frame = synthesizer.frame(ocean.time(f));
        std::erase_if(frame.fields, [&](const auto& entry) {
          return std::find(fields.begin(), fields.end(), entry.first) == fields.end();
        });
        swell::validation::write_frame(directory / folder, ocean.grid, frame, f, write);
      }
      auto input = swell::validation::frame_input_spec(fields, write);
      input.files = folder + "/" + input.files;
      return input;
    };
    for (std::size_t c = 0; c < set.cascades.size(); ++c) {
      set.cascades[c].input = write_surface(set.cascade_case(c), "cascade" + std::to_string(c));
    }
    const bool with_sum = name == "additive";
    if (with_sum) set.sum = write_surface(*set.summed_case(), "sum");
    swell::validation::write_case_file(directory / "case.toml", set);

    const CaseFile read_back = swell::validation::read_case_file(directory / "case.toml");
    std::vector<FrameSequence> whole;
    for (std::size_t c = 0; c < read_back.cascades.size(); ++c) {
      CaseFile surface;
      surface.ocean = read_back.cascade_case(c);
      surface.input = read_back.cascades[c].input;
      surface.directory = read_back.directory;
      whole.push_back(swell::validation::read_frames(surface));
    }
    FrameSequence sum;
    if (with_sum) {
      CaseFile surface;
      surface.ocean = *read_back.summed_case();
      surface.input = read_back.sum;
      surface.directory = read_back.directory;
      sum = swell::validation::read_frames(surface);
    }
    for (int threads : {1, 2}) {
      SCOPED_TRACE(threads);
      GateOptions options;
      options.threads = threads;
      const auto in_memory =
          swell::validation::run_cascade_gate(read_back, whole, with_sum ? &sum : nullptr, options);
      const auto streamed = swell::validation::run_gate(directory / "case.toml", options);
      EXPECT_EQ(comparable(streamed).dump(1), comparable(in_memory).dump(1));
      EXPECT_TRUE(streamed.passed()) << swell::validation::gate_json(streamed).dump(1);
      EXPECT_GT(streamed.read_seconds, 0);
      // Every set check ran.
      const auto json = comparable(streamed);
      for (const char* check : with_sum ? std::vector<const char*>{"cascades.energy", "cascades.independence",
                                                                     "cascades.patch", "sum.band.outside"}
                                        : std::vector<const char*>{"cascades.nested"}) {
        bool found = false;
        for (const auto& result : json["checks"]) found = found || result["check"] == check;
        EXPECT_TRUE(found) << check;
      }
    }
  }
}

// What the streamed gate needs does not grow with the frame count: a million frames of 64² are
// not refused for memory (they fail on their first missing file), and a grid whose analysis
// alone exceeds the machine is refused before any file is looked for, with the figure and what
// to reduce.
TEST_F(StreamedGate, OnlyTheGridNeverTheFrameCountMakesACaseTooLarge) {
  CaseFile many;
  many.ocean = small_case(1000000);
  many.input.files = (dir_ / "frame_%07d.npy").string();
  many.input.channels[Field::height] = "h";
  swell::validation::write_case_file(dir_ / "many.toml", many);
  try {
    (void)swell::validation::run_gate(dir_ / "many.toml", GateOptions{});
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("missing frame file (frame 0 of 1000000"), std::string::npos)
        << e.what();
  }

  CaseFile huge;
  huge.ocean = small_case(4);
  huge.ocean.grid = Grid::create(131072, 131072, 4000, 4000);
  huge.input.files = (dir_ / "frame_%04d.exr").string();
  huge.input.channels[Field::height] = "h";
  swell::validation::write_case_file(dir_ / "huge.toml", huge);
  try {
    (void)swell::validation::run_gate(dir_ / "huge.toml", GateOptions{});
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("for the analysis of the 131072×131072 grid"), std::string::npos) << what;
    EXPECT_NE(what.find("whatever the frame count"), std::string::npos) << what;
    EXPECT_NE(what.find("use a smaller grid ([grid] n)"), std::string::npos) << what;
    EXPECT_EQ(what.find("missing"), std::string::npos) << what;
  }
}

// A cascade set whose set checks' sums over every cascade's wave vectors exceed the machine is
// refused before any file is looked for, with the figure; the frame count never decides it.
TEST_F(StreamedGate, ACascadeSetTooLargeForItsSumsIsRefusedBeforeReading) {
  auto set_with = [&](int n, int frames) {
    std::string text = "[time]\ndt = 0.5\nframes = " + std::to_string(frames) +
                       "\n[spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 8.0\n"
                       "[spreading]\nmodel = \"cos2s\"\ns = 10.0\n[cascades]\nrelation = \"independent\"\n";
    for (const char* length : {"4000.0", "1000.0"}) {
      text += "[[cascade]]\nn = " + std::to_string(n) + "\nlength = " + length + "\nfiles = \"" +
              (dir_ / "missing_%04d.exr").string() + "\"\nheight = \"h\"\n";
    }
    return swell::validation::parse_case_toml(text, dir_ / "set.toml");
  };
  try {
    (void)swell::validation::run_gate(set_with(65536, 8), GateOptions{});
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("for a cascade set"), std::string::npos) << what;
    EXPECT_NE(what.find("whatever the frame counts"), std::string::npos) << what;
    EXPECT_EQ(what.find("missing"), std::string::npos) << what;
  }
  // A million frames of two 64² cascades: not refused for memory, but for their first file.
  try {
    (void)swell::validation::run_gate(set_with(64, 1000000), GateOptions{});
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("missing frame file (frame 0 of 1000000"), std::string::npos) << e.what();
  }
}

}  // namespace
