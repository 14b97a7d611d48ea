#pragma once
// Spectra from files (docs/case_files.md §Spectra from files): a 1-D S(f) from CSV, or a 2-D
// E(f, θ) from netCDF (wavespectra's layout by default, WAVEWATCH III's by naming its
// variables), converted once into swell's units and frame (reference/spectrum_table.hpp) by
// the conventions the case declares — never guessed from the file.
#include <filesystem>
#include <map>
#include <string>

#include "swell/reference/spectrum_table.hpp"

namespace swell::validation {

struct SpectrumTableDeclaration {
  std::filesystem::path file;  // .csv (1-D) or .nc (2-D)
  std::string frequency_unit;        // "Hz" | "rad/s"
  std::string density_unit;          // 1-D: "m2/Hz" | "m2.s/rad"; 2-D: "m2/Hz/deg" | "m2/Hz/rad" | "m2.s/rad/rad"
  std::string direction_convention;  // 2-D: "nautical_from" | "toward_ccw_from_x"
  std::string direction_unit;        // 2-D: "deg" | "rad"
  // netCDF: the density variable and its coordinate variables, and an index for every other
  // dimension of the density variable (time, site, station, …).
  std::string variable = "efth";
  std::string frequency_variable = "freq";
  std::string direction_variable = "dir";
  std::map<std::string, long> select;
};

// The declaration's file read into swell's units: ω in rad/s, θ toward which the waves travel
// in radians counter-clockwise from +x, S in m²·s/rad or E in m²·s/rad². Throws InvalidInput
// naming the file and, for a bad value, its row and column (in the file's own order), for: a
// missing or unknown unit or convention, a file that cannot be read, missing variables or
// dimensions, an index out of range, unsorted axes, negative or non-finite values.
reference::SpectrumTable read_spectrum_table(const SpectrumTableDeclaration& declaration);

// The valid values of each declared convention, for messages and --help.
inline constexpr const char* kFrequencyUnits = "\"Hz\" | \"rad/s\"";
inline constexpr const char* kDensityUnits1d = "\"m2/Hz\" | \"m2.s/rad\"";
inline constexpr const char* kDensityUnits2d = "\"m2/Hz/deg\" | \"m2/Hz/rad\" | \"m2.s/rad/rad\"";
inline constexpr const char* kDirectionConventions = "\"nautical_from\" | \"toward_ccw_from_x\"";
inline constexpr const char* kDirectionUnits = "\"deg\" | \"rad\"";

}  // namespace swell::validation
