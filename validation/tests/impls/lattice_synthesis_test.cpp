// Rank-1 lattice synthesis (docs/conventions.md §2.1): the synthesizer on a lattice
// against the direct O(N²) sum with exact integer phases, against the same waves through a
// tensor grid that contains them, and against the independent test engine; the analysis
// transform's round trip, Parseval and aliasing; the ocean checks on lattice surfaces (right
// ones pass, the catalogue's bugs that make sense on a lattice are caught).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <iostream>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/lattice.hpp"
#include "swell/reference/sampling.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "swell/validation/checks/ocean_matrix.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "gate/gate_cases.hpp"
#include "test_engine.hpp"
#include "test_support.hpp"

namespace {

using swell::impls::LatticeTransform;
using swell::impls::Packing;
using swell::impls::Precision;
using swell::impls::Synthesizer;
using swell::impls::SynthesizerOptions;
using swell::reference::Field;
using swell::reference::OceanCase;
using swell::reference::RankOneLattice;
using swell::reference::Sampling;
using swell::test::EngineBug;
using cplx = std::complex<double>;
using lcplx = std::complex<long double>;

// The built-in JONSWAP case (deep water, cos-2s, λ = 0.8) on a lattice over its 200 m patch.
OceanCase lattice_case(std::shared_ptr<const RankOneLattice> lattice,
                       const std::string& name = "jonswap_deep") {
  for (const auto& c : swell::validation::builtin_ocean_cases(64)) {
    if (c.name != name) continue;
    OceanCase out = c.ocean_case;
    out.set_lattice(std::move(lattice));
    return out;
  }
  throw std::runtime_error("no built-in case " + name);
}

std::shared_ptr<const RankOneLattice> korobov(std::int64_t n, double l = 200) {
  return std::make_shared<const RankOneLattice>(swell::reference::korobov_lattice(n, {l, l}));
}
std::shared_ptr<const RankOneLattice> fibonacci(int j, double l = 200) {
  return std::make_shared<const RankOneLattice>(swell::reference::fibonacci_lattice(j, l, l));
}

// The six fields at every lattice point by the direct sum, in long double, with each phase
// 2π (m n mod N)/N from exact integers: f(x_n) = Σ_m f̂(k_m) e^(2πi m n / N), the coefficients
// from the definition (impls::initial_amplitude, ω of the case).
std::vector<std::vector<long double>> direct_sum(const OceanCase& c, double t) {
  const RankOneLattice& lat = *c.lattice;
  const std::int64_t n_points = lat.points();
  const Sampling s = c.sampling();
  const long double lambda = c.choppiness;
  std::vector<std::array<lcplx, 8>> coefficients(static_cast<std::size_t>(n_points));
  for (std::int64_t m = 0; m < n_points; ++m) {
    if (!lat.carries_energy(m)) continue;
    const auto k = lat.wave_vector(m);
    const long double kx = k[0] * s.dkx(), ky = k[1] * s.dky(), kk = std::hypot(kx, ky);
    const long double w = c.omega(static_cast<double>(kk));
    const cplx a = swell::impls::initial_amplitude(c, k[0], k[1]);
    const cplx b = std::conj(swell::impls::initial_amplitude(c, -k[0], -k[1]));
    const lcplx h = lcplx(a.real(), a.imag()) * std::exp(lcplx(0, -w * t)) +
                    lcplx(b.real(), b.imag()) * std::exp(lcplx(0, w * t));
    const lcplx i(0, 1);
    coefficients[static_cast<std::size_t>(m)] = {
        h, i * kx * h, i * ky * h, i * lambda * kx / kk * h, i * lambda * ky / kk * h,
        -lambda * kx * kx / kk * h, -lambda * ky * ky / kk * h, -lambda * kx * ky / kk * h};
  }
  std::vector<lcplx> roots(static_cast<std::size_t>(n_points));
  for (std::int64_t r = 0; r < n_points; ++r) {
    const long double phase = 2 * std::numbers::pi_v<long double> * r / n_points;
    roots[static_cast<std::size_t>(r)] = lcplx(std::cos(phase), std::sin(phase));
  }
  std::vector<std::vector<long double>> fields(6, std::vector<long double>(n_points));
  for (std::int64_t n = 0; n < n_points; ++n) {
    std::array<lcplx, 8> sum{};
    for (std::int64_t m = 0; m < n_points; ++m) {
      const lcplx e = roots[static_cast<std::size_t>((m * n) % n_points)];
      for (int f = 0; f < 8; ++f) sum[f] += coefficients[static_cast<std::size_t>(m)][f] * e;
    }
    const auto p = static_cast<std::size_t>(n);
    for (int f = 0; f < 5; ++f) fields[f][p] = sum[f].real();
    fields[5][p] = (1 + sum[5].real()) * (1 + sum[6].real()) - sum[7].real() * sum[7].real();
  }
  return fields;
}

using swell::test::relative_l2;

struct Exactness {
  std::shared_ptr<const RankOneLattice> lattice;
  std::string backend;
  Precision precision;
  Packing packing;
  LatticeTransform transform = LatticeTransform::automatic;
};

// The synthesizer's lattice frame against the direct sum: relative L2 of each field within
// 8 u log2 N (u the synthesis precision's unit roundoff): the transforms' own error bound
// (docs/transforms.md, c·ε·log2 N with the c of the radix-2 and FFTW bounds) plus the
// rounding of the coefficients. J − 1 is compared (J itself is ≈ 1 and would hide errors).
TEST(LatticeSynthesis, MatchesTheDirectSumWithExactIntegerPhases) {
  const std::vector<Exactness> cases = {
      {fibonacci(13), "fftw", Precision::f64, Packing::complex_pairs},   // N = 233
      {fibonacci(13), "fftw", Precision::f32, Packing::real},
      {fibonacci(12), "naive", Precision::f64, Packing::complex_pairs},  // N = 144, even
      {korobov(256), "radix2", Precision::f64, Packing::complex_pairs},
      {korobov(256), "radix2", Precision::f32, Packing::complex_pairs},
      {korobov(255), "fftw", Precision::f64, Packing::real},
      // Bailey's four-step transform (automatic from 2^16 points on; forced here on sizes the
      // direct sum can afford): 4096 = 64·64 on radix2, 6000 = 80·75 and the Fibonacci
      // N = F_18 = 2584 = 68·38 on fftw, whose twiddles e^(2πi m1 p2/N) are not powers of two.
      {korobov(4096), "radix2", Precision::f32, Packing::complex_pairs, LatticeTransform::four_step},
      {korobov(4096), "radix2", Precision::f64, Packing::complex_pairs, LatticeTransform::four_step},
      {korobov(6000), "fftw", Precision::f64, Packing::complex_pairs, LatticeTransform::four_step},
      {fibonacci(18), "fftw", Precision::f32, Packing::complex_pairs, LatticeTransform::four_step},
  };
  for (const Exactness& e : cases) {
    OceanCase c = lattice_case(e.lattice);
    SynthesizerOptions options;
    options.backend = e.backend;
    options.precision = e.precision;
    options.packing = e.packing;
    options.lattice_transform = e.transform;
    const Synthesizer synthesizer(c, options);
    if (e.transform == LatticeTransform::four_step) {
      const auto [n1, n2] = synthesizer.four_step_factors();
      ASSERT_EQ(std::int64_t(n1) * n2, e.lattice->points()) << e.lattice->describe();
    }
    const double t = 1234.5;
    const auto frame = synthesizer.frame(t);
    auto want = direct_sum(c, t);
    for (auto& v : want[5]) v -= 1;
    const double u = e.precision == Precision::f32 ? 0x1p-24 : 0x1p-53;
    const double bound = 8 * u * std::log2(double(e.lattice->points()));
    double worst = 0;
    for (std::size_t f = 0; f < swell::reference::kAllFields.size(); ++f) {
      const Field field = swell::reference::kAllFields[f];
      std::vector<double> got = frame.fields.at(field);
      if (field == Field::jacobian) for (double& v : got) v -= 1;
      const double error = relative_l2(got, want[f]);
      EXPECT_LE(error, bound) << e.lattice->describe() << " " << e.backend << " "
                              << swell::impls::to_string(e.precision) << " "
                              << swell::reference::field_name(field);
      EXPECT_GT(error, 0.0) << "compared with itself?";
      worst = std::max(worst, error);
    }
    std::cout << "[ direct sum ] " << e.lattice->describe() << " " << e.backend << " "
              << swell::impls::to_string(e.precision) << " "
              << swell::impls::to_string(e.transform) << ": largest relative L2 error " << worst
              << " (bound " << bound << ")\n";
  }
}

// Beyond the direct sum's reach: the four-step frame against the backend's one-pass 1-D plan,
// within the sum of both transforms' bounds (8 u log2 N each), on a power of two (radix2, the
// automatic choice from 2^17 points on there), on 2^17 with fftw (one pass by default: its
// large 1-D plans are blocked already) and on a 6-smooth N; the automatic choice itself; and
// four_step refused, naming why, where N has no factor pair.
TEST(LatticeSynthesis, FourStepAgreesWithTheOnePassTransformOnLargeLattices) {
  struct Large {
    std::int64_t points;
    std::string backend;
    Precision precision;
    bool automatic_four_step;  // what LatticeTransform::automatic is expected to choose
  };
  for (const Large& l : {Large{1 << 17, "radix2", Precision::f32, true},
                         Large{1 << 16, "radix2", Precision::f64, false},
                         Large{1 << 17, "fftw", Precision::f64, false},
                         Large{3 * 5 * 7 * 11 * 13 * 17, "fftw", Precision::f32, false}}) {
    const OceanCase c = lattice_case(korobov(l.points, 800));
    SynthesizerOptions options;
    options.backend = l.backend;
    options.precision = l.precision;
    const Synthesizer automatic(c, options);
    EXPECT_EQ(automatic.four_step_factors()[0] != 0, l.automatic_four_step)
        << l.points << " " << l.backend;
    options.lattice_transform = LatticeTransform::four_step;
    const Synthesizer four_step(c, options);
    const auto [n1, n2] = four_step.four_step_factors();
    ASSERT_EQ(std::int64_t(n1) * n2, l.points);
    EXPECT_LE(n2, n1);
    options.lattice_transform = LatticeTransform::one_pass;
    const Synthesizer one_pass(c, options);
    EXPECT_EQ(one_pass.four_step_factors()[0], 0);
    const double t = 77.25;
    const auto a = four_step.frame(t), b = one_pass.frame(t);
    const double u = l.precision == Precision::f32 ? 0x1p-24 : 0x1p-53;
    const double bound = 2 * 8 * u * std::log2(double(l.points));
    for (const Field field : swell::reference::kAllFields) {
      std::vector<long double> want(b.fields.at(field).begin(), b.fields.at(field).end());
      std::vector<double> got = a.fields.at(field);
      if (field == Field::jacobian) {
        for (auto& v : want) v -= 1;
        for (auto& v : got) v -= 1;
      }
      const double error = relative_l2(got, want);
      EXPECT_LE(error, bound) << l.points << " " << l.backend << " "
                              << swell::reference::field_name(field);
      EXPECT_GT(error, 0.0) << "the same transform twice?";
    }
  }
  SynthesizerOptions forced;
  forced.lattice_transform = LatticeTransform::four_step;
  try {
    Synthesizer prime(lattice_case(korobov(65537)), forced);  // a prime N
    FAIL() << "four_step on a prime N was accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("no factor pair"), std::string::npos) << e.what();
  }
}

// For a small lattice the same waves through a tensor grid: N = 64 with g = (1, a) puts every
// point on the 64×64 grid (i, j) = (n, a n mod 64), and every k_m lies inside that grid's band
// (|k_d| < 32), so a 2-D inverse FFT of the coefficients placed at the k_m, read at the
// lattice points, is the lattice field.
TEST(LatticeSynthesis, EqualsTheSameWavesThroughATensorGrid) {
  const auto lattice = korobov(64);
  const OceanCase c = lattice_case(lattice);
  SynthesizerOptions options;
  options.precision = Precision::f64;
  const auto frame = Synthesizer(c, options).frame(3.0);
  const int n = 64;
  std::vector<cplx> grid_spectrum(std::size_t(n) * n, 0.0);
  const swell::reference::Grid grid{n, n, 200, 200};
  for (std::int64_t m = 0; m < n; ++m) {
    if (!lattice->carries_energy(m)) continue;
    const auto k = lattice->wave_vector(m);
    ASSERT_LT(std::abs(k[0]), n / 2);
    ASSERT_LT(std::abs(k[1]), n / 2);
    const double kk = std::hypot(k[0] * grid.dkx(), k[1] * grid.dky());
    const double w = c.omega(kk);
    const cplx h = swell::impls::initial_amplitude(c, k[0], k[1]) * std::exp(cplx(0, -w * 3.0)) +
                   std::conj(swell::impls::initial_amplitude(c, -k[0], -k[1])) *
                       std::exp(cplx(0, w * 3.0));
    grid_spectrum[std::size_t((k[1] + n) % n) * n + std::size_t((k[0] + n) % n)] = h;
  }
  const auto on_grid = swell::validation::field_from_spectrum(grid_spectrum, grid);
  const auto& height = frame.fields.at(Field::height);
  double worst = 0, rms = 0;
  for (std::int64_t p = 0; p < n; ++p) {
    const auto g = lattice->generator();
    const std::size_t i = std::size_t((p * g[0]) % n), j = std::size_t((p * g[1]) % n);
    worst = std::max(worst, std::abs(height[std::size_t(p)] - on_grid[j * n + i]));
    rms += height[std::size_t(p)] * height[std::size_t(p)];
  }
  rms = std::sqrt(rms / n);
  EXPECT_LE(worst, 1e-13 * rms) << lattice->describe();
  EXPECT_GT(rms, 0.0);
}

// The synthesizer and the test engine (an independent implementation of the conventions) make
// the same lattice surface.
TEST(LatticeSynthesis, AgreesWithTheIndependentTestEngine) {
  for (const auto& lattice : {fibonacci(17), korobov(4096)}) {
    OceanCase c = lattice_case(lattice);
    c.frames = 2;
    SynthesizerOptions options;
    options.precision = Precision::f64;
    const auto ours = Synthesizer(c, options).frames();
    const auto theirs = swell::test::render_surface(c, EngineBug::none);
    for (std::size_t f = 0; f < ours.frames.size(); ++f) {
      for (Field field : swell::reference::kAllFields) {
        const auto& a = ours.frames[f].fields.at(field);
        const auto& b = theirs.frames[f].fields.at(field);
        double error = 0, norm = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
          const double shift = field == Field::jacobian ? 1.0 : 0.0;
          error += (a[i] - b[i]) * (a[i] - b[i]);
          norm += (b[i] - shift) * (b[i] - shift);
        }
        EXPECT_LE(std::sqrt(error / norm), 1e-13)
            << lattice->describe() << " frame " << f << " " << swell::reference::field_name(field);
      }
    }
  }
}

// The analysis transform: the round trip gives back the coefficients the synthesis put in (at
// the k_m of every class, to rounding), and Parseval holds: Σ_m |ĥ_m|² = mean h².
TEST(LatticeAnalysis, RoundTripAndParseval) {
  for (const auto& lattice : {fibonacci(15), korobov(1000)}) {
    const OceanCase c = lattice_case(lattice);
    SynthesizerOptions options;
    options.precision = Precision::f64;
    const double t = 7.5;
    const auto frame = Synthesizer(c, options).frame(t);
    const Sampling s = c.sampling();
    const auto& h = frame.fields.at(Field::height);
    const auto spectrum = swell::validation::field_spectrum(h, s);
    double largest = 0, worst = 0, power = 0, mean_square = 0;
    for (std::size_t m = 0; m < s.size(); ++m) {
      cplx want = 0;
      if (s.carries_energy(m)) {
        const auto [kn, km] = s.wave_index(m);
        const double w = c.omega(std::hypot(kn * s.dkx(), km * s.dky()));
        want = swell::impls::initial_amplitude(c, kn, km) * std::exp(cplx(0, -w * t)) +
               std::conj(swell::impls::initial_amplitude(c, -kn, -km)) * std::exp(cplx(0, w * t));
      }
      largest = std::max(largest, std::abs(want));
      worst = std::max(worst, std::abs(spectrum[m] - want));
      power += std::norm(spectrum[m]);
    }
    for (double v : h) mean_square += v * v;
    mean_square /= double(h.size());
    EXPECT_LE(worst, 1e-13 * largest) << lattice->describe();
    EXPECT_NEAR(power, mean_square, 1e-13 * mean_square) << lattice->describe();
    const auto back = swell::validation::field_from_spectrum(spectrum, s);
    for (std::size_t p = 0; p < h.size(); ++p) ASSERT_NEAR(back[p], h[p], 1e-13 * std::sqrt(mean_square));
  }
}

// Aliasing: a plane wave cos(K·x) at any integer k, however far outside the band, lands exactly
// in the classes ±k·g mod N (half its square in each), nowhere else.
TEST(LatticeAnalysis, APlaneWaveLandsExactlyInItsResidueClass) {
  const auto lattice = korobov(997, 150);
  const Sampling s(lattice);
  std::mt19937_64 random(12);
  std::uniform_int_distribution<int> component(-5000, 5000);
  for (int trial = 0; trial < 20; ++trial) {
    const std::int64_t k[2] = {component(random), component(random)};
    if (k[0] == 0 && k[1] == 0) continue;
    std::vector<double> field(s.size());
    for (std::size_t p = 0; p < s.size(); ++p) {
      // The phase k·x_n/L·2π from exact integers: (k·g n) mod N.
      const auto& g = lattice->generator();
      const std::int64_t r = ((k[0] * g[0] + k[1] * g[1]) % 997 + 997) % 997 * std::int64_t(p) % 997;
      field[p] = std::cos(2 * std::numbers::pi * double(r) / 997);
    }
    const auto spectrum = swell::validation::field_spectrum(field, s);
    const auto plus = static_cast<std::size_t>(lattice->residue(std::span<const std::int64_t>(k, 2)));
    const auto minus = s.conjugate(plus);
    for (std::size_t m = 0; m < s.size(); ++m) {
      const double want = m == plus || m == minus ? 0.5 : 0.0;
      ASSERT_NEAR(std::abs(spectrum[m]), want, 1e-13) << "k = (" << k[0] << ", " << k[1] << ") m = " << m;
    }
    // And its class's minimal vector is what the lattice calls k_m: K·x_n agrees there.
    const auto km = lattice->wave_vector(static_cast<std::int64_t>(plus));
    const std::int64_t kmv[2] = {km[0], km[1]};
    EXPECT_EQ(lattice->residue(std::span<const std::int64_t>(kmv, 2)), static_cast<std::int64_t>(plus));
  }
}

// ------------------------------------------------------------------ the checks on lattices

struct LatticeRow {
  std::string name;
  std::shared_ptr<const RankOneLattice> lattice;
  Precision precision;
  std::string backend;
};

// Right lattice surfaces pass every check (α = 1e-3 each), for each built-in case, on a
// Fibonacci and a spectral-test Korobov lattice of about 64² points, in fp32 and fp64.
TEST(LatticeChecks, RightSurfacesPassEveryCheck) {
  const std::vector<LatticeRow> rows = {
      {"fibonacci F19", fibonacci(19), Precision::f32, "fftw"},
      {"fibonacci F19", fibonacci(19), Precision::f64, "fftw"},
      {"korobov 4096", korobov(4096), Precision::f32, "radix2"},
      {"korobov 4096", korobov(4096), Precision::f64, "fftw"},
  };
  for (const auto& builtin : swell::validation::builtin_ocean_cases(64)) {
    for (const LatticeRow& row : rows) {
      const OceanCase c = lattice_case(row.lattice, builtin.name);
      SynthesizerOptions options;
      options.precision = row.precision;
      options.backend = row.backend;
      const auto frames = Synthesizer(c, options).frames();
      const auto report = swell::validation::run_ocean_checks(c, frames);
      EXPECT_TRUE(report.skipped.empty());
      EXPECT_GE(report.results.size(), 20u);
      for (const auto& r : report.results) {
        EXPECT_TRUE(r.passed) << builtin.name << " " << row.name << " "
                              << swell::impls::to_string(row.precision) << ": " << r.check << ": "
                              << r.reason;
      }
    }
  }
}

struct LatticeBug {
  EngineBug bug;
  std::string failing_check;  // a result that must fail
  std::string naming;         // in its reason
  bool shallow = false;
};

// The gate catalogue's sea (gate_cases.hpp), sampled by `lattice` (set_lattice replaces its
// grid); shallow: TMA Hs 1.5 m over 10 m of water.
OceanCase catalogue_case(std::shared_ptr<const RankOneLattice> lattice, bool shallow) {
  OceanCase c = shallow ? swell::test::shallow_case() : swell::test::catalogue_case();
  c.set_lattice(std::move(lattice));
  return c;
}

// The catalogue's engine bugs that make sense on a lattice are caught on lattice frames, by the
// check that names them on grids.
TEST(LatticeChecks, CatalogueBugsAreCaughtOnLatticeFrames) {
  const std::vector<LatticeBug> bugs = {
      {EngineBug::energy_doubled, "energy", "Tessendorf"},
      {EngineBug::independent_minus_k_real_part, "energy", "not paired as conj"},
      {EngineBug::reversed_time, "direction.distribution", "against the wind"},
      {EngineBug::deep_water_dispersion, "dispersion.residual",
       "dispersion of deep water; the case says 10 m", true},
      {EngineBug::displacement_sign_flipped, "derived.disp_x", "sign flipped"},
      {EngineBug::uniform_noise, "statistics.gaussian_amplitudes", "uniform noise"},
      {EngineBug::same_pair_for_minus_k, "direction.travelling", "same random pair"},
  };
  // About the catalogue grid's 128² points: Korobov 2^14 and Fibonacci F21 = 10946.
  for (const auto& lattice : {korobov(16384, 800), fibonacci(21, 800)}) {
    for (const LatticeBug& b : bugs) {
      const OceanCase c = catalogue_case(lattice, b.shallow);
      const auto frames = swell::test::render_surface(c, b.bug);
      const auto report = swell::validation::run_ocean_checks(c, frames);
      bool found = false;
      for (const auto& r : report.results) {
        if (r.check.rfind(b.failing_check, 0) != 0 || r.passed) continue;
        found = true;
        EXPECT_NE(r.reason.find(b.naming), std::string::npos)
            << swell::test::to_string(b.bug) << ": '" << b.naming << "' not in " << r.reason;
      }
      EXPECT_TRUE(found) << lattice->describe() << ": " << swell::test::to_string(b.bug)
                         << " passed " << b.failing_check;
    }
  }
}

// Frames on another sampling than the case's are refused, naming both.
TEST(LatticeChecks, RefuseFramesOfAnotherSampling) {
  const OceanCase c = lattice_case(korobov(4096));
  auto frames = swell::test::render_surface(lattice_case(fibonacci(18)), EngineBug::none);
  try {
    (void)swell::validation::run_ocean_checks(c, frames);
    FAIL() << "accepted frames of another lattice";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("fibonacci"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("korobov"), std::string::npos) << e.what();
  }
}

}  // namespace
