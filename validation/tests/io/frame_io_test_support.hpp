#pragma once
// What the frame I/O tests share (frame_io_test.cpp, and frame_io_openimageio_test.cpp, whose
// foreign files OpenImageIO writes): frame sequences of known values, the case that reads them,
// bit-exact comparison, and a scratch directory per test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "swell/reference/errors.hpp"
#include "swell/validation/io/frame_io.hpp"

namespace swell::test {

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
using swell::validation::frame_file_name;
using swell::validation::read_frames;
using swell::validation::write_frames;

// A non-square grid, so that a transposed reader or writer cannot pass.
constexpr int kNx = 7, kNy = 5;
constexpr int kFrames = 3;
constexpr double kT0 = 1.5, kDt = 0.25;

inline bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

// Values exactly representable in float32 (when `float32`), of mixed signs and magnitudes,
// different in every field and frame.
inline FrameSequence make_sequence(const std::vector<Field>& fields, bool float32, unsigned seed) {
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
inline CaseFile case_for(const fs::path& directory, const InputSpec& input, int frames = kFrames) {
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

inline void expect_bit_exact(const FrameSequence& want, const FrameSequence& got) {
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

inline const std::vector<Field> kSome = {Field::height, Field::slope_x, Field::disp_x, Field::jacobian};
inline const std::vector<Field> kAll(swell::reference::kAllFields.begin(), swell::reference::kAllFields.end());


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

// Values of a few metres, as an engine's heights and displacements are.
inline FrameSequence make_metres(const std::vector<Field>& fields, unsigned seed) {
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

}  // namespace swell::test
