#include <cmath>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/spreading.hpp"

namespace swell::reference {
namespace {
constexpr double kPi = std::numbers::pi;

void require_omega(double omega) {
  require(std::isfinite(omega) && omega >= 0, "ω", "finite and ≥ 0 rad/s", omega);
}
}  // namespace

double wrap_angle(double theta) {
  // Within (−π, π) — every atan2 but of ±π — remainder would return θ itself (the quotient
  // rounds to 0): answered without it, a tenth of a spectrum's evaluation.
  if (std::abs(theta) < kPi) return theta;
  double r = std::remainder(theta, 2.0 * kPi);  // in [−π, π]
  if (r <= -kPi) r += 2.0 * kPi;
  return r;
}

// ---------------------------------------------------------------- cos-2s

Cos2s::Cos2s(Law law, double s_or_s_max, double omega_p, double wave_age)
    : law_(law), s_or_s_max_(s_or_s_max), omega_p_(omega_p), wave_age_(wave_age) {
  if (law_ == Law::constant) constant_normalization_ = normalization(s_or_s_max_);
}

std::shared_ptr<const Cos2s> Cos2s::constant(double s) {
  require(std::isfinite(s) && s >= 0, "s (cos-2s spreading exponent)", "finite and ≥ 0", s);
  return std::shared_ptr<const Cos2s>(new Cos2s(Law::constant, s, 0, 0));
}

std::shared_ptr<const Cos2s> Cos2s::mitsuyasu(double s_max, double omega_p) {
  require(std::isfinite(s_max) && s_max >= 0, "s_max (Mitsuyasu spreading at the peak)",
          "finite and ≥ 0", s_max);
  require(std::isfinite(omega_p) && omega_p > 0, "omega_p", "finite and > 0 rad/s", omega_p);
  return std::shared_ptr<const Cos2s>(new Cos2s(Law::mitsuyasu, s_max, omega_p, 0));
}

std::shared_ptr<const Cos2s> Cos2s::hasselmann(double omega_p, double wave_age) {
  require(std::isfinite(omega_p) && omega_p > 0, "omega_p", "finite and > 0 rad/s", omega_p);
  require(std::isfinite(wave_age) && wave_age > 0, "wave_age (U10/cp at the peak)",
          "finite and > 0", wave_age);
  return std::shared_ptr<const Cos2s>(new Cos2s(Law::hasselmann, 0, omega_p, wave_age));
}

double Cos2s::s(double omega) const {
  require_omega(omega);
  switch (law_) {
    case Law::constant:
      return s_or_s_max_;
    case Law::mitsuyasu: {
      // Goda (1985) eq. 2.24 after Mitsuyasu et al. (1975).
      const double r = omega / omega_p_;
      return s_or_s_max_ * (r <= 1 ? std::pow(r, 5.0) : std::pow(r, -2.5));
    }
    case Law::hasselmann: {
      // Hasselmann, Dunckel & Ewing (1980), eq. 41–42.
      const double r = omega / omega_p_;
      if (r < 1.05) return 6.97 * std::pow(r, 4.06);
      return 9.77 * std::pow(r, -2.33 - 1.45 * (wave_age_ - 1.17));
    }
  }
  return 0;  // unreachable: every law is handled above
}

double Cos2s::normalization(double s) {
  // G(s) = 2^(2s−1) Γ(s+1)² / (π Γ(2s+1)), in logarithms so that large s does not overflow.
  return std::exp((2 * s - 1) * std::numbers::ln2 + 2 * std::lgamma(s + 1) - std::lgamma(2 * s + 1)) /
         kPi;
}

double Cos2s::operator()(double omega, double theta) const {
  const double exponent = s(omega);
  const double c = std::cos(0.5 * wrap_angle(theta));  // ≥ 0 on (−π, π]
  return (law_ == Law::constant ? constant_normalization_ : normalization(exponent)) * std::pow(c, 2 * exponent);
}

std::string Cos2s::name() const {
  switch (law_) {
    case Law::constant: return "cos2s";
    case Law::mitsuyasu: return "mitsuyasu";
    case Law::hasselmann: return "hasselmann";
  }
  return "cos2s";
}

std::vector<Parameter> Cos2s::parameters() const {
  switch (law_) {
    case Law::constant: return {{"s", s_or_s_max_, ""}};
    case Law::mitsuyasu: return {{"s_max", s_or_s_max_, ""}, {"omega_p", omega_p_, "rad/s"}};
    case Law::hasselmann: return {{"omega_p", omega_p_, "rad/s"}, {"wave_age", wave_age_, ""}};
  }
  return {};
}

// ---------------------------------------------------------------- Donelan–Banner

std::shared_ptr<const DonelanBanner> DonelanBanner::create(double omega_p) {
  require(std::isfinite(omega_p) && omega_p > 0, "omega_p", "finite and > 0 rad/s", omega_p);
  return std::shared_ptr<const DonelanBanner>(new DonelanBanner(omega_p));
}

double DonelanBanner::beta(double omega) const {
  require_omega(omega);
  const double r = omega / omega_p_;
  if (r < 0.95) return 2.61 * std::pow(r, 1.3);   // Donelan et al. (1985) eq. 8.6
  if (r < 1.6) return 2.28 * std::pow(r, -1.3);   // idem
  return std::pow(10.0, -0.4 + 0.8393 * std::exp(-0.567 * std::log(r * r)));  // Banner (1990)
}

double DonelanBanner::operator()(double omega, double theta) const {
  const double b = beta(omega);
  // β/(2 tanh βπ) → 1/(2π) as β → 0: the uniform distribution (below the 1e-8 cut the
  // relative difference is under 1e-16).
  if (b < 1e-8) return 0.5 / kPi;
  const double sech = 1.0 / std::cosh(b * wrap_angle(theta));
  return b / (2.0 * std::tanh(b * kPi)) * sech * sech;
}

std::vector<Parameter> DonelanBanner::parameters() const {
  return {{"omega_p", omega_p_, "rad/s"}};
}

// ---------------------------------------------------------------- |cos θ|^p

CosPower::CosPower(double p, bool one_sided) : p_(p), one_sided_(one_sided) {
  // ∫ |cos θ|^p dθ over the circle = 2 √π Γ((p+1)/2) / Γ(p/2 + 1).
  const double integral =
      2.0 * std::sqrt(kPi) * std::exp(std::lgamma(0.5 * (p + 1)) - std::lgamma(0.5 * p + 1));
  normalization_ = (one_sided ? 2.0 : 1.0) / integral;
}

std::shared_ptr<const CosPower> CosPower::create(double p, bool one_sided) {
  require(std::isfinite(p) && p >= 0, "p (cos-power exponent)", "finite and ≥ 0", p);
  return std::shared_ptr<const CosPower>(new CosPower(p, one_sided));
}

double CosPower::operator()(double omega, double theta) const {
  require_omega(omega);
  const double c = std::cos(wrap_angle(theta));
  if (one_sided_ && c < 0) return 0;
  return normalization_ * std::pow(std::abs(c), p_);
}

std::vector<Parameter> CosPower::parameters() const {
  return {{"p", p_, ""}, {"one_sided", one_sided_ ? 1.0 : 0.0, ""}};
}

}  // namespace swell::reference
