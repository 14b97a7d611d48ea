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
// Bindings: the waves (a, b) per half entry, λ/|k| per half entry, ω per half entry (double),
// the tables (8 field scales, 8 inverse scales, kx of the nx columns, ky of the ny rows), and
// the eight output planes, each bound on its own (one plane of a large fp64 batch fits
// maxStorageBufferRange when the whole batch does not). frame.base[p] is the element where
// plane p starts within its binding (0 unless a small grid's planes share an aligned window).
#ifdef SWELL_FP64
#define real double
#define real4 dvec4
#else
#define real float
#define real4 vec4
#endif

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const bool PAIRS = true;

layout(set = 0, binding = 0) readonly buffer Waves { real4 waves[]; };  // (a.re, a.im, b.re, b.im)
layout(set = 0, binding = 1) readonly buffer LambdaOverK { real lambda_over_k[]; };
layout(set = 0, binding = 2) readonly buffer Omega { double omega[]; };
layout(set = 0, binding = 3) readonly buffer Tables {
  real field_scale[8];
  real inverse_scale[8];
  real wave_number[];  // kx[0 … nx), then ky[0 … ny)
};
layout(set = 0, binding = 4) writeonly buffer Plane0 { real plane0[]; };
layout(set = 0, binding = 5) writeonly buffer Plane1 { real plane1[]; };
layout(set = 0, binding = 6) writeonly buffer Plane2 { real plane2[]; };
layout(set = 0, binding = 7) writeonly buffer Plane3 { real plane3[]; };
layout(set = 0, binding = 8) writeonly buffer Plane4 { real plane4[]; };
layout(set = 0, binding = 9) writeonly buffer Plane5 { real plane5[]; };
layout(set = 0, binding = 10) writeonly buffer Plane6 { real plane6[]; };
layout(set = 0, binding = 11) writeonly buffer Plane7 { real plane7[]; };

layout(push_constant) uniform Frame {
  double t;               // s
  uint nx, ny;
  uint half_columns;      // nx/2 + 1
  uint spectrum_columns;  // of the output spectra: nx (PAIRS) or nx/2 + 1
  uint base[8];
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

void put(uint p, uint index, real v) {
  const uint at = frame.base[p] + index;
  switch (p) {
    case 0u: plane0[at] = v; break;
    case 1u: plane1[at] = v; break;
    case 2u: plane2[at] = v; break;
    case 3u: plane3[at] = v; break;
    case 4u: plane4[at] = v; break;
    case 5u: plane5[at] = v; break;
    case 6u: plane6[at] = v; break;
    default: plane7[at] = v; break;
  }
}

// The eight fields' spectra at k = (kx, ky) from h̃ = (hr, hi), times their scales
// (synthesizer.cpp's field_spectra), stored at complex element `element` of each plane.
void store(uint element, real hr, real hi, real kx, real ky, real lk) {
  const real lkx = lk * kx, lky = lk * ky;
  real re[8], im[8];
  re[0] = hr;              im[0] = hi;
  re[1] = -kx * hi;        im[1] = kx * hr;
  re[2] = -ky * hi;        im[2] = ky * hr;
  re[3] = -lkx * hi;       im[3] = lkx * hr;
  re[4] = -lky * hi;       im[4] = lky * hr;
  re[5] = -lkx * kx * hr;  im[5] = -lkx * kx * hi;
  re[6] = -lky * ky * hr;  im[6] = -lky * ky * hi;
  re[7] = -lkx * ky * hr;  im[7] = -lkx * ky * hi;
  for (uint r = 0u; r < 8u; ++r) {
    re[r] *= field_scale[r];
    im[r] *= field_scale[r];
  }
  if (PAIRS) {
    // Two real fields A, B per complex spectrum Â + iB̂: its inverse transform is A + iB.
    for (uint p = 0u; p < 4u; ++p) {
      put(p, 2u * element, re[2u * p] - im[2u * p + 1u]);
      put(p, 2u * element + 1u, im[2u * p] + re[2u * p + 1u]);
    }
  } else {
    for (uint r = 0u; r < 8u; ++r) {
      put(r, 2u * element, re[r]);
      put(r, 2u * element + 1u, im[r]);
    }
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
  const real4 w = waves[e];
  const real hr = (w.x + w.z) * cr + (w.y - w.w) * sr;
  const real hi = (w.y + w.w) * cr - (w.x - w.z) * sr;
  const real lk = lambda_over_k[e];
  const uint columns = frame.spectrum_columns;
  store(j * columns + i, hr, hi, wave_number[i], wave_number[nx + j], lk);
  if (PAIRS && i >= 1u && i < half_columns - 1u) {
    // Column nx − i of the mirror row holds −k of this entry: conj(h̃), the same λ/|k|.
    const uint mirror = (ny - j) % ny, column = nx - i;
    store(mirror * columns + column, hr, -hi, wave_number[column], wave_number[nx + mirror], lk);
  }
}
