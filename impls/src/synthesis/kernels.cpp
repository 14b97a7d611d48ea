#include "synthesis/kernels.hpp"

#include <algorithm>

#include "swell/impls/phasor.hpp"

namespace swell::impls::synthesis {

// The per-row kernels are compiled for three instruction sets and picked when the program
// loads (GCC function multiversioning): swell builds without -march, and with 4 or 8 doubles
// a vector the assembly is several times cheaper. Other compilers get the baseline build.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SWELL_SIMD_CLONES [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#else
#define SWELL_SIMD_CLONES
#endif

// The spectra of the eight real fields at k = (kx, ky), in packing order, from h̃(k)
// (conventions §Derived fields, λ in the displacement terms):
//   h: 1   ∂h/∂x: i kx   ∂h/∂y: i ky   λDx: iλ kx/k   λDy: iλ ky/k
//   λ∂Dx/∂x: −λ kx²/k   λ∂Dy/∂y: −λ ky²/k   λ∂Dx/∂y: −λ kx ky/k
// Every field is real, so its spectrum at −k is the conjugate of its spectrum at k.
template <typename Real>
struct FieldSpectra {
  Real re[kRealFields], im[kRealFields];
};

// The fields' power-of-two scales (the synthesizer's field scales) ride on the multipliers: m·scale is
// exact, and so (m·scale)·h̃ rounds to the same value as (m·h̃)·scale, barring overflow and
// underflow — 9 multiplications an entry instead of 16. (The compiler's FMA contraction in
// store_pairs then fuses other products than before: the frames moved in their last bits,
// 2.9e-16 relative rms in fp64.)
template <typename Real>
[[gnu::always_inline]] inline FieldSpectra<Real> field_spectra(Real hr, Real hi, Real kx, Real ky,
                                                               Real lk, const Real* scale) {
  const Real lkx = lk * kx, lky = lk * ky;
  const Real m1 = kx * scale[1], m2 = ky * scale[2], m3 = lkx * scale[3], m4 = lky * scale[4];
  const Real m5 = -lkx * kx * scale[5], m6 = -lky * ky * scale[6], m7 = -lkx * ky * scale[7];
  FieldSpectra<Real> f;
  f.re[0] = hr * scale[0];  f.im[0] = hi * scale[0];
  f.re[1] = -m1 * hi;       f.im[1] = m1 * hr;
  f.re[2] = -m2 * hi;       f.im[2] = m2 * hr;
  f.re[3] = -m3 * hi;       f.im[3] = m3 * hr;
  f.re[4] = -m4 * hi;       f.im[4] = m4 * hr;
  f.re[5] = m5 * hr;        f.im[5] = m5 * hi;
  f.re[6] = m6 * hr;        f.im[6] = m6 * hi;
  f.re[7] = m7 * hr;        f.im[7] = m7 * hi;
  return f;
}

// Two real fields A, B per complex spectrum: the inverse transform of Â + iB̂ with Â and B̂
// Hermitian is A + iB, so its real and imaginary parts are the two fields.
template <typename Real>
[[gnu::always_inline]] inline void store_pairs(const FieldSpectra<Real>& f, Real* out,
                                               std::size_t plane, int i) {
  for (int p = 0; p < kComplexPairs; ++p) {
    out[p * plane + 2 * i] = f.re[2 * p] - f.im[2 * p + 1];
    out[p * plane + 2 * i + 1] = f.im[2 * p] + f.re[2 * p + 1];
  }
}

// PerColumnKy: a lattice's row, whose classes each have their own ky (a separate
// instantiation, so that the grids' loops stay as they were). The phases are computed in the
// loop that uses them (no scratch arrays of cos and sin to write and read back).
template <typename Real, bool PerColumnKy>
[[gnu::always_inline]] inline void assemble_row_body(const RowTask<Real>& task) {
  const int width = task.width;
  const int begin = task.begin, end = task.end;
  const double* __restrict omega = task.omega;
  const double t = task.t;
  const Real* __restrict a_re = task.a_re;
  const Real* __restrict a_im = task.a_im;
  const Real* __restrict b_re = task.b_re;
  const Real* __restrict b_im = task.b_im;
  const Real* __restrict lk = task.lambda_over_k;
  const Real* __restrict kx = task.kx;
  // The scratch array is indexed from `begin`.
  Real* __restrict h_re = task.h_re - begin;
  Real* __restrict h_im = task.h_im - begin;
  Real* __restrict out = task.out;
  const std::size_t plane = task.plane;
  const Real ky = task.ky;
  const Real* __restrict ky_column = task.ky_column;
  // h̃ = a e^(−iωt) + b e^(+iωt), then the fields at k: columns 0 … nx/2 of row j.
  const auto wave = [&](int i, Real& hr, Real& hi) {
    Real cr, sr;
    phasor(omega[i], t, cr, sr);
    hr = (a_re[i] + b_re[i]) * cr + (a_im[i] - b_im[i]) * sr;
    hi = (a_im[i] + b_im[i]) * cr - (a_re[i] - b_re[i]) * sr;
  };
  if (!task.pairs) {
#pragma omp simd
    for (int i = begin; i < end; ++i) {
      Real hr, hi;
      wave(i, hr, hi);
      const auto f = field_spectra(hr, hi, kx[i], PerColumnKy ? ky_column[i] : ky, lk[i],
                                   task.field_scale);
      for (int r = 0; r < kRealFields; ++r) {
        out[r * plane + 2 * i] = f.re[r];
        out[r * plane + 2 * i + 1] = f.im[r];
      }
    }
    return;
  }
#pragma omp simd
  for (int i = begin; i < end; ++i) {
    Real hr, hi;
    wave(i, hr, hi);
    h_re[i] = hr;
    h_im[i] = hi;
    store_pairs(field_spectra(hr, hi, kx[i], PerColumnKy ? ky_column[i] : ky, lk[i],
                              task.field_scale),
                out, plane, i);
  }
  // The columns nx/2 + 1 … nx − 1 of the mirror row hold −k of columns nx − 1 … 1 here:
  // h̃(−k) = conj(h̃(k)), and λ/|k| is the same. This task writes those whose source column
  // nx − i lies in [begin, end).
  Real* __restrict mirror = task.out_mirror;
  const Real ky_mirror = task.ky_mirror;
  const int nx = task.nx;
  const int mirror_begin = std::max(width, nx - end + 1);
  const int mirror_end = nx - std::max(begin, 1) + 1;
#pragma omp simd
  for (int i = mirror_begin; i < mirror_end; ++i) {
    const int source = nx - i;
    const auto f = field_spectra(h_re[source], -h_im[source], kx[i],
                                 PerColumnKy ? ky_column[i] : ky_mirror, lk[source],
                                 task.field_scale);
    store_pairs(f, mirror, plane, i);
  }
}

SWELL_SIMD_CLONES void assemble_row(const RowTask<float>& task) { assemble_row_body<float, false>(task); }
SWELL_SIMD_CLONES void assemble_row(const RowTask<double>& task) { assemble_row_body<double, false>(task); }
SWELL_SIMD_CLONES void assemble_lattice_row(const RowTask<float>& task) {
  assemble_row_body<float, true>(task);
}
SWELL_SIMD_CLONES void assemble_lattice_row(const RowTask<double>& task) {
  assemble_row_body<double, true>(task);
}

template <typename Real>
[[gnu::always_inline]] inline Real unpack_body(const UnpackTask<Real>& task) {
  const std::size_t n = task.count;
  Real* __restrict h = task.fields;
  Real* __restrict sx = h + n;
  Real* __restrict sy = h + 2 * n;
  Real* __restrict dx = h + 3 * n;
  Real* __restrict dy = h + 4 * n;
  Real* __restrict jacobian = h + 5 * n;
  const std::size_t dn = task.data_plane;
  const Real* __restrict d = task.data;
  // The synthesizer checks its own output (a non-finite value is a bug, never a written file):
  // x·0 is 0 for finite x and NaN for ±inf or NaN, so the sum is finite iff every value is.
  // Folded into the loop that writes the values, it costs a multiply-add per value.
  Real probe = 0;
  if (task.pairs) {  // (h, ∂h/∂x), (∂h/∂y, λDx), (λDy, λ∂Dx/∂x), (λ∂Dy/∂y, λ∂Dx/∂y)
    const Real* __restrict p0 = d;
    const Real* __restrict p1 = d + 2 * dn;
    const Real* __restrict p2 = d + 4 * dn;
    const Real* __restrict p3 = d + 6 * dn;
    const Real* v = task.inverse_scale;
#pragma omp simd reduction(+ : probe)
    for (std::size_t p = task.begin; p < task.end; ++p) {
      const Real h_p = p0[2 * p] * v[0], sx_p = p0[2 * p + 1] * v[1];
      const Real sy_p = p1[2 * p] * v[2], dx_p = p1[2 * p + 1] * v[3];
      const Real dy_p = p2[2 * p] * v[4];
      const Real dxx = p2[2 * p + 1] * v[5], dyy = p3[2 * p] * v[6], dxy = p3[2 * p + 1] * v[7];
      const Real j_p = (Real(1) + dxx) * (Real(1) + dyy) - dxy * dxy;
      h[p] = h_p;
      sx[p] = sx_p;
      sy[p] = sy_p;
      dx[p] = dx_p;
      dy[p] = dy_p;
      jacobian[p] = j_p;
      probe += Real(0) * h_p + Real(0) * sx_p + Real(0) * sy_p + Real(0) * dx_p +
               Real(0) * dy_p + Real(0) * j_p;
    }
  } else {
    const Real* v = task.inverse_scale;
    const Real* __restrict dxx = d + 5 * dn;
    const Real* __restrict dyy = d + 6 * dn;
    const Real* __restrict dxy = d + 7 * dn;
#pragma omp simd reduction(+ : probe)
    for (std::size_t p = task.begin; p < task.end; ++p) {
      h[p] = d[p] * v[0];
      sx[p] = d[dn + p] * v[1];
      sy[p] = d[2 * dn + p] * v[2];
      dx[p] = d[3 * dn + p] * v[3];
      dy[p] = d[4 * dn + p] * v[4];
      const Real xx = dxx[p] * v[5], yy = dyy[p] * v[6], xy = dxy[p] * v[7];
      jacobian[p] = (Real(1) + xx) * (Real(1) + yy) - xy * xy;
      probe += Real(0) * h[p] + Real(0) * sx[p] + Real(0) * sy[p] + Real(0) * dx[p] +
               Real(0) * dy[p] + Real(0) * jacobian[p];
    }
  }
  return probe;
}

SWELL_SIMD_CLONES float unpack_range(const UnpackTask<float>& task) { return unpack_body(task); }
SWELL_SIMD_CLONES double unpack_range(const UnpackTask<double>& task) { return unpack_body(task); }

}  // namespace swell::impls::synthesis
