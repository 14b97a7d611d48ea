#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/frequency_spectrum.hpp"

namespace swell::reference {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Torsethaugen & Haver (2004), Table 1, the simplified model's empirical constants, in the
// form DNV-RP-C205 (2010) §3.5.6 writes them into its formulas.
constexpr double kFullyDevelopedPeakCoefficient = 6.6;  // a_f: Tpf = a_f Hs^(1/3), s·m^(−1/3)
constexpr double kLowerPeakCoefficient = 2.0;           // a_e: T_l = a_e Hs^(1/2), s·m^(−1/2)
constexpr double kUpperPeakPeriod = 25.0;               // a_u: T_u, s
constexpr double kWindSeaShareFloor = 0.7;              // a10
constexpr double kWindSeaShareWidth = 0.5;              // a1
constexpr double kSwellShareFloor = 0.6;                // a20
constexpr double kSwellShareWidth = 0.3;                // a2
constexpr double kGammaCoefficient = 35.0;              // k_g
// DNV prints the steepness exponent as 0.857; the paper writes 6/7 (= 0.857142…). Following
// DNV changes γ by |ln s| · 1.4e-4 relative, at most 7e-4 for the steepness s of any sea.
constexpr double kGammaSteepnessExponent = 0.857;
constexpr double kSwellGammaGrowth = 6.0;               // a3: γ = γ_F (1 + a3 ε_u)
constexpr double kSecondaryWindPeakOffset = 2.0;        // b1: Tp2 = Tpf + b1, s
// The gamma spectrum x^−4 exp(−x^−4) (N = M = 4) and its normalization as DNV rounds them:
// G0 = 1/∫x^−4 exp(−x^−4) dx = 4/Γ(3/4) = 3.26420…; with 3.26 a γ = 1 peak carries
// 0.998713 of its Hs²/16.
constexpr double kG0 = 3.26;
constexpr double kSigmaBelow = 0.07, kSigmaAbove = 0.09;

// Aγ = (1 + 1.1 (ln γ)^1.19) / γ, DNV's fit of 1/∫ (gamma spectrum × γ^r) for N = M = 4.
double a_gamma(double gamma) {
  return (1.0 + 1.1 * std::pow(std::log(gamma), 1.19)) / gamma;
}

}  // namespace

Torsethaugen::Torsethaugen(double hs, double tp, double gravity)
    : hs_(hs), tp_(tp), gravity_(gravity), tpf_(kFullyDevelopedPeakCoefficient * std::cbrt(hs)),
      swell_dominated_(tp > tpf_), peaks_{}, peak_omega_(0) {
  const double t_lower = kLowerPeakCoefficient * std::sqrt(hs);
  auto gamma_of = [&](double h, double t) {
    return kGammaCoefficient * std::pow(kTwoPi * h / (gravity * t * t), kGammaSteepnessExponent);
  };
  double share = 0, gamma = 0, tp2 = 0;
  if (!swell_dominated_) {
    // Wind-sea dominated: the primary peak is the wind sea at Tp, the secondary a swell at
    // Tpf + 2 s. DNV: r_pw = 0.7 + 0.3 exp(−[2 (Tpf − Tp)/(Tpf − 2√Hs)]²).
    const double epsilon_l = (tpf_ - tp) / (tpf_ - t_lower);
    share = kWindSeaShareFloor + (1.0 - kWindSeaShareFloor) *
                                     std::exp(-std::pow(epsilon_l / kWindSeaShareWidth, 2));
    gamma = gamma_of(share * hs, tp);
    tp2 = tpf_ + kSecondaryWindPeakOffset;
  } else {
    // Swell dominated: the primary peak is the swell at Tp, the secondary a wind sea at the
    // fully developed period of its own height. DNV: r_ps = 0.6 + 0.4 exp(−[(Tp − Tpf) /
    // (0.3 (25 − Tpf))]²), γ = 35 (2π Hs/(g Tpf²))^0.857 (1 + 6 (Tp − Tpf)/(25 − Tpf)).
    const double epsilon_u = (tp - tpf_) / (kUpperPeakPeriod - tpf_);
    share = kSwellShareFloor +
            (1.0 - kSwellShareFloor) * std::exp(-std::pow(epsilon_u / kSwellShareWidth, 2));
    gamma = gamma_of(hs, tpf_) * (1.0 + kSwellGammaGrowth * epsilon_u);
  }
  // γ < 1 (Hs below about 1.24 m with Tp near Tpf) would make (ln γ)^1.19 in Aγ undefined and
  // turn the peak enhancement into a depression: it is held at 1, a plain gamma-spectrum peak,
  // as WAFO holds its Torsethaugen γ (the rule DNV's text leaves unstated).
  gamma = std::max(gamma, 1.0);
  const double hs2 = std::sqrt(std::max(0.0, 1.0 - share * share)) * hs;
  if (swell_dominated_) tp2 = kFullyDevelopedPeakCoefficient * std::cbrt(hs2);
  peaks_[0] = {share * hs, tp, gamma};
  peaks_[1] = {hs2, tp2, 1.0};

  // Each peak rises below its ωp and falls above it (x^−4 exp(−x^−4) and γ^r both peak at
  // x = 1), so the sum's maximum lies between the two; a secondary of no height has none.
  const double omega1 = kTwoPi / peaks_[0].tp;
  if (peaks_[1].hs > 0) {
    const double omega2 = kTwoPi / peaks_[1].tp;
    const double lo = std::min(omega1, omega2), hi = std::max(omega1, omega2);
    peak_omega_ = hi > lo * (1 + 1e-12) ? find_peak_omega(*this, lo, hi) : lo;
  } else {
    peak_omega_ = omega1;
  }
}

std::shared_ptr<const Torsethaugen> Torsethaugen::create(double hs, double tp, double gravity) {
  require(std::isfinite(hs) && hs > 0, "hs (significant wave height)", "finite and > 0 m", hs);
  require(std::isfinite(tp) && tp > 0, "tp (peak period)", "finite and > 0 s", tp);
  require(std::isfinite(gravity) && gravity > 0, "gravity", "finite and > 0 m/s²", gravity);
  // The fit covers T_l = 2√Hs ≤ Tp ≤ T_u = 25 s: there the paper's ε_l = (Tpf − Tp)/(Tpf − T_l)
  // and ε_u = (Tp − Tpf)/(T_u − Tpf) lie in [0, 1]. Outside, DNV's formulas and the paper's
  // (which hold ε at 1) disagree, and the sea is steeper than breaking (Tp < 2√Hs) or longer
  // than any observed: refused rather than extrapolated.
  const double t_lower = kLowerPeakCoefficient * std::sqrt(hs);
  require(tp >= t_lower && tp <= kUpperPeakPeriod, "tp (peak period)",
          fmt::format("in [2√Hs, 25 s] = [{:.6g}, 25] s for torsethaugen with hs = {:g} m",
                      t_lower, hs),
          tp);
  return std::shared_ptr<const Torsethaugen>(new Torsethaugen(hs, tp, gravity));
}

double Torsethaugen::peak_spectrum(int j, double omega) const {
  const auto& p = peaks_.at(j);
  if (!(omega > 0) || p.hs == 0) return 0;
  const double x = omega * p.tp / kTwoPi;  // ω/ωpj = f Tpj
  const double x2 = x * x;
  // x^−4 exp(−x^−4) as one exponential: x^−4 alone overflows for tiny x.
  const double shape = std::exp(-1.0 / (x2 * x2) - 4.0 * std::log(x));
  const double sigma = x < 1 ? kSigmaBelow : kSigmaAbove;
  const double r = std::exp(-(x - 1) * (x - 1) / (2 * sigma * sigma));
  // E_j = Hs² Tp / 16 is the energy scale of S(f) in m²/Hz; over 2π it is S(ω) in m²·s/rad.
  const double energy = p.hs * p.hs * p.tp / (16.0 * kTwoPi);
  return energy * kG0 * a_gamma(p.gamma) * shape * std::pow(p.gamma, r);
}

double Torsethaugen::operator()(double omega) const {
  return peak_spectrum(0, omega) + peak_spectrum(1, omega);
}

std::vector<double> Torsethaugen::breakpoints() const {
  const double omega1 = kTwoPi / peaks_[0].tp;
  // The peak enhancement lives within a few σ of ωp1, with its kink in σ at ωp1 itself.
  std::vector<double> points = {omega1 * (1 - 4 * kSigmaBelow), omega1,
                                omega1 * (1 + 4 * kSigmaAbove), peak_omega_};
  if (peaks_[1].hs > 0) points.push_back(kTwoPi / peaks_[1].tp);
  std::sort(points.begin(), points.end());
  return points;
}

std::vector<Parameter> Torsethaugen::parameters() const {
  return {{"hs", hs_, "m"}, {"tp", tp_, "s"}, {"gravity", gravity_, "m/s²"}};
}

}  // namespace swell::reference
