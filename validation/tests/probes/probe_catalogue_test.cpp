// The catalogue of probe-series bugs (docs/probes.md §4): a test engine that makes each bug the
// offshore trackers record — from swell's own lines, changed the way the engine slips — and the
// check whose message names it. Each bug is judged at the gate's α = 1e-3 on a record of one
// repeat period (or Welch-judged where the bug needs it), with a seed the right series pass on.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "swell/impls/probe_synthesis.hpp"
#include "swell/validation/checks/probe_checks.hpp"

namespace {

namespace sr = swell::reference;
namespace sv = swell::validation;
constexpr double kPi = std::numbers::pi;
constexpr double kAlpha = 1e-3;
// Seed 11 is the most kurtotic of 4000 seeds of the deterministic sea (g2 = 2.22, 8.8 sd above
// the mean: one wave group of 4.7 σ), which series.kurtosis rejects at p = 6e-5 per probe.
constexpr std::uint64_t kSeed = 12;

// The sea, shortened: JONSWAP Hs 3 m, Tp 10 s, γ 3.3 in 30 m of water; three probes;
// 2048 samples at 0.5 s, one repeat period of 1024 s.
sr::ProbeCase sea(sr::ProbeAmplitudes amplitudes, sr::ProbeDirections directions, int n_directions = 1) {
  sr::ProbeCase c;
  c.sea.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 10.0}, {"gamma", 3.3}}, {}};
  if (directions != sr::ProbeDirections::long_crested) c.sea.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.sea.wind_dir_deg = 30;
  c.sea.depth = 30;
  c.layout.positions = {{0.0, 0.0}, {20.0, 0.0}, {0.0, 20.0}};
  c.layout.dt = 0.5;
  c.layout.samples = 2048;
  c.synthesis.amplitudes = amplitudes;
  c.synthesis.frequencies = sr::ProbeFrequencies::uniform;
  c.synthesis.repeat_period = 1024;
  c.synthesis.omega_low = 0;
  c.synthesis.omega_high = 4;
  c.synthesis.directions = directions;
  c.synthesis.n_directions = n_directions;
  c.validate();
  return c;
}

using Series = std::vector<std::vector<double>>;

Series sum_lines(const sr::ProbeCase& c, const std::vector<sr::WaveLine>& lines) {
  Series out;
  for (const auto& x : c.layout.positions) out.push_back(sr::probe_series_direct(lines, x[0], x[1], c.layout));
  return out;
}

// The engine: swell's lines for the case, changed by `slip`, summed line by line.
Series engine(const sr::ProbeCase& c, const std::function<void(std::vector<sr::WaveLine>&)>& slip) {
  auto lines = sr::probe_wave_lines(c, kSeed);
  slip(lines);
  return sum_lines(c, lines);
}

sv::ProbeCheckReport judge(const sr::ProbeCase& c, const Series& series) {
  return sv::run_probe_checks(c, series, std::vector<double>(series.size(), 0.0), kAlpha);
}

const sv::CheckResult* find(const sv::ProbeCheckReport& report, const std::string& check) {
  for (const auto& r : report.results) {
    if (r.check == check) return &r;
  }
  return nullptr;
}

// The named check failed and its reason holds `part`.
void expect_named(const sv::ProbeCheckReport& report, const std::string& check, const std::string& part) {
  const auto* result = find(report, check);
  ASSERT_NE(result, nullptr) << check << " did not run";
  EXPECT_FALSE(result->passed) << check << ": " << result->reason;
  EXPECT_NE(result->reason.find(part), std::string::npos) << check << ": " << result->reason;
}

void expect_all_pass(const sv::ProbeCheckReport& report) {
  for (const auto& r : report.results) EXPECT_TRUE(r.passed) << r.check << ": " << r.reason;
}

TEST(ProbeCatalogue, TheRightSeriesOfEachSchemePass) {
  for (const auto& c : {sea(sr::ProbeAmplitudes::deterministic, sr::ProbeDirections::long_crested),
                        sea(sr::ProbeAmplitudes::rayleigh, sr::ProbeDirections::long_crested),
                        sea(sr::ProbeAmplitudes::deterministic, sr::ProbeDirections::double_summation, 8),
                        sea(sr::ProbeAmplitudes::rayleigh, sr::ProbeDirections::single_per_frequency)}) {
    SCOPED_TRACE(c.describe());
    expect_all_pass(judge(c, engine(c, [](auto&) {})));
  }
}

TEST(ProbeCatalogue, ConventionFactorsOfTheEnergyAreNamed) {
  const auto c = sea(sr::ProbeAmplitudes::deterministic, sr::ProbeDirections::long_crested);
  const auto scaled = [&](double factor) {
    return engine(c, [factor](auto& lines) {
      for (auto& line : lines) line.amplitude *= factor;
    });
  };
  expect_named(judge(c, scaled(2 * kPi)), "series.energy", "amplitudes × 2π");
  expect_named(judge(c, scaled(std::sqrt(2 * kPi))), "series.energy", "m²/Hz used as m²·s/rad");
  expect_named(judge(c, scaled(std::sqrt(0.5))), "series.energy", "two-sided density used as one-sided");
  expect_named(judge(c, scaled(4)), "series.energy", "Hs²");
  // The same factors under Rayleigh amplitudes, where the energy's law leaves a range: × 4π²
  // stands far outside it.
  const auto r = sea(sr::ProbeAmplitudes::rayleigh, sr::ProbeDirections::long_crested);
  expect_named(judge(r, engine(r, [](auto& lines) {
                 for (auto& line : lines) line.amplitude *= 2 * kPi;
               })),
               "series.energy", "amplitudes × 2π");
}

TEST(ProbeCatalogue, AMissingSquareRootIsNamed) {
  const auto c = sea(sr::ProbeAmplitudes::deterministic, sr::ProbeDirections::long_crested);
  // a = 2 S Δω (scaled to the right m0's order) instead of √(2 S Δω).
  expect_named(judge(c, engine(c, [](auto& lines) {
                 for (auto& line : lines) line.amplitude = 20 * line.amplitude * line.amplitude;
               })),
               "series.spectrum", "missing √");
}

TEST(ProbeCatalogue, SpreadingWeightsThatDoNotConserveEnergyAreNamed) {
  const int n = 8;
  const auto c = sea(sr::ProbeAmplitudes::deterministic, sr::ProbeDirections::double_summation, n);
  // Variance weights √(1/n) per direction instead of 1/n: amplitudes × n^(1/4).
  expect_named(judge(c, engine(c, [n](auto& lines) {
                 for (auto& line : lines) line.amplitude *= std::pow(double(n), 0.25);
               })),
               "series.energy", "√D per direction instead of D");
  const auto r = sea(sr::ProbeAmplitudes::rayleigh, sr::ProbeDirections::double_summation, n);
  expect_named(judge(r, engine(r, [n](auto& lines) {
                 for (auto& line : lines) line.amplitude *= std::pow(double(n), 0.25);
               })),
               "series.energy", "√D per direction instead of D");
}

TEST(ProbeCatalogue, DispersionTravelAndProbePlacementAreNamed) {
  const auto c = sea(sr::ProbeAmplitudes::deterministic, sr::ProbeDirections::long_crested);
  expect_named(judge(c, engine(c, [](auto& lines) {
                 for (auto& line : lines) line.k = line.omega * line.omega / 9.80665;
               })),
               "series.phase", "deep-water");
  expect_named(judge(c, engine(c, [](auto& lines) {
                 for (auto& line : lines) line.theta += kPi;
               })),
               "series.phase", "against the declared direction");
  auto clamped = engine(c, [](auto&) {});
  clamped[2] = clamped[0];  // probe 2 outside the domain repeats the edge node's series
  expect_named(judge(c, clamped), "series.phase", "clamped");
}

TEST(ProbeCatalogue, FrequenciesRescaledAndRepeatingSoonerAreNamed) {
  const auto c = sea(sr::ProbeAmplitudes::deterministic, sr::ProbeDirections::long_crested);
  // Each line's S Δω put at 1.5 ω, as an engine that puts the spectrum's lines on another
  // time grid's spacing: over two repeat periods (bins Δω/2 apart) 1.5 i Δω is bin 3i.
  auto twice = c;
  twice.layout.samples = 4096;
  twice.validate();
  expect_named(judge(twice, engine(twice, [&](auto& lines) {
                 const auto dispersion = twice.sea.dispersion();
                 for (auto& line : lines) line.omega *= 1.5, line.k = dispersion.wavenumber(line.omega);
               })),
               "series.moments", "frequencies rescaled");
  // Lines 2 Δω apart: the series repeats after half the declared period.
  expect_named(judge(c, engine(c, [](auto& lines) {
                 for (auto& line : lines) {
                   if (line.frequency % 2 == 0) line.amplitude = 0;
                   line.amplitude *= std::sqrt(2.0);
                 }
               })),
               "series.spectrum", "sooner than declared");
}

TEST(ProbeCatalogue, NonlinearAndClippedSeriesAreNamed) {
  const auto c = sea(sr::ProbeAmplitudes::rayleigh, sr::ProbeDirections::long_crested);
  auto series = engine(c, [](auto&) {});
  double square = 0;
  for (double v : series[0]) square += v * v;
  const double sigma = std::sqrt(square / double(series[0].size()));
  auto bound_waves = series;
  for (auto& probe : bound_waves) {
    for (double& v : probe) v += 0.2 * v * v / sigma;
  }
  expect_named(judge(c, bound_waves), "series.skewness", "second-order");
}

TEST(ProbeCatalogue, WelchJudgedRecordsNameTheirEnergyFactor) {
  auto c = sea(sr::ProbeAmplitudes::rayleigh, sr::ProbeDirections::long_crested);
  c.synthesis.frequencies = sr::ProbeFrequencies::equal_energy;
  c.synthesis.repeat_period = 0;
  c.synthesis.n_frequencies = 200;
  c.validate();
  expect_all_pass(judge(c, engine(c, [](auto&) {})));
  expect_named(judge(c, engine(c, [](auto& lines) {
                 for (auto& line : lines) line.amplitude *= 2 * kPi;
               })),
               "series.energy", "amplitudes × 2π");
}

// One direction per frequency read from three probes or more: each line must be one plane wave
// at the case's k(ω), and the lines' directions must follow D(ω, θ).
TEST(ProbeCatalogue, DirectionsOfSinglePerFrequencySeasAreNamed) {
  auto c = sea(sr::ProbeAmplitudes::rayleigh, sr::ProbeDirections::single_per_frequency);
  c.layout.positions = {{0.0, 0.0}, {8.0, 0.0}, {0.0, 8.0}, {20.0, 12.0}};
  c.validate();
  expect_all_pass(judge(c, engine(c, [](auto&) {})));
  const double mean = c.spectrum()->mean_direction();
  expect_named(judge(c, engine(c, [](auto& lines) {
                 for (auto& line : lines) line.theta += kPi;
               })),
               "series.direction", "against the declared direction");
  // Directions spread three times wider about the mean than D: a wider spreading than declared.
  expect_named(judge(c, engine(c, [mean](auto& lines) {
                 for (auto& line : lines) line.theta = mean + 3 * std::remainder(line.theta - mean, 2 * kPi);
               })),
               "series.direction", "wider spreading");
  expect_named(judge(c, engine(c, [](auto& lines) {
                 for (auto& line : lines) line.k = line.omega * line.omega / 9.80665;
               })),
               "series.phase", "deep-water");
  // Two directions per frequency judged as one: no plane wave explains a line.
  auto two = c;
  two.synthesis.directions = sr::ProbeDirections::double_summation;
  two.synthesis.n_directions = 2;
  two.validate();
  expect_named(judge(c, engine(two, [](auto&) {})), "series.phase", "more than one direction");
}

// Several directions per frequency: the probes' cross-spectra against the declared spreading.
TEST(ProbeCatalogue, TheCoherenceOfDoubleSummationSeasNamesReversedTravel) {
  for (const auto amplitudes : {sr::ProbeAmplitudes::rayleigh, sr::ProbeAmplitudes::deterministic}) {
    const auto c = sea(amplitudes, sr::ProbeDirections::double_summation, 8);
    SCOPED_TRACE(sr::to_string(amplitudes));
    expect_all_pass(judge(c, engine(c, [](auto&) {})));
    expect_named(judge(c, engine(c, [](auto& lines) {
                   for (auto& line : lines) line.theta += kPi;
                 })),
                 "series.coherence", "against the declared direction");
  }
}

}  // namespace
