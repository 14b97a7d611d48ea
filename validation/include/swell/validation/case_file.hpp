#pragma once
// Case files: the TOML an engine developer writes by hand, and what `swell synth` writes as
// DIR/case.toml (docs/case_files.md has the schema). toml++ parses them.
//
//   [grid]      n = [256, 256]  length = [200.0, 200.0]            samples, metres
//   [time]      t0 = 0.0  dt = 0.25  frames = 16                   seconds
//   [physics]   gravity = 9.81  depth = "inf" (or metres)
//   [spectrum]  model = "jonswap"  hs = 3.0  tp = 8.0  gamma = 3.3 … (model_factory vocabulary)
//               scale = "absolute" | "free"
//   [spreading] model = "cos2s"  s = 10.0  wind_dir_deg = 30.0      (phillips: wind_dir_deg here
//                                                                   or in [spectrum])
//   [synthesis] choppiness = 1.0  loop_period = 0.0  seed = 1
//   [input]     files = "frame_%04d.exr"  height = "h"  disp_x = "dx" …
//               value_range = [-4.0, 4.0] (integer images: the values of pixel 0 and the top pixel)
#include <filesystem>
#include <map>
#include <string>

#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"

namespace swell::validation {

// The field values that an integer image's pixel 0 and its largest pixel (255 for 8 bits, 65535
// for 16) stand for, in the field's unit (metres; 1 for the Jacobian): a pixel p of b bits holds
// low + (high − low) · p / (2^b − 1).
struct IntegerRange {
  double low = 0, high = 0;
  bool operator==(const IntegerRange& other) const {
    return low == other.low && high == other.high;
  }
};

// Where the frames of a case are and which channel (EXR/TIFF) or file suffix (.npy/.raw) holds
// each field. A field without a channel is not provided and not checked.
struct InputSpec {
  std::string files;  // printf pattern with one integer (the frame), relative to the case file
  std::map<reference::Field, std::string> channels;
  std::string raw_type = "float32";  // element type of .raw files: float32 | float64
  // Per field, for frames stored as 8- or 16-bit integers (PNG, integer TIFF); every integer
  // channel needs one and a float channel must have none.
  std::map<reference::Field, IntegerRange> value_ranges;
};

enum class SpectrumScale {
  absolute,  // the case's spectrum is the engine's, energy included
  free,      // the engine scales its spectrum by an unknown constant (Phillips' A, a slider)
};

struct CaseFile {
  reference::OceanCase ocean;
  InputSpec input;
  SpectrumScale scale = SpectrumScale::absolute;
  std::filesystem::path directory;  // the case file's directory: base of relative paths
};

// Reads and validates a case file. Unknown sections or keys, wrong types, missing required keys
// and non-physical values throw InvalidInput naming the file, the key and the problem.
CaseFile read_case_file(const std::filesystem::path& path);
CaseFile parse_case_toml(const std::string& text, const std::filesystem::path& origin);
// The TOML text of a case (round-trips exactly through parse_case_toml: numbers in shortest
// round-trip form).
std::string case_toml(const CaseFile& case_file);
void write_case_file(const std::filesystem::path& path, const CaseFile& case_file);

}  // namespace swell::validation
