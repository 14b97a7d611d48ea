#include <cmath>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/frequency_spectrum.hpp"

namespace swell::reference {

GaussianSwell::GaussianSwell(double hs, double tp, double sigma)
    : hs_(hs), tp_(tp), sigma_(sigma), omega_p_(2.0 * std::numbers::pi / tp) {}

std::shared_ptr<const GaussianSwell> GaussianSwell::create(double hs, double tp, double sigma) {
  require(std::isfinite(hs) && hs > 0, "hs (significant wave height)", "finite and > 0 m", hs);
  require(std::isfinite(tp) && tp > 0, "tp (peak period)", "finite and > 0 s", tp);
  require(std::isfinite(sigma) && sigma > 0, "sigma (Gaussian width in ω)", "finite and > 0 rad/s",
          sigma);
  return std::shared_ptr<const GaussianSwell>(new GaussianSwell(hs, tp, sigma));
}

double GaussianSwell::operator()(double omega) const {
  if (!(omega > 0)) return 0;
  const double z = (omega - omega_p_) / sigma_;
  // 1/√(2π) σ: the normal density's height, so that the full Gaussian would carry Hs²/16.
  return hs_ * hs_ / 16.0 / (sigma_ * std::sqrt(2.0 * std::numbers::pi)) * std::exp(-0.5 * z * z);
}

std::vector<double> GaussianSwell::breakpoints() const {
  // The mass lies within a few σ of ωp; splitting there keeps a narrow peak (σ ≪ ωp) from
  // slipping between a rule's nodes on [0, ∞). Points at or below ω = 0 are dropped.
  std::vector<double> points;
  for (double k : {-6.0, -2.0, 0.0, 2.0, 6.0}) {
    const double omega = omega_p_ + k * sigma_;
    if (omega > 0) points.push_back(omega);
  }
  return points;
}

double GaussianSwell::energy_fraction() const {
  // Φ(x) = erfc(−x/√2)/2, accurate to rounding for every x (no cancellation in 1 − erfc).
  return 0.5 * std::erfc(-omega_p_ / (sigma_ * std::numbers::sqrt2));
}

std::vector<Parameter> GaussianSwell::parameters() const {
  return {{"hs", hs_, "m"}, {"tp", tp_, "s"}, {"sigma", sigma_, "rad/s"}};
}

}  // namespace swell::reference
