// Frames on disk: EXR, TIFF, .npy and .raw round trips of a FrameSequence, bit for bit for
// float32 data (and float64/complex for .npy), with the orientation and names the docs promise;
// and every broken input — truncated or corrupt file, missing channel, wrong size, NaN, missing
// or surplus frame — rejected with InvalidInput naming the file and the problem.
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "swell/reference/errors.hpp"
#include "swell/validation/frame_io.hpp"
#include "swell/validation/npy.hpp"

namespace {

namespace fs = std::filesystem;
using swell::InvalidInput;
using swell::reference::Field;
using swell::reference::FieldFrame;
using swell::reference::FrameSequence;
using swell::reference::Grid;
using swell::validation::CaseFile;
using swell::validation::FrameFormat;
using swell::validation::FrameWriteOptions;
using swell::validation::InputSpec;
using swell::validation::NpyArray;
using swell::validation::frame_file_name;
using swell::validation::read_frames;
using swell::validation::write_frames;

// A non-square grid, so that a transposed reader or writer cannot pass.
constexpr int kNx = 7, kNy = 5;
constexpr int kFrames = 3;
constexpr double kT0 = 1.5, kDt = 0.25;

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

// Values exactly representable in float32 (when `float32`), of mixed signs and magnitudes,
// different in every field and frame.
FrameSequence make_sequence(const std::vector<Field>& fields, bool float32, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  FrameSequence s;
  s.grid = {kNx, kNy, 70.0, 50.0};
  for (int f = 0; f < kFrames; ++f) {
    FieldFrame frame;
    frame.time = kT0 + f * kDt;
    for (Field field : fields) {
      std::vector<double> values(kNx * kNy);
      for (auto& v : values) {
        const double x = u(random) * std::pow(10.0, std::floor(6 * u(random)));
        v = float32 ? static_cast<double>(static_cast<float>(x)) : x;
      }
      frame.fields[field] = values;
    }
    s.frames.push_back(frame);
  }
  return s;
}

// The case that reads `frames` from `directory`.
CaseFile case_for(const fs::path& directory, const InputSpec& input, int frames = kFrames) {
  CaseFile c;
  c.ocean.grid = {kNx, kNy, 70.0, 50.0};
  c.ocean.t0 = kT0;
  c.ocean.dt = kDt;
  c.ocean.frames = frames;
  c.ocean.spectrum = {"jonswap", {{"hs", 2.0}, {"tp", 7.0}}, {}};
  c.ocean.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.input = input;
  c.directory = directory;
  return c;
}

void expect_bit_exact(const FrameSequence& want, const FrameSequence& got) {
  ASSERT_EQ(got.frames.size(), want.frames.size());
  EXPECT_EQ(got.grid.nx, want.grid.nx);
  EXPECT_EQ(got.grid.ny, want.grid.ny);
  for (std::size_t f = 0; f < want.frames.size(); ++f) {
    EXPECT_EQ(got.frames[f].time, want.frames[f].time) << "frame " << f;
    ASSERT_EQ(got.frames[f].fields.size(), want.frames[f].fields.size()) << "frame " << f;
    for (const auto& [field, values] : want.frames[f].fields) {
      ASSERT_TRUE(got.frames[f].fields.count(field)) << swell::reference::field_name(field);
      const auto& back = got.frames[f].fields.at(field);
      ASSERT_EQ(back.size(), values.size());
      for (std::size_t k = 0; k < values.size(); ++k) {
        ASSERT_EQ(std::bit_cast<std::uint64_t>(back[k]), std::bit_cast<std::uint64_t>(values[k]))
            << swell::reference::field_name(field) << " frame " << f << " sample (" << k % kNx
            << ", " << k / kNx << "): " << back[k] << " vs " << values[k];
      }
    }
  }
}

// Expects InvalidInput whose message contains every fragment; returns the message.
template <typename F>
std::string expect_invalid(F&& action, const std::vector<std::string>& fragments) {
  try {
    action();
    ADD_FAILURE() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    for (const auto& fragment : fragments) {
      EXPECT_TRUE(contains(message, fragment)) << "'" << fragment << "' not in: " << message;
    }
    return message;
  }
  return "";
}

class FrameIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("swell_frame_io_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

const std::vector<Field> kSome = {Field::height, Field::slope_x, Field::disp_x, Field::jacobian};
const std::vector<Field> kAll(swell::reference::kAllFields.begin(), swell::reference::kAllFields.end());

// ------------------------------------------------------------------ names

TEST(FrameFileName, ExpandsOneIntegerConversionAndInsertsTheSuffix) {
  EXPECT_EQ(frame_file_name("frame_%04d.npy", 3, "h"), "frame_0003_h.npy");
  EXPECT_EQ(frame_file_name("frame_%04d.exr", 12), "frame_0012.exr");
  EXPECT_EQ(frame_file_name("dir.v2/f%d.raw", 12345, "dx"), "dir.v2/f12345_dx.raw");
  EXPECT_EQ(frame_file_name("f%3i.tif", 7), "f  7.tif");
  EXPECT_EQ(frame_file_name("100%%_%u.exr", 2), "100%_2.exr");
  EXPECT_EQ(frame_file_name("still.exr", 5), "still.exr");
  EXPECT_THROW((void)frame_file_name("f_%s.exr", 1), InvalidInput);
  EXPECT_THROW((void)frame_file_name("f_%d_%d.exr", 1), InvalidInput);
  EXPECT_THROW((void)frame_file_name("f_%x.exr", 1), InvalidInput);
  EXPECT_THROW((void)frame_file_name("f_%", 1), InvalidInput);
}

// ------------------------------------------------------------------ round trips

TEST_F(FrameIo, ExrRoundTripIsBitExactForFloat32) {
  const auto frames = make_sequence(kAll, true, 1);
  const InputSpec spec = write_frames(dir_, frames, {FrameFormat::exr, false});
  EXPECT_EQ(spec.files, "frame_%04d.exr");
  EXPECT_EQ(spec.channels.at(Field::height), "h");
  EXPECT_EQ(spec.channels.at(Field::jacobian), "J");
  EXPECT_EQ(spec.channels.size(), 6u);
  for (int f = 0; f < kFrames; ++f) EXPECT_TRUE(fs::exists(dir_ / frame_file_name("frame_%04d.exr", f)));
  const FrameSequence back = read_frames(case_for(dir_, spec));
  expect_bit_exact(frames, back);
  EXPECT_EQ(back.unit_roundoff, 0x1p-24);
}

TEST_F(FrameIo, ExrHoldsNamedFloatChannelsWithRowJAsScanlineJ) {
  const auto frames = make_sequence(kSome, true, 2);
  write_frames(dir_, frames, {FrameFormat::exr, false});
  auto in = OIIO::ImageInput::open(file("frame_0001.exr"));
  ASSERT_TRUE(in) << OIIO::geterror();
  const auto& spec = in->spec();
  EXPECT_EQ(spec.width, kNx);
  EXPECT_EQ(spec.height, kNy);
  std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"J", "dx", "h", "sx"}));
  const int h = spec.channelindex("h");
  ASSERT_GE(h, 0);
  EXPECT_EQ(spec.channelformat(h), OIIO::TypeDesc::FLOAT);
  std::vector<float> pixels(kNx * kNy);
  ASSERT_TRUE(in->read_image(0, 0, h, h + 1, OIIO::TypeDesc::FLOAT, pixels.data()));
  const auto& want = frames.frames[1].fields.at(Field::height);
  for (int j = 0; j < kNy; ++j) {
    for (int i = 0; i < kNx; ++i) {
      ASSERT_EQ(pixels[j * kNx + i], static_cast<float>(want[j * kNx + i])) << i << ", " << j;
    }
  }
}

TEST_F(FrameIo, TiffRoundTripIsBitExactAndKeepsChannelNames) {
  const auto frames = make_sequence(kSome, true, 3);
  const InputSpec spec = write_frames(dir_, frames, {FrameFormat::tiff, false});
  EXPECT_EQ(spec.files, "frame_%04d.tif");
  const FrameSequence back = read_frames(case_for(dir_, spec));
  expect_bit_exact(frames, back);
  EXPECT_EQ(back.unit_roundoff, 0x1p-24);

  // A subset of the channels, by name, in any order.
  InputSpec subset = spec;
  subset.channels = {{Field::jacobian, "J"}, {Field::slope_x, "sx"}};
  const FrameSequence part = read_frames(case_for(dir_, subset));
  EXPECT_EQ(part.frames[2].fields.size(), 2u);
  EXPECT_EQ(part.frames[2].fields.at(Field::jacobian), frames.frames[2].fields.at(Field::jacobian));
  EXPECT_EQ(part.frames[2].fields.at(Field::slope_x), frames.frames[2].fields.at(Field::slope_x));
}

// A TIFF from another writer has no channel names: fields go by position in swell's order
// (h, sx, sy, dx, dy, J among those listed), or by OpenImageIO's generic names (R, G, B, …).
TEST_F(FrameIo, ForeignTiffChannelsByPositionOrByGenericName) {
  std::vector<std::vector<float>> planes(2, std::vector<float>(kNx * kNy));
  for (int k = 0; k < kNx * kNy; ++k) {
    planes[0][k] = 0.5f * k;
    planes[1][k] = -0.25f * k - 1;
  }
  auto out = OIIO::ImageOutput::create(file("foreign_0.tif"));
  OIIO::ImageSpec spec(kNx, kNy, 2, OIIO::TypeDesc::FLOAT);
  spec.alpha_channel = -1;
  ASSERT_TRUE(out->open(file("foreign_0.tif"), spec));
  std::vector<float> interleaved;
  for (int k = 0; k < kNx * kNy; ++k) {
    interleaved.push_back(planes[0][k]);
    interleaved.push_back(planes[1][k]);
  }
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, interleaved.data()));
  out->close();

  InputSpec input;
  input.files = "foreign_%d.tif";
  input.channels = {{Field::disp_y, "my_dy"}, {Field::height, "my_h"}};  // names the file lacks
  auto back = read_frames(case_for(dir_, input, 1));
  EXPECT_EQ(back.frames[0].fields.at(Field::height), std::vector<double>(planes[0].begin(), planes[0].end()));
  EXPECT_EQ(back.frames[0].fields.at(Field::disp_y), std::vector<double>(planes[1].begin(), planes[1].end()));

  input.channels = {{Field::height, "G"}};  // OpenImageIO's name of the second channel
  back = read_frames(case_for(dir_, input, 1));
  EXPECT_EQ(back.frames[0].fields.at(Field::height), std::vector<double>(planes[1].begin(), planes[1].end()));

  // Three fields for two channels: no positional guess.
  input.channels = {{Field::height, "a"}, {Field::disp_x, "b"}, {Field::disp_y, "c"}};
  expect_invalid([&] { (void)read_frames(case_for(dir_, input, 1)); },
                 {"foreign_0.tif", "missing channel 'a'", "R, G"});
}

TEST_F(FrameIo, NpyRoundTripFloat32AndFloat64) {
  const auto frames32 = make_sequence(kSome, true, 4);
  const InputSpec spec = write_frames(dir_ / "f32", frames32, {FrameFormat::npy, false});
  EXPECT_EQ(spec.files, "frame_%04d.npy");
  EXPECT_TRUE(fs::exists(dir_ / "f32" / "frame_0002_h.npy"));
  EXPECT_TRUE(fs::exists(dir_ / "f32" / "frame_0000_J.npy"));
  const NpyArray array = swell::validation::read_npy(dir_ / "f32" / "frame_0002_dx.npy");
  EXPECT_EQ(array.dtype, NpyArray::Dtype::f4);
  EXPECT_EQ(array.shape, (std::vector<std::size_t>{kNy, kNx}));
  auto back = read_frames(case_for(dir_ / "f32", spec));
  expect_bit_exact(frames32, back);
  EXPECT_EQ(back.unit_roundoff, 0x1p-24);

  const auto frames64 = make_sequence(kAll, false, 5);  // not representable in float32
  write_frames(dir_ / "f64", frames64, {FrameFormat::npy, true});
  EXPECT_EQ(swell::validation::read_npy(dir_ / "f64" / "frame_0000_sy.npy").dtype, NpyArray::Dtype::f8);
  back = read_frames(case_for(dir_ / "f64", swell::validation::frame_input_spec(kAll, {FrameFormat::npy, true})));
  expect_bit_exact(frames64, back);
  EXPECT_EQ(back.unit_roundoff, 0x1p-53);
}

TEST_F(FrameIo, ComplexNpyFillsTheImaginaryParts) {
  auto frames = make_sequence({Field::height}, true, 6);
  for (auto& frame : frames.frames) {
    auto im = frame.fields.at(Field::height);
    for (auto& v : im) v = -0.5 * v;  // exact in float32
    frame.imaginary[Field::height] = im;
  }
  const InputSpec spec = write_frames(dir_, frames, {FrameFormat::npy, false});
  EXPECT_EQ(swell::validation::read_npy(dir_ / "frame_0001_h.npy").dtype, NpyArray::Dtype::c8);
  const auto back = read_frames(case_for(dir_, spec));
  expect_bit_exact(frames, back);
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_EQ(back.frames[f].imaginary.at(Field::height), frames.frames[f].imaginary.at(Field::height));
  }
  // EXR and TIFF have no room for them.
  expect_invalid([&] { write_frames(dir_ / "exr", frames, {FrameFormat::exr, false}); },
                 {"imaginary", "npy"});
}

void write_raw(const fs::path& path, const std::vector<double>& values, bool float64) {
  std::ofstream out(path, std::ios::binary);
  for (double v : values) {
    if (float64) {
      out.write(reinterpret_cast<const char*>(&v), 8);
    } else {
      const float x = static_cast<float>(v);
      out.write(reinterpret_cast<const char*>(&x), 4);
    }
  }
}

TEST_F(FrameIo, RawRoundTripFloat32AndFloat64) {
  for (const bool float64 : {false, true}) {
    SCOPED_TRACE(float64 ? "float64" : "float32");
    const auto frames = make_sequence({Field::height, Field::disp_y}, !float64, 7);
    const fs::path sub = dir_ / (float64 ? "f64" : "f32");
    fs::create_directories(sub);
    for (int f = 0; f < kFrames; ++f) {
      write_raw(sub / frame_file_name("eta%03d.raw", f, "H"), frames.frames[f].fields.at(Field::height), float64);
      write_raw(sub / frame_file_name("eta%03d.raw", f, "Dy"), frames.frames[f].fields.at(Field::disp_y), float64);
    }
    EXPECT_TRUE(fs::exists(sub / "eta002_Dy.raw"));
    InputSpec input;
    input.files = "eta%03d.raw";
    input.channels = {{Field::height, "H"}, {Field::disp_y, "Dy"}};
    input.raw_type = float64 ? "float64" : "float32";
    const auto back = read_frames(case_for(sub, input));
    expect_bit_exact(frames, back);
    EXPECT_EQ(back.unit_roundoff, float64 ? 0x1p-53 : 0x1p-24);

    // The same bytes read as the other type have the wrong size.
    input.raw_type = float64 ? "float32" : "float64";
    expect_invalid([&] { (void)read_frames(case_for(sub, input)); },
                   {"eta000_", ".raw", "wrong size", float64 ? "280 bytes" : "140 bytes"});
  }
}

TEST_F(FrameIo, HalfExrChannelsSetTheUnitRoundoff) {
  auto out = OIIO::ImageOutput::create(file("half_0000.exr"));
  OIIO::ImageSpec spec(kNx, kNy, 1, OIIO::TypeDesc::HALF);
  spec.channelnames = {"h"};
  ASSERT_TRUE(out->open(file("half_0000.exr"), spec));
  std::vector<float> values(kNx * kNy);
  for (int k = 0; k < kNx * kNy; ++k) values[k] = 0.125f * k - 2;  // exact in half
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
  out->close();
  InputSpec input;
  input.files = "half_%04d.exr";
  input.channels = {{Field::height, "h"}};
  const auto back = read_frames(case_for(dir_, input, 1));
  EXPECT_EQ(back.unit_roundoff, 0x1p-11);
  EXPECT_EQ(back.frames[0].fields.at(Field::height), std::vector<double>(values.begin(), values.end()));
}

TEST_F(FrameIo, PatternOverrideIsRelativeToTheCurrentDirectory) {
  const auto frames = make_sequence({Field::height}, true, 8);
  InputSpec spec = write_frames(dir_ / "elsewhere", frames, {FrameFormat::exr, false});
  CaseFile c = case_for(dir_ / "not_here", spec);
  const auto back = read_frames(c, (dir_ / "elsewhere" / "frame_%04d.exr").string());
  expect_bit_exact(frames, back);
}

// ------------------------------------------------------------------ writer input

TEST_F(FrameIo, WriterRejectsInconsistentFrames) {
  auto frames = make_sequence({Field::height}, true, 9);
  frames.frames[1].fields.at(Field::height).pop_back();
  expect_invalid([&] { write_frames(dir_, frames, {FrameFormat::exr, false}); },
                 {"frame 1", "height", "34 values", "35"});
  frames = make_sequence({Field::height}, true, 9);
  frames.frames[2].fields[Field::slope_x] = frames.frames[2].fields.at(Field::height);
  expect_invalid([&] { write_frames(dir_, frames, {FrameFormat::npy, false}); }, {"frame 2", "same fields"});
  expect_invalid([&] { write_frames(dir_, make_sequence({Field::height}, true, 9), {FrameFormat::exr, true}); },
                 {"float64", "npy"});
  expect_invalid([&] { write_frames(dir_, FrameSequence{}, {FrameFormat::exr, false}); }, {"no frames"});
}

// ------------------------------------------------------------------ broken input

class BrokenFrames : public FrameIo {
 protected:
  void write(FrameFormat format, const std::vector<Field>& fields = kSome) {
    frames_ = make_sequence(fields, true, 10);
    spec_ = write_frames(dir_, frames_, {format, false});
  }
  CaseFile the_case(int frames = kFrames) const { return case_for(dir_, spec_, frames); }
  std::string read_error(const std::vector<std::string>& fragments, int frames = kFrames) {
    return expect_invalid([&] { (void)read_frames(the_case(frames)); }, fragments);
  }

  FrameSequence frames_;
  InputSpec spec_;
};

TEST_F(BrokenFrames, TruncatedExr) {
  write(FrameFormat::exr);
  const fs::path victim = dir_ / "frame_0001.exr";
  fs::resize_file(victim, fs::file_size(victim) - 40);  // the end of the pixel data
  read_error({victim.string(), "cannot read"});
  fs::resize_file(victim, fs::file_size(victim) / 3);  // into the header
  read_error({victim.string(), "cannot read"});
  fs::resize_file(victim, 0);
  read_error({victim.string(), "cannot read"});
}

TEST_F(BrokenFrames, CorruptExrBytes) {
  write(FrameFormat::exr);
  const fs::path victim = dir_ / "frame_0002.exr";
  {
    std::fstream f(victim, std::ios::in | std::ios::out | std::ios::binary);
    f.write("JUNK", 4);  // the magic number
  }
  read_error({victim.string(), "cannot read the image"});
}

TEST_F(FrameIo, CorruptCompressedExrData) {
  // Data that zip compresses well (OpenEXR stores a chunk raw when compression does not help,
  // and raw bytes cannot be told from garbage): a scribble anywhere in the compressed pixel data
  // breaks zlib's checksum or the decompressed size.
  FrameSequence frames;
  frames.grid = {64, 48, 1, 1};
  FieldFrame frame;
  std::vector<double> values(64 * 48);
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = 0.5 * static_cast<double>(k % 16);
  frame.fields = {{Field::height, values}, {Field::disp_x, values}};
  frames.frames = {frame};
  const InputSpec spec = write_frames(dir_, frames, {FrameFormat::exr, false});
  const fs::path victim = dir_ / "frame_0000.exr";
  const auto size = fs::file_size(victim);
  ASSERT_LT(size, 64u * 48u * 8u / 4u) << "the pixel data is expected to compress";
  for (const double where : {0.8, 0.97}) {
    SCOPED_TRACE(where);
    fs::copy_file(victim, dir_ / "frame_0000.good", fs::copy_options::overwrite_existing);
    {
      std::fstream f(victim, std::ios::in | std::ios::out | std::ios::binary);
      f.seekp(static_cast<std::streamoff>(size * where));
      const std::string junk(16, '\xA5');
      f.write(junk.data(), 16);
    }
    CaseFile c = case_for(dir_, spec, 1);
    c.ocean.grid = frames.grid;
    expect_invalid([&] { (void)read_frames(c); }, {victim.string(), "cannot read channel"});
    fs::copy_file(dir_ / "frame_0000.good", victim, fs::copy_options::overwrite_existing);
    EXPECT_NO_THROW((void)read_frames(c));
  }
}

TEST_F(BrokenFrames, TruncatedAndCorruptTiff) {
  write(FrameFormat::tiff);
  const fs::path victim = dir_ / "frame_0001.tif";
  fs::resize_file(victim, fs::file_size(victim) / 2);
  read_error({victim.string(), "cannot read"});
  std::ofstream(dir_ / "frame_0001.tif", std::ios::binary) << "not a tiff at all";
  read_error({victim.string(), "cannot read the image"});
}

TEST_F(BrokenFrames, MissingChannel) {
  write(FrameFormat::exr, {Field::height, Field::disp_x});
  spec_.channels[Field::slope_y] = "sy";
  read_error({"frame_0000.exr", "missing channel 'sy'", "slope_y", "2 channels", "dx", "h"});
}

TEST_F(BrokenFrames, MissingNpyFieldFile) {
  write(FrameFormat::npy, {Field::height});
  spec_.channels[Field::jacobian] = "J";
  read_error({"frame_0000_J.npy", "missing frame file", "frame 0 of 3", "jacobian"});
}

TEST_F(BrokenFrames, WrongSize) {
  write(FrameFormat::exr);
  CaseFile c = the_case();
  c.ocean.grid.nx = kNx + 1;
  expect_invalid([&] { (void)read_frames(c); }, {"frame_0000.exr", "wrong size", "7×5", "8×5"});
  c.ocean.grid = {kNy, kNx, 1, 1};  // transposed
  expect_invalid([&] { (void)read_frames(c); }, {"frame_0000.exr", "wrong size", "7×5", "5×7"});
}

TEST_F(BrokenFrames, WrongNpyShape) {
  write(FrameFormat::npy, {Field::height});
  const auto values = frames_.frames[1].fields.at(Field::height);
  std::vector<float> transposed(values.begin(), values.end());
  swell::validation::write_npy(dir_ / "frame_0001_h.npy",
                               NpyArray::from_values<float>({kNx, kNy}, transposed));
  read_error({"frame_0001_h.npy", "wrong shape (7, 5)", "(5, 7)"});
}

TEST_F(BrokenFrames, TruncatedNpy) {
  write(FrameFormat::npy, {Field::height});
  const fs::path victim = dir_ / "frame_0002_h.npy";
  fs::resize_file(victim, fs::file_size(victim) - 4);
  read_error({victim.string(), "truncated"});
}

TEST_F(BrokenFrames, NaNInExrNamesFileFieldAndSample) {
  frames_ = make_sequence(kSome, true, 11);
  frames_.frames[1].fields.at(Field::disp_x)[2 * kNx + 3] = std::numeric_limits<double>::quiet_NaN();
  frames_.frames[1].fields.at(Field::disp_x)[4 * kNx + 6] = std::numeric_limits<double>::quiet_NaN();
  spec_ = write_frames(dir_, frames_, {FrameFormat::exr, false});
  read_error({"frame_0001.exr", "disp_x (dx)", "NaN at (i, j) = (3, 2)", "2 non-finite values"});
}

TEST_F(BrokenFrames, InfinityInNpyAndRaw) {
  frames_ = make_sequence({Field::height}, true, 12);
  frames_.frames[2].fields.at(Field::height)[kNx * kNy - 1] = -std::numeric_limits<double>::infinity();
  spec_ = write_frames(dir_, frames_, {FrameFormat::npy, false});
  read_error({"frame_0002_h.npy", "height", "-Inf at (i, j) = (6, 4)"});

  write_raw(dir_ / "r_0_h.raw", frames_.frames[2].fields.at(Field::height), false);
  spec_.files = "r_%d.raw";
  read_error({"r_0_h.raw", "-Inf at (i, j) = (6, 4)"}, 1);
}

TEST_F(BrokenFrames, MissingFrameFile) {
  write(FrameFormat::exr);
  fs::remove(dir_ / "frame_0002.exr");
  read_error({"frame_0002.exr", "missing frame file", "frame 2 of 3"});
}

TEST_F(BrokenFrames, MoreFramesOnDiskThanTheCaseSays) {
  write(FrameFormat::tiff);
  read_error({"frame_0002.tif", "beyond", "frames = 2"}, 2);
}

TEST_F(BrokenFrames, FramePatternProblems) {
  write(FrameFormat::exr);
  spec_.files = "frame_%04s.exr";
  read_error({"[input] files", "unsupported conversion"});
  spec_.files = "frame.jpg";
  read_error({"[input] files", ".jpg"});
  spec_.files = "frame_0000.exr";
  read_error({"no frame number", "3 frames"});
  spec_.files = "";
  read_error({"no frames to read"});
  spec_.files = "frame_%04d.exr";
  spec_.channels.clear();
  read_error({"names no field"});
}

// Integer pixels carry no unit: without [input] value_range they are refused; with it they
// read as low + (high − low)·p/65535. A float channel refuses a value range, and integer types
// other than 8- and 16-bit unsigned are refused.
TEST_F(BrokenFrames, IntegerImagesNeedAValueRangeAndFloatChannelsRefuseOne) {
  auto write_integer_tiff = [&](const std::string& name, OIIO::TypeDesc type) {
    auto out = OIIO::ImageOutput::create(file(name));
    OIIO::ImageSpec spec(kNx, kNy, 1, type);
    ASSERT_TRUE(out->open(file(name), spec));
    std::vector<std::uint16_t> values(kNx * kNy, 7);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, values.data()));
    out->close();
  };
  write_integer_tiff("int_0.tif", OIIO::TypeDesc::UINT16);
  spec_.files = "int_%d.tif";
  spec_.channels = {{Field::height, "Y"}};
  read_error({"int_0.tif", "channel 'Y' for height", "16-bit integers", "value_range"}, 1);

  spec_.value_ranges[Field::height] = {-1.0, 2.0};
  const auto back = read_frames(the_case(1));
  // p/65535 passes through float (OpenImageIO's normalized pixel): 2⁻²⁴ relative, far below
  // the quantization step 3/65535.
  for (double v : back.frames[0].fields.at(Field::height)) ASSERT_NEAR(v, -1.0 + 3.0 * 7 / 65535, 1e-6);

  write_integer_tiff("wide_0.tif", OIIO::TypeDesc::INT32);
  spec_.files = "wide_%d.tif";
  read_error({"wide_0.tif", "stores int values", "8- or 16-bit unsigned"}, 1);

  write(FrameFormat::exr);
  spec_.value_ranges[Field::disp_x] = {-1.0, 1.0};
  read_error({"frame_0000.exr", "channel 'dx' for disp_x", "need no [input] value_range"});
  spec_.value_ranges.clear();
  spec_.value_ranges[Field::slope_y] = {-1.0, 1.0};  // a field the input does not provide
  read_error({"value_range", "slope_y", "does not provide"});
}

// ------------------------------------------------------------------ integer images

// Values of a few metres, as an engine's heights and displacements are.
FrameSequence make_metres(const std::vector<Field>& fields, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-3, 3);
  FrameSequence s = make_sequence(fields, false, seed);
  for (auto& frame : s.frames) {
    for (auto& [field, values] : frame.fields) {
      for (auto& v : values) v = u(random);
    }
  }
  return s;
}

// PNG frames hold 16-bit pixels standing for values through the value range: every value
// comes back within half a quantization step q = (high − low)/65535 (and float rounding) of the
// value written, on
// the channels R, G, B in swell's field order; the unit roundoff is the quantization's,
// q/√(12 mean v²) (largest over fields and frames).
TEST_F(FrameIo, PngRoundTripIsWithinHalfAQuantizationStep) {
  const auto frames = make_metres({Field::disp_y, Field::height, Field::disp_x}, 21);
  FrameWriteOptions write;
  write.format = FrameFormat::png;
  write.png_range = {-4.0, 4.0};
  const InputSpec spec = write_frames(dir_, frames, write);
  EXPECT_EQ(spec.files, "frame_%04d.png");
  EXPECT_EQ(spec.channels.at(Field::height), "R");
  EXPECT_EQ(spec.channels.at(Field::disp_x), "G");
  EXPECT_EQ(spec.channels.at(Field::disp_y), "B");
  ASSERT_EQ(spec.value_ranges.size(), 3u);
  for (const auto& [field, range] : spec.value_ranges) {
    EXPECT_EQ(range, (swell::validation::IntegerRange{-4.0, 4.0}));
  }
  auto in = OIIO::ImageInput::open(file("frame_0001.png"));
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT16);
  EXPECT_EQ(in->spec().nchannels, 3);
  in->close();

  const auto back = read_frames(case_for(dir_, spec));
  const double step = 8.0 / 65535;
  double largest_error = 0, roundoff = 0;
  for (int f = 0; f < kFrames; ++f) {
    for (const auto& [field, want] : frames.frames[f].fields) {
      const auto& got = back.frames[f].fields.at(field);
      double sum = 0;
      for (std::size_t k = 0; k < want.size(); ++k) {
        largest_error = std::max(largest_error, std::abs(got[k] - want[k]));
        sum += got[k] * got[k];
      }
      roundoff = std::max(roundoff, step / std::sqrt(12 * sum / double(got.size())));
    }
  }
  // Half a step, plus the pixel's pass through float as p/65535 (2⁻²⁴ relative) times the width.
  EXPECT_LE(largest_error, step / 2 + 8.0 * 0x1p-24);
  EXPECT_GT(largest_error, step / 100);  // quantized, not stored exactly
  EXPECT_NEAR(back.unit_roundoff, roundoff, 1e-12 * roundoff);
}

// An 8-bit grey PNG from another writer: one channel, Y, pixel p ↦ low + (high − low)·p/255,
// its channel found by name or, alone, by position.
TEST_F(FrameIo, EightBitGreyPngThroughTheValueRange) {
  std::vector<std::uint8_t> pixels(kNx * kNy);
  for (int k = 0; k < kNx * kNy; ++k) pixels[k] = static_cast<std::uint8_t>(37 * k % 256);
  auto out = OIIO::ImageOutput::create(file("grey_0.png"));
  ASSERT_TRUE(out->open(file("grey_0.png"), OIIO::ImageSpec(kNx, kNy, 1, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
  for (const std::string channel : {"Y", "eta"}) {
    SCOPED_TRACE(channel);
    InputSpec input;
    input.files = "grey_%d.png";
    input.channels = {{Field::height, channel}};
    input.value_ranges = {{Field::height, {-2.0, 3.0}}};
    const auto back = read_frames(case_for(dir_, input, 1));
    const auto& h = back.frames[0].fields.at(Field::height);
    for (int k = 0; k < kNx * kNy; ++k) ASSERT_NEAR(h[k], -2.0 + 5.0 * pixels[k] / 255, 1e-6) << k;
  }
}

TEST_F(FrameIo, PngWritingRefusesWhatItCannotStore) {
  const auto frames = make_metres({Field::height, Field::disp_x}, 22);
  FrameWriteOptions write;
  write.format = FrameFormat::png;
  expect_invalid([&] { write_frames(dir_, frames, write); }, {"value range", "low < high"});
  write.png_range = {-1.0, 1.0};  // the values reach ±3 m: never clipped
  expect_invalid([&] { write_frames(dir_, frames, write); },
                 {"frame_0000.png", "outside the PNG value range [-1, 1]"});
  write.png_range = {-4.0, 4.0};
  expect_invalid([&] { write_frames(dir_, make_metres(kAll, 23), write); }, {"at most 4 channels"});
}

// ------------------------------------------------------------------ fields read but not kept

// read_frames' filter drops fields after reading them: what it keeps is bit-exact, and a
// non-finite value in a field it drops is still reported, naming the file and the field.
TEST_F(BrokenFrames, FieldsNotKeptAreStillReadAndChecked) {
  for (FrameFormat format : {FrameFormat::exr, FrameFormat::npy}) {
    SCOPED_TRACE(swell::validation::to_string(format));
    fs::remove_all(dir_);
    write(format);
    const auto keep = [](int frame, Field field) { return frame != 1 || field == Field::height; };
    const auto back = read_frames(the_case(), "", keep);
    EXPECT_EQ(back.frames[0].fields.size(), kSome.size());
    EXPECT_EQ(back.frames[1].fields.size(), 1u);
    EXPECT_EQ(back.frames[1].fields.at(Field::height), frames_.frames[1].fields.at(Field::height));
    EXPECT_EQ(back.frames[2].fields.at(Field::jacobian), frames_.frames[2].fields.at(Field::jacobian));

    frames_.frames[1].fields.at(Field::disp_x)[3 * kNx + 5] = std::numeric_limits<double>::infinity();
    spec_ = write_frames(dir_, frames_, {format, false});
    expect_invalid([&] { (void)read_frames(the_case(), "", keep); },
                   {format == FrameFormat::exr ? "frame_0001.exr" : "frame_0001_dx.npy", "disp_x",
                    "+Inf at (i, j) = (5, 3)", "1 non-finite value in all"});
  }
}

}  // namespace
