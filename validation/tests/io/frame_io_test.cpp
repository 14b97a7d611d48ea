// Frames on disk: EXR, TIFF, .npy and .raw round trips of a FrameSequence, bit for bit for
// float32 data (and float64/complex for .npy), with the orientation and names the docs promise;
// and every broken input — truncated or corrupt file, missing channel, wrong size, NaN, missing
// or surplus frame — rejected with InvalidInput naming the file and the problem. Files written
// by OpenImageIO itself, and swell's files read by it: frame_io_openimageio_test.cpp.
#include <gtest/gtest.h>

#include <complex>
#include <fstream>
#include <limits>

#include "io/frame_io_test_support.hpp"
#include "swell/validation/io/npy.hpp"

namespace {

using namespace swell::test;
using swell::validation::NpyArray;

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


// ------------------------------------------------------------------ integer images




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
