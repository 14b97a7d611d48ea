// radix2: Cooley–Tukey radix-2 decimation in time, powers of two only, fp32 and fp64.
//
// Layout for speed: every pass (rows along x, then columns along y) takes a block of L signals
// (L = 16 floats or 8 doubles: one AVX-512 register) into a scratch array in split form,
// re[i·L + lane], im[i·L + lane], in bit-reversed order. Each butterfly then works on whole
// vectors — one twiddle broadcast against L signals — with no shuffles, and the block (L·N
// complex values) stays in L1/L2 for all log2 N stages. Twiddles come from long double cos/sin.
// Signals left over when a count is not a multiple of L go through the same code with L = 1.
#include <omp.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "backends.hpp"
#include "complex_engine.hpp"

namespace swell::impls {
namespace {

template <typename T>
struct Axis {
  int n = 1;
  std::vector<int> bit_reversed;
  // Stage with butterfly span h uses w_j = e^(∓iπ j/h), j < h, stored at [h + j].
  std::vector<T> w_re, w_im_forward, w_im_inverse;

  explicit Axis(int size) : n(size), bit_reversed(size), w_re(size), w_im_forward(size), w_im_inverse(size) {
    int bits = 0;
    while ((1 << bits) < n) ++bits;
    for (int i = 0; i < n; ++i) {
      int r = 0;
      for (int b = 0; b < bits; ++b) r |= ((i >> b) & 1) << (bits - 1 - b);
      bit_reversed[i] = r;
    }
    for (int h = 1; h < n; h <<= 1) {
      for (int j = 0; j < h; ++j) {
        const long double angle = std::numbers::pi_v<long double> * j / h;
        w_re[h + j] = static_cast<T>(std::cos(angle));
        w_im_forward[h + j] = static_cast<T>(-std::sin(angle));
        w_im_inverse[h + j] = static_cast<T>(std::sin(angle));
      }
    }
  }
};

// log2 n radix-2 stages on L signals held split and bit-reversed in re/im.
template <typename T, int L>
void butterflies(T* __restrict re, T* __restrict im, const Axis<T>& axis, bool inverse) {
  const int n = axis.n;
  for (int s = 0; s < n; s += 2) {  // span 1: w = 1
    T* ar = re + s * L;
    T* ai = im + s * L;
    for (int l = 0; l < L; ++l) {
      const T br = ar[L + l], bi = ai[L + l];
      ar[L + l] = ar[l] - br;
      ai[L + l] = ai[l] - bi;
      ar[l] += br;
      ai[l] += bi;
    }
  }
  const T* w_im_table = inverse ? axis.w_im_inverse.data() : axis.w_im_forward.data();
  for (int h = 2; h < n; h <<= 1) {
    const T* wr = axis.w_re.data() + h;
    const T* wi = w_im_table + h;
    for (int s = 0; s < n; s += 2 * h) {
      for (int j = 0; j < h; ++j) {
        const T c = wr[j], d = wi[j];
        T* ar = re + (s + j) * L;
        T* ai = im + (s + j) * L;
        T* br = ar + h * L;
        T* bi = ai + h * L;
#pragma GCC ivdep
        for (int l = 0; l < L; ++l) {
          const T tr = c * br[l] - d * bi[l];
          const T ti = c * bi[l] + d * br[l];
          br[l] = ar[l] - tr;
          bi[l] = ai[l] - ti;
          ar[l] += tr;
          ai[l] += ti;
        }
      }
    }
  }
}

// Scratch per thread, reused across calls: a fresh allocation of this size per block would be
// an mmap and page faults every time.
template <typename T>
T* scratch(std::size_t count) {
  thread_local std::vector<T> buffer;
  if (buffer.size() < count) buffer.resize(count);
  return buffer.data();
}

// Transforms `count` rows of length axis.n (row r at src + r·n) into dst.
template <typename T, int L>
void row_block(const std::complex<T>* src, std::complex<T>* dst, const Axis<T>& axis, bool inverse) {
  const int n = axis.n;
  T* re = scratch<T>(2 * std::size_t(n) * L);
  T* im = re + std::size_t(n) * L;
  for (int l = 0; l < L; ++l) {
    const std::complex<T>* row = src + std::size_t(l) * n;
    for (int i = 0; i < n; ++i) {
      const int k = axis.bit_reversed[i];
      re[i * L + l] = row[k].real();
      im[i * L + l] = row[k].imag();
    }
  }
  butterflies<T, L>(re, im, axis, inverse);
  for (int l = 0; l < L; ++l) {
    std::complex<T>* row = dst + std::size_t(l) * n;
    for (int i = 0; i < n; ++i) row[i] = std::complex<T>(re[i * L + l], im[i * L + l]);
  }
}

// Transforms L adjacent columns (starting at data + column) of an nx-wide array, in place.
template <typename T, int L>
void column_block(std::complex<T>* data, int nx, const Axis<T>& axis, bool inverse) {
  const int n = axis.n;
  T* re = scratch<T>(2 * std::size_t(n) * L);
  T* im = re + std::size_t(n) * L;
  for (int i = 0; i < n; ++i) {
    const std::complex<T>* p = data + std::size_t(axis.bit_reversed[i]) * nx;
    for (int l = 0; l < L; ++l) {
      re[i * L + l] = p[l].real();
      im[i * L + l] = p[l].imag();
    }
  }
  butterflies<T, L>(re, im, axis, inverse);
  for (int i = 0; i < n; ++i) {
    std::complex<T>* p = data + std::size_t(i) * nx;
    for (int l = 0; l < L; ++l) p[l] = std::complex<T>(re[i * L + l], im[i * L + l]);
  }
}

template <typename T>
class Radix2Engine final : public detail::ComplexEngine<T> {
 public:
  static constexpr int kLanes = 64 / sizeof(T);  // one AVX-512 register of reals

  Radix2Engine(int nx, int ny, int threads) : x_(nx), y_(ny), threads_(threads) {}

  // `rows` rows of length nx from src to dst (may alias).
  void rows(const std::complex<T>* src, std::complex<T>* dst, int rows, bool inverse) const {
    const int nx = x_.n;
    const int blocks = rows / kLanes;
#pragma omp parallel for num_threads(threads_) schedule(static) if (threads_ > 1)
    for (int b = 0; b < blocks; ++b) {
      const std::size_t offset = std::size_t(b) * kLanes * nx;
      row_block<T, kLanes>(src + offset, dst + offset, x_, inverse);
    }
    for (int r = blocks * kLanes; r < rows; ++r) {
      row_block<T, 1>(src + std::size_t(r) * nx, dst + std::size_t(r) * nx, x_, inverse);
    }
  }

  void columns(std::complex<T>* data, bool inverse) const {
    const int nx = x_.n;
    const int blocks = nx / kLanes;
#pragma omp parallel for num_threads(threads_) schedule(static) if (threads_ > 1)
    for (int b = 0; b < blocks; ++b) column_block<T, kLanes>(data + b * kLanes, nx, y_, inverse);
    for (int c = blocks * kLanes; c < nx; ++c) column_block<T, 1>(data + c, nx, y_, inverse);
  }

  void c2c(const std::complex<T>* in, std::complex<T>* out, Direction d) const override {
    const bool inverse = d == Direction::inverse;
    rows(in, out, y_.n, inverse);
    if (y_.n > 1) columns(out, inverse);
  }

  int nx() const { return x_.n; }

 private:
  Axis<T> x_, y_;
  int threads_;
};

template <typename T>
class Radix2Plan final : public Plan {
 public:
  Radix2Plan(const TransformSpec& spec, int threads)
      : Plan(spec), engine_(spec.nx, spec.ny, threads) {}

  void execute(const void* in, void* out) const override {
    const auto& s = spec();
    if (s.kind == Kind::c2c && s.rank() == 1) {
      // A batch of 1-D transforms is one pass over all its rows.
      engine_.rows(static_cast<const std::complex<T>*>(in), static_cast<std::complex<T>*>(out),
                   s.howmany, s.direction == Direction::inverse);
      return;
    }
    detail::run_via_complex<T>(s, engine_, in, out);
  }
  using Plan::execute;

 private:
  Radix2Engine<T> engine_;
};

class Radix2Backend final : public Backend {
 public:
  explicit Radix2Backend(const BackendOptions& options) : threads_(options.threads) {
    if (!options.planner.empty()) {
      throw InvalidInput("radix2 takes no planner option (got planner=" + options.planner + ")");
    }
  }
  std::string name() const override { return "radix2"; }
  Capabilities capabilities() const override {
    Capabilities c;
    c.precisions = {Precision::f32, Precision::f64};
    c.any_size = false;
    c.size_rule = "powers of two";
    c.multi_threaded = true;
    return c;
  }
  std::unique_ptr<Plan> plan(const TransformSpec& spec) const override {
    validate(spec);
    if (spec.precision == Precision::f32) return std::make_unique<Radix2Plan<float>>(spec, threads_);
    return std::make_unique<Radix2Plan<double>>(spec, threads_);
  }

 private:
  int threads_;
};

}  // namespace

std::unique_ptr<Backend> make_radix2_backend(const BackendOptions& options) {
  return std::make_unique<Radix2Backend>(options);
}

}  // namespace swell::impls
