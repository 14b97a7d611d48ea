#include <cmath>
#include <numbers>

#include "swell/reference/directional.hpp"
#include "swell/reference/errors.hpp"

namespace swell::reference {

// ---------------------------------------------------------------- S(ω) D(ω, θ) → Ψ(k)

SpreadSpectrum::SpreadSpectrum(FrequencySpectrumPtr spectrum, SpreadingPtr spreading,
                               Dispersion dispersion, double mean_direction)
    : spectrum_(std::move(spectrum)), spreading_(std::move(spreading)),
      dispersion_(dispersion), mean_direction_(mean_direction) {}

std::shared_ptr<const SpreadSpectrum> SpreadSpectrum::create(FrequencySpectrumPtr spectrum,
                                                             SpreadingPtr spreading,
                                                             Dispersion dispersion,
                                                             double mean_direction) {
  if (!spectrum) throw InvalidInput("a directional spectrum needs a frequency spectrum");
  if (!spreading) throw InvalidInput("a directional spectrum needs a spreading function");
  require(std::isfinite(mean_direction), "mean direction", "finite (radians)", mean_direction);
  return std::shared_ptr<const SpreadSpectrum>(new SpreadSpectrum(
      std::move(spectrum), std::move(spreading), dispersion, mean_direction));
}

SpreadSpectrum::Factors SpreadSpectrum::factors(double kx, double ky) const {
  Factors f;
  f.k = std::hypot(kx, ky);
  if (f.k == 0) return f;
  f.omega = dispersion_.omega(f.k);
  f.theta = std::atan2(ky, kx) - mean_direction_;
  f.spectrum = (*spectrum_)(f.omega);
  f.spreading = (*spreading_)(f.omega, f.theta);
  f.group_velocity = dispersion_.group_velocity(f.k);
  return f;
}

// Ψ(k) k dk dθ = S(ω) D dω dθ  ⇒  Ψ = S D (dω/dk) / k.
double SpreadSpectrum::psi(double kx, double ky) const { return psi_of(factors(kx, ky)); }

// ---------------------------------------------------------------- Phillips

namespace {
double circular_integral_of_cos_power(double p) {
  // ∫ |cos θ|^p dθ over the circle = 2 √π Γ((p+1)/2) / Γ(p/2 + 1).
  return 2.0 * std::sqrt(std::numbers::pi) *
         std::exp(std::lgamma(0.5 * (p + 1)) - std::lgamma(0.5 * p + 1));
}
}  // namespace

Phillips::Phillips(Parameters parameters, Dispersion dispersion)
    : parameters_(parameters), dispersion_(dispersion), directional_integral_(0), peak_omega_(0) {
  // Half the circle has k̂·ŵ < 0 and is scaled by the against-wind factor.
  directional_integral_ = circular_integral_of_cos_power(parameters_.exponent) *
                          0.5 * (1.0 + parameters_.against_wind_factor);
  // Ψ integrated over direction peaks near k = √(2/3)/L (where k⁻³ e^(−1/(kL)²) does); the
  // Jacobian dk/dω moves the peak of S(ω) by less than a factor 2 either way.
  const double L = parameters_.wind_speed * parameters_.wind_speed / dispersion_.gravity();
  const double omega_l = dispersion_.omega(std::sqrt(2.0 / 3.0) / L);
  peak_omega_ = find_peak_omega(*this, 0.25 * omega_l, 4.0 * omega_l);
}

std::shared_ptr<const Phillips> Phillips::create(Parameters p, Dispersion dispersion) {
  require(std::isfinite(p.amplitude) && p.amplitude > 0, "amplitude (Phillips A)",
          "finite and > 0 (dimensionless)", p.amplitude);
  require(std::isfinite(p.wind_speed) && p.wind_speed > 0, "wind_speed (Phillips V)",
          "finite and > 0 m/s", p.wind_speed);
  require(std::isfinite(p.wind_direction), "wind direction", "finite", p.wind_direction);
  require(std::isfinite(p.exponent) && p.exponent >= 0, "exponent (Phillips p)",
          "finite and ≥ 0", p.exponent);
  require(std::isfinite(p.small_wave_cutoff) && p.small_wave_cutoff >= 0,
          "small_wave_cutoff (Phillips l)", "finite and ≥ 0 m", p.small_wave_cutoff);
  require(p.against_wind_factor >= 0 && p.against_wind_factor <= 1, "against_wind_factor",
          "in [0, 1]", p.against_wind_factor);
  return std::shared_ptr<const Phillips>(new Phillips(p, dispersion));
}

double Phillips::radial(double k) const {
  const double L = parameters_.wind_speed * parameters_.wind_speed / dispersion_.gravity();
  const double kl = k * L;
  // e^(−1/(kL)²) is below e^(−1000) (zero in double) for kL < 0.0316, where 1/k⁴ may overflow.
  if (kl < 0.0316) return 0;
  const double k2 = k * k;
  // Beyond k ≈ 1e77, k⁴ overflows and Ψ is 0 in double (avoiding ∞·0 in the cutoff term).
  if (std::isinf(k2 * k2)) return 0;
  const double l = parameters_.small_wave_cutoff;
  return parameters_.amplitude * std::exp(-1.0 / (kl * kl) - k2 * l * l) / (k2 * k2);
}

double Phillips::psi(double kx, double ky) const {
  const double k = std::hypot(kx, ky);
  if (k == 0) return 0;
  const double cosine =
      (kx * std::cos(parameters_.wind_direction) + ky * std::sin(parameters_.wind_direction)) / k;
  const double directional = std::pow(std::abs(cosine), parameters_.exponent) *
                             (cosine < 0 ? parameters_.against_wind_factor : 1.0);
  return radial(k) * directional;
}

double Phillips::directional_integral_of_psi(double k) const {
  return radial(k) * directional_integral_;
}

double Phillips::operator()(double omega) const {
  if (omega <= 0) return 0;
  const double k = dispersion_.wavenumber(omega);
  // S(ω) dω = (∫ Ψ dθ) k dk  ⇒  S = (∫ Ψ dθ) k / (dω/dk).
  const double directional = directional_integral_of_psi(k);
  return directional == 0 ? 0.0 : directional * k / dispersion_.group_velocity(k);
}

double Phillips::tail_exponent() const {
  if (parameters_.small_wave_cutoff > 0) return std::numeric_limits<double>::infinity();
  // Gravity waves: k ~ ω², Ψ k ~ k⁻³ ⇒ S ~ ω⁻⁵. Capillary: k ~ ω^(2/3) ⇒ S ~ ω^(−7/3).
  return dispersion_.tension_over_density() > 0 ? 7.0 / 3.0 : 5.0;
}

std::vector<Parameter> Phillips::parameters() const {
  return {{"amplitude", parameters_.amplitude, ""},
          {"wind_speed", parameters_.wind_speed, "m/s"},
          {"wind_dir", parameters_.wind_direction * 180.0 / std::numbers::pi, "deg"},
          {"exponent", parameters_.exponent, ""},
          {"small_wave_cutoff", parameters_.small_wave_cutoff, "m"},
          {"against_wind_factor", parameters_.against_wind_factor, ""},
          {"depth", dispersion_.depth(), "m"},
          {"gravity", dispersion_.gravity(), "m/s²"}};
}

}  // namespace swell::reference
