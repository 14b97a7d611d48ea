#pragma once
// A direct reader for the EXR files engines and `swell synth` write most: one part of scanlines,
// channels of float or half sampled at every pixel, stored raw or ZIP/ZIPS (zlib) compressed.
// It decodes through OpenEXRCore's chunk table and libdeflate instead of OpenImageIO's reader,
// which inflates with zlib and allocates its buffers afresh for every 16-scanline block: at
// 64 frames of 512² with six float channels that reading took ~2 s of CPU (zlib alone ~0.9 s,
// page faults ~0.4 s); per frame on one thread this one takes 11 ms, OpenImageIO ~40 ms
// (docs/gate.md §6).
//
// Any other file (tiled, deep, multi-part, subsampled or uint channels, PIZ, RLE, B44, DWA…),
// and any error, returns false: the caller reads the file through OpenImageIO, which takes every
// EXR and names what is wrong with a broken one.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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

// Undoes the two filters OpenEXR's ZIP and ZIPS compression applies to a block before zlib
// (ImfZip.cpp, Zip::compress/uncompress): the bytes were reordered, even-indexed ones first,
// then the odd-indexed ones, and each stored as its difference to the byte before plus 128.
// `bytes` (size of them, inflated) is overwritten; the block's bytes go to `out`.
void undo_zip_filters(std::uint8_t* bytes, std::size_t size, std::uint8_t* out);

}  // namespace swell::validation::detail
