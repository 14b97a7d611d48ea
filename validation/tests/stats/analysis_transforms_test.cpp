// stats/periodogram.hpp's analysis transforms that write where their caller keeps the result:
// field_spectrum into the caller's spectrum, inverse_transform into arrays the caller holds.
// Each is the transform the thread-scratch path makes, bit for bit (the gate's reports depend
// on it), and the DFT itself (a direct sum, independent of FFTW).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "swell/reference/grid.hpp"
#include "swell/reference/sampling.hpp"
#include "swell/validation/stats/periodogram.hpp"

namespace {

using Complex = std::complex<double>;
using swell::reference::Grid;
using swell::reference::Sampling;
namespace v = swell::validation;

std::vector<double> random_field(std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> field(count);
  for (double& x : field) x = normal(rng);
  return field;
}

// X(n, m) = Σ h(x, y) e^(−2πi (n x / nx + m y / ny)), summed directly.
Complex direct_dft(const std::vector<double>& h, const Grid& grid, int n, int m) {
  Complex sum = 0;
  for (int y = 0; y < grid.ny; ++y) {
    for (int x = 0; x < grid.nx; ++x) {
      const double phase = -2 * std::numbers::pi * (double(n) * x / grid.nx + double(m) * y / grid.ny);
      sum += h[std::size_t(y) * grid.nx + x] * Complex(std::cos(phase), std::sin(phase));
    }
  }
  return sum;
}

// 64 columns of fp64 complex make 1 KiB rows, which the estimate plan pads (the FFTW backend's
// pads_rows); 48 × 20 does not pad.
const Grid kGrids[] = {Grid{64, 32, 100.0, 50.0}, Grid{48, 20, 30.0, 10.0}};

TEST(AnalysisTransforms, FieldSpectrumIntoTheCallersArrayIsTheScratchTransformOverN) {
  for (const Grid& grid : kGrids) {
    const Sampling sampling(grid);
    const std::size_t count = sampling.size();
    const auto h = random_field(count, 7);
    std::vector<Complex> spectrum;
    long double energy = 0, scratch_energy = 0;
    v::field_spectrum(h, sampling, spectrum, &energy);
    ASSERT_EQ(spectrum.size(), count);
    const auto transform = v::analysis_transform(h, sampling, &scratch_energy);
    const double scale = 1.0 / double(count);
    std::size_t differing = 0;
    for (std::size_t e = 0; e < count; ++e) differing += spectrum[e] != transform[e] * scale;
    EXPECT_EQ(differing, 0u) << grid.nx << "×" << grid.ny;
    EXPECT_EQ(energy, scratch_energy);
    // The DFT itself, at a few wave vectors: fp64 rounding of sums of count terms.
    for (const auto& [n, m] : {std::pair{0, 0}, {1, 0}, {3, -2}, {-5, 7}, {grid.nx / 2, grid.ny / 2}}) {
      const std::size_t e = std::size_t((m + grid.ny) % grid.ny) * grid.nx + std::size_t((n + grid.nx) % grid.nx);
      const Complex expected = direct_dft(h, grid, n, m) * scale;
      EXPECT_NEAR(std::abs(spectrum[e] - expected), 0.0, 1e-13) << grid.nx << "×" << grid.ny << " at " << n << ", " << m;
    }
    // Σ|X|²/N is Σ h² (Parseval).
    double sum_squares = 0;
    for (double x : h) sum_squares += x * x;
    EXPECT_NEAR(double(energy), sum_squares, 1e-11 * sum_squares);
  }
}

TEST(AnalysisTransforms, InverseTransformIsWhatFieldsFromSpectrumGives) {
  v::InverseTransformArrays arrays;  // one pair across both sizes: resized between them
  for (const Grid& grid : kGrids) {
    const Sampling sampling(grid);
    const std::size_t count = sampling.size();
    // Two real fields' spectra packed as A + iB.
    std::vector<Complex> a, b;
    v::field_spectrum(random_field(count, 3), sampling, a);
    v::field_spectrum(random_field(count, 4), sampling, b);
    auto fill = [&](std::span<Complex> s) {
      ASSERT_EQ(s.size(), count);
      for (std::size_t e = 0; e < count; ++e) s[e] = a[e] + Complex(0, 1) * b[e];
    };
    std::vector<double> real_field, imaginary_field;
    v::fields_from_spectrum(sampling, fill, real_field, imaginary_field);
    const auto out = v::inverse_transform(sampling, arrays, fill);
    ASSERT_EQ(out.size(), count);
    std::size_t differing = 0;
    for (std::size_t p = 0; p < count; ++p) {
      differing += out[p].real() != real_field[p] || out[p].imag() != imaginary_field[p];
    }
    EXPECT_EQ(differing, 0u) << grid.nx << "×" << grid.ny;
    // The inverse of each field's own spectrum: the fields drawn, to fp64 rounding.
    const auto first = random_field(count, 3), second = random_field(count, 4);
    double worst = 0;
    for (std::size_t p = 0; p < count; ++p) {
      worst = std::max({worst, std::abs(out[p].real() - first[p]), std::abs(out[p].imag() - second[p])});
    }
    EXPECT_LT(worst, 1e-13) << grid.nx << "×" << grid.ny;
  }
}

}  // namespace
