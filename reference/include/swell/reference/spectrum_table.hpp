#pragma once
// A measured or modelled spectrum given as a table, in swell's units (docs/conventions.md): a
// 1-D S(ω) in m²·s/rad, or a 2-D E(ω, θ) in m²·s/rad² with θ the direction toward which the
// waves travel, in radians counter-clockwise from +x. Whatever the file's own units and
// direction convention, its reader converts into this form once (and says what it did in
// `notes`); everything downstream sees only this.
#include <string>
#include <vector>

namespace swell::reference {

struct SpectrumTable {
  std::vector<double> omega;    // rad/s, > 0, strictly increasing
  // rad, strictly increasing, each in [0, 2π); empty for a 1-D table (then a spreading model
  // of the case applies, as for a parametric S(ω)).
  std::vector<double> theta;
  // 1-D: S(ω_i), omega.size() values. 2-D: E(ω_i, θ_j) at [i·theta.size() + j].
  std::vector<double> density;
  // Empty: the values are point densities, interpolated linearly in ω between table points.
  // Else one width per ω_i (rad/s): the values are band averages over [ω_i − w_i/2, ω_i + w_i/2]
  // (NDBC's bands), the density is constant over each band and zero outside every band, and
  // m0 = Σ S_i w_i as the buoy's own figures are.
  std::vector<double> band_width;
  std::string source;              // the file and the record selected, for messages
  std::vector<std::string> notes;  // what the reader did to it (clipped, renormalized, …)

  bool is_directional() const { return !theta.empty(); }
};

}  // namespace swell::reference
