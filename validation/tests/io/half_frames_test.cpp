// Frames stored in half precision (docs/conventions.md, storage precision): float16 .npy read
// exactly; float frames whose every value is a half detected as half; [input] precision declared,
// and refused where the files cannot hold it. What the gate's exact checks then allow is tested
// with the gate (gate_catalogue_test.cpp, HalfPrecision).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "half_rounding.hpp"
#include "io/frame_io_test_support.hpp"
#include "swell/validation/io/half.hpp"
#include "swell/validation/io/npy.hpp"

namespace {

using namespace swell::test;
using swell::validation::is_half_value;
using swell::validation::NpyArray;

// The 16 bits of a value that is exactly a half (an independent encoder: the reader decodes).
std::uint16_t half_bits(double v) {
  const std::uint16_t sign = std::signbit(v) ? 0x8000 : 0;
  const double a = std::abs(v);
  if (a == 0) return sign;
  if (a < 0x1p-14) return std::uint16_t(sign | std::uint16_t(std::ldexp(a, 24)));
  int exponent = 0;
  const double significand = std::frexp(a, &exponent);  // [0.5, 1)
  const int biased = exponent - 1 + 15;
  const int mantissa = int(std::ldexp(significand, 11)) - 1024;
  return std::uint16_t(sign | (biased << 10) | mantissa);
}

void write_half_npy(const fs::path& path, const std::vector<double>& values) {
  NpyArray array;
  array.dtype = NpyArray::Dtype::f2;
  array.shape = {std::size_t(kNy), std::size_t(kNx)};
  for (double v : values) {
    const std::uint16_t bits = half_bits(v);
    array.data.push_back(static_cast<unsigned char>(bits & 0xff));
    array.data.push_back(static_cast<unsigned char>(bits >> 8));
  }
  swell::validation::write_npy(path, array);
}

FrameSequence half_sequence() {
  auto frames = make_sequence(kSome, true, 11);
  for (auto& frame : frames.frames) {
    for (auto& [field, values] : frame.fields) {
      for (double& v : values) v = swell::test::to_half(v / 4, true);  // |v| < 10⁶/4, within a half's range
    }
  }
  return frames;
}

TEST(HalfValues, TheTestAndTheDecoderAgreeOnEveryHalf) {
  int halves = 0;
  for (std::uint32_t bits = 0; bits < 0x10000; ++bits) {
    const double v = swell::validation::half_bits_to_double(std::uint16_t(bits));
    if (!std::isfinite(v)) continue;
    EXPECT_TRUE(is_half_value(v)) << bits;
    if (v != 0) {
      EXPECT_EQ(half_bits(v), bits) << v;
    }
    ++halves;
  }
  EXPECT_EQ(halves, 0x10000 - 2 * 1024);  // less ±infinity and the NaNs
  EXPECT_EQ(swell::validation::half_bits_to_double(0x3c00), 1.0);
  EXPECT_EQ(swell::validation::half_bits_to_double(0x7bff), 65504.0);
  EXPECT_EQ(swell::validation::half_bits_to_double(0x0001), 0x1p-24);
  EXPECT_FALSE(is_half_value(1.0 + 0x1p-11));
  EXPECT_FALSE(is_half_value(65520.0));
  EXPECT_FALSE(is_half_value(0x1p-25));
  EXPECT_TRUE(is_half_value(-0x1p-24 * 3));
}

TEST_F(FrameIo, Float16NpyIsReadExactlyAsHalfStorage) {
  const auto frames = half_sequence();
  InputSpec spec = swell::validation::frame_input_spec(kSome, {FrameFormat::npy, false});
  for (int f = 0; f < kFrames; ++f) {
    for (const auto& [field, values] : frames.frames[f].fields) {
      write_half_npy(dir_ / swell::validation::frame_file_name(
                                "frame_%04d_" + spec.channels.at(field) + ".npy", f),
                     values);
    }
  }
  EXPECT_EQ(swell::validation::read_npy(dir_ / "frame_0001_h.npy").dtype, NpyArray::Dtype::f2);
  const auto back = read_frames(case_for(dir_, spec));
  expect_bit_exact(frames, back);
  EXPECT_EQ(back.unit_roundoff, 0x1p-24);  // float32 arithmetic
  EXPECT_EQ(back.storage_roundoff, 0x1p-10);  // one ulp of a half
}

TEST_F(FrameIo, FloatFramesOfHalvesAreDetectedAsHalf) {
  const auto halves = half_sequence();
  const InputSpec spec = write_frames(dir_ / "halves", halves, {FrameFormat::exr, false});
  const auto back = read_frames(case_for(dir_ / "halves", spec));
  EXPECT_EQ(back.storage_roundoff, 0x1p-10);
  EXPECT_EQ(back.unit_roundoff, 0x1p-24);
  // Ordinary float frames are not.
  const auto floats = make_sequence(kSome, true, 11);
  write_frames(dir_ / "floats", floats, {FrameFormat::exr, false});
  const auto plain = read_frames(case_for(dir_ / "floats", spec));
  EXPECT_EQ(plain.storage_roundoff, 0.0);
  EXPECT_EQ(plain.unit_roundoff, 0x1p-24);
}

TEST_F(FrameIo, DeclaredPrecisionSetsTheRoundingOrIsRefused) {
  const auto floats = make_sequence(kSome, true, 12);
  const InputSpec spec = write_frames(dir_, floats, {FrameFormat::npy, false});
  auto with = [&](const std::string& precision) {
    auto c = case_for(dir_, spec);
    c.input.precision = precision;
    return c;
  };
  const auto half = read_frames(with("half"));
  EXPECT_EQ(half.storage_roundoff, 0x1p-10);
  EXPECT_EQ(half.unit_roundoff, 0x1p-24);
  EXPECT_EQ(read_frames(with("float")).unit_roundoff, 0x1p-24);
  expect_invalid([&] { (void)read_frames(with("double")); },
                 {"[input] precision = \"double\"", "stored in float"});
  // Doubles declared as float: an engine's float32 arithmetic written out as float64.
  const auto doubles = make_sequence(kSome, false, 13);
  const InputSpec spec64 = write_frames(dir_ / "f64", doubles, {FrameFormat::npy, true});
  auto c = case_for(dir_ / "f64", spec64);
  c.input.precision = "float";
  EXPECT_EQ(read_frames(c).unit_roundoff, 0x1p-24);
  EXPECT_EQ(read_frames(case_for(dir_ / "f64", spec64)).unit_roundoff, 0x1p-53);
}

}  // namespace
