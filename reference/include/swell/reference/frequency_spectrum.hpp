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
  // operator()'s constants, made once (a pow and a log per evaluation were a tenth of the
  // gate's τ(k) at 4096²): α g², 1.25 ωp⁴ and log γ.
  double alpha_g2_ = 0, b_ = 0, log_gamma_ = 0;
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

// Gaussian swell spectrum, DNV-RP-C205 (2010) §3.5.6 (two-peak spectra: the swell part):
//   S(ω) = (Hs²/16) / (σ √(2π)) · exp(−(ω − ωp)² / (2σ²)) for ω > 0,   ωp = 2π/Tp,
// σ the width in ω (rad/s). The formula is kept as published, not renormalized: S is 0 for
// ω ≤ 0 (docs/conventions.md §3.1), so the Gaussian's part below ω = 0 is cut off and
//   m0 = (Hs²/16) Φ(ωp/σ),   Φ the standard normal CDF,
// i.e. Hs²/16 less (Hs²/16) Φ(−ωp/σ): 1.3e-3 of it at σ = ωp/3, 7.6e-24 at σ = ωp/10.
// S(0⁺) > 0, so m−1 (and Te) diverge; every m_n with n ≥ 0 is finite.
class GaussianSwell final : public FrequencySpectrum {
 public:
  static std::shared_ptr<const GaussianSwell> create(double hs, double tp, double sigma);

  double operator()(double omega) const override;
  double peak_omega() const override { return omega_p_; }
  double tail_exponent() const override { return std::numeric_limits<double>::infinity(); }
  double low_frequency_exponent() const override { return 0.0; }
  std::vector<double> breakpoints() const override;
  std::string name() const override { return "gaussian"; }
  std::vector<Parameter> parameters() const override;

  // Φ(ωp/σ): the share of the full Gaussian's Hs²/16 that lies above ω = 0, so m0 / (Hs²/16).
  double energy_fraction() const;

 private:
  GaussianSwell(double hs, double tp, double sigma);
  double hs_, tp_, sigma_, omega_p_;
};

// One component of the Ochi–Hubble spectrum: significant height Hs (m), peak period Tp (s) and
// shape λ (dimensionless, > 0; λ = 1 is the Bretschneider spectrum).
struct OchiHubbleComponent {
  double hs;
  double tp;
  double lambda;
};

// Ochi & Hubble (1976), the six-parameter spectrum (in ω):
//   S(ω) = Σ_j (1/4) [((4λj + 1)/4) ωpj⁴]^λj / Γ(λj) · Hsj² / ω^(4λj + 1)
//                · exp(−((4λj + 1)/4) (ωpj/ω)⁴),         ωpj = 2π/Tpj, j = 1, 2.
// Each component peaks at its ωpj and carries exactly Hsj²/16, so m0 = (Hs1² + Hs2²)/16; its
// moments are m_n,j = (Hsj²/16) ωpj^n ((4λj + 1)/4)^(n/4) Γ(λj − n/4) / Γ(λj) for n < 4λj.
// peak_omega() is the maximum of the sum, found numerically between the two ωpj.
class OchiHubble final : public FrequencySpectrum {
 public:
  static std::shared_ptr<const OchiHubble> create(OchiHubbleComponent first,
                                                  OchiHubbleComponent second);

  double operator()(double omega) const override;
  double peak_omega() const override { return peak_omega_; }
  // The slower-decaying component sets the tail: ω^−(4 min λj + 1).
  double tail_exponent() const override;
  std::vector<double> breakpoints() const override;
  std::string name() const override { return "ochi-hubble"; }
  std::vector<Parameter> parameters() const override;

  // S_j(ω) of component j = 0 (first) or 1 (second).
  double component(int j, double omega) const;
  const OchiHubbleComponent& component_parameters(int j) const { return components_.at(j); }

 private:
  explicit OchiHubble(std::array<OchiHubbleComponent, 2> components);
  std::array<OchiHubbleComponent, 2> components_;
  std::array<double, 2> omega_p_, log_scale_;
  double peak_omega_;
};

// One peak of the Torsethaugen spectrum: its significant height (m), peak period (s) and
// peak enhancement γ (1 for the secondary peak).
struct TorsethaugenPeak {
  double hs;
  double tp;
  double gamma;
};

// Torsethaugen & Haver (2004), the simplified two-peak model, as DNV-RP-C205 (2010, 2014)
// §3.5.6 gives it: the sum of a primary and a secondary peak, each a gamma spectrum (N = M = 4)
// with JONSWAP peak enhancement,
//   S(ω) = Σ_j E_j · G0 Aγj · x^−4 exp(−x^−4) · γj^exp(−(x − 1)²/(2σ²)),   x = ω Tpj/(2π),
//   E_j = (1/(2π)) (1/16) Hsj² Tpj,   G0 = 3.26,   Aγ = (1 + 1.1 (ln γ)^1.19) / γ,
//   σ = 0.07 for x < 1, 0.09 for x ≥ 1.
// Hs and Tp split the sea at Tpf = 6.6 Hs^(1/3): wind-sea dominated for Tp ≤ Tpf, swell
// dominated above (the peaks' Hs, Tp and γ: docs/conventions.md §3.3). The model holds for
// 2√Hs ≤ Tp ≤ 25 s, where the paper's ε_l and ε_u lie in [0, 1]; outside it is refused.
// G0 and Aγ are DNV's rounded fits, so m0 is not Hs²/16: m0/(Hs²/16) runs from 0.988 to
// 1.035 over Hs = 0.5…15 m (measured by quadrature; docs/conventions.md §3.3). γ < 1, which
// leaves Aγ undefined, is held at 1. The tail is ω⁻⁴: m3 and m4 diverge.
class Torsethaugen final : public FrequencySpectrum {
 public:
  static std::shared_ptr<const Torsethaugen> create(double hs, double tp,
                                                    double gravity = kStandardGravity);

  double operator()(double omega) const override;
  double peak_omega() const override { return peak_omega_; }
  double tail_exponent() const override { return 4.0; }
  std::vector<double> breakpoints() const override;
  std::string name() const override { return "torsethaugen"; }
  std::vector<Parameter> parameters() const override;

  bool swell_dominated() const { return swell_dominated_; }
  double tpf() const { return tpf_; }  // 6.6 Hs^(1/3), s
  const TorsethaugenPeak& primary() const { return peaks_[0]; }
  const TorsethaugenPeak& secondary() const { return peaks_[1]; }
  // E_j G0 Aγj x^−4 exp(−x^−4) γj^r of peak j = 0 (primary) or 1 (secondary).
  double peak_spectrum(int j, double omega) const;

 private:
  Torsethaugen(double hs, double tp, double gravity);
  double hs_, tp_, gravity_, tpf_;
  bool swell_dominated_;
  std::array<TorsethaugenPeak, 2> peaks_;
  double peak_omega_;
};

// ω at the maximum of S on [lo, hi] (a scan then Brent's method); used where no closed form is.
double find_peak_omega(const FrequencySpectrum& s, double lo, double hi);

}  // namespace swell::reference
