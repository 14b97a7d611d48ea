#pragma once
// One-sided frequency spectra S(ω) in m²·s/rad of angular frequency ω in rad/s
// (docs/conventions.md §Spectra). Every model is immutable once built; factories validate their
// arguments and throw swell::InvalidInput naming the parameter that is wrong.
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "swell/reference/dispersion.hpp"

namespace swell::reference {

struct Parameter {
  std::string name;   // snake_case, as in JSON output: "hs", "tp", "gamma", …
  double value;
  std::string unit;   // "m", "s", "rad/s", "" for dimensionless
};

class FrequencySpectrum {
 public:
  virtual ~FrequencySpectrum() = default;
  virtual double operator()(double omega) const = 0;  // S(ω); 0 for ω ≤ 0
  // ω at the maximum of S.
  virtual double peak_omega() const = 0;
  // p such that S(ω) ~ ω^(−p) as ω → ∞ (∞ for a faster decay). m_n is finite iff n < p − 1.
  virtual double tail_exponent() const = 0;
  // q such that S(ω) ~ ω^q as ω → 0⁺ (∞ for a faster decay, as exp(−b ω⁻⁴)). A moment over a
  // band from ω = 0 is finite iff n > −q − 1: S(0⁺) > 0 (q = 0) makes m−1 diverge.
  virtual double low_frequency_exponent() const { return std::numeric_limits<double>::infinity(); }
  // Frequencies where S changes character (peak, branch boundaries of a piecewise law);
  // quadrature splits its interval there.
  virtual std::vector<double> breakpoints() const { return {peak_omega()}; }
  virtual std::string name() const = 0;                 // "jonswap", "tma", …
  virtual std::vector<Parameter> parameters() const = 0;
};

using FrequencySpectrumPtr = std::shared_ptr<const FrequencySpectrum>;

// Pierson–Moskowitz family: S(ω) = a ω⁻⁵ exp(−b ω⁻⁴).
class PiersonMoskowitz final : public FrequencySpectrum {
 public:
  // Pierson & Moskowitz (1964): a = α g², α = 8.1e-3; b = β (g/U19.5)⁴, β = 0.74;
  // u19_5 is the wind speed 19.5 m above the sea, m/s.
  static std::shared_ptr<const PiersonMoskowitz> from_wind(double u19_5,
                                                           double gravity = kStandardGravity);
  // Bretschneider form: a = (5/16) Hs² ωp⁴, b = (5/4) ωp⁴, so m0 = Hs²/16 exactly.
  static std::shared_ptr<const PiersonMoskowitz> bretschneider(double hs, double tp);

  double operator()(double omega) const override;
  double peak_omega() const override;
  double tail_exponent() const override { return 5.0; }
  std::string name() const override { return name_; }
  std::vector<Parameter> parameters() const override { return parameters_; }

 private:
  PiersonMoskowitz(double a, double b, std::string name, std::vector<Parameter> parameters);
  double a_, b_;
  std::string name_;
  std::vector<Parameter> parameters_;
};

enum class JonswapNormalization {
  exact,  // α chosen so that ∫ S dω = Hs²/16 (by quadrature)
  dnv,    // DNV-RP-C205: (1 − 0.287 ln γ) × Pierson–Moskowitz(Hs, Tp) — approximate
};

// JONSWAP (Hasselmann et al. 1973):
//   S(ω) = α g² ω⁻⁵ exp(−(5/4)(ωp/ω)⁴) γ^r,   r = exp(−(ω − ωp)² / (2 σ² ωp²)),
//   σ = σa for ω ≤ ωp, σb above.
struct JonswapShape {
  double gamma = 3.3;     // peak enhancement γ ≥ 1
  double sigma_a = 0.07;  // peak width below ωp
  double sigma_b = 0.09;  // peak width above ωp
};

class Jonswap final : public FrequencySpectrum {
 public:
  using Shape = JonswapShape;
  static std::shared_ptr<const Jonswap> from_alpha(double alpha, double omega_p, Shape shape = {},
                                                   double gravity = kStandardGravity);
  // Hasselmann 1973: α = 0.076 (U10²/(F g))^0.22, ωp = 22 (g²/(U10 F))^(1/3); fetch F in m.
  static std::shared_ptr<const Jonswap> from_wind_fetch(double u10, double fetch, Shape shape = {},
                                                        double gravity = kStandardGravity);
  static std::shared_ptr<const Jonswap> from_hs_tp(
      double hs, double tp, Shape shape = {},
      JonswapNormalization normalization = JonswapNormalization::exact,
      double gravity = kStandardGravity);

  double operator()(double omega) const override;
  double peak_omega() const override { return omega_p_; }
  double tail_exponent() const override { return 5.0; }
  std::vector<double> breakpoints() const override;
  std::string name() const override { return "jonswap"; }
  std::vector<Parameter> parameters() const override { return parameters_; }

  double alpha() const { return alpha_; }
  const Shape& shape() const { return shape_; }
  double gravity() const { return gravity_; }

 private:
  Jonswap(double alpha, double omega_p, Shape shape, double gravity,
          std::vector<Parameter> parameters);
  static std::shared_ptr<const Jonswap> assemble(double alpha, double omega_p, Shape shape,
                                                 double gravity, std::vector<Parameter> parameters);
  double alpha_, omega_p_;
  Shape shape_;
  double gravity_;
  std::vector<Parameter> parameters_;
};

enum class TmaFactor {
  exact,             // Kitaigorodskii et al. 1975: Φ = tanh²(kh) / (1 + 2kh / sinh 2kh)
  thompson_vincent,  // Thompson & Vincent 1983: piecewise in ωh = ω √(h/g)
};

// Kitaigorodskii depth factor Φ(ω, h), both forms; h may be kInfiniteDepth (Φ = 1).
double kitaigorodskii_exact(double omega, double depth, double gravity = kStandardGravity);
double kitaigorodskii_thompson_vincent(double omega, double depth,
                                       double gravity = kStandardGravity);

// TMA (Bouws et al. 1985): S_TMA(ω) = S_JONSWAP(ω) Φ(ω, h). The JONSWAP part keeps its own
// parameters (with from_hs_tp, its deep-water Hs); the TMA spectrum's Hs is smaller.
class Tma final : public FrequencySpectrum {
 public:
  static std::shared_ptr<const Tma> create(std::shared_ptr<const Jonswap> jonswap, double depth,
                                           TmaFactor factor = TmaFactor::exact);

  double operator()(double omega) const override;
  double peak_omega() const override { return peak_omega_; }
  double tail_exponent() const override { return 5.0; }
  std::vector<double> breakpoints() const override;
  std::string name() const override { return "tma"; }
  std::vector<Parameter> parameters() const override;
  double depth_factor(double omega) const;

 private:
  Tma(std::shared_ptr<const Jonswap> jonswap, double depth, TmaFactor factor);
  std::shared_ptr<const Jonswap> jonswap_;
  double depth_;
  TmaFactor factor_;
  double peak_omega_;
};

// ω at the maximum of S on [lo, hi] (a scan then Brent's method); used where no closed form is.
double find_peak_omega(const FrequencySpectrum& s, double lo, double hi);

}  // namespace swell::reference
