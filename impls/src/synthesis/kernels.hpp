#pragma once
// Internal: the synthesizer's per-frame kernels (docs/synthesis.md). Each frame assembles the
// packed spectra at time t row by row (assemble_row, assemble_lattice_row), transforms them, and
// unpacks the six fields (unpack_range). The kernels are compiled for several instruction sets
// and picked when the program loads (kernels.cpp).
#include <cstddef>
#include <vector>

namespace swell::impls::synthesis {

// The eight real fields one frame needs, in the order they are packed: (h, ∂h/∂x),
// (∂h/∂y, λDx), (λDy, λ∂Dx/∂x), (λ∂Dy/∂y, λ∂Dx/∂y). The last three only feed J.
constexpr int kRealFields = 8;
constexpr int kComplexPairs = kRealFields / 2;

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
  const Real* field_scale = nullptr;  // [kRealFields] powers of two (the synthesizer's field scales)
};

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
  const Real* inverse_scale = nullptr;  // [kRealFields]: undoes the field scales (0: a zero field)
};

// The assembly of columns [task.begin, task.end) of one half-spectrum row at time task.t: a
// grid's row (one ky), or a block of a lattice's single row (ky per class).
void assemble_row(const RowTask<float>& task);
void assemble_row(const RowTask<double>& task);
void assemble_lattice_row(const RowTask<float>& task);
void assemble_lattice_row(const RowTask<double>& task);

// Unpacks samples [task.begin, task.end); returns a sum that is finite iff every value written is.
float unpack_range(const UnpackTask<float>& task);
double unpack_range(const UnpackTask<double>& task);

}  // namespace swell::impls::synthesis
