// The synthesizer's options by name (synthesizer.hpp).
#include <string>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"

namespace swell::impls {

std::string to_string(Packing packing) {
  switch (packing) {
    case Packing::complex_pairs: return "complex_pairs";
    case Packing::real: return "real";
    case Packing::automatic: return "automatic";
  }
  return "?";
}

Packing packing_from_string(const std::string& name) {
  if (name == "complex_pairs") return Packing::complex_pairs;
  if (name == "real") return Packing::real;
  if (name == "automatic") return Packing::automatic;
  throw InvalidInput("unknown packing '" + name + "'; valid: complex_pairs, real, automatic");
}

std::string to_string(LatticeTransform transform) {
  switch (transform) {
    case LatticeTransform::automatic: return "automatic";
    case LatticeTransform::one_pass: return "one_pass";
    case LatticeTransform::four_step: return "four_step";
  }
  return "?";
}

LatticeTransform lattice_transform_from_string(const std::string& name) {
  if (name == "automatic") return LatticeTransform::automatic;
  if (name == "one_pass") return LatticeTransform::one_pass;
  if (name == "four_step") return LatticeTransform::four_step;
  throw InvalidInput("unknown lattice transform '" + name +
                     "'; valid: automatic, one_pass, four_step");
}

}  // namespace swell::impls
