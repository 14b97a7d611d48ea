#pragma once
// Directional spreading D(ω, θ): θ in radians from the mean direction toward which the waves
// travel; ∫ D dθ over (−π, π] = 1 for every ω (docs/conventions.md §Spectra). Any real θ is
// accepted and wrapped to (−π, π].
#include <memory>
#include <string>
#include <vector>

#include "swell/reference/dispersion.hpp"
#include "swell/reference/frequency_spectrum.hpp"

namespace swell::reference {

class Spreading {
 public:
  virtual ~Spreading() = default;
  virtual double operator()(double omega, double theta) const = 0;
  virtual std::string name() const = 0;
  virtual std::vector<Parameter> parameters() const = 0;
};

using SpreadingPtr = std::shared_ptr<const Spreading>;

// cos-2s (Longuet-Higgins et al. 1963): D = G(s) cos^(2s)(θ/2),
//   G(s) = 2^(2s−1) Γ(s+1)² / (π Γ(2s+1)).
// s is constant, or follows a law in ω/ωp:
//   Mitsuyasu et al. 1975 as given by Goda (1985): s = s_max (ω/ωp)^5 for ω ≤ ωp,
//                                                   s_max (ω/ωp)^−2.5 above;
//   Hasselmann, Dunckel & Ewing (1980): s = 6.97 (ω/ωp)^4.06 for ω < 1.05 ωp,
//        9.77 (ω/ωp)^μ above, μ = −2.33 − 1.45 (U10/cp − 1.17) (U10/cp: wave age at the peak).
class Cos2s final : public Spreading {
 public:
  static std::shared_ptr<const Cos2s> constant(double s);
  static std::shared_ptr<const Cos2s> mitsuyasu(double s_max, double omega_p);
  static std::shared_ptr<const Cos2s> hasselmann(double omega_p, double wave_age = 1.17);

  double operator()(double omega, double theta) const override;
  double s(double omega) const;                   // the spreading exponent at ω
  static double normalization(double s);          // G(s)
  std::string name() const override;
  std::vector<Parameter> parameters() const override;

 private:
  enum class Law { constant, mitsuyasu, hasselmann };
  Cos2s(Law law, double s_or_s_max, double omega_p, double wave_age);
  Law law_;
  double s_or_s_max_, omega_p_, wave_age_;
  double constant_normalization_ = 0;  // G(s) of the constant law, made once (two lgamma per call were a third of Ψ's time)
};

// Donelan, Hamilton & Hui (1985) with Banner's (1990) high-frequency branch:
//   D = β sech²(βθ) / (2 tanh(βπ))  (the tanh makes it integrate to 1 over the circle),
//   β = 2.61 (ω/ωp)^1.3 for ω/ωp < 0.95 (Donelan's range starts at 0.56; below, the same law),
//       2.28 (ω/ωp)^−1.3 for 0.95 ≤ ω/ωp < 1.6,
//       10^(−0.4 + 0.8393 exp(−0.567 ln((ω/ωp)²))) for ω/ωp ≥ 1.6 (Banner 1990).
class DonelanBanner final : public Spreading {
 public:
  static std::shared_ptr<const DonelanBanner> create(double omega_p);
  double operator()(double omega, double theta) const override;
  double beta(double omega) const;
  std::string name() const override { return "donelan-banner"; }
  std::vector<Parameter> parameters() const override;

 private:
  explicit DonelanBanner(double omega_p) : omega_p_(omega_p) {}
  double omega_p_;
};

// D = C |cos θ|^p over the whole circle, C = Γ(p/2 + 1) / (2 √π Γ((p+1)/2)); with one_sided,
// zero for |θ| > π/2 (no energy against the mean direction) and C doubled.
class CosPower final : public Spreading {
 public:
  static std::shared_ptr<const CosPower> create(double p, bool one_sided = false);
  double operator()(double omega, double theta) const override;
  std::string name() const override { return "cos-power"; }
  std::vector<Parameter> parameters() const override;

 private:
  CosPower(double p, bool one_sided);
  double p_;
  bool one_sided_;
  double normalization_;
};

// Horvath (2015), "Empirical directional wave spectra for computer graphics", DigiPro '15: the
// Hasselmann cos-2s spreading with the paper's branch at ωp, the swell elongation and a blend
// toward a uniform spread,
//   s(ω)   = 6.97 (ω/ωp)^4.06                                   for ω ≤ ωp,
//            9.77 (ω/ωp)^(−2.33 − 1.45 (U10/cp − 1.17))          for ω > ωp,
//   s_ξ(ω) = 16 tanh(ωp/ω) ξ²,
//   D(ω, θ) = (1 − b) G(s + s_ξ) cos^(2(s + s_ξ))(θ/2) + b/(2π),   G = Cos2s::normalization.
// ξ ≥ 0 (swell) elongates the long waves into parallel crests; b ∈ [0, 1] (spread_blend) mixes
// in a uniform spread; U10/cp is the wave age at the peak. Cos2s::hasselmann is the same law
// with Hasselmann et al.'s own branch at 1.05 ωp. Where the shipped Godot and Unity FFT oceans
// differ (normalization, blend sense, angle origin): docs/conventions.md §3.4.
struct HorvathParameters {
  double wave_age = 1.17;   // U10/cp at the peak (Hasselmann's fully developed sea)
  double swell = 0;         // ξ, dimensionless, ≥ 0
  double spread_blend = 0;  // b, weight of the uniform spread, in [0, 1]
};

class Horvath final : public Spreading {
 public:
  using Parameters = HorvathParameters;
  static std::shared_ptr<const Horvath> create(double omega_p, Parameters parameters = {});
  // U10/cp at the peak, cp = ωp/kp the phase speed at ωp under `dispersion` (kp = k(ωp)): the
  // case's own depth, not only deep water. Deep water gives U10 ωp/g, the paper's form.
  static double wave_age(double u10, double omega_p, const Dispersion& dispersion);

  double operator()(double omega, double theta) const override;
  double s(double omega) const;            // Hasselmann's exponent, branch at ωp
  double swell_exponent(double omega) const;  // s_ξ = 16 tanh(ωp/ω) ξ²
  std::string name() const override { return "horvath"; }
  std::vector<Parameter> parameters() const override;

 private:
  Horvath(double omega_p, Parameters parameters);
  double omega_p_;
  Parameters parameters_;
};

// θ wrapped to (−π, π].
double wrap_angle(double theta);

}  // namespace swell::reference
