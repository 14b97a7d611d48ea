#include "swell/reference/dispersion.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "swell/reference/errors.hpp"

namespace swell::reference {

Dispersion::Dispersion(double gravity, double depth, double tension_over_density)
    : gravity_(gravity), depth_(depth), tension_over_density_(tension_over_density) {
  require(std::isfinite(gravity) && gravity > 0, "gravity", "finite and > 0 m/s²", gravity);
  require(!std::isnan(depth) && depth > 0, "depth", "> 0 m (or infinite for deep water)", depth);
  require(std::isfinite(tension_over_density) && tension_over_density >= 0,
          "surface tension over density", "finite and ≥ 0 m³/s²", tension_over_density);
}

Dispersion Dispersion::deep(double gravity) { return {gravity, kInfiniteDepth, 0.0}; }

Dispersion Dispersion::finite_depth(double depth, double gravity) { return {gravity, depth, 0.0}; }

Dispersion Dispersion::capillary_gravity(double tension_over_density, double depth,
                                         double gravity) {
  return {gravity, depth, tension_over_density};
}

double Dispersion::omega_squared(double k) const {
  require(k >= 0, "wave number k", "≥ 0 rad/m", k);
  const double restoring = gravity_ * k + tension_over_density_ * k * k * k;
  return is_deep() ? restoring : restoring * std::tanh(k * depth_);
}

double Dispersion::omega(double k) const { return std::sqrt(omega_squared(k)); }

double Dispersion::d_omega_squared_dk(double k) const {
  const double d_restoring = gravity_ + 3.0 * tension_over_density_ * k * k;
  if (is_deep()) return d_restoring;
  const double restoring = gravity_ * k + tension_over_density_ * k * k * k;
  const double kh = k * depth_;
  const double sech = 1.0 / std::cosh(kh);  // cosh overflows to ∞ for kh > 710: sech = 0, right
  return d_restoring * std::tanh(kh) + restoring * depth_ * sech * sech;
}

double Dispersion::group_velocity(double k) const {
  require(k >= 0, "wave number k", "≥ 0 rad/m", k);
  if (k == 0) {
    return is_deep() ? std::numeric_limits<double>::infinity() : std::sqrt(gravity_ * depth_);
  }
  // dω/dk = (dω²/dk) / (2ω).
  return d_omega_squared_dk(k) / (2.0 * omega(k));
}

double Dispersion::phase_velocity(double k) const {
  require(k > 0, "wave number k", "> 0 rad/m for a phase velocity", k);
  return omega(k) / k;
}

double Dispersion::wavenumber(double omega) const {
  require(std::isfinite(omega) && omega >= 0, "angular frequency ω", "finite and ≥ 0 rad/s",
          omega);
  if (omega == 0) return 0;
  const double target = omega * omega;
  // ω > ~1e154: ω² overflows and so does k, which grows at least as ω²/g... or as ω^(2/3) with
  // surface tension, where (gk + τk³/ρ) alone overflows first. Either way k is ∞ in double.
  if (std::isinf(target)) return std::numeric_limits<double>::infinity();
  auto residual = [&](double k) { return omega_squared(k) - target; };

  // Initial guess: Eckart (1952), k ≈ k∞ / √tanh(k∞ h) with k∞ = ω²/g, within ~5 % for gravity
  // waves; capillary terms only make the true k smaller, and the bracket below takes care of it.
  const double k_deep = target / gravity_;
  double k = is_deep() ? k_deep : k_deep / std::sqrt(std::tanh(k_deep * depth_));

  // Bracket: ω²(k) is strictly increasing in k, 0 at k = 0.
  double lo = 0, hi = k;
  while (residual(hi) < 0) {
    lo = hi;
    hi *= 2;
  }
  // Newton's method, falling back to bisection whenever a step leaves [lo, hi] (Press et al.,
  // Numerical Recipes §9.4, "rtsafe"). Converges quadratically from Eckart's guess; the loop
  // stops when a step changes k by less than 1e-15 relative, well inside the 1e-12 promised.
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double f = residual(k);
    if (f == 0) return k;
    (f < 0 ? lo : hi) = k;
    double next = k - f / d_omega_squared_dk(k);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - k) <= 1e-15 * k || hi - lo <= 2e-16 * hi) return next;
    k = next;
  }
  throw NumericalError("dispersion: k(ω) did not converge for ω = " + std::to_string(omega) +
                       " rad/s, " + describe());
}

std::string Dispersion::describe() const {
  std::ostringstream text;
  if (is_deep()) {
    text << "deep water";
  } else {
    text << "finite depth h = " << depth_ << " m";
  }
  text << ", g = " << gravity_ << " m/s²";
  if (tension_over_density_ > 0) text << ", τ/ρ = " << tension_over_density_ << " m³/s²";
  return text.str();
}

double quantize_omega(double omega, double loop_period) {
  require(!std::isnan(loop_period) && loop_period >= 0, "loop period T", "≥ 0 s (0 = none)",
          loop_period);
  if (loop_period == 0 || std::isinf(loop_period)) return omega;
  const double omega0 = 2.0 * std::numbers::pi / loop_period;
  return std::floor(omega / omega0) * omega0;
}

}  // namespace swell::reference
