// Frame I/O against OpenImageIO, an implementation of EXR, TIFF and PNG that swell's own
// readers and writers do not share: swell's EXR and PNG frames as OpenImageIO reads them, and
// files OpenImageIO writes (foreign TIFF channels, half EXR, integer TIFF and PNG) as swell
// reads them. The only test program besides exr_scanlines_test.cpp's that links OpenImageIO.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "io/frame_io_test_support.hpp"

namespace {

using namespace swell::test;

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

// Half channels are half storage (docs/conventions.md §2.3): float32 arithmetic, one ulp (2⁻¹⁰)
// per stored value.
TEST_F(FrameIo, HalfExrChannelsAreReadAsHalfStorage) {
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
  EXPECT_EQ(back.unit_roundoff, 0x1p-24);
  EXPECT_EQ(back.storage_roundoff, 0x1p-10);
  EXPECT_EQ(back.frames[0].fields.at(Field::height), std::vector<double>(values.begin(), values.end()));
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

}  // namespace
