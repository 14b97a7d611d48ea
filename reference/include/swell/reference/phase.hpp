#pragma once
// The phase ω t of a wave, reduced to about (−π, π], as the exact real product of the two
// doubles ω and t (docs/conventions.md §Amplitudes: h̃(k, t) = h̃0 e^(−iωt) + …).
//
// Why not fl(ω·t) then sin/cos: rounding the product loses |ωt|·2⁻⁵³ rad, 10⁻¹¹ rad at
// ωt = 10⁵ (a 2-hour run of a 1 km patch), which an fp64 surface and the dispersion check's
// rounding bound (64 u log2 N)² both notice. Here ωt = p + e exactly (an FMA gives the rounding
// error e of p = fl(ωt)), q = round(p / 2π), and 2π = c1 + c2 + c3 to 160 bits, so
//
//     r = ((p − q c1) − q c2) + e − q c3
//
// where p − fl(q c1) is exact (Sterbenz: they are within a factor 2 for q ≠ 0), fl(q c1)'s own
// error comes back exactly from an FMA, and the terms q c2 ≈ 2.4e-16 q and q c3 carry rounding
// errors of ≈ 2⁻¹⁰⁶ |ωt|. The reduced phase is therefore right to a few units of 2⁻⁵³·4 rad
// (the roundings of O(π) sums) for every |ωt| ≤ kLargestPhase = 2⁵⁰ rad: the q c2 term's
// rounding stays below 2⁻⁵⁶ rad there, and q = round(p/2π) < 2⁴⁸ stays an exact integer.
// Beyond it a phase carries fewer than the 53 bits of a double, and the case is refused
// (sampling_validity.hpp); 2⁵⁰ rad is 3.6 million years of a 10 rad/s wave.
#include <cmath>
#include <complex>

namespace swell::reference {

inline constexpr double kLargestPhase = 0x1p50;  // rad, ≈ 1.13e15

// ω t reduced by a multiple q of the period P = 2π/2^Halvings: returns r = ωt − q·P, with
// |r| ≤ P/2 + 2⁻³ for |ωt| ≤ kLargestPhase (q is chosen from p alone, and p's rounding error e
// reaches ulp(p)/2 = 2⁻³ rad at 2⁵⁰), accurate to ≈ 2e-15 rad (several ulps of π), and sets
// `shifted` to q + 1.5·2⁵², whose low mantissa bits are q mod 2⁵¹ (the quadrant, for P = π/2).
// P's three parts are 2π's scaled by a power of two, so the argument above holds for each P
// and Halvings = 0 is reduced_phase, bit for bit. Inline, branch-free and FMA-based so a loop
// over waves vectorizes. Precondition: |ω t| ≤ kLargestPhase (not checked here: a case whose
// frames exceed it is refused before any phase is computed).
template <int Halvings>
[[gnu::always_inline]] inline double reduce_phase_by(double omega, double t, double& shifted) {
  constexpr double scale = 1.0 / double(1 << Halvings);
  constexpr double inverse_period = 0x1.45f306dc9c883p-3 / scale;  // 1/(2π) rounded, over scale
  constexpr double c1 = 0x1.921fb54442d18p+2 * scale;  // 2π = c1 + c2 + c3 (160 bits), scaled
  constexpr double c2 = 0x1.1a62633145c07p-52 * scale;
  constexpr double c3 = -0x1.f1976b7ed8fbcp-108 * scale;
  constexpr double round_shift = 0x1.8p52;  // x + 1.5·2⁵² rounds x to an integer (|x| < 2⁵¹)
  const double p = omega * t;
  const double e = std::fma(omega, t, -p);  // ωt = p + e exactly
  shifted = p * inverse_period + round_shift;
  const double q = shifted - round_shift;
  const double a = q * c1;
  const double b = std::fma(q, c1, -a);  // q c1 = a + b exactly
  return (((p - a) - b) - q * c2) + e - q * c3;
}

// ω t reduced by a multiple of 2π, |result| ≤ π + 2⁻² (reduce_phase_by).
[[gnu::always_inline]] inline double reduced_phase(double omega, double t) {
  double shifted;
  return reduce_phase_by<0>(omega, t, shifted);
}

// e^(i·phase) = (cos phase, sin phase) from one sincos call: glibc's sincos shares sin's and
// cos's argument reduction and polynomials and returns exactly what they return (checked on
// 10⁸ arguments, UnitPhasor.EqualsSeparateSinAndCosBitForBit), in about two thirds of
// their time — the per-wave fits evaluate 8 million of these at 512² × 64 frames.
inline std::complex<double> unit_phasor(double phase) {
  double s, c;
  ::sincos(phase, &s, &c);
  return {c, s};
}

}  // namespace swell::reference
