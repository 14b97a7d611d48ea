#version 450
// The evolution kernel of a device-resident ocean frame (docs/synthesis.md §vulkan): per entry
// (i, j) of the half spectrum (columns 0 … nx/2 of every row, FFT order) it computes
//
//   h̃(k, t) = a e^(−iωt) + b e^(+iωt),   a = h̃0(k), b = conj(h̃0(−k))
//
// (docs/conventions.md §Amplitudes) and writes the spectra of the eight real fields exactly as
// Synthesizer::State::assemble does on the host (impls/src/synthesizer.cpp: field_spectra,
// store_pairs, the mirror row), scaled by the per-field powers of two:
//   PAIRS   four c2c spectra of nx columns, (h, ∂h/∂x), (∂h/∂y, λDx), (λDy, λ∂Dx/∂x),
//           (λ∂Dy/∂y, λ∂Dx/∂y), each pair A + iB; columns nx/2 + 1 … nx − 1 of row (ny − j) mod ny
//           hold −k of columns nx − 1 … 1 of row j: h̃(−k) = conj(h̃(k)) and ω(−k) = ω(k), so each
//           phase is computed once, by the invocation of the half-spectrum entry
//   !PAIRS  eight c2r half spectra of nx/2 + 1 columns
// The fields' multipliers at k = (kx, ky) (conventions §Derived fields, λ in the displacements):
//   h: 1   ∂h/∂x: i kx   ∂h/∂y: i ky   λDx: iλ kx/k   λDy: iλ ky/k
//   λ∂Dx/∂x: −λ kx²/k   λ∂Dy/∂y: −λ ky²/k   λ∂Dx/∂y: −λ kx ky/k
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
// Memory accesses are what a frame costs on lavapipe (each one is a loop over the SIMD lanes),
// so the kernel makes few: kx and ky come from the integer indices (as the host's tables do:
// the signed index times Δk in double, rounded once), the scales are push constants, and an fp32
// complex value is read and written as one 64-bit word (its two floats' bits in a double, never
// used as a number: no arithmetic touches it, so its bits stay as written).
//
// Bindings: the waves (a, b) per half entry, λ/|k| per half entry, ω per half entry (double),
// and the eight output planes (complex), each bound on its own: one plane of a large fp64 batch
// fits maxStorageBufferRange when the whole batch does not. A tiny grid's planes, smaller than
// minStorageBufferOffsetAlignment, share one binding of the whole buffer instead, and plane p
// then starts at element p · frame.plane_stride (0 otherwise).
#ifdef SWELL_FP64
#define real double
#define complex_word dvec2
complex_word word(double re, double im) { return dvec2(re, im); }
#define wave_words dvec4
#else
#define real float
#define complex_word double
// An fp32 complex as one 64-bit word, real part in the low half (the float pair's layout).
complex_word word(float re, float im) { return packDouble2x32(uvec2(floatBitsToUint(re), floatBitsToUint(im))); }
#define wave_words dvec2
#endif

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const bool PAIRS = true;

layout(set = 0, binding = 0) readonly buffer Waves { wave_words waves[]; };  // (a, b), see main
layout(set = 0, binding = 1) readonly buffer LambdaOverK { real lambda_over_k[]; };
layout(set = 0, binding = 2) readonly buffer Omega { double omega[]; };
layout(set = 0, binding = 3) writeonly buffer Plane0 { complex_word plane0[]; };
layout(set = 0, binding = 4) writeonly buffer Plane1 { complex_word plane1[]; };
layout(set = 0, binding = 5) writeonly buffer Plane2 { complex_word plane2[]; };
layout(set = 0, binding = 6) writeonly buffer Plane3 { complex_word plane3[]; };
layout(set = 0, binding = 7) writeonly buffer Plane4 { complex_word plane4[]; };
layout(set = 0, binding = 8) writeonly buffer Plane5 { complex_word plane5[]; };
layout(set = 0, binding = 9) writeonly buffer Plane6 { complex_word plane6[]; };
layout(set = 0, binding = 10) writeonly buffer Plane7 { complex_word plane7[]; };

layout(push_constant) uniform Frame {
  double t;               // s
  double dkx, dky;        // rad/m
  uint nx, ny;
  uint half_columns;      // nx/2 + 1
  uint spectrum_columns;  // of the output spectra: nx (PAIRS) or nx/2 + 1
  uint plane_stride;
  uint reserved;
  real field_scale[8];    // powers of two, packing order (synthesizer.cpp's State::field_scale)
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

// Grid::signed_index: the wave-number index of array index i along an axis of n samples.
int signed_index(uint i, uint n) { return i < (n + 1u) / 2u ? int(i) : int(i) - int(n); }
// kx of column i (ky of row j) as the host's table holds it: signed index × Δk in double, then
// rounded once to the precision.
real wave_number(uint i, uint n, double dk) { return real(double(signed_index(i, n)) * dk); }

// The eight fields' spectra at k = (kx, ky) from h̃ = (hr, hi), times their scales
// (synthesizer.cpp's field_spectra), stored at complex element `element` of each plane.
// Straight-line code on named values: no arrays, no loops.
void store(uint element, real hr, real hi, real kx, real ky, real lk) {
  const real lkx = lk * kx, lky = lk * ky;
  const real re0 = hr * frame.field_scale[0],             im0 = hi * frame.field_scale[0];
  const real re1 = -kx * hi * frame.field_scale[1],       im1 = kx * hr * frame.field_scale[1];
  const real re2 = -ky * hi * frame.field_scale[2],       im2 = ky * hr * frame.field_scale[2];
  const real re3 = -lkx * hi * frame.field_scale[3],      im3 = lkx * hr * frame.field_scale[3];
  const real re4 = -lky * hi * frame.field_scale[4],      im4 = lky * hr * frame.field_scale[4];
  const real re5 = -lkx * kx * hr * frame.field_scale[5], im5 = -lkx * kx * hi * frame.field_scale[5];
  const real re6 = -lky * ky * hr * frame.field_scale[6], im6 = -lky * ky * hi * frame.field_scale[6];
  const real re7 = -lkx * ky * hr * frame.field_scale[7], im7 = -lkx * ky * hi * frame.field_scale[7];
  const uint stride = frame.plane_stride;
  if (PAIRS) {
    // Two real fields A, B per complex spectrum Â + iB̂: its inverse transform is A + iB.
    plane0[element] = word(re0 - im1, im0 + re1);
    plane1[stride + element] = word(re2 - im3, im2 + re3);
    plane2[2u * stride + element] = word(re4 - im5, im4 + re5);
    plane3[3u * stride + element] = word(re6 - im7, im6 + re7);
  } else {
    plane0[element] = word(re0, im0);
    plane1[stride + element] = word(re1, im1);
    plane2[2u * stride + element] = word(re2, im2);
    plane3[3u * stride + element] = word(re3, im3);
    plane4[4u * stride + element] = word(re4, im4);
    plane5[5u * stride + element] = word(re5, im5);
    plane6[6u * stride + element] = word(re6, im6);
    plane7[7u * stride + element] = word(re7, im7);
  }
}

void main() {
  // One invocation per half-spectrum entry, counted along x then y of the dispatch (the host
  // spreads more than maxComputeWorkGroupCount[0] workgroups over y).
  const uint e = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  const uint half_columns = frame.half_columns, nx = frame.nx, ny = frame.ny;
  if (e >= half_columns * ny) return;
  const uint i = e % half_columns, j = e / half_columns;
  double s, c;
  sin_cos(reduced_phase(omega[e], frame.t), s, c);
  // h̃ = a e^(−iωt) + b e^(+iωt), with cos and sin rounded once to the synthesis precision.
  const real cr = real(c), sr = real(s);
#ifdef SWELL_FP64
  const dvec4 w = waves[e];  // (a.re, a.im, b.re, b.im)
  const double a_re = w.x, a_im = w.y, b_re = w.z, b_im = w.w;
#else
  const dvec2 w = waves[e];  // a and b, each an fp32 complex word
  const vec2 a = uintBitsToFloat(unpackDouble2x32(w.x)), b = uintBitsToFloat(unpackDouble2x32(w.y));
  const float a_re = a.x, a_im = a.y, b_re = b.x, b_im = b.y;
#endif
  const real hr = (a_re + b_re) * cr + (a_im - b_im) * sr;
  const real hi = (a_im + b_im) * cr - (a_re - b_re) * sr;
  const real lk = lambda_over_k[e];
  const uint columns = frame.spectrum_columns;
  store(j * columns + i, hr, hi, wave_number(i, nx, frame.dkx), wave_number(j, ny, frame.dky), lk);
  if (PAIRS && i >= 1u && i < half_columns - 1u) {
    // Column nx − i of the mirror row holds −k of this entry: conj(h̃), the same λ/|k|.
    const uint mirror = (ny - j) % ny, column = nx - i;
    store(mirror * columns + column, hr, -hi, wave_number(column, nx, frame.dkx),
          wave_number(mirror, ny, frame.dky), lk);
  }
}
