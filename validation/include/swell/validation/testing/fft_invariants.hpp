#pragma once
// Invariants every correct DFT obeys, as GoogleTest assertions that any engine's tests can call
// on its own transform (link swell::fft_invariants). The randomized ones follow Ergün's
// self-test as FFTW's own verifier uses it (Ergün 1995, "Testing multivariate linear functions";
// FFTW's libbench2/verify-lib.c): linearity, impulse response, time shift, frequency shift —
// together they pin a linear map to the DFT with high probability.
//
// A transform under test maps nx × ny complex values (row-major, x fastest) to nx × ny,
// X[k] = Σ x[n] e^(sign·2πi k·n/N) unnormalized (sign −1 forward, +1 inverse). Tolerances are
// relative L2 norms: ‖lhs − rhs‖₂ ≤ tolerance · ‖rhs‖₂.
//
//   swell::fft_invariants::Setup setup{.nx = 64, .ny = 32, .sign = -1, .tolerance = 1e-5};
//   EXPECT_TRUE(swell::fft_invariants::linearity_holds<float>(my_fft, setup));
//   EXPECT_FFT_INVARIANTS_HOLD(float, my_forward, my_inverse, setup);
#include <gtest/gtest.h>

#include <complex>
#include <cstdint>
#include <cstring>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

namespace swell::fft_invariants {

template <typename T>
using Complex = std::complex<T>;
template <typename T>
using Transform = std::function<void(const Complex<T>* in, Complex<T>* out)>;
// nx × ny half spectrum (nx/2 + 1 per row) → nx × ny real values.
template <typename T>
using HalfToReal = std::function<void(const Complex<T>* in, T* out)>;

struct Setup {
  int nx = 1;
  int ny = 1;
  int sign = -1;             // −1: e^(−i…) (forward); +1: e^(+i…) (inverse)
  double tolerance = 1e-12;  // relative L2
  std::uint64_t seed = 1;
  int trials = 2;            // random trials per invariant
};

namespace detail {

template <typename T>
std::vector<Complex<T>> random_vector(std::size_t n, std::mt19937_64& engine) {
  std::vector<Complex<T>> v(n);
  auto uniform = [&] { return T(2.0 * ((engine() >> 11) * 0x1.0p-53) - 1.0); };
  for (auto& z : v) z = Complex<T>(uniform(), uniform());
  return v;
}

// ‖a − b‖₂ / ‖b‖₂ in long double.
template <typename T>
long double relative_l2(const std::vector<Complex<T>>& a, const std::vector<std::complex<long double>>& b) {
  long double err = 0, ref = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::complex<long double> d = std::complex<long double>(a[i].real(), a[i].imag()) - b[i];
    err += std::norm(d);
    ref += std::norm(b[i]);
  }
  return ref == 0 ? std::sqrt(err) : std::sqrt(err / ref);
}

template <typename T>
std::vector<std::complex<long double>> widen(const std::vector<Complex<T>>& v) {
  std::vector<std::complex<long double>> w(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) w[i] = {v[i].real(), v[i].imag()};
  return w;
}

// e^(sign·2πi·m/n) in long double, from the exact index m mod n.
inline std::complex<long double> root(int sign, long long m, int n) {
  m %= n;
  if (m < 0) m += n;
  const long double angle = sign * 2 * std::numbers::pi_v<long double> * m / n;
  return {std::cos(angle), std::sin(angle)};
}

template <typename T>
std::vector<Complex<T>> apply(const Transform<T>& f, const std::vector<Complex<T>>& x) {
  std::vector<Complex<T>> y(x.size());
  f(x.data(), y.data());
  return y;
}

inline testing::AssertionResult verdict(const char* what, long double error, const Setup& s) {
  if (error <= s.tolerance) return testing::AssertionSuccess();
  std::ostringstream text;
  text << what << " fails for " << s.nx << "×" << s.ny << " (sign " << s.sign
       << "): relative L2 error " << double(error) << " > tolerance " << s.tolerance;
  return testing::AssertionFailure() << text.str();
}

}  // namespace detail

// T(a·x + b·y) = a·T(x) + b·T(y) for random complex a, b and random x, y.
template <typename T>
testing::AssertionResult linearity_holds(const Transform<T>& f, const Setup& s) {
  std::mt19937_64 engine(s.seed);
  const std::size_t n = std::size_t(s.nx) * s.ny;
  long double worst = 0;
  for (int trial = 0; trial < s.trials; ++trial) {
    const auto x = detail::random_vector<T>(n, engine), y = detail::random_vector<T>(n, engine);
    const auto ab = detail::random_vector<T>(2, engine);
    std::vector<Complex<T>> mix(n);
    for (std::size_t i = 0; i < n; ++i) mix[i] = ab[0] * x[i] + ab[1] * y[i];
    const auto tx = detail::apply(f, x), ty = detail::apply(f, y), tmix = detail::apply(f, mix);
    std::vector<std::complex<long double>> expected(n);
    const std::complex<long double> a(ab[0].real(), ab[0].imag()), b(ab[1].real(), ab[1].imag());
    for (std::size_t i = 0; i < n; ++i) {
      expected[i] = a * std::complex<long double>(tx[i].real(), tx[i].imag()) +
                    b * std::complex<long double>(ty[i].real(), ty[i].imag());
    }
    worst = std::max(worst, detail::relative_l2(tmix, expected));
  }
  return detail::verdict("linearity", worst, s);
}

// The transform of an impulse at p is the plane wave e^(sign·2πi k·p/N); at p = 0, all ones.
template <typename T>
testing::AssertionResult impulse_response_holds(const Transform<T>& f, const Setup& s) {
  std::mt19937_64 engine(s.seed);
  const std::size_t n = std::size_t(s.nx) * s.ny;
  long double worst = 0;
  for (int trial = 0; trial <= s.trials; ++trial) {
    const int px = trial == 0 ? 0 : int(engine() % s.nx), py = trial == 0 ? 0 : int(engine() % s.ny);
    std::vector<Complex<T>> impulse(n);
    impulse[std::size_t(py) * s.nx + px] = 1;
    const auto got = detail::apply(f, impulse);
    std::vector<std::complex<long double>> expected(n);
    for (int ky = 0; ky < s.ny; ++ky) {
      for (int kx = 0; kx < s.nx; ++kx) {
        expected[std::size_t(ky) * s.nx + kx] =
            detail::root(s.sign, (long long)kx * px, s.nx) * detail::root(s.sign, (long long)ky * py, s.ny);
      }
    }
    worst = std::max(worst, detail::relative_l2(got, expected));
  }
  return detail::verdict("impulse response", worst, s);
}

namespace detail {

// Worst relative error, over each axis and `s.trials` random inputs x, between T(change(x)) and
// predicted(T(x)): the shape shared by the time- and frequency-shift invariants.
template <typename T, typename Change, typename Predict>
long double worst_over_axes(const Transform<T>& f, const Setup& s, Change change, Predict predict) {
  std::mt19937_64 engine(s.seed);
  const std::size_t n = std::size_t(s.nx) * s.ny;
  long double worst = 0;
  for (int axis = 0; axis < (s.ny > 1 ? 2 : 1); ++axis) {
    for (int trial = 0; trial < s.trials; ++trial) {
      const auto x = random_vector<T>(n, engine);
      const auto tx = detail::apply(f, x), tchanged = detail::apply(f, change(x, axis));
      worst = std::max(worst, relative_l2(tchanged, predict(tx, axis)));
    }
  }
  return worst;
}

}  // namespace detail

// Shifting the input by one sample along an axis multiplies bin k by e^(sign·2πi k/N).
template <typename T>
testing::AssertionResult time_shift_holds(const Transform<T>& f, const Setup& s) {
  const std::size_t n = std::size_t(s.nx) * s.ny;
  auto shift = [&](const std::vector<Complex<T>>& x, int axis) {
    std::vector<Complex<T>> shifted(n);
    for (int j = 0; j < s.ny; ++j) {
      for (int i = 0; i < s.nx; ++i) {
        const int si = axis == 0 ? (i + s.nx - 1) % s.nx : i;
        const int sj = axis == 1 ? (j + s.ny - 1) % s.ny : j;
        shifted[std::size_t(j) * s.nx + i] = x[std::size_t(sj) * s.nx + si];
      }
    }
    return shifted;
  };
  auto rotate_phases = [&](const std::vector<Complex<T>>& tx, int axis) {
    std::vector<std::complex<long double>> expected(n);
    for (int ky = 0; ky < s.ny; ++ky) {
      for (int kx = 0; kx < s.nx; ++kx) {
        const auto k = std::size_t(ky) * s.nx + kx;
        const auto phase = axis == 0 ? detail::root(s.sign, kx, s.nx) : detail::root(s.sign, ky, s.ny);
        expected[k] = phase * std::complex<long double>(tx[k].real(), tx[k].imag());
      }
    }
    return expected;
  };
  return detail::verdict("time shift", detail::worst_over_axes<T>(f, s, shift, rotate_phases), s);
}

// Multiplying the input by e^(sign·2πi n/N) along an axis moves bin k + 1 to bin k.
template <typename T>
testing::AssertionResult frequency_shift_holds(const Transform<T>& f, const Setup& s) {
  const std::size_t n = std::size_t(s.nx) * s.ny;
  auto modulate = [&](const std::vector<Complex<T>>& x, int axis) {
    std::vector<Complex<T>> modulated(n);
    for (int j = 0; j < s.ny; ++j) {
      for (int i = 0; i < s.nx; ++i) {
        const auto k = std::size_t(j) * s.nx + i;
        const auto phase = axis == 0 ? detail::root(s.sign, i, s.nx) : detail::root(s.sign, j, s.ny);
        const auto z = std::complex<long double>(x[k].real(), x[k].imag()) * phase;
        modulated[k] = Complex<T>(T(z.real()), T(z.imag()));
      }
    }
    return modulated;
  };
  auto move_bins = [&](const std::vector<Complex<T>>& tx, int axis) {
    std::vector<std::complex<long double>> expected(n);
    for (int ky = 0; ky < s.ny; ++ky) {
      for (int kx = 0; kx < s.nx; ++kx) {
        const int sx = axis == 0 ? (kx + 1) % s.nx : kx, sy = axis == 1 ? (ky + 1) % s.ny : ky;
        const auto from = std::size_t(sy) * s.nx + sx;
        expected[std::size_t(ky) * s.nx + kx] = {tx[from].real(), tx[from].imag()};
      }
    }
    return expected;
  };
  return detail::verdict("frequency shift", detail::worst_over_axes<T>(f, s, modulate, move_bins), s);
}

// Σ|X|² = N Σ|x|² (relative difference of the two sums).
template <typename T>
testing::AssertionResult parseval_holds(const Transform<T>& f, const Setup& s) {
  std::mt19937_64 engine(s.seed);
  const std::size_t n = std::size_t(s.nx) * s.ny;
  const auto x = detail::random_vector<T>(n, engine);
  const auto y = detail::apply(f, x);
  long double ex = 0, ey = 0;
  for (std::size_t i = 0; i < n; ++i) {
    ex += std::norm(std::complex<long double>(x[i].real(), x[i].imag()));
    ey += std::norm(std::complex<long double>(y[i].real(), y[i].imag()));
  }
  return detail::verdict("Parseval", std::abs(ey - n * ex) / (n * ex), s);
}

// inverse(forward(x)) = N·x.
template <typename T>
testing::AssertionResult round_trip_holds(const Transform<T>& forward, const Transform<T>& inverse,
                                          const Setup& s) {
  std::mt19937_64 engine(s.seed);
  const std::size_t n = std::size_t(s.nx) * s.ny;
  const auto x = detail::random_vector<T>(n, engine);
  const auto back = detail::apply(inverse, detail::apply(forward, x));
  auto expected = detail::widen(x);
  for (auto& z : expected) z *= static_cast<long double>(n);
  return detail::verdict("round trip", detail::relative_l2(back, expected), s);
}

// An out-of-place transform leaves its input bit-identical.
template <typename T>
testing::AssertionResult input_preserved(const Transform<T>& f, const Setup& s) {
  std::mt19937_64 engine(s.seed);
  const std::size_t n = std::size_t(s.nx) * s.ny;
  const auto x = detail::random_vector<T>(n, engine);
  auto copy = x;
  std::vector<Complex<T>> y(n);
  f(copy.data(), y.data());
  if (std::memcmp(copy.data(), x.data(), n * sizeof(Complex<T>)) == 0) return testing::AssertionSuccess();
  return testing::AssertionFailure() << "the transform changed its input (" << s.nx << "×" << s.ny << ")";
}

// c2r of a Hermitian half spectrum equals the real part of the c2c inverse of the full one
// (relative L2 against that real part); `c2c_inverse` must be an e^(+i…) transform.
template <typename T>
testing::AssertionResult c2r_matches_c2c(const HalfToReal<T>& c2r, const Transform<T>& c2c_inverse,
                                         const Setup& s) {
  std::mt19937_64 engine(s.seed);
  const std::size_t n = std::size_t(s.nx) * s.ny;
  const int width = s.nx / 2 + 1;
  // A Hermitian full spectrum: that of a random real field, built as F[k] = Σ f e^(−2πi k·n/N).
  std::vector<std::complex<long double>> field(n);
  for (auto& v : field) v = (long double)(2.0 * ((engine() >> 11) * 0x1.0p-53) - 1.0);
  std::vector<Complex<T>> full(n), half(std::size_t(s.ny) * width);
  for (int ky = 0; ky < s.ny; ++ky) {
    for (int kx = 0; kx < s.nx; ++kx) {
      std::complex<long double> sum = 0;
      for (int j = 0; j < s.ny; ++j) {
        for (int i = 0; i < s.nx; ++i) {
          sum += field[std::size_t(j) * s.nx + i] * detail::root(-1, (long long)kx * i, s.nx) *
                 detail::root(-1, (long long)ky * j, s.ny);
        }
      }
      full[std::size_t(ky) * s.nx + kx] = Complex<T>(T(sum.real()), T(sum.imag()));
      if (kx < width) half[std::size_t(ky) * width + kx] = full[std::size_t(ky) * s.nx + kx];
    }
  }
  std::vector<T> real(n);
  c2r(half.data(), real.data());
  const auto complex_result = detail::apply(c2c_inverse, full);
  long double err = 0, ref = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const long double want = complex_result[i].real();
    err += (real[i] - want) * (real[i] - want);
    ref += want * want;
  }
  return detail::verdict("c2r = Re(c2c inverse)", std::sqrt(err / ref), s);
}

}  // namespace swell::fft_invariants

// Every invariant of a forward/inverse pair at once (sign −1 for `forward`, +1 for `inverse`).
#define EXPECT_FFT_INVARIANTS_HOLD(T, forward, inverse, setup)                                  \
  do {                                                                                          \
    namespace fi_ = ::swell::fft_invariants;                                                    \
    fi_::Setup fwd_ = (setup), inv_ = (setup);                                                  \
    fwd_.sign = -1;                                                                             \
    inv_.sign = +1;                                                                             \
    EXPECT_TRUE(fi_::linearity_holds<T>((forward), fwd_));                                      \
    EXPECT_TRUE(fi_::impulse_response_holds<T>((forward), fwd_));                               \
    EXPECT_TRUE(fi_::time_shift_holds<T>((forward), fwd_));                                     \
    EXPECT_TRUE(fi_::frequency_shift_holds<T>((forward), fwd_));                                \
    EXPECT_TRUE(fi_::linearity_holds<T>((inverse), inv_));                                      \
    EXPECT_TRUE(fi_::impulse_response_holds<T>((inverse), inv_));                               \
    EXPECT_TRUE(fi_::time_shift_holds<T>((inverse), inv_));                                     \
    EXPECT_TRUE(fi_::frequency_shift_holds<T>((inverse), inv_));                                \
    EXPECT_TRUE(fi_::parseval_holds<T>((forward), fwd_));                                       \
    EXPECT_TRUE(fi_::round_trip_holds<T>((forward), (inverse), fwd_));                          \
    EXPECT_TRUE(fi_::input_preserved<T>((forward), fwd_));                                      \
  } while (0)
