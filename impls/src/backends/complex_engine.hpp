#pragma once
// Internal: backends that have a complex-to-complex engine get r2c and c2r from it.
//   r2c: the real input as complex (imaginary 0), c2c forward, keep the half spectrum.
//   c2r: the half spectrum extended by Hermitian symmetry, c2c inverse, the real part.
// Twice the work of a dedicated real transform, and exact in the same sense as the c2c.
#include <complex>
#include <vector>

#include "swell/impls/transform.hpp"

namespace swell::impls::detail {

template <typename T>
class ComplexEngine {
 public:
  virtual ~ComplexEngine() = default;
  // One nx × ny c2c transform; in may equal out.
  virtual void c2c(const std::complex<T>* in, std::complex<T>* out, Direction direction) const = 0;
};

// full[m][k] for k > nx/2 is conj(half[(ny − m) mod ny][nx − k]): the spectrum of a real field.
template <typename T>
void extend_hermitian(const std::complex<T>* half, std::complex<T>* full, int nx, int ny) {
  const int width = nx / 2 + 1;
  for (int m = 0; m < ny; ++m) {
    for (int k = 0; k < width; ++k) full[std::size_t(m) * nx + k] = half[std::size_t(m) * width + k];
    const int mirror_row = (ny - m) % ny;
    for (int k = width; k < nx; ++k) {
      full[std::size_t(m) * nx + k] = std::conj(half[std::size_t(mirror_row) * width + (nx - k)]);
    }
  }
}

template <typename T>
void run_via_complex(const TransformSpec& spec, const ComplexEngine<T>& engine, const void* in,
                     void* out) {
  using C = std::complex<T>;
  const std::size_t n = std::size_t(spec.nx) * spec.ny;
  const std::size_t in_count = spec.input_elements(), out_count = spec.output_elements();
  if (spec.kind == Kind::c2c) {
    for (int b = 0; b < spec.howmany; ++b) {
      engine.c2c(static_cast<const C*>(in) + b * in_count, static_cast<C*>(out) + b * out_count,
                 spec.direction);
    }
    return;
  }
  std::vector<C> work(n);
  const int width = spec.nx / 2 + 1;
  for (int b = 0; b < spec.howmany; ++b) {
    if (spec.kind == Kind::r2c) {
      const T* real = static_cast<const T*>(in) + b * in_count;
      for (std::size_t i = 0; i < n; ++i) work[i] = C(real[i], 0);
      engine.c2c(work.data(), work.data(), Direction::forward);
      C* half = static_cast<C*>(out) + b * out_count;
      for (int m = 0; m < spec.ny; ++m) {
        for (int k = 0; k < width; ++k) half[std::size_t(m) * width + k] = work[std::size_t(m) * spec.nx + k];
      }
    } else {
      extend_hermitian(static_cast<const C*>(in) + b * in_count, work.data(), spec.nx, spec.ny);
      engine.c2c(work.data(), work.data(), Direction::inverse);
      T* real = static_cast<T*>(out) + b * out_count;
      for (std::size_t i = 0; i < n; ++i) real[i] = work[i].real();
    }
  }
}

}  // namespace swell::impls::detail
