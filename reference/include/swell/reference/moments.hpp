#pragma once
// Spectral moments and the periods built from them (docs/conventions.md §Moments), in angular
// frequency: m_n = ∫ ω^n S(ω) dω; Hs = 4 √m0; Tp = 2π/ωp; Tm01 = 2π m0/m1;
// Tm02 = 2π √(m0/m2); Te = Tm−10 = 2π m−1/m0; ε4 = √(1 − m2²/(m0 m4));
// ν = √(m0 m2/m1² − 1) (Longuet-Higgins 1975). A moment that diverges (m4 of an ω⁻⁵ tail over
// the whole spectrum, m−1 of a spectrum with S(0⁺) > 0) is +∞; ε4 then takes its limit, 1.
#include <limits>
#include <vector>

#include "swell/reference/directional.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/grid.hpp"

namespace swell::reference {

// A band of angular frequencies [omega_min, omega_max] in rad/s.
struct Band {
  double omega_min = 0;
  double omega_max = std::numeric_limits<double>::infinity();
  static Band whole() { return {}; }
};

struct Moments {
  double m_minus1 = 0, m0 = 0, m1 = 0, m2 = 0, m4 = 0;
};

struct SeaState {
  Moments moments;
  double omega_p = 0;  // rad/s
  double hs = 0, tp = 0, tm01 = 0, tm02 = 0, te = 0, epsilon4 = 0, nu = 0;
};

// Relative accuracy every quadrature here is held to; a moment that misses it throws
// swell::NumericalError rather than returning a wrong number quietly.
inline constexpr double kMomentRelativeTolerance = 1e-9;

// m_n of S over a band by adaptive Gauss–Kronrod quadrature (Boost.Math), split at the
// spectrum's breakpoints.
double spectral_moment(const FrequencySpectrum& spectrum, int n, Band band = Band::whole());
// The moments and periods; Tp from the peak of S inside the band.
SeaState sea_state(const FrequencySpectrum& spectrum, Band band = Band::whole());

// Band-limited to the wave vectors of a grid: m_n = Σ ω(k)^n Ψ(k) Δkx Δky over every k that
// carries energy (not k = 0, not the Nyquist row and column) — E[mean h²] of a surface
// synthesized on that grid is exactly this m0. Tp is that of the omnidirectional spectrum,
// clamped to the band of ω the grid holds.
SeaState grid_sea_state(const DirectionalSpectrum& spectrum, const Grid& grid);

// The range of ω the grid resolves: from ω(min(Δkx, Δky)) to ω(the largest |k| on it).
Band grid_band(const Grid& grid, const Dispersion& dispersion);

// Periods from moments; ω_p is the peak frequency in rad/s.
SeaState sea_state_from_moments(const Moments& moments, double omega_p);

// A measured spectrum in Hz (buoy files): S_f in m²/Hz at bin-centre frequencies f (Hz) with bin
// widths df (Hz). Moments are Σ S f^n Δf in Hz units — m_n[Hz] = m_n[rad/s] / (2π)^n — and
// the periods (s) are the same as in angular units. Tp from the bin with the largest S.
struct HzSeaState {
  Moments moments_hz;  // m²·Hz^n
  double hs = 0, tp = 0, tm01 = 0, tm02 = 0, te = 0, epsilon4 = 0, nu = 0;
};
HzSeaState measured_sea_state_hz(const std::vector<double>& frequency_hz,
                                 const std::vector<double>& density_m2_per_hz,
                                 const std::vector<double>& bin_width_hz);

}  // namespace swell::reference
