#pragma once
// Frames on disk, through OpenImageIO (EXR, TIFF) and .npy (npy.hpp):
//
//   exr:  DIR/frame_0000.exr, … one file per frame, float32 channels h, sx, sy, dx, dy, J
//         (reference::channel_name), rows = y (row 0 is j = 0), columns = x.
//   npy:  DIR/frame_0000_h.npy, DIR/frame_0000_dx.npy, … one file per field and frame,
//         shape (ny, nx), float32 (fp32 synthesis) or float64.
//
// Readers check everything against the case (sizes, channels, frame count, finite values) and
// throw InvalidInput naming the file and the problem.
#include <filesystem>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/validation/case_file.hpp"

namespace swell::validation {

enum class FrameFormat { exr, npy, tiff };
FrameFormat frame_format_from_string(const std::string& name);  // "exr" | "npy" | "tiff"
std::string to_string(FrameFormat format);

struct FrameWriteOptions {
  FrameFormat format = FrameFormat::exr;
  bool float64 = false;  // npy only: store float64 instead of float32
};

// Writes every frame of `frames` into `directory` (created if missing) and returns the InputSpec
// that reads them back (files pattern and channels, relative to `directory`).
InputSpec write_frames(const std::filesystem::path& directory,
                       const reference::FrameSequence& frames, const FrameWriteOptions& options);

// Reads the frames a case file names (its [input] section), frame times from its [time]
// section. `pattern_override`, when not empty, replaces input.files (relative to the current
// directory, as the command line gives it).
reference::FrameSequence read_frames(const CaseFile& case_file,
                                     const std::string& pattern_override = "");

}  // namespace swell::validation
