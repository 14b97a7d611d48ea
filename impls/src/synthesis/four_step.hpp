#pragma once
// Internal: Bailey's four-step FFT of a lattice frame's 1-D inverse transforms of N = n1·n2
// points (D. H. Bailey, "FFTs in external or hierarchical memory", J. Supercomputing 4, 1990),
// on the backend's own batched 1-D plans. With class m = m1 + n1·m2 and point n = n2·p1 + p2,
//   f(n) = Σ_m1 e^(2πi m1 p1/n1) · [e^(2πi m1 p2/N) · Σ_m2 c(m1 + n1 m2) e^(2πi m2 p2/n2)]:
// (1) for each m1 the transform of length n2 over m2 — a column of the n2 × n1 array the
// spectrum already is — done a block of columns at a time in a scratch that stays in cache,
// with the twiddle e^(2πi m1 p2/N) applied there; (2) for each p2 the transform of length n1
// over m1, a contiguous row. The result lies transposed (point n at p2·n1 + p1), and the unpack
// transposes it back block by block. Its passes over memory are a 2-D transform's: one by
// columns, one by rows (a one-pass 1-D plan of 2^20 points and more costs 2× the 2-D
// transform of as many points with FFTW, 5–7× with radix2: docs/lattice.md).
#include <complex>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <vector>

#include "swell/impls/synthesizer.hpp"
#include "swell/impls/transform.hpp"

namespace swell::impls::synthesis {

template <typename Real>
struct FourStepTwiddles {
  // e^(2πi e/N) = high[e >> shift] · low[e & (2^shift − 1)], two tables of about √N entries
  // each computed in long double: the product is within 2 ulp of Real.
  std::vector<std::complex<Real>> low, high;
};

class FourStep {
 public:
  // The four-step transform of a lattice frame whose one-pass batch is `frame` (4 complex
  // pairs of N = frame.nx points, in place) on `backend`, as `choice` asks: none where a one-pass
  // plan is chosen; an InvalidInput naming why where four_step is asked for and cannot be had.
  static std::unique_ptr<FourStep> make(LatticeTransform choice, const Backend& backend,
                                        const TransformSpec& frame, Packing packing);

  int n1() const { return n1_; }  // the rows' length (step 2)
  int n2() const { return n2_; }  // the columns' length (step 1)

  // Steps 1 and 2 on the four packed spectra (4·N complex Real), in place.
  template <typename Real>
  void transform(void* spectra, int threads) const;
  // The six fields of the transformed spectra (synthesis/kernels.hpp's unpack, in natural
  // order); returns a sum that is finite iff every value written is.
  template <typename Real>
  Real unpack(const void* spectra, std::byte* fields, const Real* inverse_scale,
              int threads) const;

 private:
  template <typename Real>
  const FourStepTwiddles<Real>& twiddles() const {
    if constexpr (std::is_same_v<Real, float>) return twiddles32_; else return twiddles64_;
  }

  int points_ = 0;  // N
  int n1_ = 0, n2_ = 0;
  int shift_ = 0;
  std::unique_ptr<Plan> columns_;  // block transforms of n2, in place, contiguous
  std::unique_ptr<Plan> rows_;     // 4·n2 transforms of n1, in place on the spectra
  FourStepTwiddles<float> twiddles32_;
  FourStepTwiddles<double> twiddles64_;
};

}  // namespace swell::impls::synthesis
