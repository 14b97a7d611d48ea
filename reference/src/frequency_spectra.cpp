#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/moments.hpp"

namespace swell::reference {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// e^x, with the arguments below −746 — where e^x is below half the least subnormal and rounds
// to +0 — answered without calling exp, whose underflow path (errno, a scaled retry) costs
// several times a normal call; far from the peak both spectra's exponentials underflow.
double exp_or_underflow(double x) { return x < -746 ? 0.0 : std::exp(x); }

// a ω⁻⁵ exp(−b ω⁻⁴) without overflow: for tiny ω, ω⁻⁵ alone overflows while the product is 0.
double pierson_moskowitz_shape(double a, double b, double omega) {
  if (omega <= 0) return 0;
  const double x = b / (omega * omega * omega * omega);
  if (x > 700) return a * exp_or_underflow(-x - 5.0 * std::log(omega));
  const double omega5 = omega * omega * omega * omega * omega;
  return a * std::exp(-x) / omega5;
}

void require_positive(double value, const std::string& name, const std::string& unit) {
  require(std::isfinite(value) && value > 0, name, "finite and > 0 " + unit, value);
}

void validate_shape(const Jonswap::Shape& shape) {
  require(std::isfinite(shape.gamma) && shape.gamma >= 1, "gamma (JONSWAP peak enhancement γ)",
          "finite and ≥ 1", shape.gamma);
  require_positive(shape.sigma_a, "sigma_a (JONSWAP peak width below ωp)", "");
  require_positive(shape.sigma_b, "sigma_b (JONSWAP peak width above ωp)", "");
}

std::vector<Parameter> shape_parameters(const Jonswap::Shape& shape) {
  return {{"gamma", shape.gamma, ""}, {"sigma_a", shape.sigma_a, ""},
          {"sigma_b", shape.sigma_b, ""}};
}

}  // namespace

// ---------------------------------------------------------------- Pierson–Moskowitz

PiersonMoskowitz::PiersonMoskowitz(double a, double b, std::string name,
                                   std::vector<Parameter> parameters)
    : a_(a), b_(b), name_(std::move(name)), parameters_(std::move(parameters)) {}

std::shared_ptr<const PiersonMoskowitz> PiersonMoskowitz::from_wind(double u19_5, double gravity) {
  require_positive(u19_5, "u19_5 (wind speed at 19.5 m)", "m/s");
  require_positive(gravity, "gravity", "m/s²");
  // Pierson & Moskowitz (1964), eq. 2: α = 8.1e-3, β = 0.74, ω0 = g/U19.5.
  constexpr double kAlpha = 8.1e-3, kBeta = 0.74;
  const double omega0 = gravity / u19_5;
  const double b = kBeta * std::pow(omega0, 4);
  return std::shared_ptr<const PiersonMoskowitz>(new PiersonMoskowitz(
      kAlpha * gravity * gravity, b, "pierson-moskowitz",
      {{"u19_5", u19_5, "m/s"}, {"alpha", kAlpha, ""}, {"gravity", gravity, "m/s²"}}));
}

std::shared_ptr<const PiersonMoskowitz> PiersonMoskowitz::bretschneider(double hs, double tp) {
  require_positive(hs, "hs (significant wave height)", "m");
  require_positive(tp, "tp (peak period)", "s");
  const double omega_p = kTwoPi / tp;
  const double omega_p4 = std::pow(omega_p, 4);
  return std::shared_ptr<const PiersonMoskowitz>(new PiersonMoskowitz(
      5.0 / 16.0 * hs * hs * omega_p4, 1.25 * omega_p4, "bretschneider",
      {{"hs", hs, "m"}, {"tp", tp, "s"}}));
}

double PiersonMoskowitz::operator()(double omega) const {
  return pierson_moskowitz_shape(a_, b_, omega);
}

// dS/dω = 0 where 4b/ω⁴ = 5.
double PiersonMoskowitz::peak_omega() const { return std::pow(0.8 * b_, 0.25); }

// ---------------------------------------------------------------- JONSWAP

Jonswap::Jonswap(double alpha, double omega_p, Shape shape, double gravity,
                 std::vector<Parameter> parameters)
    : alpha_(alpha), omega_p_(omega_p), shape_(shape), gravity_(gravity),
      parameters_(std::move(parameters)),
      alpha_g2_(alpha_ * gravity_ * gravity_),
      b_(1.25 * std::pow(omega_p_, 4)),
      log_gamma_(std::log(shape_.gamma)) {}

std::shared_ptr<const Jonswap> Jonswap::from_alpha(double alpha, double omega_p, Shape shape,
                                                   double gravity) {
  require_positive(alpha, "alpha (Phillips constant α)", "");
  require_positive(omega_p, "omega_p (peak angular frequency)", "rad/s");
  require_positive(gravity, "gravity", "m/s²");
  validate_shape(shape);
  auto parameters = std::vector<Parameter>{{"alpha", alpha, ""}, {"omega_p", omega_p, "rad/s"}};
  return assemble(alpha, omega_p, shape, gravity, std::move(parameters));
}

std::shared_ptr<const Jonswap> Jonswap::from_wind_fetch(double u10, double fetch, Shape shape,
                                                        double gravity) {
  require_positive(u10, "u10 (wind speed at 10 m)", "m/s");
  require_positive(fetch, "fetch", "m");
  require_positive(gravity, "gravity", "m/s²");
  validate_shape(shape);
  // Hasselmann et al. (1973), with the dimensionless fetch F g / U10².
  const double alpha = 0.076 * std::pow(u10 * u10 / (fetch * gravity), 0.22);
  const double omega_p = 22.0 * std::cbrt(gravity * gravity / (u10 * fetch));
  auto parameters = std::vector<Parameter>{{"u10", u10, "m/s"},
                                           {"fetch", fetch, "m"},
                                           {"alpha", alpha, ""},
                                           {"omega_p", omega_p, "rad/s"}};
  return assemble(alpha, omega_p, shape, gravity, std::move(parameters));
}

std::shared_ptr<const Jonswap> Jonswap::from_hs_tp(double hs, double tp, Shape shape,
                                                   JonswapNormalization normalization,
                                                   double gravity) {
  require_positive(hs, "hs (significant wave height)", "m");
  require_positive(tp, "tp (peak period)", "s");
  require_positive(gravity, "gravity", "m/s²");
  validate_shape(shape);
  const double omega_p = kTwoPi / tp;
  // Bretschneider's α: with γ = 1 it gives m0 = Hs²/16 exactly.
  const double alpha_pm = 5.0 / 16.0 * hs * hs * std::pow(omega_p, 4) / (gravity * gravity);
  double alpha = 0;
  if (normalization == JonswapNormalization::dnv) {
    // DNV-RP-C205 (2010) eq. 3.5.5.2: A_γ = 1 − 0.287 ln γ, an approximation of the m0 ratio.
    alpha = alpha_pm * (1.0 - 0.287 * std::log(shape.gamma));
  } else {
    // Exact: scale α so that the integral of S is Hs²/16.
    const auto unit = Jonswap(1.0, omega_p, shape, gravity, {});
    alpha = hs * hs / 16.0 / spectral_moment(unit, 0);
  }
  auto parameters = std::vector<Parameter>{{"hs", hs, "m"}, {"tp", tp, "s"}};
  parameters.push_back({"alpha", alpha, ""});
  return assemble(alpha, omega_p, shape, gravity, std::move(parameters));
}

// The parameters a factory was given (and α, ωp it derived), then the peak shape's.
std::shared_ptr<const Jonswap> Jonswap::assemble(double alpha, double omega_p, Shape shape,
                                                 double gravity, std::vector<Parameter> parameters) {
  for (auto& p : shape_parameters(shape)) parameters.push_back(p);
  return std::shared_ptr<const Jonswap>(
      new Jonswap(alpha, omega_p, shape, gravity, std::move(parameters)));
}

double Jonswap::operator()(double omega) const {
  if (omega <= 0) return 0;
  const double sigma = omega <= omega_p_ ? shape_.sigma_a : shape_.sigma_b;
  const double d = (omega - omega_p_) / (sigma * omega_p_);
  const double r = exp_or_underflow(-0.5 * d * d);
  return pierson_moskowitz_shape(alpha_g2_, b_, omega) * std::exp(r * log_gamma_);
}

std::vector<double> Jonswap::breakpoints() const {
  // The peak enhancement lives within a few σ of ωp, with a kink in σ at ωp itself.
  return {omega_p_ * (1 - 4 * shape_.sigma_a), omega_p_, omega_p_ * (1 + 4 * shape_.sigma_b)};
}

// ---------------------------------------------------------------- TMA

double kitaigorodskii_exact(double omega, double depth, double gravity) {
  require(std::isfinite(omega) && omega >= 0, "ω", "finite and ≥ 0 rad/s", omega);
  const auto dispersion = Dispersion::finite_depth(depth, gravity);
  if (dispersion.is_deep()) return 1.0;
  if (omega == 0) return 0.0;
  // k ≥ ω²/g (the deep-water k), so beyond ω²h/g = 40: tanh²(kh) = 1 and 2kh/sinh 2kh < 1e-32,
  // Φ = 1 in double. Returning it here also keeps ω → ∞ (where k overflows) finite.
  if (omega * omega * depth / gravity > 40) return 1.0;
  const double kh = dispersion.wavenumber(omega) * depth;
  const double t = std::tanh(kh);
  // sinh overflows to ∞ for kh > 355, where 2kh/sinh(2kh) is 0 to double precision anyway.
  return t * t / (1.0 + 2.0 * kh / std::sinh(2.0 * kh));
}

double kitaigorodskii_thompson_vincent(double omega, double depth, double gravity) {
  require(std::isfinite(omega) && omega >= 0, "ω", "finite and ≥ 0 rad/s", omega);
  require(!std::isnan(depth) && depth > 0, "depth", "> 0 m", depth);
  require_positive(gravity, "gravity", "m/s²");
  const double omega_h = omega * std::sqrt(depth / gravity);  // ∞ in deep water
  if (omega_h <= 1) return 0.5 * omega_h * omega_h;
  if (omega_h < 2) return 1.0 - 0.5 * (2.0 - omega_h) * (2.0 - omega_h);
  return 1.0;
}

Tma::Tma(std::shared_ptr<const Jonswap> jonswap, double depth, TmaFactor factor)
    : jonswap_(std::move(jonswap)), depth_(depth), factor_(factor), peak_omega_(0) {
  // Φ rises with ω, so the peak moves up from the JONSWAP ωp, never by more than a factor 2.
  const double omega_p = jonswap_->peak_omega();
  peak_omega_ = find_peak_omega(*this, 0.5 * omega_p, 2.0 * omega_p);
}

std::shared_ptr<const Tma> Tma::create(std::shared_ptr<const Jonswap> jonswap, double depth,
                                       TmaFactor factor) {
  if (!jonswap) throw InvalidInput("tma needs a JONSWAP spectrum");
  require(!std::isnan(depth) && depth > 0, "depth", "> 0 m (TMA is a finite-depth spectrum)",
          depth);
  return std::shared_ptr<const Tma>(new Tma(std::move(jonswap), depth, factor));
}

double Tma::depth_factor(double omega) const {
  const double g = jonswap_->gravity();
  return factor_ == TmaFactor::exact ? kitaigorodskii_exact(omega, depth_, g)
                                     : kitaigorodskii_thompson_vincent(omega, depth_, g);
}

double Tma::operator()(double omega) const {
  if (omega <= 0) return 0;
  return (*jonswap_)(omega) * depth_factor(omega);
}

std::vector<double> Tma::breakpoints() const {
  auto points = jonswap_->breakpoints();
  points.push_back(peak_omega_);
  if (factor_ == TmaFactor::thompson_vincent) {
    // The Thompson–Vincent branches meet at ωh = 1 and 2, where Φ has a kink.
    const double scale = std::sqrt(jonswap_->gravity() / depth_);
    points.push_back(scale);
    points.push_back(2 * scale);
  }
  std::sort(points.begin(), points.end());
  return points;
}

std::vector<Parameter> Tma::parameters() const {
  auto parameters = jonswap_->parameters();
  parameters.push_back({"depth", depth_, "m"});
  return parameters;
}

// ---------------------------------------------------------------- peak search

double find_peak_omega(const FrequencySpectrum& s, double lo, double hi) {
  require(lo > 0 && hi > lo, "peak search interval", "0 < lo < hi", lo);
  // A log-spaced scan finds the right hump; Brent's method polishes it to ~√ε relative, far
  // finer than any period is reported to.
  constexpr int kScan = 512;
  const double ratio = std::pow(hi / lo, 1.0 / (kScan - 1));
  int best = 0;
  double best_value = -1;
  for (int i = 0; i < kScan; ++i) {
    const double value = s(lo * std::pow(ratio, i));
    if (value > best_value) best_value = value, best = i;
  }
  const double a = lo * std::pow(ratio, std::max(best - 1, 0));
  const double b = lo * std::pow(ratio, std::min(best + 1, kScan - 1));
  const auto [omega, negative_s] = boost::math::tools::brent_find_minima(
      [&](double w) { return -s(w); }, a, b, std::numeric_limits<double>::digits / 2);
  (void)negative_s;
  return omega;
}

}  // namespace swell::reference
