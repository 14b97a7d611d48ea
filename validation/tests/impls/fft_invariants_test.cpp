// The reusable FFT invariants (swell/validation/testing/fft_invariants.hpp) must pass on a correct DFT
// and fail on each kind of wrong one; otherwise they prove nothing about another engine's FFT.
#include "swell/validation/testing/fft_invariants.hpp"

#include <gtest/gtest.h>

namespace {

namespace fi = swell::fft_invariants;
using C = std::complex<double>;

// A textbook DFT in long double, written here independently of swell's backends.
fi::Transform<double> dft(int nx, int ny, int sign) {
  return [=](const C* in, C* out) {
    for (int ky = 0; ky < ny; ++ky) {
      for (int kx = 0; kx < nx; ++kx) {
        std::complex<long double> sum = 0;
        for (int j = 0; j < ny; ++j) {
          for (int i = 0; i < nx; ++i) {
            const auto z = in[j * nx + i];
            sum += std::complex<long double>(z.real(), z.imag()) *
                   fi::detail::root(sign, (long long)kx * i, nx) * fi::detail::root(sign, (long long)ky * j, ny);
          }
        }
        out[ky * nx + kx] = C(double(sum.real()), double(sum.imag()));
      }
    }
  };
}

fi::Setup setup(int nx, int ny) {
  fi::Setup s;
  s.nx = nx;
  s.ny = ny;
  s.tolerance = 1e-13;  // a long-double DFT rounded to double: a few ε
  return s;
}

TEST(FftInvariants, HoldForATextbookDft) {
  const auto s = setup(6, 5);
  EXPECT_FFT_INVARIANTS_HOLD(double, dft(6, 5, -1), dft(6, 5, +1), s);
  fi::HalfToReal<double> c2r = [&](const C* half, double* out) {
    // Hermitian extension then the inverse DFT's real part, written out.
    std::vector<C> full(30);
    for (int m = 0; m < 5; ++m)
      for (int k = 0; k < 6; ++k)
        full[m * 6 + k] = k <= 3 ? half[m * 4 + k] : std::conj(half[((5 - m) % 5) * 4 + (6 - k)]);
    std::vector<C> y(30);
    dft(6, 5, +1)(full.data(), y.data());
    for (int i = 0; i < 30; ++i) out[i] = y[i].real();
  };
  auto inv = s;
  inv.sign = +1;
  EXPECT_TRUE(fi::c2r_matches_c2c<double>(c2r, dft(6, 5, +1), inv));
}

TEST(FftInvariants, CatchTheWrongSign) {
  auto s = setup(8, 4);
  s.sign = -1;
  EXPECT_FALSE(fi::impulse_response_holds<double>(dft(8, 4, +1), s));
  EXPECT_FALSE(fi::time_shift_holds<double>(dft(8, 4, +1), s));
  EXPECT_FALSE(fi::frequency_shift_holds<double>(dft(8, 4, +1), s));
}

TEST(FftInvariants, CatchAScaleError) {
  const auto s = setup(8, 4);
  const auto doubled = [&](const C* in, C* out) {
    dft(8, 4, -1)(in, out);
    for (int i = 0; i < 32; ++i) out[i] *= 2.0;
  };
  EXPECT_FALSE(fi::parseval_holds<double>(doubled, s));
  EXPECT_FALSE(fi::round_trip_holds<double>(doubled, dft(8, 4, +1), s));
  EXPECT_FALSE(fi::impulse_response_holds<double>(doubled, s));
}

TEST(FftInvariants, CatchANonlinearTransform) {
  const auto s = setup(8, 1);
  const auto offset = [&](const C* in, C* out) {
    dft(8, 1, -1)(in, out);
    out[3] += 1e-3;  // an affine, not linear, map
  };
  EXPECT_FALSE(fi::linearity_holds<double>(offset, s));
}

TEST(FftInvariants, CatchOneWrongTwiddle) {
  const auto s = setup(16, 1);
  const auto skewed = [&](const C* in, C* out) {
    dft(16, 1, -1)(in, out);
    out[5] *= std::polar(1.0, 1e-6);  // bin 5's twiddles off by a micro-radian
  };
  // Linearity and the time shift cannot see it (the map is linear and scaling one bin commutes
  // with a shift); the frequency shift, which moves bins, and the impulse response can.
  EXPECT_TRUE(fi::linearity_holds<double>(skewed, s));
  EXPECT_TRUE(fi::time_shift_holds<double>(skewed, s));
  EXPECT_FALSE(fi::frequency_shift_holds<double>(skewed, s));
  EXPECT_FALSE(fi::impulse_response_holds<double>(skewed, s));
}

TEST(FftInvariants, CatchATransformThatWritesItsInput) {
  const auto s = setup(4, 4);
  const auto clobber = [&](const C* in, C* out) {
    dft(4, 4, -1)(in, out);
    const_cast<C*>(in)[0] = 0;
  };
  EXPECT_FALSE(fi::input_preserved<double>(clobber, s));
}

}  // namespace
