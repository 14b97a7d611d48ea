// The grid synthesizer against its definition (docs/conventions.md §Amplitudes): every field by
// direct summation Σk multiplier(k) h̃(k, t) e^(ik·x) on small grids, the two packings against
// each other, fp32 against fp64, the nesting of resolutions that the counter-based noise
// promises, the loop period, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/periodogram.hpp"

namespace {

using swell::impls::Packing;
using swell::impls::Precision;
using swell::impls::Synthesizer;
using swell::impls::SynthesizerOptions;
using swell::reference::Field;
using swell::reference::FieldFrame;
using swell::reference::Grid;
using swell::reference::OceanCase;

OceanCase jonswap_case(int nx, int ny, double lx, double ly) {
  OceanCase c;
  c.grid = Grid::create(nx, ny, lx, ly);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
  c.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.wind_dir_deg = 30;
  c.choppiness = 0.8;
  c.dt = 0.5;
  c.frames = 3;
  c.seed = 1234;
  return c;
}

double rms(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x * x;
  return std::sqrt(sum / double(v.size()));
}

double relative_rms_difference(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> d(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
  return rms(d) / rms(b);
}

// The six fields at time t by the definition, summed directly in long double.
FieldFrame direct_sum(const OceanCase& c, double t) {
  const Grid& g = c.grid;
  const double lambda = c.choppiness;
  std::vector<std::complex<double>> a, b;
  std::vector<double> kxs, kys, omegas;
  for (int m = -g.ny / 2; m < (g.ny + 1) / 2; ++m) {
    for (int n = -g.nx / 2; n < (g.nx + 1) / 2; ++n) {
      if (!g.carries_energy(n, m)) continue;
      a.push_back(swell::impls::initial_amplitude(c, n, m));
      b.push_back(std::conj(swell::impls::initial_amplitude(c, -n, -m)));
      kxs.push_back(n * g.dkx());
      kys.push_back(m * g.dky());
      omegas.push_back(c.omega(std::hypot(kxs.back(), kys.back())));
    }
  }
  FieldFrame frame;
  frame.time = t;
  for (Field f : swell::reference::kAllFields) frame.fields[f].resize(std::size_t(g.nx) * g.ny);
  using LC = std::complex<long double>;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const long double x = i * g.lx / g.nx, y = j * g.ly / g.ny;
      LC h = 0, sx = 0, sy = 0, dx = 0, dy = 0, dxx = 0, dyy = 0, dxy = 0;
      for (std::size_t w = 0; w < a.size(); ++w) {
        const long double kx = kxs[w], ky = kys[w], k = std::hypot(kx, ky);
        const LC ht = LC(a[w]) * std::exp(LC(0, -omegas[w] * t)) +
                      LC(b[w]) * std::exp(LC(0, omegas[w] * t));
        const LC term = ht * std::exp(LC(0, kx * x + ky * y));
        const LC i1(0, 1);
        h += term;
        sx += i1 * kx * term;
        sy += i1 * ky * term;
        dx += i1 * (kx / k) * term;
        dy += i1 * (ky / k) * term;
        dxx += -(kx * kx / k) * term;
        dyy += -(ky * ky / k) * term;
        dxy += -(kx * ky / k) * term;
      }
      const std::size_t p = std::size_t(j) * g.nx + i;
      frame.fields[Field::height][p] = double(h.real());
      frame.fields[Field::slope_x][p] = double(sx.real());
      frame.fields[Field::slope_y][p] = double(sy.real());
      frame.fields[Field::disp_x][p] = double(lambda * dx.real());
      frame.fields[Field::disp_y][p] = double(lambda * dy.real());
      frame.fields[Field::jacobian][p] =
          double((1 + lambda * dxx.real()) * (1 + lambda * dyy.real()) -
                 lambda * lambda * dxy.real() * dxy.real());
    }
  }
  return frame;
}

void expect_frames_close(const FieldFrame& got, const FieldFrame& want, double tolerance,
                         const std::string& what) {
  for (Field f : swell::reference::kAllFields) {
    const auto& w = want.fields.at(f);
    std::vector<double> reference = w;
    if (f == Field::jacobian) {  // J ≈ 1: compare J − 1, the part the waves make
      for (double& v : reference) v -= 1;
    }
    std::vector<double> g = got.fields.at(f);
    if (f == Field::jacobian) {
      for (double& v : g) v -= 1;
    }
    EXPECT_LE(relative_rms_difference(g, reference), tolerance)
        << what << " field " << swell::reference::field_name(f);
  }
}

struct DefinitionCase {
  std::string backend;
  Precision precision;
  Packing packing;
  int nx, ny;
  double tolerance;
};

class SynthesizerDefinition : public ::testing::TestWithParam<DefinitionCase> {};

// fp64: the FFT's rounding, about ε log N relative; fp32 likewise with ε = 6e-8, plus the
// rounding of the stored amplitudes.
TEST_P(SynthesizerDefinition, EveryFieldEqualsTheDirectSumOfItsDefinition) {
  const auto& p = GetParam();
  OceanCase c = jonswap_case(p.nx, p.ny, 160.0, 120.0);
  c.depth = 12.0;
  const Synthesizer synth(c, {p.backend, p.precision, p.packing});
  for (double t : {0.0, 3.7, 250.0}) {
    expect_frames_close(synth.frame(t), direct_sum(c, t), p.tolerance,
                        p.backend + " t=" + std::to_string(t));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Backends, SynthesizerDefinition,
    ::testing::Values(
        DefinitionCase{"naive", Precision::f64, Packing::complex_pairs, 16, 8, 1e-12},
        DefinitionCase{"naive", Precision::f64, Packing::real, 15, 9, 1e-12},
        DefinitionCase{"fftw", Precision::f64, Packing::complex_pairs, 16, 16, 1e-12},
        DefinitionCase{"fftw", Precision::f64, Packing::complex_pairs, 15, 9, 1e-12},
        DefinitionCase{"fftw", Precision::f64, Packing::real, 12, 7, 1e-12},
        DefinitionCase{"fftw", Precision::f32, Packing::complex_pairs, 32, 16, 2e-6},
        DefinitionCase{"fftw", Precision::f32, Packing::real, 32, 16, 2e-6},
        DefinitionCase{"radix2", Precision::f64, Packing::complex_pairs, 32, 16, 1e-12},
        DefinitionCase{"radix2", Precision::f64, Packing::real, 16, 32, 1e-12},
        DefinitionCase{"radix2", Precision::f32, Packing::complex_pairs, 32, 32, 2e-6}),
    [](const auto& info) {
      const auto& p = info.param;
      return p.backend + "_" + swell::impls::to_string(p.precision) + "_" +
             swell::impls::to_string(p.packing) + "_" + std::to_string(p.nx) + "x" +
             std::to_string(p.ny);
    });

TEST(Synthesizer, PackingsAndBackendsAgreeAt256) {
  const OceanCase c = jonswap_case(256, 256, 400.0, 400.0);
  const auto reference = Synthesizer(c, {"fftw", Precision::f64, Packing::real}).frame(7.25);
  for (const auto& backend : {"fftw", "radix2"}) {
    for (auto packing : {Packing::complex_pairs, Packing::real}) {
      expect_frames_close(Synthesizer(c, {backend, Precision::f64, packing}).frame(7.25),
                          reference, 1e-13, backend);
      expect_frames_close(Synthesizer(c, {backend, Precision::f32, packing}).frame(7.25),
                          reference, 2e-6, std::string(backend) + " fp32");
    }
  }
}

TEST(Synthesizer, ThreadsDoNotChangeTheResult) {
  const OceanCase c = jonswap_case(128, 64, 300.0, 150.0);
  const auto one = Synthesizer(c, {"fftw", Precision::f64, Packing::complex_pairs, 1}).frame(2.0);
  const auto two = Synthesizer(c, {"fftw", Precision::f64, Packing::complex_pairs, 2}).frame(2.0);
  for (Field f : swell::reference::kAllFields) {
    EXPECT_EQ(one.fields.at(f), two.fields.at(f)) << swell::reference::field_name(f);
  }
}

// Counter-based noise keyed by (seed, n, m): the 32² surface is the band-limited part of the
// 64² surface over the same patch, wave for wave.
TEST(Synthesizer, ACoarseGridHoldsExactlyTheCommonWavesOfAFineOne) {
  const OceanCase fine = jonswap_case(64, 64, 400.0, 400.0);
  OceanCase coarse = fine;
  coarse.grid = Grid::create(32, 32, 400.0, 400.0);
  const auto hf = swell::validation::field_spectrum(
      Synthesizer(fine, {"fftw", Precision::f64}).frame(1.5).fields.at(Field::height), fine.grid);
  const auto hc = swell::validation::field_spectrum(
      Synthesizer(coarse, {"fftw", Precision::f64}).frame(1.5).fields.at(Field::height),
      coarse.grid);
  double max_difference = 0, max_value = 0;
  int compared = 0;
  for (int m = -15; m < 16; ++m) {
    for (int n = -15; n < 16; ++n) {
      const auto f = hf[std::size_t((m + 64) % 64) * 64 + (n + 64) % 64];
      const auto c = hc[std::size_t((m + 32) % 32) * 32 + (n + 32) % 32];
      max_difference = std::max(max_difference, std::abs(f - c));
      max_value = std::max(max_value, std::abs(f));
      ++compared;
    }
  }
  EXPECT_EQ(compared, 31 * 31);
  EXPECT_GT(max_value, 0.01);
  EXPECT_LE(max_difference, 1e-14 * 64 * max_value);
  // And a different seed gives different waves.
  OceanCase other = coarse;
  other.seed += 1;
  const auto ho = swell::validation::field_spectrum(
      Synthesizer(other, {"fftw", Precision::f64}).frame(1.5).fields.at(Field::height),
      other.grid);
  EXPECT_GT(std::abs(ho[33] - hc[33]), 1e-6);
}

// With a loop period T every ω is a multiple of 2π/T: the surface repeats after T.
TEST(Synthesizer, LoopPeriodRepeatsTheSurface) {
  OceanCase c = jonswap_case(64, 64, 300.0, 300.0);
  c.loop_period = 20.0;
  const Synthesizer synth(c, {"fftw", Precision::f64});
  expect_frames_close(synth.frame(33.0 + 20.0), synth.frame(33.0), 1e-11, "t + T");
  // Without it, the surface does not repeat.
  c.loop_period = 0;
  const auto h0 = Synthesizer(c, {"fftw", Precision::f64}).frame(33.0).fields.at(Field::height);
  const auto h1 = Synthesizer(c, {"fftw", Precision::f64}).frame(53.0).fields.at(Field::height);
  EXPECT_GT(relative_rms_difference(h1, h0), 0.1);
}

TEST(Synthesizer, ZeroWaveAndNyquistCarryNothingInAnyField) {
  const OceanCase c = jonswap_case(32, 16, 100.0, 50.0);
  const auto frame = Synthesizer(c, {"fftw", Precision::f64}).frame(4.0);
  for (Field f : {Field::height, Field::slope_x, Field::slope_y, Field::disp_x, Field::disp_y}) {
    const auto spectrum = swell::validation::field_spectrum(frame.fields.at(f), c.grid);
    double largest = 0;
    for (auto v : spectrum) largest = std::max(largest, std::abs(v));
    EXPECT_LE(std::abs(spectrum[0]), 1e-15 * 32 * largest) << swell::reference::field_name(f);
    for (int i = 0; i < 32; ++i) {
      EXPECT_LE(std::abs(spectrum[8 * 32 + i]), 1e-15 * 32 * largest);  // row m = −8
    }
    for (int j = 0; j < 16; ++j) {
      EXPECT_LE(std::abs(spectrum[j * 32 + 16]), 1e-15 * 32 * largest);  // column n = −16
    }
  }
}

TEST(Synthesizer, RefusesWhatItCannotDoWithNamedReasons) {
  const OceanCase c = jonswap_case(48, 48, 100.0, 100.0);
  try {
    Synthesizer(c, {"radix2", Precision::f32});
    FAIL() << "radix2 accepted 48×48";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("radix2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Synthesizer(c, {"fftw", Precision::f80}), swell::InvalidInput);
  EXPECT_THROW(Synthesizer(c, {"no-such-backend", Precision::f32}), swell::InvalidInput);
  OceanCase bad = c;
  bad.spectrum.numbers["hs"] = -1;
  EXPECT_THROW(Synthesizer(bad, {"fftw", Precision::f32}), swell::InvalidInput);
  bad = c;
  bad.spreading.model.clear();
  EXPECT_THROW(Synthesizer(bad, {"fftw", Precision::f32}), swell::InvalidInput);
  const Synthesizer synth(c, {"fftw", Precision::f32});
  std::vector<std::byte> small(synth.frame_bytes() - 1);
  EXPECT_THROW(synth.evaluate(0.0, small), swell::InvalidInput);
}

}  // namespace
