#pragma once
// What the gate's analysis holds of a case on its samples while it runs (checks/ocean): work
// beside it — the power table (gate/power.hpp) — reads these rather than compute them again.
#include <cstddef>
#include <vector>

namespace swell::validation {

// One energy-carrying wave vector k of the half plane (its partner −k is implied).
struct HalfPlaneWave {
  std::size_t index = 0, minus_index = 0;  // positions of k and −k in FFT order
  double kx = 0, ky = 0, k = 0;  // rad/m; k = hypot(kx, ky)
  double omega = 0;              // the case's ω(k), rad/s
  double theta = 0;              // atan2(ky, kx), rad
  double mu = 0;         // E I(k) = τ(k) + τ(−k)
  double tau_plus = 0;   // E|a|²: power travelling along +k
  double tau_minus = 0;  // E|b|²: power travelling along −k
};

// The case's expected power on its samples, in FFT order: τ(k) (travelling along k) and
// μ(k) = τ(k) + τ(−k) over every sample, and the half plane's wave vectors in FFT order (those
// that carry energy, one of each ±k pair: reference::in_half_plane).
struct CaseSamples {
  const std::vector<double>& travelling_power;
  const std::vector<double>& expected_periodogram;
  const std::vector<HalfPlaneWave>& half_plane;
};

}  // namespace swell::validation
