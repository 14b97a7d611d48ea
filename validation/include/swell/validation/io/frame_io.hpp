#pragma once
// Frames on disk: EXR (through OpenEXRCore), TIFF and PNG (through OpenImageIO, loaded only
// for them), .npy (npy.hpp) and raw:
//
//   exr:  DIR/frame_0000.exr, … one file per frame, float32 channels h, sx, sy, dx, dy, J
//         (reference::channel_name), rows = y (row 0 is j = 0), columns = x.
//   npy:  DIR/frame_0000_h.npy, DIR/frame_0000_dx.npy, … one file per field and frame,
//         shape (ny, nx), float32 (fp32 synthesis) or float64; complex64/complex128 when the
//         frame carries imaginary parts (read back into FieldFrame::imaginary).
//   tiff: as exr, DIR/frame_0000.tif, float32; the channel names, which TIFF cannot hold, go
//         into the ImageDescription tag ("swell channels: h sx …").
//   png:  as exr, DIR/frame_0000.png, 8- or 16-bit unsigned integers (written 16-bit unless
//         FrameWriteOptions::png_bits says 8), each
//         pixel standing for a value of the field through [input] value_range (pixel 0 ↦ low,
//         the largest pixel ↦ high); channels R, G, B, A (Y for grey). Integer TIFF reads alike.
//   raw:  read only: headerless little-endian float32 or float64 ([input] raw_type), ny·nx
//         values, one file per field and frame named as for npy.
//
// docs/case_files.md gives the naming rules and how channels are found in each format.
// Readers check everything against the case (sizes, channels, frame count, finite values) and
// throw InvalidInput naming the file and the problem.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/npy.hpp"

namespace swell::validation {

// The unit roundoff of values stored as integers over a value range (docs/case_files.md): the
// quantization step q = (high − low)/levels as uniform noise of rms q/√12, relative to the
// values' rms (1 at most). The gate judges integer frames by it; swell synth refuses a PNG
// whose quantization would hide every wave vector.
double quantization_roundoff(const IntegerRange& range, double levels,
                             const std::vector<double>& values);

enum class FrameFormat { exr, npy, tiff, png };
FrameFormat frame_format_from_string(const std::string& name);  // "exr" | "npy" | "tiff" | "png"
std::string to_string(FrameFormat format);

struct FrameWriteOptions {
  FrameFormat format = FrameFormat::exr;
  bool float64 = false;  // npy only: store float64 instead of float32
  // png only (required): the values pixel 0 and the largest pixel stand for, every field. A
  // value outside it cannot be stored: InvalidInput, never clipped.
  IntegerRange png_range{};
  int png_bits = 16;  // 8 or 16
};

// Writes every frame of `frames` into `directory` (created if missing) and returns the InputSpec
// that reads them back (files pattern and channels, relative to `directory`).
InputSpec write_frames(const std::filesystem::path& directory,
                       const reference::FrameSequence& frames, const FrameWriteOptions& options);

// Writes one frame, as write_frames writes frame `index` (the fields present in `frame`, each
// grid.nx·grid.ny values); returns the files written. For `swell synth`, which writes frames as
// it makes them.
std::vector<std::filesystem::path> write_frame(const std::filesystem::path& directory,
                                               const reference::Grid& grid,
                                               const reference::FieldFrame& frame, int index,
                                               const FrameWriteOptions& options);
// The InputSpec that reads back what write_frame(s) write for these fields:
// files "frame_%04d.exr" (or .npy, .tif, .png) and each field's channel_name (PNG: R, G, B, A
// in swell's field order, with value_range = png_range).
InputSpec frame_input_spec(const std::vector<reference::Field>& fields,
                           const FrameWriteOptions& options);

// The file a pattern names for frame `index`: one printf integer conversion (%d, %4d, %04d, %i,
// %u; %% is a literal %), and for one file per field (.npy, .raw) the suffix inserted before
// the extension with an underscore: ("frame_%04d.npy", 3, "h") → "frame_0003_h.npy". A pattern
// without a conversion names the same file for every frame. Throws InvalidInput for any other
// conversion or more than one.
std::string frame_file_name(const std::string& pattern, int index, const std::string& suffix = "");

// Reads the frames a case file names (its [input] section), frame times from its [time]
// section. `pattern_override`, when not empty, replaces input.files (relative to the current
// directory, as the command line gives it).
//
// `keep`, when given, says which fields of which frame to keep: the others are still read and
// checked (sizes, finite values) but not stored, so that a caller that needs only some fields
// of some frames (the gate: heights throughout, every field at the ends) saves the memory.
//
// `threads` (0: every hardware thread) read frames in parallel, and decode within a file what
// threads the frames leave over.
using FieldFilter = std::function<bool(int frame, reference::Field field)>;
reference::FrameSequence read_frames(const CaseFile& case_file,
                                     const std::string& pattern_override = "",
                                     const FieldFilter& keep = {}, int threads = 0);

// The precision frames were stored in (reference::FrameSequence's unit_roundoff and
// storage_roundoff), from the largest unit roundoff `stored` of their files and whether every
// value of every frame is a half (`all_halves`): declared by [input] precision (`declared`,
// checked against what was stored; messages begin with `origin`) or detected — float frames
// whose every value is a half were stored in half (a GPU texture widened on the way out). Half
// frames are taken as computed in float32 (2⁻²⁴) and stored to within one ulp (2⁻¹⁰;
// docs/conventions.md §storage precision).
struct FramePrecision {
  double unit_roundoff = 0x1p-53;
  double storage_roundoff = 0;
  bool operator==(const FramePrecision&) const = default;
};
FramePrecision storage_precision(double stored, bool all_halves, const std::string& declared,
                                 const std::string& origin);
bool all_half_values(const reference::FieldFrame& frame);  // every value, imaginary parts included

namespace detail {
struct PixelScratch;
}
// A reading thread's decoding buffers, kept from frame to frame.
class FrameReadScratch {
 public:
  FrameReadScratch();
  ~FrameReadScratch();
  detail::PixelScratch& pixels() { return *pixels_; }

 private:
  std::unique_ptr<detail::PixelScratch> pixels_;
};

// The frames a case file names, read one at a time (read_frames reads them all; the gate streams
// them through io/frame_source.hpp). Made, it has checked the case's [input] and the pattern;
// read() checks each frame's files (sizes, channels, finite values) as read_frames does and
// returns their unit roundoff. `threads_per_file` bounds the threads decoding within one file.
class FrameFileReader {
 public:
  FrameFileReader(const CaseFile& case_file, const std::string& pattern_override = "",
                  int threads_per_file = 1);
  ~FrameFileReader();
  int frames() const;
  const std::string& origin() const;  // "[input] files" or "--input", for messages
  const reference::OceanCase& ocean() const { return ocean_; }
  const InputSpec& input() const { return input_; }
  reference::FrameSequence empty_sequence() const;  // the case's samples, no frames
  // Frame f into `frame` (its fields replaced); fields `keep` rejects are read, checked and
  // dropped. Safe to call from several threads, each with its own scratch.
  double read(int f, reference::FieldFrame& frame, FrameReadScratch& scratch,
              const FieldFilter& keep = {}) const;
  // Throws InvalidInput when a frame beyond the case's last is on disk.
  void require_no_extra_frame() const;
  // storage_precision with the case's declaration; needs_half_scan: whether all_halves matters.
  FramePrecision precision(double stored, bool all_halves) const;
  bool needs_half_scan(double stored) const;

 private:
  struct Layout;
  std::filesystem::path file_of(int f, reference::Field field) const;
  reference::OceanCase ocean_;
  InputSpec input_;
  std::shared_ptr<Layout> layout_;
  int threads_per_file_ = 1;
};

// Frames handed over in memory (the Python module): arrays[field][frame], each as the .npy file
// of that field and frame would hold it (float16, float32, float64, complex64 or complex128;
// (ny, nx), or (N,) on a lattice). Read, checked and given their precision exactly as
// read_frames reads .npy files, with `declared_precision` as [input] precision; messages name
// the field and frame ("height, frame 3: wrong shape …"). Every field needs the case's frame
// count.
reference::FrameSequence frames_from_arrays(const reference::OceanCase& ocean,
                                            const std::string& declared_precision,
                                            const std::map<reference::Field, std::vector<NpyArray>>& arrays);

}  // namespace swell::validation
