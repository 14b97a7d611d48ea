#include "swell/impls/synthesizer.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numbers>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "device_frame.hpp"
#include "synthesis/amplitudes.hpp"
#include "swell/impls/phasor.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/phase.hpp"
#include "swell/reference/wave_noise.hpp"

namespace swell::impls {
namespace {

using reference::Field;
using reference::Grid;
using reference::OceanCase;

// The eight real fields one frame needs, in the order they are packed: (h, ∂h/∂x),
// (∂h/∂y, λDx), (λDy, λ∂Dx/∂x), (λ∂Dy/∂y, λ∂Dx/∂y). The last three only feed J.
constexpr int kRealFields = 8;
constexpr int kComplexPairs = kRealFields / 2;
// Classes of a lattice's row per assembly task: the task's scratch (h̃, 8 bytes a class in fp32,
// 16 in fp64) stays in L1/L2.
constexpr int kLatticeBlock = 4096;

using synthesis::amplitude;

// The per-row kernels are compiled for three instruction sets and picked when the program
// loads (GCC function multiversioning): swell builds without -march, and with 4 or 8 doubles
// a vector the assembly is several times cheaper. Other compilers get the baseline build.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SWELL_SIMD_CLONES [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#else
#define SWELL_SIMD_CLONES
#endif

// What does not change from frame to frame, per entry of the half spectrum (columns
// 0 … nx/2 of every row; FFT order): the two waves a = h̃0(k) travelling along +k and
// b = conj(h̃0(−k)) along −k, λ/|k|, and ω(|k|). The other half follows from Hermitian
// symmetry: ω(−k) = ω(k) and h̃(−k, t) = conj(h̃(k, t)), so each phase is computed once.
// Structure of arrays, so that a row's loop vectorizes. For fp32, a, b and λ/|k| are stored
// in float: the spectrum the fp32 transform takes is rounded to float anyway, and this halves
// the memory a frame reads. ω and the phase ωt stay in double: ωt reaches 10⁴ rad and more
// over long runs, where a float phase would be off by 10⁻³ rad.
template <typename Real>
struct Waves {
  std::vector<Real> a_re, a_im, b_re, b_im, lambda_over_k;
  void resize(std::size_t n) {
    for (auto* v : {&a_re, &a_im, &b_re, &b_im, &lambda_over_k}) v->assign(n, Real(0));
  }
};

// One row of the assembly: half-spectrum row j, and where its fields go.
template <typename Real>
struct RowTask {
  int width = 0;  // nx/2 + 1
  int nx = 0;
  // The columns [begin, end) of the half row this task assembles (a grid: the whole half row;
  // a lattice: one block of its N/2 + 1 classes, so that its scratch stays in the caches and
  // the threads share the row), and the mirror columns nx − i of those.
  int begin = 0, end = 0;
  bool pairs = false;
  double t = 0;
  const double* omega = nullptr;  // [width]
  const Real *a_re = nullptr, *a_im = nullptr, *b_re = nullptr, *b_im = nullptr;
  const Real* lambda_over_k = nullptr;  // [width]
  const Real* kx = nullptr;             // [nx]: kx of every column of a full row
  Real ky = 0, ky_mirror = 0;           // of row j and of row (ny − j) mod ny
  // A lattice (one row of N classes, docs/conventions.md §2.1): ky of every class [nx], used
  // instead of ky and ky_mirror; null on grids.
  const Real* ky_column = nullptr;
  Real* out = nullptr;         // row j of the first spectrum (interleaved re, im)
  Real* out_mirror = nullptr;  // pairs: row (ny − j) mod ny of the first spectrum
  std::size_t plane = 0;       // Reals from one spectrum to the next
  // Scratch of end − begin entries, indexed from begin: h̃ of the row, for its mirror.
  Real *h_re = nullptr, *h_im = nullptr;
  const Real* field_scale = nullptr;  // [kRealFields] powers of two (State::field_scale)
};

// The spectra of the eight real fields at k = (kx, ky), in packing order, from h̃(k)
// (conventions §Derived fields, λ in the displacement terms):
//   h: 1   ∂h/∂x: i kx   ∂h/∂y: i ky   λDx: iλ kx/k   λDy: iλ ky/k
//   λ∂Dx/∂x: −λ kx²/k   λ∂Dy/∂y: −λ ky²/k   λ∂Dx/∂y: −λ kx ky/k
// Every field is real, so its spectrum at −k is the conjugate of its spectrum at k.
template <typename Real>
struct FieldSpectra {
  Real re[kRealFields], im[kRealFields];
};

// The fields' power-of-two scales (State::field_scale) ride on the multipliers: m·scale is
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

// From the transformed spectra (eight real fields) to the six outputs: copy five, and
// J = (1 + λ∂Dx/∂x)(1 + λ∂Dy/∂y) − (λ∂Dx/∂y)², over samples [begin, end).
template <typename Real>
struct UnpackTask {
  bool pairs = false;
  const Real* data = nullptr;  // the transformed spectra: 4 complex or 8 real planes
  std::size_t count = 0;       // samples per field
  Real* fields = nullptr;      // 6 planes of count
  std::size_t begin = 0, end = 0;
  // Samples in each plane of data: count for a whole frame; a four-step lattice frame unpacks
  // blocks it has first transposed into natural order (its fields then start at the block).
  std::size_t data_plane = 0;
  const Real* inverse_scale = nullptr;  // [kRealFields]: undoes State::field_scale (0: a zero field)
};

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

// Packing::automatic. Frame CPU time, complex_pairs / real, ms (docs/synthesis.md: medians
// of 5 in one run of bench/frame_bench.cpp, 2026-11-22, 2-core AMD EPYC VM, one thread):
//            fp32 512²   1024²       2048²      fp64 512²   1024²       2048²
//   fftw     4.98/4.70   20.6/45.3   93.8/200        8.44/10.1   35.2/77.7   167/297
//   radix2   4.07/7.96   20.0/31.1   89.3/278        6.69/12.8   34.8/87.0   165/420
// complex_pairs is 1.2× to 3× faster everywhere except fftw fp32 512², a tie (real/pairs 0.94
// here, 1.19 in a second run): radix2 (like naive) runs a c2r through a full complex transform,
// and FFTW destroys the input of a multi-dimensional c2r, so the fftw backend runs it on a
// fresh copy each time (FFTW's own eight c2r cost about what its four c2c do). Both packings
// compute the same N²/2 phases. real would pay only on a backend whose c2r costs less than half
// its c2c and needs no copy; none has one, so there is nothing to choose.
Packing automatic_packing(const Backend&) { return Packing::complex_pairs; }

}  // namespace

// Bailey's four-step FFT of a lattice frame's 1-D inverse transforms of N = n1·n2 points
// (D. H. Bailey, "FFTs in external or hierarchical memory", J. Supercomputing 4, 1990), on
// the backend's own batched 1-D plans. With class m = m1 + n1·m2 and point n = n2·p1 + p2,
//   f(n) = Σ_m1 e^(2πi m1 p1/n1) · [e^(2πi m1 p2/N) · Σ_m2 c(m1 + n1 m2) e^(2πi m2 p2/n2)]:
// (1) for each m1 the transform of length n2 over m2 — a column of the n2 × n1 array the
// spectrum already is — done `block` columns at a time in a scratch that stays in cache, with
// the twiddle e^(2πi m1 p2/N) applied there; (2) for each p2 the transform of length n1 over
// m1, a contiguous row. The result lies transposed (point n at p2·n1 + p1), and the unpack
// transposes it back block by block. Its passes over memory are a 2-D transform's: one by
// columns, one by rows (a one-pass 1-D plan of 2^20 points and more costs 2× the 2-D
// transform of as many points with FFTW, 5–7× with radix2: docs/lattice.md).
template <typename Real>
struct FourStepTwiddles {
  // e^(2πi e/N) = high[e >> shift] · low[e & (2^shift − 1)], two tables of about √N entries
  // each computed in long double: the product is within 2 ulp of Real.
  std::vector<std::complex<Real>> low, high;
};

struct FourStep {
  int n1 = 0, n2 = 0;  // N = n1·n2: n1 the rows' length (step 2), n2 the columns' (step 1)
  int shift = 0;
  std::unique_ptr<Plan> columns;  // block transforms of n2, in place, contiguous
  std::unique_ptr<Plan> rows;     // 4·n2 transforms of n1, in place on the spectra
  FourStepTwiddles<float> twiddles32;
  FourStepTwiddles<double> twiddles64;
  template <typename Real>
  const FourStepTwiddles<Real>& twiddles() const {
    if constexpr (std::is_same_v<Real, float>) return twiddles32; else return twiddles64;
  }
};

// From this many points on, a lattice frame's automatic transform is the four-step one where
// it can be, on a backend whose large 1-D plans are not blocked already (radix2; measured in
// docs/lattice.md §Measured: at 2^16 radix2's four-step won in fp32 in two runs, 2.40 against
// 3.53 ms and 2.13 against 4.24, and in fp64 lost once and won once, 3.94 against 3.37 ms and
// 4.35 against 4.99; from 2^18 on it wins 1.8–2.7× in both).
constexpr long kFourStepMinPoints = 1L << 17;
constexpr int kFourStepComplexPlanes = 4;  // the complex pairs of one frame
// Values of p1 per unpack band: kFourStepBand consecutive complex values of a row (128 bytes
// in fp32) per read.
constexpr int kFourStepBand = 16;
// Step 1's columns per batch: radix2 transforms 16 fp32 (8 fp64) signals at once, one per
// vector lane; FFTW's batch of 16 columns of 2048 fp32 complex values is 256 KB, in L2.
constexpr int kFourStepBlock = 16;
constexpr int kFourStepPrefetchRows = 16;

struct Synthesizer::State {
  OceanCase ocean_case;
  SynthesizerOptions options;
  Packing packing = Packing::complex_pairs;
  std::unique_ptr<Backend> backend;
  TransformSpec spec;          // the batch of inverse transforms of a frame
  std::unique_ptr<Plan> plan;  // its plan (host backends; a device frame builds its own program)
  int nx = 0, ny = 0;
  int half_columns = 0;       // nx/2 + 1: the half spectrum the waves are stored for
  int spectrum_columns = 0;   // of the spectra the transforms take: nx (c2c) or nx/2 + 1 (c2r)
  std::vector<double> omega;  // per half-spectrum entry
  double max_omega = 0;
  // Each of the eight real fields is synthesized times a power of two that brings its rms near
  // 1, and unpack divides it out (exactly). Two fields share a complex transform, whose
  // rounding is relative to the pair's larger field: unscaled, a patch of 0.5 m (|k| ~ 100
  // rad/m) puts slopes 100× above heights and displacements, and the smaller field of a pair
  // is off by 100 u; λ = 1e-18 leaves a displacement below its partner's rounding. Scaled, every
  // field carries its own precision (found by the property test of the command line). A field
  // that is zero by definition (λ = 0) gets inverse scale 0: its output is exactly 0, not its
  // partner's rounding.
  std::array<double, kRealFields> field_scale{}, inverse_scale{};
  std::array<float, kRealFields> field_scale32{}, inverse_scale32{};
  Waves<float> waves32;       // fp32 synthesizers
  Waves<double> waves64;      // fp64 synthesizers
  std::vector<float> kx32, ky32;  // per column of a full row (FFT order), per row
  std::vector<double> kx64, ky64;
  // A lattice case is one row of N classes (nx = N, ny = 1), class m at column m with its own
  // ky (ky_column, N entries; empty on grids): its frame is 1-D transforms of size N.
  bool lattice = false;
  std::vector<float> ky_column32;
  std::vector<double> ky_column64;
  // The packed spectra, and the fields the transforms make of them (the same buffer when the
  // backend transforms in place). Host backends only.
  std::unique_ptr<Buffer> spectra, transformed_storage;
  // A device-resident backend's frame (device_frame.hpp), which holds the waves on the device
  // and records the transforms of `spec` into its own submission.
  std::unique_ptr<DeviceFrame> device_frame;
  // A lattice frame's four-step transform (empty: one-pass 1-D plans, and on grids).
  std::unique_ptr<FourStep> four_step;
  Buffer& transformed() const { return transformed_storage ? *transformed_storage : *spectra; }

  std::size_t real_bytes() const { return real_size(options.precision); }

  template <typename Real>
  const Waves<Real>& waves() const {
    if constexpr (std::is_same_v<Real, float>) return waves32; else return waves64;
  }
  template <typename Real>
  const Real* scales(bool inverse) const {
    if constexpr (std::is_same_v<Real, float>) {
      return inverse ? inverse_scale32.data() : field_scale32.data();
    } else {
      return inverse ? inverse_scale.data() : field_scale.data();
    }
  }
  template <typename Real>
  const std::vector<Real>& kx() const {
    if constexpr (std::is_same_v<Real, float>) return kx32; else return kx64;
  }
  template <typename Real>
  const std::vector<Real>& ky() const {
    if constexpr (std::is_same_v<Real, float>) return ky32; else return ky64;
  }
  template <typename Real>
  const std::vector<Real>& ky_column() const {
    if constexpr (std::is_same_v<Real, float>) return ky_column32; else return ky_column64;
  }
  // The signed wave index (n, m) of half-spectrum entry (i, j) and whether it carries energy.
  std::array<int, 2> wave_index(int i, int j) const {
    if (lattice) {
      const auto k = ocean_case.lattice->wave_vector(i);
      return {k[0], k[1]};
    }
    return {Grid::signed_index(i, nx), Grid::signed_index(j, ny)};
  }
  bool carries_energy(int i, int j) const {
    if (lattice) return ocean_case.lattice->carries_energy(i);
    const auto [n, m] = wave_index(i, j);
    return ocean_case.grid.carries_energy(n, m);
  }
  template <typename Real>
  void fill_waves(Waves<Real>& waves);
  template <typename Real>
  void make_device_frame();
  template <typename Real>
  void assemble(double t) const;
  template <typename Real>
  bool unpack(std::byte* fields) const;  // false when some value is not finite
  void make_four_step();
  template <typename Real>
  void run_four_step() const;
  template <typename Real>
  Real unpack_four_step(std::byte* fields) const;
  std::string describe_non_finite(double t, std::span<const std::byte> fields) const;
};

Synthesizer::Synthesizer(OceanCase ocean_case, SynthesizerOptions options)
    : state_(std::make_unique<State>()) {
  ocean_case.validate();
  auto& s = *state_;
  s.ocean_case = std::move(ocean_case);
  s.options = std::move(options);
  require(s.options.threads >= 1, "synthesizer threads", "≥ 1", s.options.threads);
  if (s.options.precision == Precision::f80) {
    throw InvalidInput("the synthesizer runs in fp32 or fp64, not fp80");
  }
  s.backend = make_backend(s.options.backend);
  s.packing = s.options.packing == Packing::automatic ? automatic_packing(*s.backend)
                                                      : s.options.packing;
  if (s.packing == Packing::real && !s.backend->capabilities().real_transforms) {
    throw InvalidInput("backend " + s.backend->name() + " has no c2r transform; use packing complex_pairs");
  }
  const Grid& grid = s.ocean_case.grid;
  s.lattice = s.ocean_case.is_lattice();
  if (s.lattice) {
    const auto points = s.ocean_case.lattice->points();
    if (points > std::numeric_limits<int>::max()) {
      throw InvalidInput(fmt::format("a lattice of {} points is beyond the synthesizer's "
                                     "transforms (at most 2^31 − 1 points)", points));
    }
    s.nx = static_cast<int>(points);
    s.ny = 1;
  } else {
    s.nx = grid.nx;
    s.ny = grid.ny;
  }
  s.half_columns = s.nx / 2 + 1;

  TransformSpec spec;
  spec.nx = s.nx;
  spec.ny = s.ny;
  spec.precision = s.options.precision;
  spec.direction = Direction::inverse;
  if (s.packing == Packing::complex_pairs) {
    spec.kind = Kind::c2c;
    spec.howmany = kComplexPairs;
    spec.placement = s.backend->capabilities().in_place ? Placement::in_place : Placement::out_of_place;
    s.spectrum_columns = s.nx;
  } else {
    spec.kind = Kind::c2r;
    spec.howmany = kRealFields;
    s.spectrum_columns = s.half_columns;
  }
  s.spec = spec;
  // A device backend's fused frame (device_frame.hpp) is built for grids; a lattice frame
  // assembles on the host and runs the device's 1-D transforms through host memory.
  const bool on_device = s.backend->capabilities().device_resident && !s.lattice;
  // The backend's rules before the waves are computed (seconds for a large grid): a device
  // frame builds its program after them.
  s.backend->validate(spec);
  // A four-step lattice frame needs no plan of size N (FFTW measures one for half a minute
  // at 2^20 points).
  if (s.lattice && !on_device) s.make_four_step();
  if (!on_device) {
    if (!s.four_step) s.plan = s.backend->plan(spec);
    if (s.backend->capabilities().device_resident) {
      s.spectra = std::make_unique<HostBuffer>(spec.input_bytes());
      s.transformed_storage = std::make_unique<HostBuffer>(spec.output_bytes());
    } else {
      s.spectra = s.backend->allocate(spec.input_bytes());
      if (spec.placement == Placement::out_of_place) {
        s.transformed_storage = s.backend->allocate(spec.output_bytes());
      }
    }
  }

  s.kx64.resize(s.nx);
  s.ky64.resize(s.ny);
  if (s.lattice) {
    s.ky_column64.resize(s.nx);
    for (int i = 0; i < s.nx; ++i) {
      const auto [n, m] = s.wave_index(i, 0);
      s.kx64[i] = n * grid.dkx();
      s.ky_column64[i] = m * grid.dky();
    }
    s.ky_column32.assign(s.ky_column64.begin(), s.ky_column64.end());
  } else {
    for (int i = 0; i < s.nx; ++i) s.kx64[i] = Grid::signed_index(i, s.nx) * grid.dkx();
    for (int j = 0; j < s.ny; ++j) s.ky64[j] = Grid::signed_index(j, s.ny) * grid.dky();
  }
  s.kx32.assign(s.kx64.begin(), s.kx64.end());
  s.ky32.assign(s.ky64.begin(), s.ky64.end());
  if (s.options.precision == Precision::f32) s.fill_waves(s.waves32); else s.fill_waves(s.waves64);
  if (on_device) {
    if (s.options.precision == Precision::f32) s.make_device_frame<float>(); else s.make_device_frame<double>();
  }
}

// The waves go to the device once; the host's copies are then never read again and are freed
// (max_omega, which evaluate() checks times against, is kept).
template <typename Real>
void Synthesizer::State::make_device_frame() {
#ifdef SWELL_HAVE_VULKAN
  const auto& w = waves<Real>();
  DeviceFrameTables tables;
  tables.precision = options.precision;
  tables.pairs = packing == Packing::complex_pairs;
  tables.nx = nx;
  tables.ny = ny;
  tables.a_re = w.a_re.data();
  tables.a_im = w.a_im.data();
  tables.b_re = w.b_re.data();
  tables.b_im = w.b_im.data();
  tables.omega = omega.data();
  tables.choppiness = ocean_case.choppiness;
  tables.dkx = ocean_case.grid.dkx();
  tables.dky = ocean_case.grid.dky();
  tables.field_scale = scales<Real>(false);
  tables.inverse_scale = scales<Real>(true);
  device_frame = make_vulkan_frame(*backend, spec, tables);
  if constexpr (std::is_same_v<Real, float>) waves32 = {}; else waves64 = {};
  std::vector<double>().swap(omega);
#else
  throw InternalError("backend " + backend->name() + " is device resident in a build without Vulkan");
#endif
}

// The factorization N = n1·n2 with n2 the largest divisor of N at most √N that the backend
// plans as a batch of 1-D transforms, n1 = N/n2 likewise, and n2 ≥ the step-1 block (so
// that the columns are worth batching); none for N below kFourStepMinPoints unless asked for.
void Synthesizer::State::make_four_step() {
  const auto choice = options.lattice_transform;
  if (choice == LatticeTransform::one_pass) return;
  const auto refuse = [&](const std::string& why) {
    if (choice == LatticeTransform::four_step) {
      throw InvalidInput(fmt::format("lattice transform four_step on {} points with {}: {}", nx,
                                     backend->name(), why));
    }
  };
  if (choice == LatticeTransform::automatic &&
      (nx < kFourStepMinPoints || backend->capabilities().blocked_large_1d)) {
    return;
  }
  if (packing != Packing::complex_pairs || spec.placement != Placement::in_place) {
    return refuse("it needs complex pairs transformed in place");
  }
  if (backend->capabilities().device_resident) {
    return refuse("a device backend would copy every batch of columns through the host");
  }
  const auto plans = [&](int length, int howmany) {
    TransformSpec one = spec;
    one.nx = length;
    one.ny = 1;
    one.howmany = howmany;
    try {
      backend->validate(one);
      return true;
    } catch (const InvalidInput&) {
      return false;
    }
  };
  int n2 = 0;
  for (int d = static_cast<int>(std::sqrt(double(nx))) + 1; d >= 2; --d) {
    if (long(d) * d <= nx && nx % d == 0 && plans(d, kFourStepBlock) &&
        plans(nx / d, kFourStepComplexPlanes * (nx / d))) {
      n2 = d;
      break;
    }
  }
  if (n2 < kFourStepBlock) {
    return refuse(fmt::format("N has no factor pair n1·n2 with {} ≤ n2 ≤ √N that {} plans",
                              kFourStepBlock, backend->name()));
  }
  auto f = std::make_unique<FourStep>();
  f->n2 = n2;
  f->n1 = nx / n2;
  TransformSpec columns = spec;
  columns.nx = f->n2;
  columns.howmany = kFourStepBlock;
  f->columns = backend->plan(columns);
  TransformSpec rows = spec;
  rows.nx = f->n1;
  rows.howmany = kFourStepComplexPlanes * f->n2;
  f->rows = backend->plan(rows);
  while ((1L << (2 * f->shift)) < long(nx)) ++f->shift;
  const long low_size = 1L << f->shift;
  const long high_size = (long(nx) + low_size - 1) / low_size;
  const long double two_pi_over_n = 2 * std::numbers::pi_v<long double> / nx;
  const auto fill = [&](auto& table) {
    using Complex = typename std::decay_t<decltype(table.low)>::value_type;
    using R = typename Complex::value_type;
    table.low.resize(low_size);
    table.high.resize(high_size);
    for (long e = 0; e < low_size; ++e) {
      table.low[e] = Complex(R(std::cos(two_pi_over_n * e)), R(std::sin(two_pi_over_n * e)));
    }
    for (long e = 0; e < high_size; ++e) {
      const long double angle = two_pi_over_n * (e * low_size);
      table.high[e] = Complex(R(std::cos(angle)), R(std::sin(angle)));
    }
  };
  if (options.precision == Precision::f32) fill(f->twiddles32); else fill(f->twiddles64);
  four_step = std::move(f);
}

// Steps 1 and 2 of the four-step transform on the four packed spectra, in place.
template <typename Real>
void Synthesizer::State::run_four_step() const {
  using Complex = std::complex<Real>;
  const FourStep& f = *four_step;
  auto* data = static_cast<Complex*>(spectra->host_data());
  const auto& tw = f.twiddles<Real>();
  const long n = nx, mask = (1L << f.shift) - 1;
  const int blocks_per_plane = (f.n1 + kFourStepBlock - 1) / kFourStepBlock;
  const int tasks = kFourStepComplexPlanes * blocks_per_plane;
#pragma omp parallel num_threads(options.threads)
  {
    HostBuffer scratch(sizeof(Complex) * std::size_t(kFourStepBlock) * f.n2);
    auto* buffer = static_cast<Complex*>(scratch.host_data());
#pragma omp for schedule(static)
    for (int task = 0; task < tasks; ++task) {
      Complex* plane = data + std::size_t(task / blocks_per_plane) * n;
      const int first = (task % blocks_per_plane) * kFourStepBlock;
      const int width = std::min(kFourStepBlock, f.n1 - first);
      // Columns first … first + width − 1 of the n2 × n1 array, each to a contiguous signal
      // (a short last block leaves the rest of the scratch as it was: transformed, unused).
      for (int m2 = 0; m2 < f.n2; ++m2) {
        const Complex* row = plane + std::size_t(m2) * f.n1 + first;
        if (m2 + kFourStepPrefetchRows < f.n2) {
          const Complex* ahead = row + std::size_t(kFourStepPrefetchRows) * f.n1;
          __builtin_prefetch(ahead);
          __builtin_prefetch(ahead + width - 1);
        }
        for (int c = 0; c < width; ++c) buffer[std::size_t(c) * f.n2 + m2] = row[c];
      }
      f.columns->execute(static_cast<const void*>(buffer), static_cast<void*>(buffer));
      // The twiddles, multiplied out by hand: std::complex's operator* goes through
      // __mulsc3 (C's Annex G infinities) unless -ffast-math, several times slower.
      for (int c = 0; c < width; ++c) {
        Real* signal = reinterpret_cast<Real*>(buffer + std::size_t(c) * f.n2);
        const long m1 = first + c;
        long e = 0;  // m1·p2 mod N
        for (int p2 = 0; p2 < f.n2; ++p2) {
          const std::complex<Real> hi = tw.high[e >> f.shift], lo = tw.low[e & mask];
          const Real wr = hi.real() * lo.real() - hi.imag() * lo.imag();
          const Real wi = hi.real() * lo.imag() + hi.imag() * lo.real();
          const Real xr = signal[2 * p2], xi = signal[2 * p2 + 1];
          signal[2 * p2] = xr * wr - xi * wi;
          signal[2 * p2 + 1] = xr * wi + xi * wr;
          e += m1;
          if (e >= n) e -= n;
        }
      }
      for (int p2 = 0; p2 < f.n2; ++p2) {
        Complex* row = plane + std::size_t(p2) * f.n1 + first;
        for (int c = 0; c < width; ++c) row[c] = buffer[std::size_t(c) * f.n2 + p2];
      }
    }
  }
  f.rows->execute(static_cast<const void*>(data), static_cast<void*>(data));
}

// The unpack of a four-step frame: point n = n2·p1 + p2 lies at p2·n1 + p1 of each plane.
// Bands of kFourStepBand values of p1 (that many runs of n2 consecutive points) are first
// transposed into a scratch in natural order, reading kFourStepBand consecutive values of
// each row, then unpacked as a whole frame's samples are.
template <typename Real>
Real Synthesizer::State::unpack_four_step(std::byte* fields) const {
  using Complex = std::complex<Real>;
  const FourStep& f = *four_step;
  const auto* data = static_cast<const Complex*>(spectra->host_data());
  const std::size_t n = std::size_t(nx);
  const int bands = (f.n1 + kFourStepBand - 1) / kFourStepBand;
  Real probe = 0;
#pragma omp parallel num_threads(options.threads) reduction(+ : probe)
  {
    std::vector<Complex> scratch(std::size_t(kFourStepComplexPlanes) * kFourStepBand * f.n2);
#pragma omp for schedule(static)
    for (int band = 0; band < bands; ++band) {
      const int first = band * kFourStepBand;
      const int height = std::min(kFourStepBand, f.n1 - first);
      const std::size_t band_points = std::size_t(height) * f.n2;
      for (int plane = 0; plane < kFourStepComplexPlanes; ++plane) {
        const Complex* in = data + plane * n;
        Complex* out = scratch.data() + plane * band_points;
        for (int p2 = 0; p2 < f.n2; ++p2) {
          const Complex* row = in + std::size_t(p2) * f.n1 + first;
          for (int r = 0; r < height; ++r) out[std::size_t(r) * f.n2 + p2] = row[r];
        }
      }
      UnpackTask<Real> task;
      task.pairs = true;
      task.data = reinterpret_cast<const Real*>(scratch.data());
      task.data_plane = band_points;
      task.count = n;
      task.fields = reinterpret_cast<Real*>(fields) + std::size_t(first) * f.n2;
      task.begin = 0;
      task.end = band_points;
      task.inverse_scale = scales<Real>(true);
      probe += unpack_range(task);
    }
  }
  return probe;
}

template <typename Real>
void Synthesizer::State::fill_waves(Waves<Real>& waves) {
  const auto spectrum = ocean_case.sea_spectrum();  // amplitude() applies band weights
  const std::size_t entries = std::size_t(half_columns) * ny;
  waves.resize(entries);
  omega.assign(entries, 0.0);
  const double lambda = ocean_case.choppiness;
#pragma omp parallel for num_threads(options.threads) schedule(dynamic, 4)
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < half_columns; ++i) {
      const auto [n, m] = wave_index(i, j);
      const std::size_t e = std::size_t(j) * half_columns + i;
      if (!carries_energy(i, j)) continue;  // a = b = 0, and ω = 0 keeps the phase finite
      const double k = std::hypot(kx64[i], lattice ? ky_column64[i] : ky64[j]);
      const auto a = amplitude(*spectrum, ocean_case, n, m);
      const auto b = std::conj(amplitude(*spectrum, ocean_case, -n, -m));
      waves.a_re[e] = Real(a.real());
      waves.a_im[e] = Real(a.imag());
      waves.b_re[e] = Real(b.real());
      waves.b_im[e] = Real(b.imag());
      waves.lambda_over_k[e] = Real(lambda / k);
      omega[e] = ocean_case.omega(k);
    }
  }
  for (double w : omega) max_omega = std::max(max_omega, std::abs(w));

  // The variance of each field (up to a common factor: half-spectrum entries stand for their
  // mirror too), from the waves' power and the fields' multipliers (field_spectra).
  std::array<double, kRealFields> variance{};
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < half_columns; ++i) {
      const double ky = lattice ? ky_column64[i] : ky64[j];
      const std::size_t e = std::size_t(j) * half_columns + i;
      const double power = double(waves.a_re[e]) * double(waves.a_re[e]) +
                           double(waves.a_im[e]) * double(waves.a_im[e]) +
                           double(waves.b_re[e]) * double(waves.b_re[e]) +
                           double(waves.b_im[e]) * double(waves.b_im[e]);
      if (power == 0) continue;
      const double kx = kx64[i], lk = double(waves.lambda_over_k[e]);
      const double multipliers[kRealFields] = {1, kx, ky, lk * kx, lk * ky,
                                               lk * kx * kx, lk * ky * ky, lk * kx * ky};
      for (int r = 0; r < kRealFields; ++r) variance[r] += multipliers[r] * multipliers[r] * power;
    }
  }
  for (int r = 0; r < kRealFields; ++r) {
    const double rms = std::sqrt(variance[r]);
    if (rms > 0 && std::isfinite(rms)) {
      field_scale[r] = std::ldexp(1.0, -std::ilogb(rms));
      inverse_scale[r] = std::ldexp(1.0, std::ilogb(rms));
    } else {
      field_scale[r] = 1;
      inverse_scale[r] = rms == 0 ? 0 : 1;
    }
    field_scale32[r] = float(field_scale[r]);
    inverse_scale32[r] = float(inverse_scale[r]);
  }
}

// The message of a frame with a non-finite value: which field, where, and the case — a case
// that passed its validity rule (reference/sampling_validity.hpp) never makes one.
std::string Synthesizer::State::describe_non_finite(double t,
                                                    std::span<const std::byte> fields) const {
  const State& s = *this;
  const std::size_t count = std::size_t(s.nx) * s.ny;
  const bool f32 = s.options.precision == Precision::f32;
  for (std::size_t f = 0; f < reference::kAllFields.size(); ++f) {
    for (std::size_t p = 0; p < count; ++p) {
      const std::size_t at = f * count + p;
      const double v = f32 ? double(reinterpret_cast<const float*>(fields.data())[at])
                           : reinterpret_cast<const double*>(fields.data())[at];
      if (std::isfinite(v)) continue;
      return fmt::format("the synthesizer made {} = {} at {}, t = {:g} s, {} {}, "
                         "for the case {}; the frame is not written",
                         reference::field_name(reference::kAllFields[f]), v,
                         s.lattice ? fmt::format("lattice point n = {}", p)
                                   : fmt::format("(i, j) = ({}, {})", p % s.nx, p / s.nx),
                         t, s.backend->name(), to_string(s.options.precision),
                         s.ocean_case.describe());
    }
  }
  return "the synthesizer's output check found a non-finite value it cannot locate";
}

Synthesizer::~Synthesizer() = default;

const OceanCase& Synthesizer::ocean_case() const { return state_->ocean_case; }
const SynthesizerOptions& Synthesizer::options() const { return state_->options; }
Packing Synthesizer::packing() const { return state_->packing; }
std::array<int, 2> Synthesizer::four_step_factors() const {
  if (!state_->four_step) return {0, 0};
  return {state_->four_step->n1, state_->four_step->n2};
}

std::vector<TransformSpec> Synthesizer::transforms_per_frame() const {
  return {state_->spec};
}

std::uint64_t Synthesizer::bytes_needed(const reference::Grid& grid, Precision precision) {
  // Per sample, in reals p of the precision: the four packed spectra (8p) and, out of place,
  // their transforms (8p); the frame (6p); the half spectrum's waves (5p/2) and ω (4 bytes);
  // the frame converted to double (48 bytes). Counted in double: a grid of 2²⁰ × 2²⁰ overflows
  // nothing here.
  const double p = double(real_size(precision));
  const double per_sample = 24.5 * p + 4 + 48;
  const double bytes = double(grid.nx) * double(grid.ny) * per_sample;
  return bytes >= 1.8e19 ? std::uint64_t(1.8e19) : std::uint64_t(bytes);
}

std::size_t Synthesizer::frame_bytes() const {
  return reference::kAllFields.size() * std::size_t(state_->nx) * state_->ny *
         state_->real_bytes();
}

// Row by row of the half spectrum; with complex_pairs each row also fills the right half
// (columns nx/2 + 1 … nx − 1) of its mirror row (ny − j) mod ny. Every entry is written by
// exactly one row, computed the same way whatever the thread count.
template <typename Real>
void Synthesizer::State::assemble(double t) const {
  const std::size_t plane = 2 * std::size_t(spectrum_columns) * ny;  // Reals per spectrum
  auto* out = static_cast<Real*>(spectra->host_data());
  const auto& w = waves<Real>();
  const auto& kxs = kx<Real>();
  const auto& kys = ky<Real>();
  const bool pairs = packing == Packing::complex_pairs;
  // A grid's task is one half row; a lattice's one block of its single row's classes: its
  // scratch then stays small (a whole row's at 2^22 points is 48 MB, beyond glibc's mmap
  // threshold, so every frame faulted in fresh zeroed pages: docs/lattice.md) and the threads
  // share the row.
  const int columns_per_task = lattice ? std::min(half_columns, kLatticeBlock) : half_columns;
#pragma omp parallel num_threads(options.threads)
  {
    std::vector<Real> h(2 * std::size_t(columns_per_task));
    RowTask<Real> task;
    task.width = half_columns;
    task.nx = nx;
    task.begin = 0;
    task.end = half_columns;
    task.pairs = pairs;
    task.t = t;
    task.kx = kxs.data();
    task.plane = plane;
    task.h_re = h.data();
    task.h_im = h.data() + columns_per_task;
    task.field_scale = scales<Real>(false);
    if (lattice) {
      task.ky_column = ky_column<Real>().data();
      task.omega = omega.data();
      task.a_re = w.a_re.data();
      task.a_im = w.a_im.data();
      task.b_re = w.b_re.data();
      task.b_im = w.b_im.data();
      task.lambda_over_k = w.lambda_over_k.data();
      task.out = out;
      task.out_mirror = out;
      const int blocks = (half_columns + kLatticeBlock - 1) / kLatticeBlock;
#pragma omp for schedule(static)
      for (int b = 0; b < blocks; ++b) {
        task.begin = b * kLatticeBlock;
        task.end = std::min(half_columns, task.begin + kLatticeBlock);
        assemble_lattice_row(task);
      }
    }
#pragma omp for schedule(static)
    for (int j = 0; j < (lattice ? 0 : ny); ++j) {
      const int mirror = (ny - j) % ny;
      const std::size_t e = std::size_t(j) * half_columns;
      task.omega = omega.data() + e;
      task.a_re = w.a_re.data() + e;
      task.a_im = w.a_im.data() + e;
      task.b_re = w.b_re.data() + e;
      task.b_im = w.b_im.data() + e;
      task.lambda_over_k = w.lambda_over_k.data() + e;
      task.ky = kys[j];
      task.ky_mirror = kys[mirror];
      task.out = out + 2 * std::size_t(j) * spectrum_columns;
      task.out_mirror = out + 2 * std::size_t(mirror) * spectrum_columns;
      assemble_row(task);
    }
  }
}

template <typename Real>
bool Synthesizer::State::unpack(std::byte* fields) const {
  const std::size_t count = std::size_t(nx) * ny;
  UnpackTask<Real> task;
  task.pairs = packing == Packing::complex_pairs;
  task.data = static_cast<const Real*>(transformed().host_data());
  task.count = count;
  task.data_plane = count;
  task.fields = reinterpret_cast<Real*>(fields);
  task.inverse_scale = scales<Real>(true);
  // Blocks of whole rows, a few per thread.
  const std::size_t block = ny == 1 ? 4096 : std::size_t(nx) * std::max(1, 4096 / nx);
  const std::ptrdiff_t blocks = std::ptrdiff_t((count + block - 1) / block);
  double probe = 0;
#pragma omp parallel for num_threads(options.threads) schedule(static) firstprivate(task) \
    reduction(+ : probe)
  for (std::ptrdiff_t b = 0; b < blocks; ++b) {
    task.begin = std::size_t(b) * block;
    task.end = std::min(count, task.begin + block);
    probe += double(unpack_range(task));
  }
  return std::isfinite(probe);
}

void Synthesizer::evaluate(double t, std::span<std::byte> fields) const {
  (void)evaluate_timed(t, fields);
}

FrameTimings Synthesizer::evaluate_timed(double t, std::span<std::byte> fields) const {
  const auto& s = *state_;
  if (fields.size() < frame_bytes()) {
    throw InvalidInput("Synthesizer::evaluate: output of " + std::to_string(fields.size()) +
                       " bytes for a frame of " + std::to_string(frame_bytes()));
  }
  require(std::isfinite(t), "frame time", "finite (s)", t);
  if (s.max_omega * std::abs(t) > reference::kLargestPhase) {
    throw InvalidInput(fmt::format(
        "frame time {:g} s: the fastest wave's phase ω t = {:.3g} rad exceeds the {:.3g} rad a "
        "phase can carry to double precision (reference/phase.hpp); ω ≤ {:.4g} rad/s on this grid",
        t, s.max_omega * std::abs(t), reference::kLargestPhase, s.max_omega));
  }
  FrameTimings timings;
  if (s.device_frame) {
    if (s.device_frame->evaluate(t, fields, timings) != 0) {
      throw InternalError(s.describe_non_finite(t, fields));
    }
    return timings;
  }
  const bool f32 = s.options.precision == Precision::f32;
  if (f32) s.assemble<float>(t); else s.assemble<double>(t);
  if (s.four_step) {
    double probe = 0;
    if (f32) {
      s.run_four_step<float>();
      probe = s.unpack_four_step<float>(fields.data());
    } else {
      s.run_four_step<double>();
      probe = s.unpack_four_step<double>(fields.data());
    }
    if (!std::isfinite(probe)) throw InternalError(s.describe_non_finite(t, fields));
    return timings;
  }
  if (s.backend->capabilities().device_resident) {
    s.plan->execute(s.spectra->host_data(), s.transformed().host_data());  // a lattice
  } else {
    s.plan->execute(*s.spectra, s.transformed());
  }
  const bool finite = f32 ? s.unpack<float>(fields.data()) : s.unpack<double>(fields.data());
  if (!finite) throw InternalError(s.describe_non_finite(t, fields));
  return timings;
}

reference::FieldFrame Synthesizer::frame(double t) const {
  std::vector<std::byte> bytes(frame_bytes());
  evaluate(t, bytes);
  const std::size_t count = std::size_t(state_->nx) * state_->ny;
  reference::FieldFrame frame;
  frame.time = t;
  for (std::size_t f = 0; f < reference::kAllFields.size(); ++f) {
    auto& out = frame.fields[reference::kAllFields[f]];
    out.resize(count);
    if (state_->options.precision == Precision::f32) {
      const auto* in = reinterpret_cast<const float*>(bytes.data()) + f * count;
      std::copy(in, in + count, out.begin());
    } else {
      const auto* in = reinterpret_cast<const double*>(bytes.data()) + f * count;
      std::copy(in, in + count, out.begin());
    }
  }
  return frame;
}

reference::FrameSequence Synthesizer::frames() const {
  reference::FrameSequence sequence;
  sequence.grid = state_->ocean_case.grid;
  sequence.lattice = state_->ocean_case.lattice;
  sequence.unit_roundoff = state_->options.precision == Precision::f32 ? 0x1p-24 : 0x1p-53;
  for (int f = 0; f < state_->ocean_case.frames; ++f) {
    sequence.frames.push_back(frame(state_->ocean_case.time(f)));
  }
  return sequence;
}

}  // namespace swell::impls
