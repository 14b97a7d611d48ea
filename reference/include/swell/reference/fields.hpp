#pragma once
// The fields of a surface and a sequence of sampled frames: what a synthesizer produces, what
// files hold and what the checks consume (docs/conventions.md §Derived fields).
//
//   height   h                         m
//   slope_x  ∂h/∂x  ↔ i kx h̃           1
//   slope_y  ∂h/∂y  ↔ i ky h̃           1
//   disp_x   λ Dx,  Dx ↔ i kx/|k| h̃    m   (the displacement actually applied: x + λD)
//   disp_y   λ Dy,  Dy ↔ i ky/|k| h̃    m
//   jacobian J = (1 + λ ∂Dx/∂x)(1 + λ ∂Dy/∂y) − λ² (∂Dx/∂y)²     1
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swell/reference/grid.hpp"
#include "swell/reference/sampling.hpp"

namespace swell::reference {

enum class Field { height, slope_x, slope_y, disp_x, disp_y, jacobian };
inline constexpr std::array<Field, 6> kAllFields = {Field::height, Field::slope_x,
                                                    Field::slope_y, Field::disp_x,
                                                    Field::disp_y, Field::jacobian};

std::string field_name(Field field);     // "height", "slope_x", …, "jacobian" (case files)
std::string channel_name(Field field);   // EXR channel: "h", "sx", "sy", "dx", "dy", "J"
Field field_from_name(const std::string& name);  // either spelling; throws InvalidInput

// One frame: the fields at one time, each nx·ny values, row-major with x fastest.
struct FieldFrame {
  double time = 0;  // s
  std::map<Field, std::vector<double>> fields;
  // Imaginary parts, present only when an engine handed over complex fields (e.g. complex .npy):
  // the Hermitian check measures them.
  std::map<Field, std::vector<double>> imaginary;
};

struct FrameSequence {
  // The samples (sampling()): a grid, or a 2-D lattice (then grid holds its lengths and
  // nx = ny = 0, as in OceanCase). Each field holds sampling().size() values, in sample order.
  Grid grid;
  std::shared_ptr<const RankOneLattice> lattice;
  Sampling sampling() const { return lattice ? Sampling(lattice) : Sampling(grid); }
  std::vector<FieldFrame> frames;
  // Unit roundoff of the arithmetic that made the numbers (2⁻²⁴ for float32 and for half frames,
  // which engines compute in float32; 2⁻⁵³ for float64): what a transform amplifies by log₂N.
  double unit_roundoff = 0x1p-53;
  // Where the stored numbers are coarser than that arithmetic (half): the largest relative error
  // of one stored value, 2⁻¹⁰ (one ulp: drivers may truncate toward zero). 0 where
  // unit_roundoff covers the storage too. Not amplified by any transform: its energy is at most
  // storage_roundoff² of the field's (docs/conventions.md, storage precision).
  double storage_roundoff = 0;

  bool has(Field field) const;  // present in every frame
  const std::vector<double>& field(int frame, Field field) const;  // throws InvalidInput
};

}  // namespace swell::reference
