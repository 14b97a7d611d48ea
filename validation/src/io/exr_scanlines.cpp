#include "exr_scanlines.hpp"

#include <Imath/half.h>
#include <libdeflate.h>
#include <openexr.h>

#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>
#include <cstring>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace swell::validation::detail {

ExrScratch::ExrScratch() = default;
ExrScratch::~ExrScratch() {
  if (inflater) libdeflate_free_decompressor(inflater);
}

namespace {

// OpenEXRCore prints every error to standard error unless told otherwise; this reader only
// tries, and OpenImageIO reports the error when the file is read again through it.
void ignore_error(exr_const_context_t, exr_result_t, const char*) {}

class Context {
 public:
  explicit Context(const std::string& file) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &ignore_error;
    if (exr_start_read(&context_, file.c_str(), &init) != EXR_ERR_SUCCESS) context_ = nullptr;
  }
  ~Context() {
    if (context_) exr_finish(&context_);
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  exr_const_context_t get() const { return context_; }

 private:
  exr_context_t context_ = nullptr;
};

// ZIP and ZIPS blocks: zlib data of the block's bytes, inflated, then the two steps of
// undo_zip_filters.
bool undo_zip(const std::uint8_t* packed, std::size_t packed_size, std::size_t unpacked_size,
              ExrScratch& scratch) {
  if (!scratch.inflater) scratch.inflater = libdeflate_alloc_decompressor();
  if (!scratch.inflater) return false;
  scratch.inflated.resize(unpacked_size);
  std::size_t inflated_size = 0;
  if (libdeflate_zlib_decompress(scratch.inflater, packed, packed_size, scratch.inflated.data(),
                                 unpacked_size, &inflated_size) != LIBDEFLATE_SUCCESS ||
      inflated_size != unpacked_size) {
    return false;
  }
  scratch.raw.resize(unpacked_size);
  undo_zip_filters(scratch.inflated.data(), unpacked_size, scratch.raw.data());
  return true;
}

}  // namespace

void undo_zip_filters(std::uint8_t* bytes, std::size_t size, std::uint8_t* out) {
  if (size == 0) return;
  // 1. t[i] = t[i−1] + t[i] − 128 (mod 256) is a running sum of t[i] − 128 from t[0]. As a
  // loop over memory each byte waits on the store of the one before (~5 cycles a byte, a fifth
  // of the gate's CPU at 512² × 64 frames); 16 bytes at a time it is four shifted adds (a
  // prefix sum in log2 16 steps) and the last byte carried over.
  std::size_t i = 1;
  std::uint8_t previous = bytes[0];
#ifdef __SSE2__
  const __m128i minus_128 = _mm_set1_epi8(char(-128));
  __m128i carry = _mm_set1_epi8(char(previous));
  for (; i + 16 <= size; i += 16) {
    __m128i x = _mm_add_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(bytes + i)), minus_128);
    x = _mm_add_epi8(x, _mm_slli_si128(x, 1));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 2));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 4));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 8));
    x = _mm_add_epi8(x, carry);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(bytes + i), x);
    // Byte 15 to all 16 (SSE2 has no byte shuffle).
    const __m128i high = _mm_unpackhi_epi8(x, x);
    carry = _mm_shuffle_epi32(_mm_unpackhi_epi16(high, high), 0xFF);
  }
  previous = bytes[i - 1];
#endif
  for (; i < size; ++i) bytes[i] = previous = std::uint8_t(previous + bytes[i] - 128);
  // 2. The even-indexed bytes of the block were stored first, then the odd-indexed ones.
  const std::uint8_t* even = bytes;
  const std::uint8_t* odd = bytes + (size + 1) / 2;
  const std::size_t pairs = size / 2;
  std::size_t p = 0;
#ifdef __SSE2__
  for (; p + 16 <= pairs; p += 16) {
    const __m128i e = _mm_loadu_si128(reinterpret_cast<const __m128i*>(even + p));
    const __m128i o = _mm_loadu_si128(reinterpret_cast<const __m128i*>(odd + p));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * p), _mm_unpacklo_epi8(e, o));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * p + 16), _mm_unpackhi_epi8(e, o));
  }
#endif
  for (; p < pairs; ++p) {
    out[2 * p] = even[p];
    out[2 * p + 1] = odd[p];
  }
  if (size % 2) out[size - 1] = even[pairs];
}

std::optional<ImageHeader> read_exr_header(const std::string& file) {
  const Context context(file);
  const exr_const_context_t exr = context.get();
  if (!exr) return std::nullopt;
  int parts = 0;
  exr_storage_t storage{};
  exr_attr_box2i_t window{};
  const exr_attr_chlist_t* list = nullptr;
  if (exr_get_count(exr, &parts) != EXR_ERR_SUCCESS || parts != 1 ||
      exr_get_storage(exr, 0, &storage) != EXR_ERR_SUCCESS ||
      exr_get_data_window(exr, 0, &window) != EXR_ERR_SUCCESS ||
      exr_get_channels(exr, 0, &list) != EXR_ERR_SUCCESS || !list) {
    return std::nullopt;
  }
  ImageHeader header;
  const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
  const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
  if (width < 1 || height < 1 || width > INT32_MAX || height > INT32_MAX) return std::nullopt;
  header.width = int(width);
  header.height = int(height);
  header.deep = storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED;
  for (int c = 0; c < list->num_channels; ++c) {
    const exr_attr_chlist_entry_t& entry = list->entries[c];
    if (entry.x_sampling != 1 || entry.y_sampling != 1) return std::nullopt;
    header.channel_names.emplace_back(entry.name.str, std::size_t(entry.name.length));
    switch (entry.pixel_type) {
      case EXR_PIXEL_HALF:
        header.channel_types.push_back(SampleType::half);
        header.channel_type_names.push_back("half");
        break;
      case EXR_PIXEL_FLOAT:
        header.channel_types.push_back(SampleType::float32);
        header.channel_type_names.push_back("float");
        break;
      default:
        header.channel_types.push_back(SampleType::other);
        header.channel_type_names.push_back("uint");
        break;
    }
  }
  return header;
}

bool read_exr_scanlines(const std::string& file, const std::vector<std::string>& channels,
                        int width, int height, const ExrLineSink& sink, ExrScratch& scratch) {
  // The stored bytes are little-endian; they are read as host words below.
  if constexpr (std::endian::native != std::endian::little) return false;
  const Context context(file);
  const exr_const_context_t exr = context.get();
  if (!exr) return false;
  int parts = 0;
  exr_storage_t storage{};
  exr_compression_t compression{};
  exr_attr_box2i_t window{};
  const exr_attr_chlist_t* list = nullptr;
  int32_t lines_per_chunk = 0;
  if (exr_get_count(exr, &parts) != EXR_ERR_SUCCESS || parts != 1 ||
      exr_get_storage(exr, 0, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_SCANLINE ||
      exr_get_compression(exr, 0, &compression) != EXR_ERR_SUCCESS ||
      (compression != EXR_COMPRESSION_NONE && compression != EXR_COMPRESSION_ZIPS &&
       compression != EXR_COMPRESSION_ZIP) ||
      exr_get_data_window(exr, 0, &window) != EXR_ERR_SUCCESS ||
      exr_get_channels(exr, 0, &list) != EXR_ERR_SUCCESS || !list ||
      exr_get_scanlines_per_chunk(exr, 0, &lines_per_chunk) != EXR_ERR_SUCCESS ||
      lines_per_chunk < 1) {
    return false;
  }
  if (std::int64_t(window.max.x) - window.min.x + 1 != width ||
      std::int64_t(window.max.y) - window.min.y + 1 != height) {
    return false;
  }
  // Which of `channels` each stored channel is (−1: not wanted), and its size.
  const std::size_t span = channels.size();
  std::vector<int> slot(std::size_t(list->num_channels), -1);
  std::vector<int> bytes(std::size_t(list->num_channels), 0);
  std::size_t found = 0;
  for (int c = 0; c < list->num_channels; ++c) {
    const exr_attr_chlist_entry_t& entry = list->entries[c];
    if (entry.x_sampling != 1 || entry.y_sampling != 1) return false;
    if (entry.pixel_type == EXR_PIXEL_FLOAT) {
      bytes[c] = 4;
    } else if (entry.pixel_type == EXR_PIXEL_HALF) {
      bytes[c] = 2;
    } else {
      return false;
    }
    const std::string name(entry.name.str, std::size_t(entry.name.length));
    const auto wanted = std::find(channels.begin(), channels.end(), name);
    if (wanted != channels.end()) {
      slot[c] = int(wanted - channels.begin());
      ++found;
    }
  }
  if (found != span) return false;
  std::size_t line_bytes = 0;
  for (int b : bytes) line_bytes += std::size_t(b) * std::size_t(width);

  for (std::int64_t y = window.min.y; y <= window.max.y; y += lines_per_chunk) {
    exr_chunk_info_t chunk{};
    if (exr_read_scanline_chunk_info(exr, 0, int(y), &chunk) != EXR_ERR_SUCCESS) return false;
    // A ZIP block the writer could not shrink is stored raw: a stored block is never larger
    // than its pixels (which also bounds what a corrupt size field could make us allocate).
    if (chunk.start_y != y || chunk.width != width || chunk.height < 1 ||
        chunk.start_y + std::int64_t(chunk.height) - 1 > window.max.y ||
        chunk.unpacked_size != line_bytes * std::size_t(chunk.height) ||
        chunk.packed_size > chunk.unpacked_size) {
      return false;
    }
    scratch.packed.resize(chunk.packed_size);
    if (exr_read_chunk(exr, 0, &chunk, scratch.packed.data()) != EXR_ERR_SUCCESS) return false;
    // Raw when the writer could not shrink it, whatever the file's compression.
    const std::uint8_t* raw = scratch.packed.data();
    if (chunk.packed_size != chunk.unpacked_size) {
      if (compression == EXR_COMPRESSION_NONE ||
          !undo_zip(scratch.packed.data(), chunk.packed_size, chunk.unpacked_size, scratch)) {
        return false;
      }
      raw = scratch.raw.data();
    }
    // A block holds its scanlines one after the other, each the channels in the file's
    // (alphabetical) order, each channel's samples of the line in turn.
    const std::size_t samples = std::size_t(width);
    scratch.line.resize(samples);
    for (int line = 0; line < chunk.height; ++line) {
      const std::size_t row = std::size_t(chunk.start_y - window.min.y + line);
      for (int c = 0; c < list->num_channels; ++c) {
        if (slot[c] >= 0) {
          float* values = scratch.line.data();
          if (bytes[c] == 4) {
            std::memcpy(values, raw, 4 * samples);
          } else {
            for (std::size_t x = 0; x < samples; ++x) {
              std::uint16_t bits;
              std::memcpy(&bits, raw + 2 * x, 2);
              values[x] = imath_half_to_float(bits);
            }
          }
          sink(std::size_t(slot[c]), row, values);
        }
        raw += std::size_t(bytes[c]) * samples;
      }
    }
  }
  return true;
}

}  // namespace swell::validation::detail
