// Cascades (docs/conventions.md §2.2, docs/gate.md §10): band weights, the case
// file's [cascades] tables and their rule, the random numbers of a set, the summed surface, and
// the gate on a set — right sets pass at the calibrated rate, and each bug of the catalogue is
// failed by the check whose message names it.
#include <gtest/gtest.h>

#include <boost/math/distributions/binomial.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <functional>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/cascade.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/wave_noise.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "cli_support.hpp"

namespace {

using swell::InvalidInput;
using swell::reference::BandWeight;
using swell::reference::CascadeMember;
using swell::reference::Field;
using swell::reference::FrameSequence;
using swell::reference::Grid;
using swell::reference::OceanCase;
using swell::validation::CaseFile;
using swell::validation::GateOptions;
using swell::validation::GateReport;
using Complex = std::complex<double>;

// ------------------------------------------------------------------ band weights

TEST(BandWeight, HardCutsAreOneInsideAndZeroOutside) {
  const BandWeight band{0.1, 0.4, 1};
  EXPECT_EQ(band.weight_squared(0.0999999), 0);
  EXPECT_EQ(band.weight_squared(0.1), 1);
  EXPECT_EQ(band.weight_squared(0.3999999), 1);
  EXPECT_EQ(band.weight_squared(0.4), 0);
  EXPECT_TRUE(BandWeight{}.everywhere());
  EXPECT_EQ(BandWeight{}.weight_squared(1e6), 1);
}

// Two bands sharing an edge and a crossover ratio add to Σ w² = 1 at every |k| (sin² + cos²),
// with w² = ½ exactly at the edge and the transition confined to [edge/r, edge·r].
TEST(BandWeight, CrossoversOfAdjacentBandsShareTheSpectrumOut) {
  const double r = 1.3;
  const BandWeight low{0, 0.2, r}, mid{0.2, 0.9, r}, high{0.9, INFINITY, r};
  for (double k = 0.01; k < 5; k *= 1.01) {
    const double sum = low.weight_squared(k) + mid.weight_squared(k) + high.weight_squared(k);
    EXPECT_NEAR(sum, 1, 1e-14) << "k = " << k;
  }
  EXPECT_NEAR(low.weight_squared(0.2), 0.5, 1e-15);
  EXPECT_NEAR(mid.weight_squared(0.2), 0.5, 1e-15);
  EXPECT_EQ(mid.weight_squared(0.2 / r * 0.999), 0);
  EXPECT_EQ(mid.weight_squared(0.2 * r * 1.001), 1);
  EXPECT_THROW(BandWeight({0.2, 0.3, 1.3}).validate("x"), InvalidInput);  // 0.3/0.2 < r²
  EXPECT_THROW(BandWeight({0.3, 0.2, 1}).validate("x"), InvalidInput);
  EXPECT_THROW(BandWeight({0.1, 0.2, 0.5}).validate("x"), InvalidInput);
}

// ------------------------------------------------------------------ case files

// The sea every test shares: JONSWAP Hs 3 m, Tp 8 s (k_p = 0.063 rad/m), cos-2s s = 10 toward
// 30°, deep water. Cascade 0: 64² over 1000 m, band [0, 0.1) rad/m; cascade 1: 64² over 250 m,
// [0.1, 0.8) — the second patch a quarter of the first, as the engines that hide tiling do.
std::string sea_toml(int frames = 8) {
  return "[time]\ndt = 0.5\nframes = " + std::to_string(frames) +
         "\n[spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 8.0\ngamma = 3.3\n"
         "[spreading]\nmodel = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n"
         "[synthesis]\nchoppiness = 1.0\nseed = 11\n";
}

std::string cascade_table(int n, double length, double lo, double hi, int index) {
  return "\n[[cascade]]\nn = [" + std::to_string(n) + ", " + std::to_string(n) + "]\nlength = [" +
         std::to_string(length) + ", " + std::to_string(length) + "]\nband = [" +
         std::to_string(lo) + ", " + std::to_string(hi) + "]\nfiles = \"cascade" +
         std::to_string(index) + "/frame_%04d.exr\"\nheight = \"h\"\n";
}

std::string pair_toml(int frames = 8) {
  return sea_toml(frames) + "\n[cascades]\nrelation = \"additive\"\n" +
         cascade_table(64, 1000, 0, 0.1, 0) + cascade_table(64, 250, 0.1, 0.8, 1);
}

CaseFile parse(const std::string& text) {
  return swell::validation::parse_case_toml(text, "/tmp/cascade_test/case.toml");
}

std::string refusal(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

// The case-file spelling users were given for cascade sets, verbatim (with a sea around it).
TEST(CascadeCase, ReadsTheIssuesSpelling) {
  const std::string text = sea_toml() + R"(
[cascades]
relation = "additive"

[[cascade]]
n = [128, 128]
length = [1600.0, 1600.0]
band = [0.0, 0.0629]          # |k| in rad/m, [lo, hi)
files = "cascade0/frame_%04d.exr"
height = "h"
disp_x = "dx"
disp_y = "dy"

[[cascade]]
n = [128, 128]
length = [400.0, 400.0]
band = [0.0629, 0.2516]
files = "cascade1/frame_%04d.exr"
height = "h"
disp_x = "dx"
disp_y = "dy"
)";
  const CaseFile c = parse(text);
  ASSERT_EQ(c.cascades.size(), 2u);
  EXPECT_EQ(c.relation, swell::reference::CascadeRelation::additive);
  EXPECT_EQ(c.cascades[1].grid.nx, 128);
  EXPECT_EQ(c.cascades[1].grid.lx, 400.0);
  EXPECT_EQ(c.cascades[1].band.lo, 0.0629);
  EXPECT_EQ(c.cascades[1].band.hi, 0.2516);
  EXPECT_EQ(c.cascades[1].input.files, "cascade1/frame_%04d.exr");
  EXPECT_EQ(c.cascades[1].input.channels.at(Field::disp_y), "dy");
  EXPECT_EQ(c.cascade_case(1).cascade, 1);
  EXPECT_EQ(c.cascade_case(1).band, c.cascades[1].band);
  const auto summed = c.summed_case();
  ASSERT_TRUE(summed.has_value());
  EXPECT_EQ(summed->grid.nx, 512);  // 400 m / 128 = 3.125 m spacing over 1600 m
  EXPECT_EQ(summed->grid.lx, 1600.0);
  // The text swell synth writes reads back to the same set.
  const CaseFile again = parse(swell::validation::case_toml(c));
  ASSERT_EQ(again.cascades.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(again.cascades[k].grid.nx, c.cascades[k].grid.nx);
    EXPECT_EQ(again.cascades[k].grid.lx, c.cascades[k].grid.lx);
    EXPECT_EQ(again.cascades[k].band, c.cascades[k].band);
    EXPECT_EQ(again.cascades[k].input.files, c.cascades[k].input.files);
  }
}

// The share of m0 that the sea of cascade_test's cases holds in [k0, k1) rad/m, by trapezoids on
// S(ω) over ω(k) = √(g k) (deep water), independent of the library's quadrature.
double m0_share(const CaseFile& c, double k0, double k1) {
  const auto sea = c.ocean.sea_spectrum();
  const auto& s = sea->omnidirectional();
  const double w0 = std::sqrt(9.81 * k0), w1 = std::sqrt(9.81 * k1);
  double part = 0;
  const int steps = 20000;
  for (int i = 0; i < steps; ++i) {
    const double a = w0 + (w1 - w0) * i / steps, b = w0 + (w1 - w0) * (i + 1) / steps;
    part += 0.5 * (s(a) + s(b)) * (b - a);
  }
  return part / (3.0 * 3.0 / 16);  // m0 = Hs²/16
}

// Overlaps and gaps are read (the gate judges them: cascades.bands), and band_coverage names
// each with its range in rad/m, its factor Σ w² and the share of m0 it holds; the share is
// checked against an independent trapezoid integral of S(ω) over that range.
TEST(CascadeCase, ReadsBandsThatOverlapOrLeaveGapsAndNamesThem) {
  const CaseFile overlap = parse(sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0, 0.12, 0) +
                                 cascade_table(64, 250, 0.1, 0.8, 1));
  const auto overlaps = swell::reference::band_sharing_problems(overlap.ocean, overlap.members());
  ASSERT_EQ(overlaps.size(), 1u);
  EXPECT_EQ(overlaps[0].weight_sum, 2);
  EXPECT_EQ(overlaps[0].cascades, (std::vector<int>{0, 1}));
  EXPECT_NEAR(overlaps[0].k_lo, 0.1, 1e-12);
  EXPECT_NEAR(overlaps[0].k_hi, 0.12, 1e-12);
  EXPECT_NE(overlaps[0].describe().find("cascades 0 and 1 both carry 0.1–0.12 rad/m: energy × 2 there"),
            std::string::npos)
      << overlaps[0].describe();
  const CaseFile gap = parse(sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0, 0.08, 0) +
                             cascade_table(64, 250, 0.1, 0.8, 1));
  const auto gaps = swell::reference::band_sharing_problems(gap.ocean, gap.members());
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_NE(gaps[0].describe().find("no cascade carries 0.08–0.1 rad/m"), std::string::npos)
      << gaps[0].describe();
  const double share = m0_share(gap, 0.08, 0.1);
  EXPECT_NEAR(gaps[0].m0_share, share, 1e-6 * share);
  EXPECT_EQ(gaps[0].weight_sum, 0);
  // A right pair, and a declared crossover (a weighted overlap), have none.
  const CaseFile right_pair = parse(pair_toml());
  EXPECT_TRUE(swell::reference::band_coverage(right_pair.ocean, right_pair.members()).empty());
  const CaseFile crossover = parse(sea_toml() + "\n[cascades]\ncrossover = 1.2\n" +
                                   cascade_table(64, 1000, 0, 0.1, 0) + cascade_table(64, 250, 0.1, 0.8, 1));
  EXPECT_TRUE(swell::reference::band_sharing_problems(crossover.ocean, crossover.members()).empty());
}

// Cascades declared over the whole spectrum carry it where their grids hold whole rings of |k|
// (Δk = 2π/L to the Nyquist π n/L): three 64² grids over 1000, 250 and 62.5 m overlap two by
// two, then all three, then two by two, and the range each group shares is named.
TEST(CascadeCase, FullSpectrumCascadesOverlapWhereTheirGridsDo) {
  const CaseFile c = parse(sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0, 100, 0) +
                           cascade_table(64, 250, 0, 100, 1) + cascade_table(64, 62.5, 0, 100, 2));
  const auto problems = swell::reference::band_sharing_problems(c.ocean, c.members());
  const double pi = std::numbers::pi;
  // (Δk of 250 m, Δk of 62.5 m, Nyquist of 1000 m, Nyquist of 250 m): the groups' edges.
  const double edges[] = {2 * pi / 250, 2 * pi / 62.5, pi * 64 / 1000, pi * 64 / 250};
  const std::vector<std::vector<int>> groups = {{0, 1}, {0, 1, 2}, {1, 2}};
  ASSERT_EQ(problems.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(problems[i].cascades, groups[i]);
    EXPECT_EQ(problems[i].weight_sum, double(groups[i].size()));
    EXPECT_NEAR(problems[i].k_lo, edges[i], 1e-12);
    EXPECT_NEAR(problems[i].k_hi, edges[i + 1], 1e-12);
    const double share = m0_share(c, edges[i], edges[i + 1]);
    EXPECT_NEAR(problems[i].m0_share, share, 1e-6 * share);
  }
}

TEST(CascadeCase, RefusesWhatASetCannotBe) {
  const std::string cascades = "\n[cascades]\n" + cascade_table(64, 1000, 0, 0.1, 0) +
                               cascade_table(64, 250, 0.1, 0.8, 1);
  EXPECT_NE(refusal(sea_toml() + "[grid]\nn = 64\nlength = 100.0\n" + cascades).find("[grid]"),
            std::string::npos);
  const std::string stacked = refusal(sea_toml() + "\n[cascades]\nrelation = \"stacked\"\n" +
                                      cascade_table(64, 1000, 0, 0.1, 0));
  EXPECT_NE(stacked.find("relation"), std::string::npos) << stacked;
  EXPECT_NE(stacked.find("\"independent\""), std::string::npos) << stacked;
  // A cascade's own sea belongs to independent seas only.
  EXPECT_NE(refusal(sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0, 0.1, 0) +
                    cascade_table(64, 250, 0.1, 0.8, 1) +
                    "[cascade.spectrum]\nmodel = \"jonswap\"\nhs = 1.0\ntp = 5.0\n")
                .find("relation = \"independent\""),
            std::string::npos);
  // An additive set of two needs each band.
  EXPECT_NE(refusal(sea_toml() + "\n[cascades]\n[[cascade]]\nn = 64\nlength = 100.0\n"
                                 "[[cascade]]\nn = 64\nlength = 25.0\n")
                .find("band"),
            std::string::npos);
  // Nested bands are two samplings of one patch.
  EXPECT_NE(refusal(sea_toml() + "\n[cascades]\nrelation = \"nested\"\n[[cascade]]\nn = 64\n"
                                 "length = 1000.0\n[[cascade]]\nn = 256\nlength = 500.0\n")
                .find("nested bands are two samplings of one patch"),
            std::string::npos);
  // A sum needs integer ratios.
  EXPECT_NE(refusal(sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0, 0.1, 0) +
                    cascade_table(64, 300, 0.1, 0.8, 1) + "[sum]\nfiles = \"s_%04d.exr\"\nheight = \"h\"\n")
                .find("does not divide"),
            std::string::npos);
  // A band the sea's grid cannot hold is still a band; but an empty one is refused.
  EXPECT_NE(refusal(sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0.1, 0.1, 0)).find("empty"),
            std::string::npos);
}

// A set of independent seas: cascade 0 carries the set's sea (JONSWAP Tp 8 s), cascade 1 a sea
// of its own (JONSWAP Tp 4 s toward 120°), each over its whole band, keyed by its index.
std::string independent_toml(int frames = 8) {
  return sea_toml(frames) +
         "\n[cascades]\nrelation = \"independent\"\n"
         "\n[[cascade]]\nn = 64\nlength = 1000.0\nfiles = \"cascade0/frame_%04d.exr\"\nheight = \"h\"\n"
         "\n[[cascade]]\nn = 64\nlength = 250.0\nfiles = \"cascade1/frame_%04d.exr\"\nheight = \"h\"\n"
         "[cascade.spectrum]\nmodel = \"jonswap\"\nhs = 1.0\ntp = 4.0\ngamma = 3.3\n"
         "[cascade.spreading]\nmodel = \"cos2s\"\ns = 4.0\nwind_dir_deg = 120.0\n";
}

// The sum of independent seas carries every cascade's sea: its expected energy on the fine
// grid, Σ μ, is the cascades' own Σ μ_c added (each from its own case), and its sea has both
// components; the text swell synth writes reads back to the same set.
TEST(CascadeCase, ReadsIndependentSeas) {
  const CaseFile c = parse(independent_toml());
  EXPECT_EQ(c.relation, swell::reference::CascadeRelation::independent);
  EXPECT_EQ(swell::reference::to_string(c.relation), "independent");
  ASSERT_EQ(c.cascades.size(), 2u);
  EXPECT_TRUE(c.cascades[0].components.empty());
  ASSERT_EQ(c.cascades[1].components.size(), 1u);
  const OceanCase c0 = c.cascade_case(0), c1 = c.cascade_case(1);
  EXPECT_EQ(c0.cascade, 0);
  EXPECT_EQ(c1.cascade, 1);
  EXPECT_TRUE(c1.band.everywhere());
  EXPECT_EQ(c0.spectrum.numbers.at("tp"), 8.0);
  EXPECT_EQ(c1.spectrum.numbers.at("tp"), 4.0);
  EXPECT_EQ(c1.spreading.numbers.at("s"), 4.0);
  EXPECT_EQ(c1.wind_dir_deg, 120.0);
  const auto summed = c.summed_case();
  ASSERT_TRUE(summed.has_value());
  EXPECT_EQ(summed->grid.nx, 256);
  EXPECT_EQ(summed->components().size(), 2u);
  auto total = [](const OceanCase& o) {
    double sum = 0;
    for (double mu : swell::validation::expected_periodogram(*o.directional_spectrum(), o.grid)) sum += mu;
    return sum;
  };
  const double parts = total(c0) + total(c1);
  EXPECT_NEAR(total(*summed), parts, 1e-12 * parts);
  // Cascade 1's own sea is most of its energy: carrying the set's instead would show.
  OceanCase set_sea = c1;
  set_sea.set_components(c0.components());
  EXPECT_GT(std::abs(total(set_sea) - total(c1)), 0.1 * total(c1));
  const CaseFile again = parse(swell::validation::case_toml(c));
  EXPECT_EQ(again.relation, c.relation);
  ASSERT_EQ(again.cascades.size(), 2u);
  EXPECT_TRUE(again.cascades[0].components.empty());
  const OceanCase back = again.cascade_case(1);
  EXPECT_EQ(back.spectrum.numbers, c1.spectrum.numbers);
  EXPECT_EQ(back.spreading.numbers, c1.spreading.numbers);
  EXPECT_EQ(back.wind_dir_deg, c1.wind_dir_deg);
  EXPECT_TRUE(back.band.everywhere());
  // Every cascade with its own sea: the set's [spectrum] may be left out.
  const CaseFile own = parse(
      "[time]\ndt = 0.5\nframes = 4\n[synthesis]\nseed = 3\n[cascades]\nrelation = \"independent\"\n"
      "[[cascade]]\nn = 64\nlength = 1000.0\n[cascade.spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 8.0\n"
      "[cascade.spreading]\nmodel = \"cos2s\"\ns = 10.0\n"
      "[[cascade]]\nn = 64\nlength = 250.0\n[cascade.spectrum]\nmodel = \"jonswap\"\nhs = 1.0\ntp = 4.0\n"
      "[cascade.spreading]\nmodel = \"cos2s\"\ns = 4.0\n");
  EXPECT_EQ(own.ocean.spectrum.numbers.at("tp"), 8.0);
  EXPECT_EQ(own.cascade_case(1).spectrum.numbers.at("tp"), 4.0);
}

// The summed surface of independent seas is their sum sample by sample (fp64), each cascade
// synthesized alone from its own case.
TEST(CascadeSynthesis, TheSumOfIndependentSeasIsTheSumOfTheCascades) {
  const CaseFile set = parse(independent_toml(1));
  const auto summed = set.summed_case();
  ASSERT_TRUE(summed.has_value());
  ASSERT_EQ(summed->grid.nx, 256);
  const swell::impls::SynthesizerOptions fp64{"fftw", swell::impls::Precision::f64};
  const double t = 2.3;
  const auto sum = swell::impls::Synthesizer(*summed, fp64).frame(t).fields.at(Field::height);
  const auto c0 = swell::impls::Synthesizer(set.cascade_case(0), fp64).frame(t).fields.at(Field::height);
  const auto c1 = swell::impls::Synthesizer(set.cascade_case(1), fp64).frame(t).fields.at(Field::height);
  double worst = 0, scale = 0;
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) {
      const double expected = c0[j * 64 + i] + c1[((4 * j) % 64) * 64 + (4 * i) % 64];
      worst = std::max(worst, std::abs(sum[(4 * j) * 256 + 4 * i] - expected));
      scale = std::max(scale, std::abs(expected));
    }
  }
  EXPECT_LT(worst, 1e-12 * scale);
}

// ------------------------------------------------------------------ random numbers and the sum

// A set of one cascade (band everywhere) is the single-grid surface, bit for bit; a second
// cascade draws other numbers at the same (n, m).
TEST(CascadeSynthesis, CascadeZeroIsTheSingleGridSurface) {
  const CaseFile set = parse(sea_toml(2) + "\n[cascades]\n[[cascade]]\nn = 64\nlength = 400.0\n");
  OceanCase single = set.ocean;
  single.grid = Grid::create(64, 64, 400, 400);
  const swell::impls::Synthesizer a(set.cascade_case(0), {"fftw", swell::impls::Precision::f64});
  const swell::impls::Synthesizer b(single, {"fftw", swell::impls::Precision::f64});
  EXPECT_EQ(a.frame(0.5).fields.at(Field::height), b.frame(0.5).fields.at(Field::height));
  const auto x0 = swell::reference::wave_noise(11, 3, -2, 0, 0);
  const auto x1 = swell::reference::wave_noise(11, 3, -2, 0, 1);
  EXPECT_NE(x0.xi1, x1.xi1);
}

// The summed surface on the fine grid (3.90625 m over 1000 m, 256²) is the sum of the cascades:
// at the fine sample (4i, 4j), cascade 0's sample (i, j) plus cascade 1's sample at the same
// point of its 250 m patch, tiled — to fp64 rounding, for the linear fields.
TEST(CascadeSynthesis, TheSummedSurfaceIsTheSumOfTheCascades) {
  const CaseFile set = parse(pair_toml(1));
  const auto summed = set.summed_case();
  ASSERT_TRUE(summed.has_value());
  ASSERT_EQ(summed->grid.nx, 256);
  const swell::impls::SynthesizerOptions fp64{"fftw", swell::impls::Precision::f64};
  const double t = 3.7;
  const auto sum = swell::impls::Synthesizer(*summed, fp64).frame(t);
  const auto c0 = swell::impls::Synthesizer(set.cascade_case(0), fp64).frame(t);
  const auto c1 = swell::impls::Synthesizer(set.cascade_case(1), fp64).frame(t);
  for (Field field : {Field::height, Field::slope_x, Field::disp_y}) {
    double worst = 0, scale = 0;
    for (int j = 0; j < 64; ++j) {
      for (int i = 0; i < 64; ++i) {
        const double expected = c0.fields.at(field)[j * 64 + i] +
                                c1.fields.at(field)[((4 * j) % 64) * 64 + (4 * i) % 64];
        worst = std::max(worst, std::abs(sum.fields.at(field)[(4 * j) * 256 + 4 * i] - expected));
        scale = std::max(scale, std::abs(expected));
      }
    }
    EXPECT_LT(worst, 1e-12 * scale) << swell::reference::field_name(field);
  }
  // Between cascade 0's samples the sum still holds cascade 1 exactly: its samples at the fine
  // points (i, j) with i, j ≢ 0 mod 4 are cascade 1's own samples (same spacing), and cascade 0
  // there is its band-limited interpolant — checked through energy: mean h² of the sum is the
  // two cascades' (their cross term averages to zero: disjoint wave vectors).
  double sum_ms = 0, c0_ms = 0, c1_ms = 0;
  for (double v : sum.fields.at(Field::height)) sum_ms += v * v / (256.0 * 256);
  for (double v : c0.fields.at(Field::height)) c0_ms += v * v / (64.0 * 64);
  for (double v : c1.fields.at(Field::height)) c1_ms += v * v / (64.0 * 64);
  EXPECT_NEAR(sum_ms, c0_ms + c1_ms, 1e-12 * sum_ms);
}

// ------------------------------------------------------------------ the gate: fixtures

// Heights of a surface from any amplitudes and any ω (fp64), frames at the case's times: the
// way an engine with a bug would make them.
using Amplitude = std::function<Complex(int n, int m)>;
using Omega = std::function<double(int n, int m)>;

FrameSequence render(const OceanCase& c, const Amplitude& amplitude, const Omega& omega) {
  const auto& g = c.grid;
  FrameSequence out;
  out.grid = g;
  out.unit_roundoff = 0x1p-53;
  std::vector<Complex> a(std::size_t(g.nx) * g.ny), b(a.size());
  std::vector<double> w(a.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const int n = Grid::signed_index(i, g.nx), m = Grid::signed_index(j, g.ny);
      const std::size_t e = std::size_t(j) * g.nx + i;
      if (!g.carries_energy(n, m)) continue;
      a[e] = amplitude(n, m);
      b[e] = std::conj(amplitude(-n, -m));
      w[e] = omega(n, m);
    }
  }
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    std::vector<Complex> spectrum(a.size());
    for (std::size_t e = 0; e < a.size(); ++e) {
      spectrum[e] = a[e] * std::polar(1.0, -w[e] * t) + b[e] * std::polar(1.0, w[e] * t);
    }
    swell::reference::FieldFrame frame;
    frame.time = t;
    frame.fields[Field::height] = swell::validation::field_from_spectrum(spectrum, g);
    out.frames.push_back(std::move(frame));
  }
  return out;
}

// h̃0 of case `c` (its band weight, Δk and cascade key), tabulated once over its grid.
Amplitude right_amplitude(const OceanCase& c) {
  auto table = std::make_shared<std::vector<Complex>>(swell::impls::initial_amplitudes(c));
  const Grid g = c.grid;
  return [table, g](int n, int m) {
    return (*table)[std::size_t((m + g.ny) % g.ny) * g.nx + std::size_t((n + g.nx) % g.nx)];
  };
}

Omega right_omega(const OceanCase& c) {
  return [c](int n, int m) { return c.omega(std::hypot(n * c.grid.dkx(), m * c.grid.dky())); };
}

FrameSequence right(const OceanCase& c) { return render(c, right_amplitude(c), right_omega(c)); }

std::string describe(const GateReport& report) { return swell::validation::render_gate(report); }

const swell::validation::CheckResult* find(const GateReport& report, const std::string& name) {
  for (const auto& r : report.results) {
    if (r.check == name) return &r;
  }
  return nullptr;
}

// The check `name` fails with a reason containing `words`.
void expect_caught(const GateReport& report, const std::string& name, const std::string& words) {
  const auto* r = find(report, name);
  ASSERT_NE(r, nullptr) << name << " did not run\n" << describe(report);
  EXPECT_FALSE(r->passed) << name << " passed\n" << describe(report);
  std::cout << "[ catalogue ] " << name << ": " << r->reason << "\n";
  EXPECT_NE(r->reason.find(words), std::string::npos)
      << name << ": \"" << r->reason << "\" does not say \"" << words << "\"";
}

GateReport gate(const CaseFile& c, const std::vector<FrameSequence>& cascades,
                const FrameSequence* sum = nullptr, double alpha = 1e-3) {
  GateOptions options;
  options.alpha = alpha;
  options.threads = 2;
  return swell::validation::run_cascade_gate(c, cascades, sum, options);
}

// ------------------------------------------------------------------ right sets

TEST(CascadeGate, ARightSetPassesEveryCheck) {
  const CaseFile c = parse(pair_toml());
  const auto summed = c.summed_case();
  ASSERT_TRUE(summed.has_value());
  const std::vector<FrameSequence> frames = {right(c.cascade_case(0)), right(c.cascade_case(1))};
  const FrameSequence sum = right(*summed);
  const auto report = gate(c, frames, &sum);
  EXPECT_TRUE(report.passed()) << describe(report);
  for (const char* name : {"cascade0.band.outside", "cascade1.band.missing", "cascades.bands",
                           "cascades.energy", "cascades.independence", "cascades.patch", "sum.energy",
                           "sum.band.outside", "sum.band.missing", "cascade1.dispersion.residual"}) {
    EXPECT_NE(find(report, name), nullptr) << name;
  }
  // The summed surface alone is judged too.
  const auto alone = gate(c, {FrameSequence{}, FrameSequence{}}, &sum);
  EXPECT_TRUE(alone.passed()) << describe(alone);
  EXPECT_EQ(find(alone, "cascades.independence"), nullptr);
}

// Mitchell's pair: a 64² low band and a 256² broad band of one 1000 m patch.
std::string nested_toml() {
  return sea_toml() + "\n[cascades]\nrelation = \"nested\"\n[[cascade]]\nn = 64\nlength = 1000.0\n"
                      "[[cascade]]\nn = 256\nlength = 1000.0\n";
}

TEST(CascadeGate, ARightNestedPairPasses) {
  const CaseFile c = parse(nested_toml());
  const auto report = gate(c, {right(c.cascade_case(0)), right(c.cascade_case(1))});
  EXPECT_TRUE(report.passed()) << describe(report);
  EXPECT_NE(find(report, "cascades.nested"), nullptr);
}

// Three 64² cascades over 1000, 250 and 62.5 m that each carry the whole spectrum, as Godot 4's
// ocean runs its cascades: declared additive (each band [0, 100) rad/m, beyond every grid) or
// as independent seas (no band).
std::string full_spectrum_toml(const std::string& relation, int frames = 8) {
  std::string text = sea_toml(frames) + "\n[cascades]\nrelation = \"" + relation + "\"\n";
  const double lengths[] = {1000, 250, 62.5};
  for (int c = 0; c < 3; ++c) {
    text += relation == "additive"
                ? cascade_table(64, lengths[c], 0, 100, c)
                : "\n[[cascade]]\nn = 64\nlength = " + std::to_string(lengths[c]) +
                      "\nfiles = \"cascade" + std::to_string(c) + "/frame_%04d.exr\"\nheight = \"h\"\n";
  }
  return text;
}

// The gate's words for cascades `who` carrying [a, b) together (Σ w² = their count), the share
// of m0 from the trapezoid integral, not from the library.
std::string carried(const CaseFile& c, const std::string& who, double a, double b, int factor) {
  return fmt::format("{} carry {:.3g}–{:.3g} rad/m: energy × {} there, {:.2g} % of m0", who, a, b,
                     factor, 100 * m0_share(c, a, b));
}

// Three cascades each carrying the whole spectrum, right as independent seas, declared as an
// additive set: the set is judged (not refused), every cascade passes against its declared
// band, and cascades.bands fails naming each overlap — its range, factor and share of m0.
// Declared as independent seas, the same frames pass.
TEST(CascadeGate, FullSpectrumCascadesDeclaredAdditiveFailNamingEachOverlap) {
  const CaseFile independent = parse(full_spectrum_toml("independent"));
  const CaseFile additive = parse(full_spectrum_toml("additive"));
  std::vector<FrameSequence> frames;
  for (std::size_t i = 0; i < 3; ++i) frames.push_back(right(independent.cascade_case(i)));
  const auto report = gate(additive, frames);
  const double pi = std::numbers::pi;
  expect_caught(report, "cascades.bands",
                carried(additive, "cascades 0, 1 and 2 all", 2 * pi / 62.5, pi * 64 / 1000, 3));
  expect_caught(report, "cascades.bands",
                carried(additive, "cascades 0 and 1 both", 2 * pi / 250, 2 * pi / 62.5, 2));
  expect_caught(report, "cascades.bands",
                carried(additive, "cascades 1 and 2 both", pi * 64 / 1000, pi * 64 / 250, 2));
  expect_caught(report, "cascades.bands", "relation = \"independent\"");
  for (const auto& r : report.results) {
    if (!r.passed) EXPECT_EQ(r.check, "cascades.bands") << r.reason;
  }
  const auto right_set = gate(independent, frames);
  EXPECT_TRUE(right_set.passed()) << describe(right_set);
  EXPECT_EQ(find(right_set, "cascades.bands"), nullptr);
  for (const char* name : {"cascade2.energy", "cascade2.band.missing", "cascades.energy",
                           "cascades.independence", "cascades.patch"}) {
    EXPECT_NE(find(right_set, name), nullptr) << name;
  }
  // The same numbers in every cascade are still caught among independent seas.
  std::vector<FrameSequence> shared = frames;
  OceanCase reused = independent.cascade_case(1);
  reused.cascade = 0;
  shared[1] = render(independent.cascade_case(1), right_amplitude(reused), right_omega(reused));
  expect_caught(gate(independent, shared), "cascades.independence",
                "cascades 0 and 1 share their random numbers");
}

// Two separate overlaps (cascade 0 up to 0.12 over cascade 1's 0.1, cascade 1 up to 0.5 over
// cascade 2's 0.45): both named, nothing else.
TEST(CascadeGate, TwoSeparateOverlapsAreBothNamed) {
  const CaseFile c = parse(sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0, 0.12, 0) +
                           cascade_table(64, 250, 0.1, 0.5, 1) + cascade_table(64, 62.5, 0.45, 3.0, 2));
  std::vector<FrameSequence> frames;
  for (std::size_t i = 0; i < 3; ++i) frames.push_back(right(c.cascade_case(i)));
  const auto report = gate(c, frames);
  expect_caught(report, "cascades.bands", carried(c, "cascades 0 and 1 both", 0.1, 0.12, 2));
  expect_caught(report, "cascades.bands", carried(c, "cascades 1 and 2 both", 0.45, 0.5, 2));
  const auto* bands = find(report, "cascades.bands");
  ASSERT_NE(bands, nullptr);
  std::size_t named = 0;
  for (std::size_t at = bands->reason.find(" carry "); at != std::string::npos;
       at = bands->reason.find(" carry ", at + 1)) {
    ++named;
  }
  EXPECT_EQ(named, 2u) << bands->reason;
}

// Independent seas with a sum: cascade 1 carries a sea of its own, and the sum carries both.
// A sum made as if cascade 1 carried the set's sea fails.
TEST(CascadeGate, IndependentSeasWithTheirSumPass) {
  const CaseFile c = parse(independent_toml());
  const auto summed = c.summed_case();
  ASSERT_TRUE(summed.has_value());
  const FrameSequence sum = right(*summed);
  const auto report = gate(c, {right(c.cascade_case(0)), right(c.cascade_case(1))}, &sum);
  EXPECT_TRUE(report.passed()) << describe(report);
  for (const char* name : {"cascade1.energy", "cascades.independence", "sum.energy", "sum.band.missing"}) {
    EXPECT_NE(find(report, name), nullptr) << name;
  }
  OceanCase wrong = *summed;
  wrong.members[1].spectrum = c.cascade_case(0).sea_spectrum();
  const FrameSequence wrong_sum = render(*summed, right_amplitude(wrong), right_omega(wrong));
  const auto alone = gate(c, {FrameSequence{}, FrameSequence{}}, &wrong_sum);
  EXPECT_FALSE(alone.passed()) << describe(alone);
}

// ------------------------------------------------------------------ the catalogue

// Overlapping bands: cascade 0 carries up to 0.13 rad/m instead of its declared 0.1, where
// cascade 1 carries too.
TEST(CascadeCatalogue, OverlappingBands) {
  const CaseFile c = parse(pair_toml());
  OceanCase wide = c.cascade_case(0);
  wide.band.hi = 0.13;
  const auto report = gate(c, {render(c.cascade_case(0), right_amplitude(wide), right_omega(wide)),
                               right(c.cascade_case(1))});
  expect_caught(report, "cascade0.band.outside", "cascades 0 and 1 both carry 0.1");
  expect_caught(report, "cascade0.band.outside", "(energy × 2");
  // The same bug in the summed surface alone.
  auto members = c.members();
  members[0].band.hi = 0.13;
  OceanCase bad_sum = *c.summed_case();
  bad_sum.members = members;
  const FrameSequence sum = render(*c.summed_case(), right_amplitude(bad_sum), right_omega(bad_sum));
  const auto alone = gate(c, {FrameSequence{}, FrameSequence{}}, &sum);
  expect_caught(alone, "sum.band.outside", "cascades 0 and 1 both carry 0.1");
}

// A gap: cascade 0 stops at 0.07 rad/m although it declares 0.1, and nobody carries the rest.
TEST(CascadeCatalogue, AGap) {
  const CaseFile c = parse(pair_toml());
  OceanCase narrow = c.cascade_case(0);
  narrow.band.hi = 0.07;
  const auto report = gate(c, {render(c.cascade_case(0), right_amplitude(narrow), right_omega(narrow)),
                               right(c.cascade_case(1))});
  expect_caught(report, "cascade0.band.missing", "no cascade carries 0.07");
  expect_caught(report, "cascade0.band.missing", "% of m0 lost");
  auto members = c.members();
  members[0].band.hi = 0.07;
  OceanCase bad_sum = *c.summed_case();
  bad_sum.members = members;
  const FrameSequence sum = render(*c.summed_case(), right_amplitude(bad_sum), right_omega(bad_sum));
  const auto alone = gate(c, {FrameSequence{}, FrameSequence{}}, &sum);
  expect_caught(alone, "sum.band.missing", "no cascade carries 0.07");
}

// Square band cuts: each cascade keeps max(|kx|, |ky|) in [lo, hi) instead of |k|.
TEST(CascadeCatalogue, SquareBandCuts) {
  const CaseFile c = parse(pair_toml());
  std::vector<FrameSequence> frames;
  for (std::size_t k = 0; k < 2; ++k) {
    const OceanCase declared = c.cascade_case(k);
    OceanCase unbanded = declared;
    unbanded.band = {};
    const auto band = declared.band;
    const auto g = declared.grid;
    const auto whole = right_amplitude(unbanded);
    frames.push_back(render(declared,
                            [=](int n, int m) {
                              const double edge = std::max(std::abs(n * g.dkx()), std::abs(m * g.dky()));
                              return edge >= band.lo && edge < band.hi ? whole(n, m) : Complex(0);
                            },
                            right_omega(declared)));
  }
  const auto report = gate(c, frames);
  expect_caught(report, "cascade0.band.outside", "cut as a square in (kx, ky)");
  expect_caught(report, "cascade1.band.outside", "cut as a square in (kx, ky)");
}

// The same random numbers in every cascade: cascade 1 keyed as cascade 0.
TEST(CascadeCatalogue, TheSameRandomNumbersInEveryCascade) {
  const CaseFile c = parse(pair_toml());
  OceanCase reused = c.cascade_case(1);
  reused.cascade = 0;
  const auto report = gate(c, {right(c.cascade_case(0)),
                               render(c.cascade_case(1), right_amplitude(reused), right_omega(reused))});
  expect_caught(report, "cascades.independence", "cascades 0 and 1 share their random numbers");
  // From one frame at t = 0 too (ĥ(k, 0) in place of the fitted h̃0).
  const CaseFile one = parse(pair_toml(1));
  OceanCase reused_one = one.cascade_case(1);
  reused_one.cascade = 0;
  const auto single = gate(one, {right(one.cascade_case(0)),
                                 render(one.cascade_case(1), right_amplitude(reused_one),
                                        right_omega(reused_one))});
  expect_caught(single, "cascades.independence", "cascades 0 and 1 share their random numbers");
}

// Amplitudes with another cascade's Δk: cascade 1 (250 m) uses cascade 0's Δk (1000 m), so its
// energy is (Δk0/Δk1)² = 1/16 of what it should be.
TEST(CascadeCatalogue, AmplitudesWithAnotherCascadesDk) {
  const CaseFile c = parse(pair_toml());
  const OceanCase c1 = c.cascade_case(1);
  const double factor = c.cascade_case(0).grid.dkx() / c1.grid.dkx();  // amplitudes ∝ Δk
  const auto amplitude = right_amplitude(c1);
  const auto report = gate(c, {right(c.cascade_case(0)),
                               render(c1, [&](int n, int m) { return factor * amplitude(n, m); },
                                      right_omega(c1))});
  expect_caught(report, "cascades.energy", "cascade 1 is scaled with cascade 0's Δk (energy × 0.0625)");
}

// A cascade whose k uses another cascade's patch length in the dispersion relation: cascade 1's
// waves move at ω(2π (n, m)/1000 m) instead of ω(2π (n, m)/250 m).
TEST(CascadeCatalogue, ACascadesKUsesAnotherPatchLength) {
  const CaseFile c = parse(pair_toml());
  const OceanCase c1 = c.cascade_case(1);
  const auto report = gate(c, {right(c.cascade_case(0)),
                               render(c1, right_amplitude(c1), [&](int n, int m) {
                                 return c1.omega(std::hypot(2 * std::numbers::pi * n / 1000.0,
                                                            2 * std::numbers::pi * m / 1000.0));
                               })});
  expect_caught(report, "cascades.patch", "cascade 1's waves move at ω(k) of cascade 0's patch length (1000 m");
  const auto* own = find(report, "cascade1.dispersion.residual");
  ASSERT_NE(own, nullptr);
  EXPECT_FALSE(own->passed);
}

// Nested bands whose low band is not the broad band's part: the low band drew another seed;
// and, separately, the low band at half the amplitude.
TEST(CascadeCatalogue, NestedBandsWhoseLowBandIsNotTheBroadBandsPart) {
  const CaseFile c = parse(nested_toml());
  OceanCase other_seed = c.cascade_case(0);
  other_seed.seed += 1;
  const auto report = gate(c, {render(c.cascade_case(0), right_amplitude(other_seed),
                                      right_omega(other_seed)),
                               right(c.cascade_case(1))});
  expect_caught(report, "cascades.nested", "not the broad band's");
  expect_caught(report, "cascades.nested", "different random numbers");
  const OceanCase low = c.cascade_case(0);
  const auto amplitude = right_amplitude(low);
  const auto halved = gate(c, {render(low, [&](int n, int m) { return 0.5 * amplitude(n, m); },
                                      right_omega(low)),
                               right(c.cascade_case(1))});
  expect_caught(halved, "cascades.nested", "broad band's part × 0.5");
}

// ------------------------------------------------------------------ the command line

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("swell_cascade_cli_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// swell synth writes each cascade under its own folder, the sum under sum/ and a case.toml that
// reads them back; swell gate passes the set (exit 0) and its JSON names the set's checks.
TEST(CascadeCli, SynthWritesASetAndTheGatePassesIt) {
  const fs::path dir = scratch("synth");
  write_text(dir / "set.toml", pair_toml(4));
  const auto synth = swell::test::swell("synth --case " + (dir / "set.toml").string() +
                                        " --impl fftw --out " + (dir / "out").string());
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  for (const char* file : {"cascade0/frame_0003.exr", "cascade1/frame_0000.exr", "sum/frame_0003.exr",
                           "case.toml"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file << "\n" << synth.output;
  }
  EXPECT_NE(synth.output.find("the sum on 256×256 over 1000×1000 m"), std::string::npos) << synth.output;
  const auto gate = swell::test::swell("gate --case " + (dir / "out/case.toml").string() +
                                       " --json " + (dir / "gate.json").string());
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
  std::ifstream json_file(dir / "gate.json");
  const auto json = nlohmann::json::parse(json_file);
  std::set<std::string> names;
  for (const auto& check : json.at("checks")) names.insert(check.at("check").get<std::string>());
  for (const char* name : {"cascade0.energy", "cascade1.band.outside", "cascades.independence",
                           "sum.dispersion.residual", "sum.band.missing"}) {
    EXPECT_TRUE(names.count(name)) << name;
  }
  // --sum no: the cascades only.
  const auto without = swell::test::swell("synth --case " + (dir / "set.toml").string() +
                                          " --impl fftw --sum no --out " + (dir / "nosum").string());
  ASSERT_EQ(without.exit_code, 0) << without.output;
  EXPECT_FALSE(fs::exists(dir / "nosum/sum"));
  fs::remove_all(dir);
}

// Cascades take every form of sea a case declares: a composite wind sea plus swell, each with
// its own spreading, and the two-peak netCDF table (docs/case_files.md). swell synth makes each
// set and swell gate passes it (exit 0), the table's share of m0 noted per cascade.
TEST(CascadeCli, CompositeAndTabulatedSeasPass) {
  const std::string composite =
      "[[spectrum]]\nmodel = \"jonswap\"\nhs = 2.5\ntp = 7.0\ngamma = 3.3\n"
      "[spectrum.spreading]\nmodel = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n"
      "[[spectrum]]\nmodel = \"gaussian\"\nhs = 1.5\ntp = 14.0\nsigma = 0.05\n"
      "[spectrum.spreading]\nmodel = \"cos2s\"\ns = 40.0\nwind_dir_deg = 75.0\n";
  const std::string table =
      "[spectrum]\nmodel = \"table\"\nfile = \"" +
      (fs::path(SWELL_TEST_DATA_DIR) / "external/twopeak/twopeak_ochi_hubble.nc").string() +
      "\"\nfrequency_unit = \"Hz\"\ndensity_unit = \"m2/Hz/deg\"\n"
      "direction_convention = \"nautical_from\"\ndirection_unit = \"deg\"\n"
      "select = {time = 0, site = 0}\n";
  for (const auto& [name, sea] : {std::pair{"composite", composite}, std::pair{"table", table}}) {
    SCOPED_TRACE(name);
    const fs::path dir = scratch(name);
    write_text(dir / "set.toml", "[time]\ndt = 0.5\nframes = 8\n" + sea +
                                     "[synthesis]\nchoppiness = 1.0\nseed = 11\n"
                                     "\n[cascades]\nrelation = \"additive\"\n" +
                                     cascade_table(64, 1000, 0, 0.1, 0) + cascade_table(64, 250, 0.1, 0.8, 1));
    const auto synth = swell::test::swell("synth --case " + (dir / "set.toml").string() +
                                          " --impl fftw --out " + (dir / "out").string());
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    const auto gate = swell::test::swell("gate --case " + (dir / "out/case.toml").string());
    EXPECT_EQ(gate.exit_code, 0) << gate.output;
    EXPECT_NE(gate.output.find("verdict: PASS"), std::string::npos) << gate.output;
    if (std::string(name) == "table") {
      EXPECT_NE(gate.output.find("note: cascade1: the grid's wave vectors carry"), std::string::npos)
          << gate.output;
    }
    fs::remove_all(dir);
  }
}

// A set the engine got wrong fails (exit 1) naming the bug: the frames of a cascade 0 that
// carries up to 0.13 rad/m, gated against the declared 0.1.
TEST(CascadeCli, AWrongSetFailsWithExitOne) {
  const fs::path dir = scratch("wrong");
  std::string wide = pair_toml(4);
  wide.replace(wide.find("band = [0.000000, 0.100000]"), std::string("band = [0.000000, 0.100000]").size(),
               "band = [0.000000, 0.130000]");
  wide.replace(wide.find("band = [0.100000, 0.800000]"), std::string("band = [0.100000, 0.800000]").size(),
               "band = [0.130000, 0.800000]");
  write_text(dir / "wide.toml", wide);
  ASSERT_EQ(swell::test::swell("synth --case " + (dir / "wide.toml").string() +
                               " --impl fftw --sum no --out " + (dir / "out").string())
                .exit_code,
            0);
  // The engine's cascade 0 frames under the declared set (cascade 1's frames are right for a
  // band from 0.1 too: it just misses 0.1–0.13, which cascade 0 carries).
  write_text(dir / "out/declared.toml", pair_toml(4));
  const auto gate = swell::test::swell("gate --case " + (dir / "out/declared.toml").string());
  EXPECT_EQ(gate.exit_code, 1) << gate.output;
  EXPECT_NE(gate.output.find("cascades 0 and 1 both carry"), std::string::npos) << gate.output;
  fs::remove_all(dir);
}

// swell synth makes three independent seas that each carry the whole spectrum; swell gate
// passes them (exit 0) and, declared an additive set, judges them and fails (exit 1) naming
// the range that all three carry — not exit 2.
TEST(CascadeCli, FullSpectrumCascadesAreJudgedNotRefused) {
  const fs::path dir = scratch("full");
  write_text(dir / "set.toml", full_spectrum_toml("independent", 4));
  const auto synth = swell::test::swell("synth --case " + (dir / "set.toml").string() +
                                        " --impl fftw --sum no --out " + (dir / "out").string());
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  EXPECT_NE(synth.output.find("independent set of 3 cascades"), std::string::npos) << synth.output;
  const auto right_set = swell::test::swell("gate --case " + (dir / "out/case.toml").string());
  EXPECT_EQ(right_set.exit_code, 0) << right_set.output;
  write_text(dir / "out/declared.toml", full_spectrum_toml("additive", 4));
  const auto declared = swell::test::swell("gate --case " + (dir / "out/declared.toml").string());
  EXPECT_EQ(declared.exit_code, 1) << declared.output;
  EXPECT_NE(declared.output.find("cascades 0, 1 and 2 all carry 0.101–0.201 rad/m: energy × 3 there"),
            std::string::npos)
      << declared.output;
  fs::remove_all(dir);
}

// Bad input exits 2 naming what is wrong, before anything is written.
TEST(CascadeCli, BadSetsExitTwoNamingTheProblem) {
  const fs::path dir = scratch("bad");
  write_text(dir / "overlap.toml", sea_toml() + "\n[cascades]\n" + cascade_table(64, 1000, 0, 0.12, 0) +
                                       cascade_table(64, 250, 0.1, 0.8, 1));
  const auto overlap = swell::test::swell("synth --case " + (dir / "overlap.toml").string() +
                                          " --impl fftw --out " + (dir / "out").string());
  EXPECT_EQ(overlap.exit_code, 2);
  EXPECT_NE(overlap.output.find("cascades 0 and 1 both carry 0.1–0.12 rad/m: energy × 2 there"),
            std::string::npos)
      << overlap.output;
  EXPECT_FALSE(fs::exists(dir / "out" / "case.toml"));
  write_text(dir / "set.toml", pair_toml());
  const auto flag = swell::test::swell("synth --case " + (dir / "set.toml").string() +
                                       " --impl fftw --n 128 --out " + (dir / "out").string());
  EXPECT_EQ(flag.exit_code, 2);
  EXPECT_NE(flag.output.find("each cascade's grid is its [[cascade]] n and length"), std::string::npos)
      << flag.output;
  const auto missing = swell::test::swell("gate --case " + (dir / "set.toml").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  const auto fit = swell::test::swell("fit --input " + (dir / "out").string() + " --case " +
                                      (dir / "set.toml").string());
  EXPECT_EQ(fit.exit_code, 2);
  EXPECT_NE(fit.output.find("takes a single-grid case"), std::string::npos) << fit.output;
  fs::remove_all(dir);
}

// ------------------------------------------------------------------ calibration

// Right sets (cascades from the synthesizer in fp32, as swell synth writes them, and their sum)
// over 200 seeds at α = 0.05: the gate fails at most as often as a binomial(200, α) count
// exceeds with probability 10⁻³.
TEST(CascadeGateCalibration, FamilyWiseFalseAlarmRateOverTwoHundredSeeds) {
  const CaseFile base = parse(pair_toml(4));
  const int seeds = 200;
  const double alpha = 0.05;
  int failed = 0;
  const swell::impls::SynthesizerOptions fp32{"fftw", swell::impls::Precision::f32};
  for (int s = 0; s < seeds; ++s) {
    CaseFile c = base;
    c.ocean.seed = 700000 + s;
    const auto summed = c.summed_case();
    const std::vector<FrameSequence> frames = {
        swell::impls::Synthesizer(c.cascade_case(0), fp32).frames(),
        swell::impls::Synthesizer(c.cascade_case(1), fp32).frames()};
    const FrameSequence sum = swell::impls::Synthesizer(*summed, fp32).frames();
    const auto report = gate(c, frames, &sum, alpha);
    EXPECT_NEAR(report.alpha_per_check * report.statistical_checks, alpha, 1e-12);
    if (!report.passed()) {
      for (const auto& r : report.results) {
        if (!r.passed) std::cout << "[ calibration ] seed " << c.ocean.seed << ": " << r.check << " — " << r.reason << "\n";
      }
    }
    failed += !report.passed();
  }
  const boost::math::binomial_distribution<double> law(seeds, alpha);
  const int bound = int(boost::math::quantile(boost::math::complement(law, 1e-3)));
  std::cout << "[ calibration ] cascade gate at α = " << alpha << ": " << failed << " of "
            << seeds << " right sets failed (bound " << bound << ")\n";
  EXPECT_LE(failed, bound);
}

}  // namespace
