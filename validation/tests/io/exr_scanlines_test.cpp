// The direct scanline EXR reader (validation/src/io/exr_scanlines.cpp) against OpenImageIO's, the
// reader it stands in for: the same floats, bit for bit, over every file it takes (raw, ZIPS,
// ZIP; float and half channels; sizes whose last block is partial; a data window off the
// origin; channels asked in any order), and false — never a crash or a partial answer taken as
// whole — for every file it leaves to OpenImageIO (other compressions, tiles, uint channels,
// missing channels, wrong size) and every broken one (truncated, corrupt zlib data). The header
// OpenEXRCore reads against OpenImageIO's, and swell's EXR writer (exr_scanlines_write.cpp) as
// OpenImageIO reads its files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "../../src/io/exr_scanlines.hpp"
#include "swell/reference/errors.hpp"

namespace {

namespace fs = std::filesystem;
using swell::validation::detail::ExrScratch;
using swell::validation::detail::apply_zip_filters;
using swell::validation::detail::read_exr_header;
using swell::validation::detail::SampleType;
using swell::validation::detail::undo_zip_filters;
using swell::validation::detail::write_exr_scanlines;

// The reader's lines, interleaved as OpenImageIO's read_image lays them out (pixel p's value of
// channels[k] at pixels[p × channels.size() + k]); a line delivered twice or out of order fails.
bool read_exr_scanlines(const std::string& path, const std::vector<std::string>& channels,
                        int width, int height, float* pixels, ExrScratch& scratch) {
  const std::size_t span = channels.size();
  std::vector<std::size_t> next_row(span, 0);
  const bool read = swell::validation::detail::read_exr_scanlines(
      path, channels, width, height,
      [&](std::size_t slot, std::size_t row, const float* values) {
        EXPECT_LT(slot, span);
        EXPECT_EQ(row, next_row[slot]++) << channels[slot];
        for (int x = 0; x < width; ++x) pixels[(row * width + x) * span + slot] = values[x];
      },
      scratch);
  if (read) {
    for (std::size_t slot = 0; slot < span; ++slot) EXPECT_EQ(next_row[slot], std::size_t(height));
  }
  return read;
}

struct ExrFile {
  std::string compression = "zip";
  OIIO::TypeDesc type = OIIO::TypeDesc::FLOAT;
  int width = 37, height = 19;  // 19 rows: ZIP's 16-row blocks end with a partial one
  int x = 0, y = 0;             // the data window's origin
  int tile = 0;                 // > 0: tiled
  std::vector<std::string> channels = {"h", "sx", "sy", "dx", "dy", "J"};
  bool smooth = false;          // slowly varying values, which ZIP compresses well
};

class ExrScanlines : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() / ("swell_exr_scanlines_" + std::to_string(getpid()));
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  // Writes `file` with values of every kind a float channel holds (normal, subnormal, ±0,
  // large, and for the raw bits, NaN and ±∞ too) and returns its path.
  std::string write(const ExrFile& file, const std::string& name) {
    const std::string path = (directory_ / name).string();
    OIIO::ImageSpec spec(file.width, file.height, int(file.channels.size()), file.type);
    spec.x = file.x;
    spec.y = file.y;
    spec.full_x = file.x;
    spec.full_y = file.y;
    spec.channelnames = file.channels;
    spec.attribute("compression", file.compression);
    if (file.tile > 0) {
      spec.tile_width = file.tile;
      spec.tile_height = file.tile;
    }
    std::mt19937_64 random(std::hash<std::string>{}(name));
    std::normal_distribution<float> normal(0.0f, 3.0f);
    std::vector<float> pixels(std::size_t(file.width) * file.height * file.channels.size());
    const float specials[] = {0.0f, -0.0f, 1e-40f, -3e-39f, 6.5e4f, -1e30f,
                              std::numeric_limits<float>::infinity(),
                              std::numeric_limits<float>::quiet_NaN()};
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      pixels[i] = file.smooth ? float(std::sin(1e-3 * double(i)))
                              : i % 97 == 5 ? specials[(i / 97) % 8] : normal(random);
    }
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, spec)) << OIIO::geterror();
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
    out->close();
    return path;
  }

  // OpenImageIO's read of `channels` (by name) as interleaved floats.
  std::vector<float> read_through_openimageio(const std::string& path,
                                              const std::vector<std::string>& channels) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> all(std::size_t(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()));
    std::vector<float> out;
    for (std::size_t p = 0; p < std::size_t(spec.width) * spec.height; ++p) {
      for (const auto& name : channels) {
        const int c = spec.channelindex(name);
        EXPECT_GE(c, 0) << name;
        out.push_back(all[p * spec.nchannels + c]);
      }
    }
    return out;
  }

  fs::path directory_;
  ExrScratch scratch_;
};

TEST_F(ExrScanlines, MatchesOpenImageIOBitForBit) {
  int files = 0;
  for (const std::string compression : {"none", "zips", "zip"}) {
    for (const OIIO::TypeDesc type : {OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::HALF}) {
      for (const auto& [width, height] : std::vector<std::pair<int, int>>{{1, 1}, {37, 19}, {64, 3}, {256, 33}}) {
        ExrFile file;
        file.compression = compression;
        file.type = type;
        file.width = width;
        file.height = height;
        const std::string name = compression + "_" + type.c_str() + "_" + std::to_string(width) +
                                 "x" + std::to_string(height) + ".exr";
        const std::string path = write(file, name);
        // Every channel in the file's order, a subset in another order, and one channel.
        for (const std::vector<std::string>& wanted :
             {std::vector<std::string>{"J", "dx", "dy", "h", "sx", "sy"},
              std::vector<std::string>{"sy", "h", "dx"}, std::vector<std::string>{"h"}}) {
          std::vector<float> direct(std::size_t(width) * height * wanted.size(), 1.25f);
          ASSERT_TRUE(read_exr_scanlines(path, wanted, width, height, direct.data(), scratch_)) << name;
          const auto expected = read_through_openimageio(path, wanted);
          ASSERT_EQ(direct.size(), expected.size());
          EXPECT_EQ(std::memcmp(direct.data(), expected.data(), direct.size() * sizeof(float)), 0)
              << name << ", " << wanted.size() << " channels";
        }
        ++files;
      }
    }
  }
  EXPECT_EQ(files, 24);
}

TEST_F(ExrScanlines, ReadsADataWindowOffTheOrigin) {
  ExrFile file;
  file.x = 5;
  file.y = -3;
  const std::string path = write(file, "offset.exr");
  std::vector<float> direct(std::size_t(file.width) * file.height * 2);
  ASSERT_TRUE(read_exr_scanlines(path, {"h", "J"}, file.width, file.height, direct.data(), scratch_));
  const auto expected = read_through_openimageio(path, {"h", "J"});
  EXPECT_EQ(std::memcmp(direct.data(), expected.data(), direct.size() * sizeof(float)), 0);
}

TEST_F(ExrScanlines, LeavesOtherFilesToOpenImageIO) {
  std::vector<float> pixels(37 * 19 * 6);
  auto declined = [&](const ExrFile& file, const std::string& name,
                      std::vector<std::string> channels = {"h"}) {
    const std::string path = write(file, name);
    return !read_exr_scanlines(path, channels, file.width, file.height, pixels.data(), scratch_);
  };
  for (const std::string compression : {"rle", "piz", "pxr24", "b44", "dwaa"}) {
    ExrFile file;
    file.compression = compression;
    EXPECT_TRUE(declined(file, compression + ".exr")) << compression;
  }
  ExrFile tiled;
  tiled.tile = 16;
  EXPECT_TRUE(declined(tiled, "tiled.exr"));
  ExrFile uint_channels;
  uint_channels.type = OIIO::TypeDesc::UINT32;
  EXPECT_TRUE(declined(uint_channels, "uint.exr"));
  EXPECT_TRUE(declined(ExrFile{}, "missing_channel.exr", {"h", "height"}));
  const std::string path = write(ExrFile{}, "size.exr");
  EXPECT_FALSE(read_exr_scanlines(path, {"h"}, 38, 19, pixels.data(), scratch_));
  EXPECT_FALSE(read_exr_scanlines(path, {"h"}, 37, 20, pixels.data(), scratch_));
  EXPECT_FALSE(read_exr_scanlines((directory_ / "absent.exr").string(), {"h"}, 37, 19, pixels.data(), scratch_));
}

TEST_F(ExrScanlines, RefusesTruncatedAndCorruptFiles) {
  ExrFile file;
  file.width = 256;
  file.height = 64;  // four ZIP blocks of 16 rows
  file.smooth = true;  // compressed: a block ZIP cannot shrink is stored raw, without a checksum
  const std::string path = write(file, "whole.exr");
  std::vector<float> pixels(std::size_t(file.width) * file.height);
  ASSERT_TRUE(read_exr_scanlines(path, {"h"}, file.width, file.height, pixels.data(), scratch_));
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto variant = [&](const std::string& name, const std::string& content) {
    const std::string changed = (directory_ / name).string();
    std::ofstream(changed, std::ios::binary) << content;
    return changed;
  };
  for (const double kept : {0.9, 0.5, 0.02}) {
    const auto truncated = variant("truncated.exr", bytes.substr(0, std::size_t(kept * bytes.size())));
    EXPECT_FALSE(read_exr_scanlines(truncated, {"h"}, file.width, file.height, pixels.data(), scratch_)) << kept;
  }
  // Bytes flipped inside the last block's zlib data: its checksum no longer matches.
  std::string corrupt = bytes;
  for (std::size_t i = corrupt.size() - 2000; i < corrupt.size() - 1990; ++i) corrupt[i] = char(~corrupt[i]);
  const auto corrupt_path = variant("corrupt.exr", corrupt);
  EXPECT_FALSE(read_exr_scanlines(corrupt_path, {"h"}, file.width, file.height, pixels.data(), scratch_));
  // OpenImageIO, which then reads it, fails too (and names the problem).
  auto image = OIIO::ImageInput::open(corrupt_path);
  ASSERT_TRUE(image);
  std::vector<float> all(pixels.size() * 6);
  const bool read = image->read_image(0, 0, 0, 6, OIIO::TypeDesc::FLOAT, all.data());
  EXPECT_TRUE(!read || !image->geterror().empty());
}

// The filters against a byte-at-a-time transcription of OpenEXR's Zip::uncompress (ImfZip.cpp),
// on every size from 0 to 200 bytes (the 16-byte vector loops and their scalar tails) and a few
// large odd ones.
TEST(ExrZipFilters, MatchOpenEXRsByteLoops) {
  std::mt19937 random(7);
  std::vector<std::size_t> sizes;
  for (std::size_t size = 0; size <= 200; ++size) sizes.push_back(size);
  sizes.insert(sizes.end(), {4095, 4096, 4097, 98304, 98317});
  for (std::size_t size : sizes) {
    std::vector<std::uint8_t> stored(size);
    for (auto& b : stored) b = std::uint8_t(random());
    // OpenEXR: predictor over the whole buffer, then interleave its two halves.
    std::vector<std::uint8_t> t = stored, expected(size);
    for (std::size_t i = 1; i < size; ++i) t[i] = std::uint8_t(int(t[i - 1]) + int(t[i]) - 128);
    std::size_t t1 = 0, t2 = (size + 1) / 2, s = 0;
    while (true) {
      if (s < size) expected[s++] = t[t1++]; else break;
      if (s < size) expected[s++] = t[t2++]; else break;
    }
    std::vector<std::uint8_t> bytes = stored, out(size, 0xA5);
    if (size > 0) undo_zip_filters(bytes.data(), size, out.data());
    EXPECT_EQ(out, expected) << size << " bytes";
  }
}

// apply_zip_filters is undo_zip_filters' inverse (which the test above ties to OpenEXR's own
// loops), on every size from 0 to 200 bytes and a few large odd ones.
TEST(ExrZipFilters, ApplyThenUndoIsTheIdentity) {
  std::mt19937 random(8);
  std::vector<std::size_t> sizes;
  for (std::size_t size = 0; size <= 200; ++size) sizes.push_back(size);
  sizes.insert(sizes.end(), {4095, 4096, 4097, 98317});
  for (std::size_t size : sizes) {
    std::vector<std::uint8_t> block(size), filtered(size), back(size, 0xA5);
    for (auto& b : block) b = std::uint8_t(random());
    apply_zip_filters(block.data(), size, filtered.data());
    if (size > 0) undo_zip_filters(filtered.data(), size, back.data());
    EXPECT_EQ(back, block) << size << " bytes";
  }
}

// The header OpenEXRCore reads, as OpenImageIO describes the same file: size, channels (as a
// set: OpenImageIO puts R, G, B, A first), their types; none for a file it cannot open.
TEST_F(ExrScanlines, HeaderAsOpenImageIODescribesIt) {
  std::vector<ExrFile> files(5);
  files[1].type = OIIO::TypeDesc::HALF;
  files[2].type = OIIO::TypeDesc::UINT32;
  files[3].tile = 16;
  files[3].compression = "piz";
  files[4].x = 5;
  files[4].y = -3;
  files[4].channels = {"R", "G", "B", "A", "h"};
  for (std::size_t k = 0; k < files.size(); ++k) {
    SCOPED_TRACE(k);
    const std::string path = write(files[k], "header_" + std::to_string(k) + ".exr");
    const auto header = read_exr_header(path);
    ASSERT_TRUE(header);
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(header->width, spec.width);
    EXPECT_EQ(header->height, spec.height);
    EXPECT_FALSE(header->deep);
    ASSERT_EQ(int(header->channel_names.size()), spec.nchannels);
    for (int c = 0; c < spec.nchannels; ++c) {
      const auto at = std::find(header->channel_names.begin(), header->channel_names.end(),
                                spec.channelnames[std::size_t(c)]);
      ASSERT_NE(at, header->channel_names.end()) << spec.channelnames[std::size_t(c)];
      const std::size_t slot = std::size_t(at - header->channel_names.begin());
      EXPECT_EQ(header->channel_type_names[slot], spec.channelformat(c).c_str());
      const SampleType type = spec.channelformat(c) == OIIO::TypeDesc::HALF    ? SampleType::half
                              : spec.channelformat(c) == OIIO::TypeDesc::FLOAT ? SampleType::float32
                                                                              : SampleType::other;
      EXPECT_EQ(header->channel_types[slot], type);
    }
  }
  EXPECT_FALSE(read_exr_header((directory_ / "absent.exr").string()));
  std::ofstream(directory_ / "junk.exr", std::ios::binary) << "not an EXR file at all";
  EXPECT_FALSE(read_exr_header((directory_ / "junk.exr").string()));
}

// swell's writer as OpenImageIO reads its files: every float bit for bit (NaN, ±∞, subnormals
// and ±0 among them), on sizes whose last ZIP block is partial, with blocks that compress and
// blocks stored raw; ZIP compression, float channels under the names given; and swell's own
// reader takes the same file.
TEST_F(ExrScanlines, WriterIsReadBackByOpenImageIOBitForBit) {
  const std::vector<std::string> channels = {"h", "sx", "sy", "dx", "dy", "J"};
  const float specials[] = {0.0f, -0.0f, 1e-40f, -3e-39f, 6.5e4f, -1e30f,
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(),
                            std::numeric_limits<float>::quiet_NaN()};
  for (const auto& size : std::vector<std::pair<int, int>>{{1, 1}, {37, 19}, {64, 16}, {256, 33}}) {
    const int width = size.first, height = size.second;  // named: lambdas below capture them
    for (const bool smooth : {false, true}) {
      const std::string name = "written_" + std::to_string(width) + "x" + std::to_string(height) +
                               (smooth ? "_smooth" : "_rough") + ".exr";
      SCOPED_TRACE(name);
      std::mt19937_64 random(std::hash<std::string>{}(name));
      std::normal_distribution<float> normal(0.0f, 3.0f);
      const std::size_t count = std::size_t(width) * std::size_t(height);
      std::vector<float> expected(count * channels.size());  // interleaved, as OpenImageIO reads
      for (std::size_t i = 0; i < expected.size(); ++i) {
        // Smooth: eighths of a slow sine, which ZIP shrinks; rough: normal noise, stored raw.
        expected[i] = smooth ? float(std::round(8 * std::sin(1e-3 * double(i))) / 8)
                             : i % 89 == 3 ? specials[(i / 89) % 9] : normal(random);
      }
      const std::string path = (directory_ / name).string();
      write_exr_scanlines(path, width, height, channels,
                          [&](std::size_t slot, std::size_t row, float* values) {
                            for (int x = 0; x < width; ++x) {
                              values[x] = expected[(row * std::size_t(width) + std::size_t(x)) *
                                                       channels.size() + slot];
                            }
                          });
      auto in = OIIO::ImageInput::open(path);
      ASSERT_TRUE(in) << OIIO::geterror();
      EXPECT_EQ(in->spec().width, width);
      EXPECT_EQ(in->spec().height, height);
      EXPECT_EQ(in->spec().get_string_attribute("compression"), "zip");
      for (int c = 0; c < in->spec().nchannels; ++c) {
        EXPECT_EQ(in->spec().channelformat(c), OIIO::TypeDesc::FLOAT);
      }
      const auto through_openimageio = read_through_openimageio(path, channels);
      ASSERT_EQ(through_openimageio.size(), expected.size());
      EXPECT_EQ(std::memcmp(through_openimageio.data(), expected.data(), expected.size() * 4), 0);
      std::vector<float> direct(expected.size());
      ASSERT_TRUE(read_exr_scanlines(path, channels, width, height, direct.data(), scratch_));
      EXPECT_EQ(std::memcmp(direct.data(), expected.data(), expected.size() * 4), 0);
      if (smooth && width == 256) {
        EXPECT_LT(fs::file_size(path), expected.size() * 4 / 2) << "smooth values should compress";
      }
    }
  }
}

TEST_F(ExrScanlines, WriterNamesTheFileItCannotWrite) {
  const std::string path = (directory_ / "no_such_directory" / "frame.exr").string();
  try {
    write_exr_scanlines(path, 4, 4, {"h"}, [](std::size_t, std::size_t, float* values) {
      for (int x = 0; x < 4; ++x) values[x] = 1.0f;
    });
    ADD_FAILURE() << "no exception";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_THROW(write_exr_scanlines((directory_ / "empty.exr").string(), 0, 4, {"h"},
                                   [](std::size_t, std::size_t, float*) {}),
               swell::InvalidInput);
}

}  // namespace
