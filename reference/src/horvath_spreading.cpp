#include <cmath>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/spreading.hpp"

namespace swell::reference {
namespace {

// Horvath (2015), the swell elongation: s_ξ = 16 tanh(ωp/ω) ξ². (His released EncinoWaves code
// first wrote 16.1, later 16, as the paper does.)
constexpr double kSwellShapeScale = 16.0;

}  // namespace

Horvath::Horvath(double omega_p, Parameters parameters)
    : omega_p_(omega_p), parameters_(parameters) {}

std::shared_ptr<const Horvath> Horvath::create(double omega_p, Parameters p) {
  require(std::isfinite(omega_p) && omega_p > 0, "omega_p", "finite and > 0 rad/s", omega_p);
  require(std::isfinite(p.wave_age) && p.wave_age > 0, "wave_age (U10/cp at the peak)",
          "finite and > 0", p.wave_age);
  require(std::isfinite(p.swell) && p.swell >= 0, "swell (Horvath's elongation ξ)",
          "finite and ≥ 0", p.swell);
  require(p.spread_blend >= 0 && p.spread_blend <= 1, "spread_blend (weight of the uniform spread)",
          "in [0, 1]", p.spread_blend);
  return std::shared_ptr<const Horvath>(new Horvath(omega_p, p));
}

double Horvath::wave_age(double u10, double omega_p, const Dispersion& dispersion) {
  require(std::isfinite(u10) && u10 > 0, "u10 (wind speed at 10 m)", "finite and > 0 m/s", u10);
  require(std::isfinite(omega_p) && omega_p > 0, "omega_p", "finite and > 0 rad/s", omega_p);
  // cp = ωp/kp: U10/cp = U10 kp/ωp, with kp from the case's dispersion relation.
  return u10 * dispersion.wavenumber(omega_p) / omega_p;
}

double Horvath::s(double omega) const {
  require(std::isfinite(omega) && omega >= 0, "ω", "finite and ≥ 0 rad/s", omega);
  const double r = omega / omega_p_;
  // The paper's branch: the lower law up to and including ωp (Hasselmann et al. 1980 switch at
  // 1.05 ωp; Cos2s::hasselmann keeps theirs).
  if (r <= 1) return 6.97 * std::pow(r, 4.06);
  return 9.77 * std::pow(r, -2.33 - 1.45 * (parameters_.wave_age - 1.17));
}

double Horvath::swell_exponent(double omega) const {
  require(std::isfinite(omega) && omega >= 0, "ω", "finite and ≥ 0 rad/s", omega);
  // ω = 0: ωp/ω = ∞ and tanh(∞) = 1, the limit.
  const double xi = parameters_.swell;
  return kSwellShapeScale * std::tanh(omega_p_ / omega) * xi * xi;
}

double Horvath::operator()(double omega, double theta) const {
  const double b = parameters_.spread_blend;
  const double uniform = 0.5 / std::numbers::pi;
  if (b == 1) return uniform;
  const double exponent = s(omega) + swell_exponent(omega);
  const double c = std::cos(0.5 * wrap_angle(theta));  // ≥ 0 on (−π, π]
  const double directional = Cos2s::normalization(exponent) * std::pow(c, 2 * exponent);
  return (1 - b) * directional + b * uniform;
}

std::vector<Parameter> Horvath::parameters() const {
  return {{"omega_p", omega_p_, "rad/s"},
          {"wave_age", parameters_.wave_age, ""},
          {"swell", parameters_.swell, ""},
          {"spread_blend", parameters_.spread_blend, ""}};
}

}  // namespace swell::reference
