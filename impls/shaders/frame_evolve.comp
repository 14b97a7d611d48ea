#version 450
// The evolution kernel of a device-resident ocean frame (docs/synthesis.md §vulkan): per entry
// (i, j) of the half spectrum (columns 0 … nx/2 of every row, FFT order) it computes
//
//   h̃(k, t) = a e^(−iωt) + b e^(+iωt),   a = h̃0(k), b = conj(h̃0(−k))
//
// (docs/conventions.md §Amplitudes) into the table the frame program's first pass reads
// (fft_lines.comp, FRAME_SOURCE), which makes each plane's packed spectrum from it — the
// fields' multipliers, the scales and the mirror half (h̃(−k) = conj(h̃(k)), ω(−k) = ω(k)), so
// each phase is computed once.
//
// The phase ωt is computed in double whatever the synthesis precision (so the device needs
// shaderFloat64): at ωt = 10⁹ rad a float phase would carry no correct digit. It is reduced as
// reference::reduced_phase does (the exact product ωt = p + e, 2π in three parts), with
// Dekker's product where the host uses an FMA (see two_product), then sin and cos by the same
// Cody–Waite step and fdlibm kernel polynomials as the host's sin_cos: GLSL has sin and cos in
// float only, and drivers' float sin/cos are often far from correctly rounded (a __sinf-like
// approximation loses digits beyond |x| ≈ π). Every variable of the reduction is `precise`
// (SPIR-V NoContraction): the exactness of Veltkamp's split, of p − q·c1 and of the error terms
// depends on each operation being rounded as written, never contracted, reassociated or
// simplified (c − (c − a) is not a).
//
// Memory accesses are what a frame costs on lavapipe (each one a loop over the SIMD lanes, each
// component a load or store in it), so an fp32 complex is read and written as one 64-bit word
// (its two floats' bits in a double, never used as a number: no arithmetic touches it, so its
// bits stay as written).
//
// Bindings: the waves (a, b) per half-spectrum entry, ω per entry (double), the table of h̃.
// Each invocation takes four adjacent entries: a load or store costs lavapipe a loop over the
// lanes, so fewer and wider accesses cost less (fp32: four entries' waves are two dvec4, their
// ω one dvec4 and their h̃ one dvec4; with two entries an invocation the kernel took 0.34 ms at
// 256² against 0.24–0.32 with four). The host pads the tables to a whole number of workgroups
// (zero waves and ω: h̃ = 0 there, never read), so no invocation tests a bound.
#ifdef SWELL_FP64
#define real double
#define vec2_or_dvec2 dvec2
#else
#define real float
#define vec2_or_dvec2 vec2
#endif

layout(local_size_x_id = 0) in;

#ifdef SWELL_FP64
layout(set = 0, binding = 0) readonly buffer Waves { dvec4 waves[]; };  // (a.re, a.im, b.re, b.im)
layout(set = 0, binding = 2) writeonly buffer Table { dvec4 table[]; };  // two entries' h̃
#else
layout(set = 0, binding = 0) readonly buffer Waves { dvec4 waves[]; };  // two entries' a and b words
layout(set = 0, binding = 2) writeonly buffer Table { dvec4 table[]; };  // four entries' h̃ words
#endif
layout(set = 0, binding = 1) readonly buffer Omega { dvec4 omega[]; };  // four entries' ω

layout(push_constant) uniform Frame {
  double t;  // s
} frame;

// The double with IEEE bits hi:lo. The constants of the reduction are given by their bits, as
// reference/phase.hpp gives them in hexadecimal: no decimal literal to be parsed or rounded.
double bits(uint hi, uint lo) { return packDouble2x32(uvec2(lo, hi)); }

// Dekker's exact product a·b = p + e from correctly rounded multiplications and additions
// alone (Veltkamp's split of each factor into two halves of 26 bits, whose products are
// exact). The host's reduced_phase gets e from an FMA; a shader cannot: Vulkan does not require
// OpExtInst Fma to be fused ("inherited from OpFMul followed by OpFAdd", Vulkan spec §Precision
// and Operation of SPIR-V Instructions), and lavapipe's is not: with fma(ω, t, −p) for e the
// frames at t = 10⁹ s (ωt ≈ 5e9 rad, ulp 1e-6 rad) were off by 6e-8 of their rms against fftw's,
// and at 10⁴ s by 6e-13; with this product by 3.5e-16 at both. Exact for |a|, |b| < 2⁹⁹⁵ without
// underflow; every value here is far inside that.
void two_product(double a, double b, out double p, out double e) {
  const double splitter = 134217729.0lf;  // 2²⁷ + 1
  precise double product = a * b;
  precise double ca = splitter * a;
  precise double a_hi = ca - (ca - a);
  precise double a_lo = a - a_hi;
  precise double cb = splitter * b;
  precise double b_hi = cb - (cb - b);
  precise double b_lo = b - b_hi;
  precise double error = (((a_hi * b_hi - product) + a_hi * b_lo) + a_lo * b_hi) + a_lo * b_lo;
  p = product;
  e = error;
}

// reference::reduced_phase: ω t reduced by a multiple of 2π to |r| ≤ π + 2⁻², accurate to
// ≈ 2e-15 rad for |ωt| ≤ 2⁵⁰ (reference::kLargestPhase; the host refuses later times), with
// Dekker's product where the host has an FMA.
double reduced_phase(double w, double t) {
  const double inverse_two_pi = bits(0x3FC45F30u, 0x6DC9C883u);  // 0x1.45f306dc9c883p-3
  const double c1 = bits(0x401921FBu, 0x54442D18u);              // 0x1.921fb54442d18p+2
  const double c2 = bits(0x3CB1A626u, 0x33145C07u);              // 0x1.1a62633145c07p-52
  const double c3 = bits(0xB93F1976u, 0xB7ED8FBCu);              // -0x1.f1976b7ed8fbcp-108
  const double round_shift = bits(0x43380000u, 0u);               // 0x1.8p52
  double p, e, a, b;
  two_product(w, t, p, e);  // ωt = p + e exactly
  precise double q = (p * inverse_two_pi + round_shift) - round_shift;
  two_product(q, c1, a, b);  // q c1 = a + b exactly
  precise double r = (((p - a) - b) - q * c2) + e - q * c3;
  return r;
}

// The host's sin_cos (impls/src/synthesizer.cpp): x = q·π/2 + r with π/2 = p1 + p2 + p3
// (fdlibm's pio2_1, pio2_2, pio2_2t), then fdlibm's __kernel_sin and __kernel_cos on
// |r| ≤ π/4; about 1 ulp for the reduced phases |x| ≤ π + 2⁻².
void sin_cos(double x, out double sin_x, out double cos_x) {
  const double two_over_pi = bits(0x3FE45F30u, 0x6DC9C883u);  // 6.36619772367581382433e-01 = 0x1.45f306dc9c883p-1
  const double p1 = bits(0x3FF921FBu, 0x54400000u);           // 1.57079632673412561417e+00 = 0x1.921fb544p+0
  const double p2 = bits(0x3DD0B461u, 0x1A600000u);           // 6.07710050630396597660e-11 = 0x1.0b4611a6p-34
  const double p3 = bits(0x3BA3198Au, 0x2E037073u);           // 2.02226624879595063154e-21 = 0x1.3198a2e037073p-69
  const double round_shift = bits(0x43380000u, 0u);            // 0x1.8p52
  precise double shifted = x * two_over_pi + round_shift;
  precise double q = shifted - round_shift;
  const uint quadrant = unpackDouble2x32(shifted).x;  // q mod 4 in its two low bits
  precise double r = ((x - q * p1) - q * p2) - q * p3;
  const double z = r * r;
  const double sin_r =
      r + r * z *
              (-1.66666666666666324348e-01lf +
               z * (8.33333333332248946124e-03lf +
                    z * (-1.98412698298579493134e-04lf +
                         z * (2.75573137070700676789e-06lf +
                              z * (-2.50507602534068634195e-08lf + z * 1.58969099521155010221e-10lf)))));
  const double cos_r =
      1.0lf - 0.5lf * z +
      z * z *
          (4.16666666666666019037e-02lf +
           z * (-1.38888888888741095749e-03lf +
                z * (2.48015872894767294178e-05lf +
                     z * (-2.75573143513906633035e-07lf +
                          z * (2.08757232129817482790e-09lf + z * -1.13596475577881948265e-11lf)))));
  // sin(qπ/2 + r), cos(qπ/2 + r) for q mod 4 = 0, 1, 2, 3: (s, c), (c, −s), (−s, −c), (−c, s).
  const bool odd = (quadrant & 1u) != 0u;
  const double s = odd ? cos_r : sin_r, c = odd ? sin_r : cos_r;
  sin_x = (quadrant & 2u) != 0u ? -s : s;
  cos_x = ((quadrant + 1u) & 2u) != 0u ? -c : c;
}

// h̃ = a e^(−iωt) + b e^(+iωt) of one entry, with cos and sin rounded once to the synthesis
// precision.
vec2_or_dvec2 evolve(double w, real a_re, real a_im, real b_re, real b_im) {
  double s, c;
  sin_cos(reduced_phase(w, frame.t), s, c);
  const real cr = real(c), sr = real(s);
  return vec2_or_dvec2((a_re + b_re) * cr + (a_im - b_im) * sr, (a_im + b_im) * cr - (a_re - b_re) * sr);
}

void main() {
  // Entries 4q … 4q + 3, q counted along x then y of the dispatch (the host spreads more than
  // maxComputeWorkGroupCount[0] workgroups over y).
  const uint q = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  const dvec4 w = omega[q];
#ifdef SWELL_FP64
  const dvec4 u0 = waves[4u * q], u1 = waves[4u * q + 1u], u2 = waves[4u * q + 2u], u3 = waves[4u * q + 3u];
  table[2u * q] = dvec4(evolve(w.x, u0.x, u0.y, u0.z, u0.w), evolve(w.y, u1.x, u1.y, u1.z, u1.w));
  table[2u * q + 1u] = dvec4(evolve(w.z, u2.x, u2.y, u2.z, u2.w), evolve(w.w, u3.x, u3.y, u3.z, u3.w));
#else
  const dvec4 u = waves[2u * q], v = waves[2u * q + 1u];
  const vec2 a0 = uintBitsToFloat(unpackDouble2x32(u.x)), b0 = uintBitsToFloat(unpackDouble2x32(u.y));
  const vec2 a1 = uintBitsToFloat(unpackDouble2x32(u.z)), b1 = uintBitsToFloat(unpackDouble2x32(u.w));
  const vec2 a2 = uintBitsToFloat(unpackDouble2x32(v.x)), b2 = uintBitsToFloat(unpackDouble2x32(v.y));
  const vec2 a3 = uintBitsToFloat(unpackDouble2x32(v.z)), b3 = uintBitsToFloat(unpackDouble2x32(v.w));
  const vec2 h0 = evolve(w.x, a0.x, a0.y, b0.x, b0.y), h1 = evolve(w.y, a1.x, a1.y, b1.x, b1.y);
  const vec2 h2 = evolve(w.z, a2.x, a2.y, b2.x, b2.y), h3 = evolve(w.w, a3.x, a3.y, b3.x, b3.y);
  table[q] = dvec4(packDouble2x32(floatBitsToUint(h0)), packDouble2x32(floatBitsToUint(h1)),
                   packDouble2x32(floatBitsToUint(h2)), packDouble2x32(floatBitsToUint(h3)));
#endif
}
