#pragma once
// EXR frames through OpenEXRCore and libdeflate, without OpenImageIO (image_module.hpp):
//
// - A direct reader for the EXR files engines and `swell synth` write most: one part of
//   scanlines, channels of float or half sampled at every pixel, stored raw or ZIP/ZIPS (zlib)
//   compressed. It decodes through OpenEXRCore's chunk table and libdeflate instead of
//   OpenImageIO's reader, which inflates with zlib and allocates its buffers afresh for every
//   16-scanline block: at 64 frames of 512² with six float channels that reading took ~2 s of
//   CPU (zlib alone ~0.9 s, page faults ~0.4 s); per frame on one thread this one takes 11 ms,
//   OpenImageIO ~40 ms (docs/gate.md §6). Any other file (tiled, deep, multi-part, subsampled
//   or uint channels, PIZ, RLE, B44, DWA…), and any error, returns false: the caller reads the
//   file through OpenImageIO, which takes every EXR and names what is wrong with a broken one.
// - The header of any single-part EXR, as OpenImageIO would describe it.
// - A writer of what `swell synth` writes: float channels, ZIP-compressed scanlines.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "image_module.hpp"

struct libdeflate_decompressor;

namespace swell::validation::detail {

// Buffers one reading thread keeps from one file to the next.
struct ExrScratch {
  ExrScratch();
  ~ExrScratch();
  ExrScratch(const ExrScratch&) = delete;
  ExrScratch& operator=(const ExrScratch&) = delete;
  std::vector<std::uint8_t> packed, inflated, raw;
  std::vector<float> line;
  libdeflate_decompressor* inflater = nullptr;
};

// Receives one scanline of one wanted channel: `slot` indexes the channels asked for, `row`
// counts from the data window's top, `values` holds the line's width samples as float (half
// widened exactly), valid during the call. Rows arrive top to bottom.
using ExrLineSink = std::function<void(std::size_t slot, std::size_t row, const float* values)>;

// Reads the data window of `file` (width × height pixels): every scanline of each of `channels`
// (names, each in the file) to `sink` — the values OpenImageIO's read_image(…, FLOAT) gives for
// them. True when every line of every channel was delivered; false when the file is not one
// this reader takes or cannot be read (see above), after delivering any number of lines.
bool read_exr_scanlines(const std::string& file, const std::vector<std::string>& channels,
                        int width, int height, const ExrLineSink& sink, ExrScratch& scratch);

// The size, channels and their types of a single-part EXR file; nullopt for a file
// OpenEXRCore cannot open, a multi-part file or subsampled channels (OpenImageIO then opens it
// and says what it is). Channels are in the file's (sorted) order.
std::optional<ImageHeader> read_exr_header(const std::string& file);

// Fills one scanline of one channel: `slot` indexes the channels given to the writer, `row`
// counts from the top; `values` has room for the line's width samples.
using ExrLineSource = std::function<void(std::size_t slot, std::size_t row, float* values)>;

// Writes `file`: one part of width × height pixels, `channels` (names) of float samples,
// ZIP-compressed blocks of 16 scanlines (a block that does not shrink stored raw), and the
// attribute Software = "swell". Throws InvalidInput naming the file and OpenEXRCore's reason; a
// file it could not finish is removed.
void write_exr_scanlines(const std::string& file, int width, int height,
                         const std::vector<std::string>& channels, const ExrLineSource& source);

// Undoes the two filters OpenEXR's ZIP and ZIPS compression applies to a block before zlib
// (ImfZip.cpp, Zip::compress/uncompress): the bytes were reordered, even-indexed ones first,
// then the odd-indexed ones, and each stored as its difference to the byte before plus 128.
// `bytes` (size of them, inflated) is overwritten; the block's bytes go to `out`.
void undo_zip_filters(std::uint8_t* bytes, std::size_t size, std::uint8_t* out);
// The filters themselves, from `size` bytes of a block to `out`: undo_zip_filters' inverse.
void apply_zip_filters(const std::uint8_t* bytes, std::size_t size, std::uint8_t* out);

}  // namespace swell::validation::detail
