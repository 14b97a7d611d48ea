#pragma once
// Directional wave-number spectra Ψ(k) in m⁴ (docs/conventions.md §Spectra):
//     Ψ(k) = S(ω(k)) · D(ω(k), θk − θw) · (dω/dk)(k) / k,     ∫∫ Ψ dk = m0,
// θw the direction (radians, counter-clockwise from +x) toward which the waves travel.
// Phillips (Tessendorf) is defined directly as a wave-number spectrum.
#include <memory>

#include "swell/reference/dispersion.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/spreading.hpp"

namespace swell::reference {

class DirectionalSpectrum {
 public:
  virtual ~DirectionalSpectrum() = default;
  virtual double psi(double kx, double ky) const = 0;  // Ψ(k), 0 at k = 0
  virtual const Dispersion& dispersion() const = 0;
  // The omnidirectional S(ω) = (∫ Ψ(k, θ) k dθ) dk/dω whose moments Ψ carries.
  virtual const FrequencySpectrum& omnidirectional() const = 0;
  virtual double mean_direction() const = 0;  // θw, radians
};

using DirectionalSpectrumPtr = std::shared_ptr<const DirectionalSpectrum>;

// Ψ built from S(ω), D(ω, θ) and the dispersion relation.
class SpreadSpectrum final : public DirectionalSpectrum {
 public:
  static std::shared_ptr<const SpreadSpectrum> create(FrequencySpectrumPtr spectrum,
                                                      SpreadingPtr spreading,
                                                      Dispersion dispersion,
                                                      double mean_direction);
  double psi(double kx, double ky) const override;
  const Dispersion& dispersion() const override { return dispersion_; }
  const FrequencySpectrum& omnidirectional() const override { return *spectrum_; }
  double mean_direction() const override { return mean_direction_; }
  const Spreading& spreading() const { return *spreading_; }

  // Ψ's factors at one wave vector: |k|, ω(|k|), θ = θk − θw, S(ω), D(ω, θ), c_g(|k|) (all 0 at
  // k = 0). psi(kx, ky) is psi_of(factors(kx, ky)), so a sea that differs from this one in S or
  // D alone is evaluated from these with the bits of its own psi.
  struct Factors {
    double k = 0, omega = 0, theta = 0, spectrum = 0, spreading = 0, group_velocity = 0;
  };
  Factors factors(double kx, double ky) const;
  static double psi_of(const Factors& f) {
    return f.k == 0 ? 0.0 : f.spectrum * f.spreading * f.group_velocity / f.k;
  }

 private:
  SpreadSpectrum(FrequencySpectrumPtr spectrum, SpreadingPtr spreading, Dispersion dispersion,
                 double mean_direction);
  FrequencySpectrumPtr spectrum_;
  SpreadingPtr spreading_;
  Dispersion dispersion_;
  double mean_direction_;
};

// Phillips spectrum as Tessendorf (2001) uses it:
//   Ψ(k) = A e^(−1/(kL)²) / k⁴ · |k̂·ŵ|^p · e^(−k² l²),   L = V²/g,
// A dimensionless (Ψ is in m⁴ because 1/k⁴ is), V the wind speed (m/s), ŵ the wind direction, p the
// directional exponent (Tessendorf: 2), l the small-wave cutoff length (m). Waves with
// k̂·ŵ < 0 are multiplied by against_wind_factor (1 keeps them, 0 removes them).
class Phillips final : public DirectionalSpectrum, public FrequencySpectrum {
 public:
  struct Parameters {
    double amplitude = 0;          // A, dimensionless
    double wind_speed = 0;         // V, m/s
    double wind_direction = 0;     // θw, radians
    double exponent = 2;           // p
    double small_wave_cutoff = 0;  // l, m
    double against_wind_factor = 1;
  };
  static std::shared_ptr<const Phillips> create(Parameters parameters, Dispersion dispersion);

  // DirectionalSpectrum
  double psi(double kx, double ky) const override;
  const Dispersion& dispersion() const override { return dispersion_; }
  const FrequencySpectrum& omnidirectional() const override { return *this; }
  double mean_direction() const override { return parameters_.wind_direction; }

  // FrequencySpectrum: the omnidirectional S(ω) through the dispersion relation.
  double operator()(double omega) const override;
  double peak_omega() const override { return peak_omega_; }
  double tail_exponent() const override;
  std::string name() const override { return "phillips"; }
  std::vector<Parameter> parameters() const override;

  // ∫ Ψ(k, θ) dθ over the circle: the radial part times the closed-form directional integral.
  double directional_integral_of_psi(double k) const;

 private:
  Phillips(Parameters parameters, Dispersion dispersion);
  double radial(double k) const;  // A e^(−1/(kL)²) / k⁴ e^(−k² l²)
  Parameters parameters_;
  Dispersion dispersion_;
  double directional_integral_;  // ∫ |cos θ|^p × (1 or against_wind_factor) dθ
  double peak_omega_;
};

}  // namespace swell::reference
