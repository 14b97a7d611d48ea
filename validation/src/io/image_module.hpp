#pragma once
// Images through OpenImageIO — TIFF, PNG, and the EXR files that swell's own OpenEXRCore reader
// does not take (exr_scanlines.hpp) — behind a table of functions in a module of its own,
// libswell_openimageio.so, loaded on first use. OpenImageIO links some 260 shared libraries
// whose symbols the dynamic loader resolves when they load (≈ 0.45 s); in the module, only a
// process that reads or writes such an image pays it, and `swell --version`, a gate on EXR or
// .npy frames, and every test program start without it (docs/performance.md §10).
//
// The module is glue over OpenImageIO and nothing else: what an image must hold (its size,
// channels, types, finite values) is checked by the caller (image_frames.cpp), once for every
// format. Errors come back as text, never as exceptions, so that nothing but this header's
// types crosses the module's boundary.
#include <memory>
#include <string>
#include <vector>

namespace swell::validation::detail {

// The sample types swell reads and writes; `other` is any else (uint32, int8, …), which a
// reader reports by name (ImageHeader::channel_type_names) and frame reading refuses.
enum class SampleType { uint8, uint16, half, float32, float64, other };

struct ImageHeader {
  int width = 0, height = 0, depth = 1;
  bool deep = false;
  std::vector<std::string> channel_names;
  std::vector<SampleType> channel_types;
  std::vector<std::string> channel_type_names;  // as OpenImageIO names them: "float", "uint"…
  std::string description;                      // the ImageDescription attribute, or empty
};

class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageHeader& header() const = 0;
  // Channels [first, last) of every pixel, interleaved, converted to `type` (float32 or
  // float64; 8- and 16-bit integers scaled to [0, 1], as OpenImageIO converts them). Returns
  // the error, or an empty string when every pixel was read.
  virtual std::string read(int first, int last, SampleType type, void* pixels) = 0;
};

struct ImageWriteSpec {
  int width = 0, height = 0;
  std::vector<std::string> channel_names;
  SampleType stored = SampleType::float32;  // float32, uint8 or uint16
  std::string compression;                  // OpenImageIO's name ("zip"), or empty: its default
  std::string description;                  // the ImageDescription attribute, or empty
};

class ImageWriter {
 public:
  virtual ~ImageWriter() = default;
  // Rows [y0, y1) of every channel, interleaved, given as `type` (converted to the stored type).
  // Each returns the error, or an empty string.
  virtual std::string write_scanlines(int y0, int y1, SampleType type, const void* pixels) = 0;
  virtual std::string close() = 0;
};

// What the module provides. `threads` bounds the threads OpenImageIO uses for one image.
struct ImageModule {
  int interface_version = 0;
  std::unique_ptr<ImageReader> (*open)(const std::string& file, int threads, std::string& error);
  std::unique_ptr<ImageWriter> (*create)(const std::string& file, const ImageWriteSpec& spec,
                                         int threads, std::string& error);
};

// Changes whenever the types above change: a module built from other sources is refused.
constexpr int kImageModuleInterfaceVersion = 1;

// The module, loaded on the first call (from any thread). Throws InvalidInput naming the files
// it tried and why none loaded, beginning with `purpose` ("reading frame_0000.tif").
const ImageModule& image_module(const std::string& purpose);

}  // namespace swell::validation::detail

// The module's one exported symbol.
extern "C" __attribute__((visibility("default"))) const swell::validation::detail::ImageModule* swell_openimageio_module();
