#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "swell/reference/errors.hpp"
#include "swell/reference/frequency_spectrum.hpp"

namespace swell::reference {
namespace {

void validate(const OchiHubbleComponent& c, const std::string& j) {
  require(std::isfinite(c.hs) && c.hs > 0,
          "hs" + j + " (significant wave height of component " + j + ")", "finite and > 0 m", c.hs);
  require(std::isfinite(c.tp) && c.tp > 0, "tp" + j + " (peak period of component " + j + ")",
          "finite and > 0 s", c.tp);
  require(std::isfinite(c.lambda) && c.lambda > 0, "lambda" + j + " (shape of component " + j + ")",
          "finite and > 0", c.lambda);
}

}  // namespace

OchiHubble::OchiHubble(std::array<OchiHubbleComponent, 2> components)
    : components_(components), omega_p_{}, log_scale_{}, peak_omega_(0) {
  for (int j = 0; j < 2; ++j) {
    const auto& c = components_[j];
    omega_p_[j] = 2.0 * std::numbers::pi / c.tp;
    // log of (1/4) [((4λ + 1)/4) ωp⁴]^λ Hs² / Γ(λ): the whole prefactor in logarithms, since
    // ωp^(4λ) and Γ(λ) alone overflow or underflow for large λ while their ratio does not.
    const double c4 = (4.0 * c.lambda + 1.0) / 4.0;
    log_scale_[j] = std::log(0.25) + c.lambda * (std::log(c4) + 4.0 * std::log(omega_p_[j])) -
                    std::lgamma(c.lambda) + 2.0 * std::log(c.hs);
  }
  // Each component rises below its ωpj and falls above it, so the sum's maximum lies between
  // the two peaks.
  const double lo = std::min(omega_p_[0], omega_p_[1]), hi = std::max(omega_p_[0], omega_p_[1]);
  peak_omega_ = hi > lo * (1 + 1e-12) ? find_peak_omega(*this, lo, hi) : lo;
}

std::shared_ptr<const OchiHubble> OchiHubble::create(OchiHubbleComponent first,
                                                     OchiHubbleComponent second) {
  validate(first, "1");
  validate(second, "2");
  return std::shared_ptr<const OchiHubble>(new OchiHubble({first, second}));
}

double OchiHubble::component(int j, double omega) const {
  if (!(omega > 0)) return 0;
  const auto& c = components_.at(j);
  const double c4 = (4.0 * c.lambda + 1.0) / 4.0;
  const double ratio = omega_p_[j] / omega;
  const double ratio2 = ratio * ratio;
  // exp of a sum of logarithms: ω^−(4λ+1) overflows for tiny ω where the exponential factor
  // has long underflowed, and the prefactor alone can leave double's range (see above).
  return std::exp(log_scale_[j] - (4.0 * c.lambda + 1.0) * std::log(omega) -
                  c4 * ratio2 * ratio2);
}

double OchiHubble::operator()(double omega) const {
  return component(0, omega) + component(1, omega);
}

double OchiHubble::tail_exponent() const {
  return 4.0 * std::min(components_[0].lambda, components_[1].lambda) + 1.0;
}

std::vector<double> OchiHubble::breakpoints() const {
  std::vector<double> points = {omega_p_[0], omega_p_[1], peak_omega_};
  std::sort(points.begin(), points.end());
  return points;
}

std::vector<Parameter> OchiHubble::parameters() const {
  const auto& a = components_[0];
  const auto& b = components_[1];
  return {{"hs1", a.hs, "m"}, {"tp1", a.tp, "s"}, {"lambda1", a.lambda, ""},
          {"hs2", b.hs, "m"}, {"tp2", b.tp, "s"}, {"lambda2", b.lambda, ""}};
}

}  // namespace swell::reference
