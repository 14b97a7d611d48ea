// naive: the separable O(N²)-per-axis DFT, every product and sum in long double, with twiddles
// e^(±2πi m/N) computed in long double from the exact index m = j·k mod N. It is the oracle
// every other backend is measured against (for sizes where O(N²) is affordable).
#include <cmath>
#include <numbers>

#include "backends.hpp"
#include "complex_engine.hpp"

namespace swell::impls {
namespace {

using LongComplex = std::complex<long double>;

// e^(sign·2πi m/n) for m = 0 … n−1.
std::vector<LongComplex> twiddles(int n, int sign) {
  std::vector<LongComplex> w(n);
  for (int m = 0; m < n; ++m) {
    const long double angle = sign * 2 * std::numbers::pi_v<long double> * m / n;
    w[m] = LongComplex(std::cos(angle), std::sin(angle));
  }
  return w;
}

// One axis: out[k] = Σ_j in[j] w[(j k) mod n], `count` lines of `n` points at `stride` apart,
// successive lines `line_step` apart.
void dft_lines(const LongComplex* in, LongComplex* out, int n, std::size_t stride,
               std::size_t line_step, std::size_t count, const std::vector<LongComplex>& w) {
  std::vector<LongComplex> line(n);
  for (std::size_t l = 0; l < count; ++l) {
    const LongComplex* src = in + l * line_step;
    for (int k = 0; k < n; ++k) {
      LongComplex sum = 0;
      std::size_t m = 0;  // j·k mod n, advanced by k each step
      for (int j = 0; j < n; ++j) {
        sum += src[j * stride] * w[m];
        m += k;
        if (m >= std::size_t(n)) m -= n;
      }
      line[k] = sum;
    }
    for (int k = 0; k < n; ++k) out[l * line_step + k * stride] = line[k];
  }
}

template <typename T>
class NaiveEngine final : public detail::ComplexEngine<T> {
 public:
  NaiveEngine(int nx, int ny)
      : nx_(nx), ny_(ny), forward_x_(twiddles(nx, -1)), inverse_x_(twiddles(nx, +1)),
        forward_y_(twiddles(ny, -1)), inverse_y_(twiddles(ny, +1)) {}

  void c2c(const std::complex<T>* in, std::complex<T>* out, Direction d) const override {
    const std::size_t n = std::size_t(nx_) * ny_;
    std::vector<LongComplex> work(n);
    for (std::size_t i = 0; i < n; ++i) work[i] = LongComplex(in[i].real(), in[i].imag());
    const bool fwd = d == Direction::forward;
    dft_lines(work.data(), work.data(), nx_, 1, nx_, ny_, fwd ? forward_x_ : inverse_x_);
    if (ny_ > 1) dft_lines(work.data(), work.data(), ny_, nx_, 1, nx_, fwd ? forward_y_ : inverse_y_);
    for (std::size_t i = 0; i < n; ++i) {
      out[i] = std::complex<T>(static_cast<T>(work[i].real()), static_cast<T>(work[i].imag()));
    }
  }

 private:
  int nx_, ny_;
  std::vector<LongComplex> forward_x_, inverse_x_, forward_y_, inverse_y_;
};

template <typename T>
class NaivePlan final : public Plan {
 public:
  explicit NaivePlan(const TransformSpec& spec) : Plan(spec), engine_(spec.nx, spec.ny) {}
  void execute(const void* in, void* out) const override {
    detail::run_via_complex<T>(spec(), engine_, in, out);
  }
  using Plan::execute;

 private:
  NaiveEngine<T> engine_;
};

class NaiveBackend final : public Backend {
 public:
  std::string name() const override { return "naive"; }
  Capabilities capabilities() const override {
    Capabilities c;
    c.precisions = {Precision::f32, Precision::f64, Precision::f80};
    c.any_size = true;
    c.size_rule = "any N ≥ 1";
    return c;
  }
  std::unique_ptr<Plan> plan(const TransformSpec& spec) const override {
    validate(spec);
    switch (spec.precision) {
      case Precision::f32: return std::make_unique<NaivePlan<float>>(spec);
      case Precision::f64: return std::make_unique<NaivePlan<double>>(spec);
      case Precision::f80: return std::make_unique<NaivePlan<long double>>(spec);
    }
    return nullptr;
  }
};

}  // namespace

std::unique_ptr<Backend> make_naive_backend(const BackendOptions&) {
  return std::make_unique<NaiveBackend>();
}

}  // namespace swell::impls
