// The EXR writer of exr_scanlines.hpp: one part of float scanlines, ZIP-compressed blocks of 16
// lines, through OpenEXRCore's header and chunk table with libdeflate's zlib deflater.
#include <fmt/format.h>
#include <libdeflate.h>
#include <openexr.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <memory>
#include <string>

#include "exr_scanlines.hpp"
#include "swell/reference/errors.hpp"

namespace swell::validation::detail {
namespace {

// OpenEXR's ZIP compression puts 16 scanlines in a block (ImfCompression.h).
constexpr int kZipLinesPerBlock = 16;
// libdeflate's level 4: within a few percent of zlib's default size at several times its speed.
constexpr int kDeflateLevel = 4;

// OpenEXRCore's last message, kept for the exception (the context's user data).
void keep_message(exr_const_context_t context, exr_result_t, const char* message) {
  void* data = nullptr;
  if (exr_get_user_data(context, &data) == EXR_ERR_SUCCESS && data && message) {
    *static_cast<std::string*>(data) = message;
  }
}

struct Compressor {
  libdeflate_compressor* deflater = libdeflate_alloc_compressor(kDeflateLevel);
  ~Compressor() {
    if (deflater) libdeflate_free_compressor(deflater);
  }
};

}  // namespace

void apply_zip_filters(const std::uint8_t* bytes, std::size_t size, std::uint8_t* out) {
  if (size == 0) return;
  // The inverse of undo_zip_filters (ImfZip.cpp, Zip::compress): even-indexed bytes first, then
  // the odd-indexed ones; then each byte as its difference to the one before, plus 128.
  std::uint8_t* even = out;
  std::uint8_t* odd = out + (size + 1) / 2;
  for (std::size_t i = 0; i < size; i += 2) *even++ = bytes[i];
  for (std::size_t i = 1; i < size; i += 2) *odd++ = bytes[i];
  std::uint8_t previous = out[0];
  for (std::size_t i = 1; i < size; ++i) {
    const std::uint8_t current = out[i];
    out[i] = std::uint8_t(current - previous + 128);
    previous = current;
  }
}

void write_exr_scanlines(const std::string& file, int width, int height,
                         const std::vector<std::string>& channels, const ExrLineSource& source) {
  if constexpr (std::endian::native != std::endian::little) {
    throw InvalidInput(file + ": EXR frames are written on little-endian machines only");
  }
  if (width < 1 || height < 1 || channels.empty()) {
    throw InvalidInput(fmt::format("{}: cannot write an EXR of {}×{} pixels and {} channels", file,
                                   width, height, channels.size()));
  }
  std::string message;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = &keep_message;
  init.user_data = &message;
  exr_context_t context = nullptr;
  auto fail = [&](const char* step) {
    if (context) exr_finish(&context);  // removes the partly written file
    throw InvalidInput(fmt::format("{}: cannot write: {} ({})", file,
                                   message.empty() ? "unknown error" : message, step));
  };
  if (exr_start_write(&context, file.c_str(), EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS) {
    context = nullptr;
    fail("create");
  }
  int part = 0;
  if (exr_add_part(context, "", EXR_STORAGE_SCANLINE, &part) != EXR_ERR_SUCCESS ||
      exr_initialize_required_attr_simple(context, part, width, height, EXR_COMPRESSION_ZIP) !=
          EXR_ERR_SUCCESS) {
    fail("header");
  }
  for (const auto& name : channels) {
    if (exr_add_channel(context, part, name.c_str(), EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC,
                        1, 1) != EXR_ERR_SUCCESS) {
      fail("channel list");
    }
  }
  if (exr_attr_set_string(context, part, "Software", "swell") != EXR_ERR_SUCCESS ||
      exr_write_header(context) != EXR_ERR_SUCCESS) {
    fail("header");
  }
  // A block holds its lines one after the other, each line the channels in the file's
  // (sorted) order, each channel's samples in turn.
  const exr_attr_chlist_t* list = nullptr;
  if (exr_get_channels(context, part, &list) != EXR_ERR_SUCCESS || !list ||
      list->num_channels != int(channels.size())) {
    fail("channel list");
  }
  std::vector<std::size_t> order;  // stored channel k is channels[order[k]]
  for (int c = 0; c < list->num_channels; ++c) {
    const std::string name(list->entries[c].name.str, std::size_t(list->entries[c].name.length));
    order.push_back(std::size_t(std::find(channels.begin(), channels.end(), name) - channels.begin()));
  }
  const Compressor compressor;
  if (!compressor.deflater) fail("deflater");
  const std::size_t line_bytes = 4 * std::size_t(width) * channels.size();
  std::vector<float> values(static_cast<std::size_t>(width));
  std::vector<std::uint8_t> raw(line_bytes * kZipLinesPerBlock), filtered(raw.size());
  std::vector<std::uint8_t> packed(libdeflate_zlib_compress_bound(compressor.deflater, raw.size()));
  for (int y = 0; y < height; y += kZipLinesPerBlock) {
    const int lines = std::min(kZipLinesPerBlock, height - y);
    std::uint8_t* at = raw.data();
    for (int line = 0; line < lines; ++line) {
      for (std::size_t slot : order) {
        source(slot, std::size_t(y + line), values.data());
        std::memcpy(at, values.data(), 4 * values.size());
        at += 4 * values.size();
      }
    }
    const std::size_t size = std::size_t(at - raw.data());
    apply_zip_filters(raw.data(), size, filtered.data());
    std::size_t packed_size = libdeflate_zlib_compress(compressor.deflater, filtered.data(), size,
                                                       packed.data(), packed.size());
    // A block that does not shrink is stored raw, as OpenEXR stores it (and reads it back).
    const bool shrunk = packed_size > 0 && packed_size < size;
    if (exr_write_scanline_chunk(context, part, y, shrunk ? packed.data() : raw.data(),
                                 shrunk ? packed_size : size) != EXR_ERR_SUCCESS) {
      fail("scanlines");
    }
  }
  if (exr_finish(&context) != EXR_ERR_SUCCESS) {
    context = nullptr;
    fail("chunk table");
  }
}

}  // namespace swell::validation::detail
