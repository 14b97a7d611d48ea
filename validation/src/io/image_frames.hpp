#pragma once
// One frame as one image file (EXR, TIFF, PNG; frame_io.hpp says what each holds): read into a
// FieldFrame with every check of the case, or written from one. EXR goes through OpenEXRCore
// (exr_scanlines.hpp) wherever it can; TIFF, PNG and the EXR files it does not take go through
// OpenImageIO's module (image_module.hpp), loaded only then.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "exr_scanlines.hpp"
#include "swell/reference/fields.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"

namespace swell::validation::detail {

// Unit roundoff of the stored number types (docs/conventions.md §Tolerances: the floor the
// checks cannot go below).
constexpr double kHalfRoundoff = 0x1p-11;
constexpr double kFloatRoundoff = 0x1p-24;
constexpr double kDoubleRoundoff = 0x1p-53;

enum class ImageKind { exr, tiff, png };

// The interleaved pixels of one image read, kept by each reading thread from one frame to the
// next: a fresh array per frame (6 MiB at 512² with six float channels, above malloc's mmap
// threshold) was mapped, faulted in page by page and unmapped again on every frame.
struct PixelScratch {
  std::vector<float> f32;
  std::vector<double> f64;
  ExrScratch exr;
};

// Reads the fields of `input.channels` from one image into `frame` (those `keep` rejects are
// read and checked, not stored) and returns their unit roundoff. `threads` bounds the threads
// OpenImageIO may use for this one image. Throws InvalidInput naming the file and the problem.
double read_image_frame(const std::filesystem::path& path, ImageKind kind,
                        const reference::Grid& grid, const InputSpec& input,
                        const std::function<bool(reference::Field)>& keep,
                        reference::FieldFrame& frame, PixelScratch& scratch, int threads);

// Writes `fields` of `frame` as one image in options.format (exr, tiff or png) and returns
// the file. A PNG value outside options.png_range is refused before the file is created.
std::vector<std::filesystem::path> write_image_frame(const std::filesystem::path& path,
                                                     const reference::Grid& grid,
                                                     const std::vector<reference::Field>& fields,
                                                     const reference::FieldFrame& frame,
                                                     const FrameWriteOptions& options);

// The channels of a PNG of `count` fields, named as OpenImageIO reads them back (Y, Y A, R G B,
// R G B A); InvalidInput beyond 4.
std::vector<std::string> png_channel_names(std::size_t count);
// InvalidInput unless 8 or 16 bits and a finite range with low < high.
void require_png_options(const FrameWriteOptions& options);

// The message for a field with `count` non-finite samples, the first at flat index `at`.
[[noreturn]] void fail_non_finite(const reference::Grid& grid, const std::string& file,
                                  const std::string& what, std::size_t at, double value,
                                  std::size_t count);

}  // namespace swell::validation::detail
