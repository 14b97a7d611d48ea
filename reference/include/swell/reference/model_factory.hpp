#pragma once
// Builds spectra from names and named parameters — one vocabulary for the command line
// (--hs 3 → "hs"), case files and JSON. Unknown names, missing or conflicting parameters and
// non-physical values throw swell::InvalidInput with a message that lists what is valid.
#include <map>
#include <string>
#include <vector>

#include "swell/reference/directional.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/spreading.hpp"

namespace swell::reference {

struct ModelSpec {
  std::string model;                             // "jonswap", "tma", …
  std::map<std::string, double> numbers;         // "hs" → 3.0, "depth" → 10 (may be ∞)
  std::map<std::string, std::string> choices;    // "normalization" → "dnv"
};

std::vector<std::string> frequency_model_names();   // phillips, pierson-moskowitz, …
std::vector<std::string> spreading_model_names();

enum class ModelKind { spectrum, spreading };
// The message for a model name that is not one of `kind`'s: what the name is if it is one of
// the other kind (phillips as a spreading: it carries its own directionality, and its wind
// direction goes with the spectrum), the nearest valid name for a misspelling, and the list.
std::string unknown_model_message(ModelKind kind, const std::string& name);

// Every parameter a model accepts, with its unit and meaning (for --help and errors).
struct ParameterInfo {
  std::string name, unit, meaning;
};
std::vector<ParameterInfo> model_parameters(const std::string& model);

// The frequency spectrum S(ω) of a model. Phillips, a wave-number spectrum, is returned as its
// omnidirectional S(ω) under the dispersion of "depth" and "gravity".
FrequencySpectrumPtr make_frequency_spectrum(const ModelSpec& spec);

// A spreading model ("cos2s", "mitsuyasu", "hasselmann", "donelan-banner", "cos-power",
// "horvath") about a spectrum whose peak is omega_p. A case that knows its wind speed U10 gives
// horvath its wave_age as Horvath::wave_age(U10, omega_p, dispersion).
SpreadingPtr make_spreading(const ModelSpec& spec, double omega_p);

// The dispersion relation a spec implies: "depth" (default ∞) and "gravity" (default 9.81).
Dispersion make_dispersion(const ModelSpec& spec);

}  // namespace swell::reference
