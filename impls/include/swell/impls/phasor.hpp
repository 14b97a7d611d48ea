#pragma once
// e^(iωt) of one wave for the synthesizer's spectrum assembly (impls/src/synthesizer.cpp): cos
// and sin of the exact phase ω t, in plain arithmetic that a loop over waves vectorizes.
// Header-only and always inlined, so that each of the assembly's instruction-set clones
// (GCC target_clones) gets its own vector code. PhasorTest (validation/tests/reference/phasor_test.cpp)
// measures both precisions against glibc's sin and cos of reference::reduced_phase.
#include <bit>
#include <cmath>
#include <cstdint>

#include "swell/reference/phase.hpp"

namespace swell::impls {

// sin x and cos x to about 1 ulp for the reduced phases |x| ≤ π + 2⁻² of
// reference::reduced_phase, in plain arithmetic that the compiler vectorizes: glibc's sincos is
// a scalar call per phase (28% of a 1024² fp32 frame before this, docs/synthesis.md); glibc
// declares its vector variants (libmvec) only under -ffast-math, and their scalar loop tails
// would round differently from the vector body. Cody–Waite reduction x = q·π/2 + r with π/2
// split as p1 + p2 + p3 (fdlibm's pio2_1, pio2_2, pio2_2t; q·p1 and q·p2 are exact for small q
// and x − q·p1 is exact by Sterbenz's lemma), then fdlibm's __kernel_sin and __kernel_cos
// minimax polynomials on |r| ≤ π/4. The large part of ωt has already been taken out exactly by
// reduced_phase (reference/phase.hpp), so no phase of any valid case falls back to std::sin.
[[gnu::always_inline]] inline void sin_cos(double x, double& sin_x, double& cos_x) {
  constexpr double two_over_pi = 6.36619772367581382433e-01;
  constexpr double p1 = 1.57079632673412561417e+00;
  constexpr double p2 = 6.07710050630396597660e-11;
  constexpr double p3 = 2.02226624879595063154e-21;
  constexpr double round_shift = 0x1.8p52;  // x + 1.5·2⁵² rounds x to an integer, in the low bits
  const double shifted = x * two_over_pi + round_shift;
  const double q = shifted - round_shift;
  const auto quadrant = std::bit_cast<std::int64_t>(shifted);  // q mod 4 in its two low bits
  const double r = ((x - q * p1) - q * p2) - q * p3;
  const double z = r * r;
  const double sin_r =
      r + r * z *
              (-1.66666666666666324348e-01 +
               z * (8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 +
                         z * (2.75573137070700676789e-06 +
                              z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
  const double cos_r =
      1.0 - 0.5 * z +
      z * z *
          (4.16666666666666019037e-02 +
           z * (-1.38888888888741095749e-03 +
                z * (2.48015872894767294178e-05 +
                     z * (-2.75573143513906633035e-07 +
                          z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  // sin(qπ/2 + r), cos(qπ/2 + r) for q mod 4 = 0, 1, 2, 3: (s, c), (c, −s), (−s, −c), (−c, s).
  const bool odd = quadrant & 1;
  const double s = odd ? cos_r : sin_r, c = odd ? sin_r : cos_r;
  sin_x = (quadrant & 2) ? -s : s;
  cos_x = ((quadrant + 1) & 2) ? -c : c;
}

// e^(−iωt) of one wave as (cos ωt, sin ωt) in the spectrum's precision: the exact phase reduction
// of reference::reduced_phase and the double-precision sin_cos, rounded once to Real.
template <typename Real>
[[gnu::always_inline]] inline void phasor(double omega, double t, Real& cos_phase,
                                          Real& sin_phase) {
  double s, c;
  sin_cos(reference::reduced_phase(omega, t), s, c);
  cos_phase = Real(c);
  sin_phase = Real(s);
}

// The fp32 spectra's phasor, with half the double-precision operations: ωt reduced exactly in
// one step by q·π/2 (reference::reduce_phase_by<2>, reduced_phase's argument with 2π's parts
// over 4), so |r| ≤ π/4 + |e| to ≈ 1e-16 rad (|e| ≤ ulp(ωt)/2, below 10⁻⁸ rad for ωt < 2²⁵).
// r is then rounded to float (≤ 3e-8 rad at |r| ≤ π/4) and sin r, cos r evaluated in float with
// FreeBSD's __kernel_sindf and __kernel_cosdf polynomials (msun k_sinf.c, k_cosf.c: |error| <
// 2⁻²⁷ on |r| ≤ π/4 in exact arithmetic; their coefficients rounded to float move that by
// < 1e-8). Each value is within about 1 ulp of float of the exact one (PhasorTest bounds it by
// 2⁻²³), against 0.5 ulp for the double path rounded once; the fp32 transform after it adds
// log2(N) roundings of its own. It makes the fp32 assembly about a fifth cheaper
// (docs/performance.md §5).
template <>
[[gnu::always_inline]] inline void phasor<float>(double omega, double t, float& cos_phase,
                                                 float& sin_phase) {
  double shifted;
  const float r = float(reference::reduce_phase_by<2>(omega, t, shifted));
  // q mod 4 in the two low bits (the low 32 bits of the shifted value's mantissa).
  const auto quadrant = static_cast<std::int32_t>(std::bit_cast<std::int64_t>(shifted));
  const float z = r * r;
  const float sin_r =
      r + r * z *
              (-0.166666666416265235595f +
               z * (0.0083333293858894631756f +
                    z * (-0.000198393348360966317347f + z * 0.0000027183114939898219064f)));
  const float cos_r =
      1.0f + z * (-0.499999997251031003120f +
                  z * (0.0416666233237390631894f +
                       z * (-0.00138867637746099294692f + z * 0.0000243904487962774090654f)));
  const bool odd = quadrant & 1;
  const float s = odd ? cos_r : sin_r, c = odd ? sin_r : cos_r;
  sin_phase = (quadrant & 2) ? -s : s;
  cos_phase = ((quadrant + 1) & 2) ? -c : c;
}

}  // namespace swell::impls
