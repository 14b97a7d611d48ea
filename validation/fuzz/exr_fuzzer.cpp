// libFuzzer target: the direct scanline EXR reader (validation/src/io/exr_scanlines.cpp) on
// arbitrary bytes, written to a file (the reader takes a path, as OpenEXRCore does). Its contract:
// false for any file it does not take or cannot read — after which OpenImageIO reads the file and
// names the problem — or true with every scanline of every channel asked for delivered once, top
// to bottom. A crash, a sanitizer report, an exception, a hang over 10 s or an allocation over
// 2 GB is a bug. The seeds (corpus/exr/) are small files of channels h and J at the sizes tried
// below, raw, ZIPS, ZIP and PIZ, float and half.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "../src/io/exr_scanlines.hpp"

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "exr fuzzer: %s\n", what);
  std::abort();
}

const std::string& input_path() {
  static const std::string path = "/tmp/swell_exr_fuzzer_" + std::to_string(getpid()) + ".exr";
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::FILE* file = std::fopen(input_path().c_str(), "wb");
  if (!file) finding("cannot write the input file");
  if (size > 0 && std::fwrite(data, 1, size, file) != size) finding("cannot write the input file");
  std::fclose(file);
  static swell::validation::detail::ExrScratch scratch;
  const std::vector<std::vector<std::string>> channel_sets = {{"h", "J"}, {"J"}};
  const int sizes[][2] = {{16, 20}, {16, 4}, {8, 8}};
  for (const auto& channels : channel_sets) {
    for (const auto& dimensions : sizes) {
      const int width = dimensions[0], height = dimensions[1];  // (a lambda cannot capture a binding)
      std::vector<int> next_row(channels.size(), 0);
      const bool read = swell::validation::detail::read_exr_scanlines(
          input_path(), channels, width, height,
          [&](std::size_t slot, std::size_t row, const float* values) {
            if (slot >= channels.size()) finding("a line of a channel not asked for");
            if (int(row) != next_row[slot]++ || int(row) >= height) finding("a line out of order or beyond the image");
            volatile float first = values[0], last = values[width - 1];  // the line is whole
            (void)first;
            (void)last;
          },
          scratch);
      if (!read) continue;
      for (int rows : next_row) {
        if (rows != height) finding("read reported, but a channel's lines are missing");
      }
    }
  }
  return 0;
}
