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
//   [cascades]  relation = "additive" | "independent" | "nested"  crossover = 1.0
//   [[cascade]] n, length, band = [lo, hi] (rad/m), files, channels   a cascade set, instead of
//               [cascade.spectrum] [cascade.spreading] (independent)  [grid] and [input]
//   [sum]       files, channels: the summed surface of an additive or independent set (optional)
#include <filesystem>
#include <map>
#include <optional>
#include <vector>
#include <string>

#include "swell/reference/cascade.hpp"
#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/reference/probe_sea.hpp"

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
  // The precision the frames were stored in: "half", "float" or "double"; empty: the files'
  // own type, or half where every value of float frames is a half (frame_io.hpp).
  std::string precision;
  // Per field, for frames stored as 8- or 16-bit integers (PNG, integer TIFF); every integer
  // channel needs one and a float channel must have none.
  std::map<reference::Field, IntegerRange> value_ranges;
};

enum class SpectrumScale {
  absolute,  // the case's spectrum is the engine's, energy included
  free,      // the engine scales its spectrum by an unknown constant (Phillips' A, a slider)
};

// One cascade of a set (docs/conventions.md §2.2): its grid, its band of |k|, its frames and,
// in a set of independent seas, its own sea.
struct CascadeInput {
  int index = 0;  // its position in the set: cascade 0, 1, …
  reference::Grid grid;
  reference::BandWeight band;  // everywhere (w = 1) unless the case gives one
  InputSpec input;
  std::vector<reference::SeaComponent> components;  // its own sea; empty: the set's
};

// Where a probes case's series are ([input] of a case with [sampling] kind = "probes"): a CSV
// file (a header, a time column, one column per probe), an OpenFAST .out table (its preamble,
// a line of names, a line of units, then whitespace-separated rows), or .npy (samples × probes,
// in the positions' order).
struct ProbeInput {
  std::string files;                // relative to the case file
  std::string time_column;          // CSV and .out: the time column's name
  std::vector<std::string> probes;  // CSV and .out: one column name per probe, in positions' order
};

// A probes case's sampling and synthesis ([sampling] positions, [time] t0, dt, samples, the
// [synthesis] scheme) and its series.
struct ProbeSetup {
  reference::ProbeLayout layout;
  reference::ProbeSynthesis synthesis;
  ProbeInput input;
};

struct CaseFile {
  reference::OceanCase ocean;
  InputSpec input;
  SpectrumScale scale = SpectrumScale::absolute;
  std::filesystem::path origin;     // the case file read (the name given to parse_case_toml)
  std::filesystem::path directory;  // the case file's directory: base of relative paths

  // A probes case ([sampling] kind = "probes"; docs/probes.md): the elevation series at points
  // instead of frames. `ocean` then holds the sea (its grid unused) and `input` is empty.
  std::optional<ProbeSetup> probes;
  bool is_probe_case() const { return probes.has_value(); }
  // The sea with its probes, for the probe synthesis and checks (is_probe_case() only).
  reference::ProbeCase probe_case() const;

  // A cascade set ([cascades] and [[cascade]] tables; docs/conventions.md §2.2): empty for a
  // single-grid case. `ocean` then holds what the cascades share, with cascade 0's grid, and
  // `input` is empty; `sum` reads the summed surface ([sum]) of an additive or independent set.
  std::vector<CascadeInput> cascades;
  reference::CascadeRelation relation = reference::CascadeRelation::additive;
  InputSpec sum;
  bool is_cascade_set() const { return !cascades.empty(); }
  // Cascade c as a case of its own: its grid, band and sea (its own, for an independent sea
  // that declares one), the random numbers of cascade c (additive and independent sets) or of
  // the one sea (nested: cascade key 0 for all).
  reference::OceanCase cascade_case(std::size_t c) const;
  // The cascades as a summed surface sees them (grid, band, random-number key, and each
  // independent sea's Ψ).
  std::vector<reference::CascadeMember> members() const;
  // The summed surface of an additive or independent set on the finest spacing over the largest
  // patch, when the patch lengths allow (reference::summed_grid); nullopt otherwise (with the
  // reason in `why`). An independent set's sum has every cascade's sea as its components.
  std::optional<reference::OceanCase> summed_case(std::string* why = nullptr) const;
};

// A refusal for commands that take one grid: "swell fit takes a single-grid case; FILE is a
// cascade set (swell synth and swell gate take those)".
void require_single_grid(const CaseFile& case_file, const std::string& command);

// Reads and validates a case file. Unknown sections or keys, wrong types, missing required keys
// and non-physical values throw InvalidInput naming the file, the key and the problem.
CaseFile read_case_file(const std::filesystem::path& path);
CaseFile parse_case_toml(const std::string& text, const std::filesystem::path& origin);
// The TOML text of a case (round-trips exactly through parse_case_toml: numbers in shortest
// round-trip form).
std::string case_toml(const CaseFile& case_file);
void write_case_file(const std::filesystem::path& path, const CaseFile& case_file);

}  // namespace swell::validation
