#pragma once
// Linear dispersion relation of surface gravity(-capillary) waves (docs/conventions.md §Dispersion):
//     ω² = (g k + (τ/ρ) k³) · tanh(k h)
// deep water is h = ∞, pure gravity waves τ/ρ = 0. Units: k in rad/m, ω in rad/s, h in m,
// g in m/s², τ/ρ in m³/s².
#include <limits>
#include <string>

namespace swell::reference {

inline constexpr double kStandardGravity = 9.81;           // m/s², swell's default (not 9.80665)
inline constexpr double kInfiniteDepth = std::numeric_limits<double>::infinity();
// Surface tension over density of sea water near 20 °C: 0.0728 N/m / 1025 kg/m³.
inline constexpr double kSeaWaterTensionOverDensity = 0.0728 / 1025.0;

class Dispersion {
 public:
  // ω² = g k.
  static Dispersion deep(double gravity = kStandardGravity);
  // ω² = g k tanh(k h); depth = kInfiniteDepth gives deep water.
  static Dispersion finite_depth(double depth, double gravity = kStandardGravity);
  // ω² = (g k + (τ/ρ) k³) tanh(k h).
  static Dispersion capillary_gravity(double tension_over_density,
                                      double depth = kInfiniteDepth,
                                      double gravity = kStandardGravity);

  double omega(double k) const;             // ω(k), k ≥ 0
  double omega_squared(double k) const;     // ω²(k), exact at k = 0
  // k(ω) for ω ≥ 0 by safeguarded Newton iteration, converged to 1e-12 relative or better.
  double wavenumber(double omega) const;
  double group_velocity(double k) const;    // dω/dk; √(g h) at k = 0 in finite depth, ∞ if deep
  double phase_velocity(double k) const;    // ω/k

  double gravity() const { return gravity_; }
  double depth() const { return depth_; }
  double tension_over_density() const { return tension_over_density_; }
  bool is_deep() const { return depth_ == kInfiniteDepth; }
  std::string describe() const;  // e.g. "finite depth h = 10 m, g = 9.81"

 private:
  Dispersion(double gravity, double depth, double tension_over_density);
  double d_omega_squared_dk(double k) const;

  double gravity_;
  double depth_;
  double tension_over_density_;
};

// A loop period T makes every ω a multiple of ω0 = 2π/T (rounded down), so the surface repeats
// after T seconds. loop_period = 0 leaves ω unchanged.
double quantize_omega(double omega, double loop_period);

}  // namespace swell::reference
