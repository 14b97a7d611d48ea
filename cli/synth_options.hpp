#pragma once
// The options of `swell synth` (synth_command.cpp), shared with its probes form
// (probe_synth_command.cpp).
#include <CLI/CLI.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "swell/reference/ocean_case.hpp"

namespace swell::cli {

struct SynthOptions {
  std::string case_file;
  std::string model;
  std::string spreading;
  // Model parameters by name; the CLI::Option tells whether each was given.
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> choices;
  std::map<std::string, CLI::Option*> number_options, choice_options;

  std::string impl;
  std::int64_t points = 0;         // --impl lattice: lattice points
  std::string kind = "korobov";    // --impl lattice: korobov (spectral test) or fibonacci
  int n = 0, ny = 0;
  double length = 0, length_y = 0;
  std::string seed;
  int frames = 1;
  double dt = 0, t0 = 0, gravity = 0, wind_dir = 0, choppiness = 0, loop_period = 0;
  std::string depth;
  std::map<std::string, CLI::Option*> given;  // flag name → option, for the case fields

  std::string precision = "fp32";
  std::string format = "exr";
  std::vector<double> value_range;  // png: the metres pixel 0 and pixel 65535 stand for
  std::vector<std::string> fields;  // --fields: the fields stored (field or channel names)
  std::string out;
  std::string json;
  std::string sum = "auto";  // cascade sets: write the summed surface (yes | no | auto)

  // Probes (docs/probes.md): --sampling probes, or a probes case file.
  std::string sampling;               // "grid" (default), "probes"
  std::vector<double> positions;      // x0,y0,x1,y1,… in m
  std::int64_t samples = 0;
  std::string amplitudes, frequencies, directions;
  double repeat_period = 0;
  std::vector<double> omega_cutoff;   // low,high in rad/s
  int n_directions = 0, n_frequencies = 0;

  bool has(const std::string& flag) const { return given.at(flag)->count() > 0; }
};

// The sea's flags on `ocean`: --model replaces the spectrum, --spreading the spreading model,
// each parameter flag sets that parameter of whichever model takes it, a non-phillips spectrum
// without a spreading model gets cos2s with s = 10; refused on a composite or tabulated sea
// (the case file's to change). Then --depth, --gravity, --wind-dir and --seed.
// `default_spreading`: whether a sea without a spreading model gets the default one (a
// long-crested probes sea needs none).
void apply_sea_flags(const SynthOptions& o, reference::OceanCase& ocean, bool default_spreading = true);

// Writes a probes case's series (the case from --case, or from --sampling probes and its flags)
// to DIR/elevation.csv with DIR/case.toml reading it back (probe_synth_command.cpp).
int run_probe_synth(const SynthOptions& o);

// Whether these options ask for probes: --sampling probes, or a probes case file.
bool wants_probes(const SynthOptions& o);

std::uint64_t parse_seed(const std::string& text);
double parse_depth(const std::string& text);

}  // namespace swell::cli
