// The catalogue of engine bugs: every buggy engine of the test engine fails the gate,
// and the check that fails names the bug in its reason. Right engines pass: over 200 seeds the
// gate's family-wise false-alarm rate is within the binomial bound of its α (label
// "calibration").
#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/math/distributions/binomial.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numbers>
#include <regex>
#include <set>

#include "swell/impls/synthesizer.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/gate/power.hpp"
#include "swell/validation/gate/render.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "gate/gate_cases.hpp"
#include "frame_edits.hpp"
#include "half_rounding.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "test_engine.hpp"

namespace {

using swell::reference::Grid;
using swell::reference::OceanCase;
using swell::test::EngineBug;
using swell::validation::CaseFile;
using swell::validation::GateOptions;
using swell::validation::GateReport;

using swell::test::as_case_file;
using swell::test::catalogue_case;
using swell::test::shallow_case;

struct CatalogueEntry {
  EngineBug bug;
  std::string check;   // the result that fails and names the bug
  std::string naming;  // words of its reason that name it
  bool shallow = false;
  bool complex_output = false;  // the engine hands over its complex fields
};

std::string describe(const GateReport& report) {
  std::string out;
  for (const auto& r : report.results) {
    if (!r.passed) out += "\n  FAIL " + r.check + ": " + r.reason;
  }
  return out;
}

class Catalogue : public ::testing::TestWithParam<CatalogueEntry> {};

TEST_P(Catalogue, TheGateFailsTheBuggyEngineAndTheFailingCheckNamesTheBug) {
  const auto& entry = GetParam();
  const OceanCase c = entry.shallow ? shallow_case() : catalogue_case();
  swell::test::EngineOptions options;
  options.keep_imaginary = entry.complex_output;
  const auto report = swell::validation::run_gate(
      as_case_file(c), swell::test::render_surface(c, entry.bug, options), GateOptions{});
  EXPECT_FALSE(report.passed()) << swell::test::to_string(entry.bug);
  bool found = false;
  for (const auto& r : report.results) {
    if (r.check != entry.check) continue;
    found = true;
    EXPECT_FALSE(r.passed) << swell::test::to_string(entry.bug) << " passed " << r.check << ": "
                           << r.reason << describe(report);
    EXPECT_NE(r.reason.find(entry.naming), std::string::npos)
        << swell::test::to_string(entry.bug) << ": '" << entry.naming << "' not in: " << r.reason;
    std::cout << "[ catalogue ] " << swell::test::to_string(entry.bug) << " → " << r.check << ": "
              << r.reason << "\n";
  }
  EXPECT_TRUE(found) << "no result " << entry.check << describe(report);
}

INSTANTIATE_TEST_SUITE_P(
    EngineBugs, Catalogue,
    ::testing::Values(
        CatalogueEntry{EngineBug::independent_minus_k_real_part, "energy", "not paired as conj"},
        CatalogueEntry{EngineBug::independent_minus_k_real_part, "hermitian.imaginary_residue",
                       "missing conjugate pairing", false, true},
        CatalogueEntry{EngineBug::same_pair_for_minus_k, "direction.travelling", "same random pair"},
        CatalogueEntry{EngineBug::checkerboard_sign, "spectrum.unexpected_energy", "checkerboard"},
        CatalogueEntry{EngineBug::amplitude_without_dk, "energy", "without Δkx Δky"},
        CatalogueEntry{EngineBug::energy_doubled, "energy", "Tessendorf"},
        CatalogueEntry{EngineBug::sigma_wrong, "spectrum.shape", "shape differs from the case's"},
        CatalogueEntry{EngineBug::alpha_sqrt_g, "energy", "α√g"},
        CatalogueEntry{EngineBug::deep_water_dispersion, "dispersion.residual",
                       "dispersion of deep water; the case says 10 m", true},
        CatalogueEntry{EngineBug::omega_equals_gk, "dispersion.residual", "ω = g k"},
        CatalogueEntry{EngineBug::reversed_time, "direction.distribution", "against the wind"},
        CatalogueEntry{EngineBug::spreading_not_normalized, "energy",
                       "spreading function not normalized"},
        CatalogueEntry{EngineBug::jacobian_without_choppiness, "derived.jacobian", "without λ"},
        CatalogueEntry{EngineBug::displacement_sign_flipped, "derived.disp_x", "sign flipped"},
        CatalogueEntry{EngineBug::uniform_noise, "statistics.gaussian_amplitudes", "uniform noise"},
        CatalogueEntry{EngineBug::band_counted_twice, "spectrum.shape", "band counted twice"},
        CatalogueEntry{EngineBug::standing_waves, "direction.distribution", "standing waves"},
        CatalogueEntry{EngineBug::time_drift, "statistics.hs_steady", "Hs drifts"},
        // Issue 16: diagnoses that name the real cause.
        CatalogueEntry{EngineBug::transposed_height, "derived.disp_x",
                       "the field is transposed (x and y exchanged)"},
        CatalogueEntry{EngineBug::swapped_displacements, "derived.disp_x", "disp_x and disp_y swapped"},
        CatalogueEntry{EngineBug::half_bin_offset_lattice, "dispersion.residual",
                       "each bin holds two frequencies, at ω(|2k ± Δk|)"},
        CatalogueEntry{EngineBug::half_bin_offset_lattice, "dispersion.omega",
                       "no single ω per wave vector"},
        CatalogueEntry{EngineBug::hash_collisions, "randomness.reused_numbers",
                       "share their random pair with another"},
        CatalogueEntry{EngineBug::heave, "spectrum.unexpected_energy", "the mean level moves (heave)"}),
    [](const auto& info) {
      // The bug, and the check of a bug's second entry (letters and digits only).
      std::string check = info.param.check;
      for (auto& ch : check) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
      const bool several = info.param.bug == EngineBug::half_bin_offset_lattice &&
                           info.param.check == "dispersion.omega";
      return swell::test::to_string(info.param.bug) + (info.param.complex_output ? "_complex" : "") +
             (several ? "_" + check : "");
    });

// Every bug of the test engine is in the catalogue above.
TEST(Catalogue, CoversEveryBugOfTheTestEngine) {
  const auto all = swell::test::all_engine_bugs();
  EXPECT_GE(all.size(), 15u);
  // The parameterized suite is instantiated once per entry; count them through the registry.
  const auto* unit = ::testing::UnitTest::GetInstance();
  std::set<std::string> names;
  for (int s = 0; s < unit->total_test_suite_count(); ++s) {
    const auto* suite = unit->GetTestSuite(s);
    if (std::string(suite->name()) != "EngineBugs/Catalogue") continue;
    for (int t = 0; t < suite->total_test_count(); ++t) names.insert(suite->GetTestInfo(t)->name());
  }
  for (EngineBug bug : all) {
    const std::string name = "TheGateFailsTheBuggyEngineAndTheFailingCheckNamesTheBug/" +
                             swell::test::to_string(bug);
    EXPECT_TRUE(names.count(name)) << swell::test::to_string(bug) << " is not in the catalogue";
  }
}

// Dispersion diagnoses beyond the catalogue: frames made for another depth, or with a loop
// period the case does not declare, are named as such.
std::string dispersion_reason(const OceanCase& rendered, const OceanCase& declared) {
  const auto report = swell::validation::run_gate(
      as_case_file(declared), swell::test::render_surface(rendered), GateOptions{});
  for (const auto& r : report.results) {
    if (r.check == "dispersion.residual") {
      EXPECT_FALSE(r.passed) << r.reason;
      return r.reason;
    }
  }
  ADD_FAILURE() << "no dispersion result" << describe(report);
  return "";
}

TEST(Diagnosis, NamesTheDepthTheFramesFollow) {
  OceanCase engine = shallow_case();
  engine.depth = 25;
  const auto reason = dispersion_reason(engine, shallow_case());
  EXPECT_NE(reason.find("a depth of 25 m; the case says 10 m"), std::string::npos) << reason;
}

TEST(Diagnosis, NamesAnUndeclaredLoopPeriod) {
  OceanCase engine = catalogue_case();
  engine.loop_period = 40;
  const auto reason = dispersion_reason(engine, catalogue_case());
  EXPECT_NE(reason.find("loop period of 40"), std::string::npos) << reason;
  EXPECT_NE(reason.find("does not declare"), std::string::npos) << reason;
}

// Another choppiness is named with the least-squares λ — only because it explains the field —
// and is not called a flipped sign; a field no λ explains says so with the best λ it found.
TEST(Diagnosis, NamesTheChoppinessTheDisplacementsCarry) {
  OceanCase engine = catalogue_case();
  engine.choppiness = 1.2;
  const auto report = swell::validation::run_gate(as_case_file(catalogue_case()),
                                                  swell::test::render_surface(engine), GateOptions{});
  bool found = false;
  for (const auto& r : report.results) {
    if (r.check != "derived.disp_x") continue;
    found = true;
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.reason.find("λ is 1.2, not the case's 0.8"), std::string::npos) << r.reason;
    EXPECT_EQ(r.reason.find("sign flipped"), std::string::npos) << r.reason;
  }
  EXPECT_TRUE(found);
  // Displacements of a half-bin-offset lattice: positive best λ, not explained, no "sign".
  const auto offset = swell::validation::run_gate(
      as_case_file(catalogue_case()),
      swell::test::render_surface(catalogue_case(), EngineBug::half_bin_offset_lattice), GateOptions{});
  for (const auto& r : offset.results) {
    if (r.check != "derived.disp_x") continue;
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.reason.find("no λ explains it"), std::string::npos) << r.reason;
    EXPECT_EQ(r.reason.find("sign flipped"), std::string::npos) << r.reason;
  }
}

// ------------------------------------------------------------------ every frame, several faults

// The result of `check` in a report (a failure of the test when there is none).
swell::validation::CheckResult result_of(const GateReport& report, const std::string& check) {
  for (const auto& r : report.results) {
    if (r.check == check) return r;
  }
  ADD_FAILURE() << "no result " << check << describe(report);
  return {};
}

// A mean level that oscillates and is zero at frame 0 (sin, not cos): read from frame 0 alone
// it passes; every frame is judged, and heave is named.
TEST(EveryFrame, AMeanLevelZeroAtTheFirstFrameIsHeave) {
  const OceanCase c = catalogue_case();
  auto frames = swell::test::render_surface(c);
  const double amplitude = 0.5 * swell::test::rms_of(frames, swell::reference::Field::height);
  for (auto& frame : frames.frames) {
    const double level = amplitude * std::sin(2 * std::numbers::pi * frame.time / (c.frames * c.dt));
    for (double& h : frame.fields[swell::reference::Field::height]) h += level;
  }
  ASSERT_EQ(frames.frames[0].time, 0.0);
  const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
  const auto r = result_of(report, "spectrum.unexpected_energy");
  EXPECT_FALSE(r.passed) << r.reason;
  EXPECT_NE(r.reason.find("the mean level moves (heave)"), std::string::npos) << r.reason;
}

// A displacement wrong in one middle frame only fails derived, which names that frame and λ.
TEST(EveryFrame, ADerivedFieldWrongInOneMiddleFrameFails) {
  const OceanCase c = catalogue_case();
  auto frames = swell::test::render_surface(c);
  for (double& d : frames.frames[3].fields[swell::reference::Field::disp_x]) d *= 1.25;
  const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
  const auto r = result_of(report, "derived.disp_x");
  EXPECT_FALSE(r.passed) << r.reason;
  EXPECT_NE(r.reason.find("at frame 3 (1 of 8 frames fail)"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("λ is 1, not the case's 0.8"), std::string::npos) << r.reason;
  EXPECT_TRUE(result_of(report, "derived.disp_y").passed);
}

// Two faults at once: a transposed height or swapped displacements, with every field's Nyquist
// row and column filled (5 % of its rms). The fit on the wave vectors the case fills names the
// first fault, and the Nyquist energy beside it.
TEST(SeveralFaults, TransposeAndSwapHoldWithNyquistStrayEnergy) {
  const OceanCase c = catalogue_case();
  struct Case {
    EngineBug bug;
    std::string naming;
  };
  for (const Case& fault : {Case{EngineBug::transposed_height, "the field is transposed"},
                            Case{EngineBug::swapped_displacements, "disp_x and disp_y swapped"}}) {
    auto frames = swell::test::render_surface(c, fault.bug);
    for (auto& frame : frames.frames) {
      for (auto& [field, values] : frame.fields) {
        if (field == swell::reference::Field::jacobian) continue;
        swell::test::add_nyquist(values, c.grid, 0.05 * swell::test::rms_of(frames, field));
      }
    }
    const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
    const auto r = result_of(report, "derived.disp_x");
    EXPECT_FALSE(r.passed) << r.reason;
    EXPECT_NE(r.reason.find(fault.naming), std::string::npos) << r.reason;
    EXPECT_NE(r.reason.find("on the Nyquist row and column"), std::string::npos) << r.reason;
    EXPECT_EQ(r.reason.find("no λ explains it"), std::string::npos) << r.reason;
    // The height's own Nyquist energy is named by its own check.
    EXPECT_NE(result_of(report, "spectrum.unexpected_energy").reason.find("Nyquist"), std::string::npos);
  }
}

// A right displacement with a Nyquist leak alone (two fields packed per transform): the field
// follows its definition with the case's λ where the case puts energy, and the leak is named —
// not "λ is 0.8, not the case's 0.8".
TEST(SeveralFaults, ANyquistLeakAloneIsNamedAsSuch) {
  const OceanCase c = catalogue_case();
  auto frames = swell::test::render_surface(c);
  const double rms = swell::test::rms_of(frames, swell::reference::Field::disp_y);
  for (auto& frame : frames.frames) swell::test::add_nyquist(frame.fields[swell::reference::Field::disp_y], c.grid, 5e-3 * rms);
  const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
  const auto r = result_of(report, "derived.disp_y");
  EXPECT_FALSE(r.passed) << r.reason;
  EXPECT_NE(r.reason.find("follows its definition with the case's λ = 0.8"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("on the Nyquist row and column"), std::string::npos) << r.reason;
  EXPECT_EQ(r.reason.find("not the case's"), std::string::npos) << r.reason;
}

// λ = 0 declares no displacement: zero fields pass (their error is measured against what λ = 1
// would put there, not divided by zero), and displacements of λ = 1 fail, saying so.
TEST(Degenerate, ChoppinessZeroMeansNoDisplacement) {
  OceanCase c = catalogue_case();
  c.choppiness = 0;
  const auto right = swell::validation::run_gate(as_case_file(c), swell::test::render_surface(c), GateOptions{});
  for (const char* check : {"derived.disp_x", "derived.disp_y", "derived.jacobian"}) {
    const auto r = result_of(right, check);
    EXPECT_TRUE(r.passed) << check << ": " << r.reason;
    EXPECT_TRUE(std::isfinite(r.measured) && r.measured == 0) << check << ": " << r.measured;
  }
  OceanCase engine = c;
  engine.choppiness = 1;
  const auto wrong = swell::validation::run_gate(as_case_file(c), swell::test::render_surface(engine), GateOptions{});
  const auto r = result_of(wrong, "derived.disp_x");
  EXPECT_FALSE(r.passed);
  EXPECT_NEAR(r.measured, 1.0, 1e-9) << r.reason;  // λ = 1's displacement against λ = 1's
  EXPECT_NE(r.reason.find("λ = 0 declares no displacement"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("holds 1 × disp_x's definition"), std::string::npos) << r.reason;
  EXPECT_NE(result_of(wrong, "derived.jacobian").reason.find("λ = 0 declares no displacement"), std::string::npos);
}

// ------------------------------------------------------------------ one cause, once

// The Godot ocean's energy × 8 (2 × 2 × 2) on a sea whose peak sits at 1.2 Δk, where a handful
// of waves carry the energy and the total's ratio is noisy: the shape check names the whole
// factor and its decomposition from the rings' median; energy, where it fails, names the same;
// the scale-dependent checks (travelling, Gaussian amplitudes) judge what is theirs and pass.
TEST(OneCause, EnergyTimesEightIsNamedWholeWhereAHandfulOfWavesCarryTheSea) {
  OceanCase c = catalogue_case();
  c.spectrum.numbers["tp"] = 20.0;  // kp = ωp²/g ≈ 1.3 Δk on 800 m
  for (unsigned seed : {7u, 8u, 9u}) {
    c.seed = seed;
    auto frames = swell::test::render_surface(c);
    swell::test::scale_energy(frames, 8.0);
    const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
    const auto shape = result_of(report, "spectrum.shape");
    EXPECT_FALSE(shape.passed) << shape.reason;
    EXPECT_NE(shape.reason.find("× 8 = 2 × 2 × 2"), std::string::npos) << shape.reason;
    EXPECT_NE(shape.reason.find("the shape is the case's, so this failure is the scale's"), std::string::npos)
        << shape.reason;
    const auto energy = result_of(report, "energy");
    if (!energy.passed) EXPECT_NE(energy.reason.find("× 8 = 2 × 2 × 2"), std::string::npos) << energy.reason;
    EXPECT_TRUE(result_of(report, "direction.travelling").passed) << result_of(report, "direction.travelling").reason;
    EXPECT_TRUE(result_of(report, "statistics.gaussian_amplitudes").passed)
        << result_of(report, "statistics.gaussian_amplitudes").reason;
    std::cout << "[ one cause ] seed " << seed << ": shape: " << shape.reason << "\n[ one cause ] energy: "
              << energy.reason << "\n";
  }
}

// On the catalogue sea (peak at 8 Δk) the total measures × 8 itself and energy names it.
TEST(OneCause, EnergyTimesEightOnAWideSeaIsNamedByEnergy) {
  const OceanCase c = catalogue_case();
  auto frames = swell::test::render_surface(c);
  swell::test::scale_energy(frames, 8.0);
  const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
  const auto energy = result_of(report, "energy");
  EXPECT_FALSE(energy.passed);
  EXPECT_NE(energy.reason.find("× 8 = 2 × 2 × 2"), std::string::npos) << energy.reason;
  EXPECT_EQ(energy.reason.find("without Δkx Δky"), std::string::npos) << energy.reason;
  EXPECT_TRUE(result_of(report, "direction.travelling").passed);
}

// An engine that mixes an undeclared isotropic part into its spreading (30 % of the energy) has
// complex Gaussian amplitudes: gaussian_amplitudes, where it fails against the case's μ, says the
// failure follows from the spreading, not the noise; the directional check names the spreading.
TEST(OneCause, AnUndeclaredSpreadingMixIsNotCalledNonGaussian) {
  const OceanCase c = catalogue_case();
  OceanCase isotropic = c;
  isotropic.spreading.numbers["s"] = 0.02;  // nearly flat in θ
  isotropic.seed = c.seed + 1000;
  auto frames = swell::test::render_surface(c);
  const auto other = swell::test::render_surface(isotropic);
  for (std::size_t f = 0; f < frames.frames.size(); ++f) {
    for (auto& [field, values] : frames.frames[f].fields) {
      const auto& add = other.frames[f].fields.at(field);
      for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::sqrt(0.7) * values[i] + std::sqrt(0.3) * add[i];
    }
    frames.frames[f].fields.erase(swell::reference::Field::jacobian);
  }
  const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
  EXPECT_FALSE(report.passed());
  const auto gaussian = result_of(report, "statistics.gaussian_amplitudes");
  if (!gaussian.passed) {
    EXPECT_NE(gaussian.reason.find("they are complex Gaussian"), std::string::npos) << gaussian.reason;
  }
  EXPECT_FALSE(result_of(report, "direction.distribution").passed) << describe(report);
  std::cout << "[ one cause ] mix: " << gaussian.reason << "\n";
}

// ------------------------------------------------------------------ the gate's power

// The table the gate makes beside its passes, from the analysis' τ, μ and half plane, is the one
// made from the case alone (`swell gate --power`, which evaluates them itself): line for line,
// to the bit.
TEST(GatePower, TheGatesTableIsTheOneMadeFromTheCaseAlone) {
  const OceanCase c = catalogue_case();
  const CaseFile file = as_case_file(c);
  GateOptions options;
  options.threads = 2;
  const auto report = swell::validation::run_gate(file, swell::test::render_surface(c), options);
  ASSERT_TRUE(report.power.has_value());
  const auto alone = swell::validation::gate_power(file, options.alpha, report.unit_roundoff, report.storage_roundoff,
                                                   swell::validation::expected_travelling_power(c), 2);
  ASSERT_EQ(report.power->lines.size(), alone.lines.size());
  ASSERT_GE(alone.lines.size(), 5u);
  for (std::size_t i = 0; i < alone.lines.size(); ++i) {
    const auto &gate = report.power->lines[i], &own = alone.lines[i];
    EXPECT_EQ(gate.error, own.error);
    EXPECT_EQ(gate.smallest, own.smallest) << own.error;
    EXPECT_EQ(gate.check, own.check) << own.error;
    if (std::isfinite(own.above)) {
      EXPECT_EQ(gate.above, own.above) << own.error;
    }
    if (std::isfinite(own.below)) {
      EXPECT_EQ(gate.below, own.below) << own.error;
    }
  }
}

// The power table's sizes against measured detection (label "calibration"): 20 seeds of the test
// engine (an implementation independent of the checks) with each statistical error at its
// predicted size are detected by the named check at 90 % — between 13 and 20 of 20 (the binomial
// 0.999 range of 0.9; 20 of 20 has probability 0.12). The exact checks' sizes are thresholds:
// 1.5× the size fails every seed, 0.5× passes every one.
TEST(PowerCalibration, PredictedSizesAreDetectedAtTheirPower) {
  const OceanCase c = catalogue_case();
  const CaseFile file = as_case_file(c);
  const double alpha = 1e-3;
  const auto table = swell::validation::gate_power(
      file, alpha, 0x1p-53, 0, swell::validation::expected_travelling_power(c));
  std::cout << swell::validation::render_power(table);
  auto line_of = [&](const std::string& error) {
    for (const auto& line : table.lines) {
      if (line.error == error) return line;
    }
    ADD_FAILURE() << "no power line " << error;
    return swell::validation::PowerLine{};
  };
  GateOptions options;
  options.alpha = alpha;
  options.power = false;  // verdicts only
  const int seeds = 20;
  // Renders the engine `engine_of(seed)` (scaled in energy by `factor`), judges it against the
  // case, and counts the seeds where `check` fails.
  auto detections = [&](const std::function<OceanCase(unsigned)>& engine_of, const std::string& check,
                        double factor = 1.0, int count = 0) {
    int detected = 0;
    for (int s = 0; s < (count > 0 ? count : seeds); ++s) {
      OceanCase declared = c;
      declared.seed = 9100 + s;
      const OceanCase engine = engine_of(declared.seed);
      auto frames = swell::test::render_surface(engine);
      if (factor != 1.0) swell::test::scale_energy(frames, factor);
      // Stamped with the declared times, as frames read from files are (an engine with another
      // time step renders its own).
      for (int f = 0; f < int(frames.frames.size()); ++f) frames.frames[std::size_t(f)].time = declared.time(f);
      const auto report = swell::validation::run_gate(as_case_file(declared), frames, options);
      bool failed = false;
      for (const auto& r : report.results) failed |= !r.passed && r.check.rfind(check, 0) == 0;
      detected += failed;
    }
    return detected;
  };
  auto same = [&](unsigned seed) {
    OceanCase e = c;
    e.seed = seed;
    return e;
  };
  const auto energy = line_of("energy factor");
  const int energy_hits = detections(same, energy.check == "energy" ? "energy" : "spectrum.shape", energy.above);
  const auto offset = line_of("mean direction offset");
  const int offset_hits = detections([&](unsigned seed) {
    OceanCase e = same(seed);
    e.wind_dir_deg += offset.above;
    return e;
  }, "direction.distribution");
  const auto spreading = line_of("spreading s");
  const int spreading_hits = detections([&](unsigned seed) {
    OceanCase e = same(seed);
    e.spreading.numbers["s"] = spreading.above;
    return e;
  }, "direction.distribution");
  const auto gamma = line_of("JONSWAP γ");
  const int gamma_hits = detections([&](unsigned seed) {
    OceanCase e = same(seed);
    e.spectrum.numbers["gamma"] = gamma.above;
    return e;
  }, "spectrum.shape");
  std::cout << "[ power ] at the predicted sizes, detected in " << seeds << " seeds: energy × " << energy.above
            << ": " << energy_hits << "; direction + " << offset.above << "°: " << offset_hits << "; s = "
            << spreading.above << ": " << spreading_hits << "; γ = " << gamma.above << ": " << gamma_hits << "\n";
  for (int hits : {energy_hits, offset_hits, spreading_hits, gamma_hits}) {
    EXPECT_GE(hits, 13);
  }
  // Exact checks: ω (through g: ω ∝ √g), λ and the time step at 1.5× and 0.5× their sizes, on
  // 5 seeds (their verdicts do not depend on the seed's draw).
  const int exact_seeds = 5;
  const auto omega = line_of("ω, relative, on every wave");
  const auto lambda = line_of("choppiness λ");
  for (double times : {1.5, 0.5}) {
    const int omega_hits = detections([&](unsigned seed) {
      OceanCase e = same(seed);
      e.gravity *= std::pow(1 + times * omega.above, 2);
      return e;
    }, "dispersion", 1.0, exact_seeds);
    const int lambda_hits = detections([&](unsigned seed) {
      OceanCase e = same(seed);
      e.choppiness *= 1 + times * lambda.above;
      return e;
    }, "derived.disp_x", 1.0, exact_seeds);
    const int dt_hits = detections([&](unsigned seed) {
      OceanCase e = same(seed);
      e.dt *= 1 + times * omega.above;
      return e;
    }, "dispersion", 1.0, exact_seeds);
    std::cout << "[ power ] at " << times << "× the exact sizes: ω " << omega_hits << ", λ " << lambda_hits
              << ", dt " << dt_hits << " of " << exact_seeds << "\n";
    const int expected = times > 1 ? exact_seeds : 0;
    EXPECT_EQ(omega_hits, expected);
    EXPECT_EQ(lambda_hits, expected);
    EXPECT_EQ(dt_hits, expected);
  }
}

// Every gate report carries the table; --power prints it without frames (cli tests).
TEST(GatePower, EveryReportCarriesTheTable) {
  const OceanCase c = catalogue_case();
  const auto report = swell::validation::run_gate(as_case_file(c), swell::test::render_surface(c), GateOptions{});
  ASSERT_TRUE(report.power.has_value());
  EXPECT_EQ(report.power->lines.size(), 7u);
  EXPECT_EQ(report.power->precision, "double");
  const std::string text = swell::validation::render_gate(report);
  EXPECT_NE(text.find("Power: the smallest error the gate detects with 90 % power"), std::string::npos);
  EXPECT_FALSE(swell::validation::gate_json(report)["power"].is_null());
}

// ------------------------------------------------------------------ half precision

// The catalogue's frames stored in half (toward zero, and to nearest) pass; no check blames the
// rounding on the engine. (A right engine's calibration in half: GateCalibration below.)
TEST(HalfPrecision, TheRightEnginePassesInHalf) {
  for (bool toward_zero : {true, false}) {
    const OceanCase c = catalogue_case();
    auto frames = swell::test::render_surface(c);
    swell::test::store_in_half(frames, toward_zero);
    const auto report = swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
    EXPECT_TRUE(report.passed()) << (toward_zero ? "toward zero" : "to nearest") << describe(report);
    bool noted = false;
    for (const auto& note : report.notes) noted |= note.find("half precision") != std::string::npos;
    EXPECT_TRUE(noted);
  }
}

// No reason contradicts itself: "λ is 0.8, not the case's 0.8", "× 1 …, not 1" — a number and the
// case's number that print the same. Over the catalogue, the Godot conventions and half frames.
TEST(HalfPrecision, NoReasonContradictsItself) {
  const std::regex contradiction(R"(is ([-0-9.e+]+), not the case's \1\b)");
  auto scan = [&](const GateReport& report, const std::string& what) {
    for (const auto& r : report.results) {
      EXPECT_FALSE(std::regex_search(r.reason, contradiction)) << what << ": " << r.check << ": " << r.reason;
    }
  };
  const OceanCase c = catalogue_case();
  for (EngineBug bug : swell::test::all_engine_bugs()) {
    if (!swell::test::engine_bug_applies(bug, c)) continue;
    for (bool half : {false, true}) {
      auto frames = swell::test::render_surface(c, bug);
      if (half) swell::test::store_in_half(frames, true);
      GateOptions options;
      options.power = false;  // the reasons only
      try {
        scan(swell::validation::run_gate(as_case_file(c), frames, options), swell::test::to_string(bug));
      } catch (const swell::InvalidInput& e) {
        std::cout << "[ half ] " << swell::test::to_string(bug) << (half ? " in half" : "") << ": " << e.what() << "\n";
        throw;
      }
    }
  }
}

// Real errors about 10× the half floor still fail: ω 6 % off at every wave (g × 1.06², deep
// water), a Nyquist leak of 5.5e-3 of a displacement's rms, slopes of a normal map divided by
// 1 + |∂Dx/∂x| — each named by its check.
TEST(HalfPrecision, ErrorsTenTimesTheFloorFail) {
  const OceanCase c = catalogue_case();
  auto judge = [&](swell::reference::FrameSequence frames) {
    swell::test::store_in_half(frames, true);
    return swell::validation::run_gate(as_case_file(c), frames, GateOptions{});
  };
  OceanCase fast = c;
  fast.gravity = c.gravity * 1.06 * 1.06;
  const auto dispersion = result_of(judge(swell::test::render_surface(fast)), "dispersion.residual");
  EXPECT_FALSE(dispersion.passed) << dispersion.reason;
  EXPECT_NE(dispersion.reason.find("ω is 1.06"), std::string::npos) << dispersion.reason;

  auto leaking = swell::test::render_surface(c);
  const double rms = swell::test::rms_of(leaking, swell::reference::Field::disp_y);
  for (auto& frame : leaking.frames) swell::test::add_nyquist(frame.fields[swell::reference::Field::disp_y], c.grid, 5.5e-3 / std::numbers::sqrt2 * rms);
  const auto leak = result_of(judge(leaking), "derived.disp_y");
  EXPECT_FALSE(leak.passed) << leak.reason;
  EXPECT_NE(leak.reason.find("on the Nyquist row and column"), std::string::npos) << leak.reason;

  auto normal_map = swell::test::render_surface(c);
  for (auto& frame : normal_map.frames) {
    // ∂Dx/∂x from the displacement's spectrum: i kx × its coefficients.
    const auto& dx = frame.fields.at(swell::reference::Field::disp_x);
    auto spectrum = swell::validation::field_spectrum(dx, c.grid);
    for (std::size_t e = 0; e < spectrum.size(); ++e) {
      const int n = int(e % std::size_t(c.grid.nx));
      const int signed_n = n < c.grid.nx / 2 ? n : n - c.grid.nx;
      spectrum[e] *= std::complex<double>(0, signed_n * c.grid.dkx());
    }
    const auto dxx = swell::validation::field_from_spectrum(spectrum, c.grid);
    auto& slope = frame.fields.at(swell::reference::Field::slope_x);
    for (std::size_t p = 0; p < slope.size(); ++p) slope[p] /= 1 + std::abs(dxx[p]);
  }
  const auto slopes = result_of(judge(normal_map), "derived.slope_x");
  EXPECT_FALSE(slopes.passed) << slopes.reason;
  for (const auto& r : {dispersion, leak, slopes}) {
    std::cout << "[ half ] " << r.check << " " << r.measured << " > " << r.tolerance << ": " << r.reason << "\n";
  }
}

// Half frames read from files: float32 EXR whose every value is a half is detected as half and
// judged as such; the same frames declared `precision = "float"` would be judged at float32's
// floor, which their rounding exceeds.
TEST(HalfPrecision, FloatFilesOfHalvesAreDetectedAndJudgedAsHalf) {
  const OceanCase c = catalogue_case();
  auto frames = swell::test::render_surface(c);
  swell::test::store_in_half(frames, true);
  const auto directory = std::filesystem::temp_directory_path() /
                         ("swell_half_gate_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  CaseFile file = as_case_file(c);
  swell::validation::FrameWriteOptions write;
  write.format = swell::validation::FrameFormat::exr;
  file.input = swell::validation::write_frames(directory, frames, write);
  swell::validation::write_case_file(directory / "case.toml", file);
  const auto detected = swell::validation::run_gate(directory / "case.toml", GateOptions{});
  EXPECT_TRUE(detected.passed()) << describe(detected);
  file.input.precision = "float";
  file.directory = directory;
  const auto declared = swell::validation::run_gate(file, GateOptions{});
  EXPECT_FALSE(declared.passed());
  std::filesystem::remove_all(directory);
}

// The right engine of both catalogue seas passes the gate.
TEST(Catalogue, TheRightEnginePasses) {
  for (const OceanCase& c : {catalogue_case(), shallow_case()}) {
    const auto report =
        swell::validation::run_gate(as_case_file(c), swell::test::render_surface(c), GateOptions{});
    EXPECT_TRUE(report.passed()) << describe(report);
  }
}

// ------------------------------------------------------------------ calibration

// Right engines (swell's synthesizer, fp32) over 200 seeds of a 64² sea: the gate fails at
// most as often as a binomial(200, α) count exceeds with probability 10⁻³.
TEST(GateCalibration, FamilyWiseFalseAlarmRateOverTwoHundredSeeds) {
  OceanCase base = catalogue_case();
  base.grid = Grid::create(64, 64, 400, 400);
  base.spreading.numbers["s"] = 10.0;
  const int seeds = 200;
  for (double alpha : {0.05, 1e-3}) {
    int failed = 0, failed_half = 0;
    for (int s = 0; s < seeds; ++s) {
      OceanCase c = base;
      c.seed = 500000 + s;
      auto frames = swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f32}).frames();
      GateOptions options;
      options.alpha = alpha;
      options.power = false;  // verdicts only
      const auto report = swell::validation::run_gate(as_case_file(c), frames, options);
      EXPECT_NEAR(report.alpha_per_check * report.statistical_checks, alpha, 1e-12 * alpha);
      failed += !report.passed();
      // The same frames stored in half, toward zero (GPU drivers may truncate).
      swell::test::store_in_half(frames, true);
      const auto half = swell::validation::run_gate(as_case_file(c), frames, options);
      failed_half += !half.passed();
      if (!half.passed() && report.passed()) std::cout << "[ calibration ] half only:" << describe(half) << "\n";
    }
    const boost::math::binomial_distribution<double> law(seeds, alpha);
    const int bound = int(boost::math::quantile(boost::math::complement(law, 1e-3)));
    std::cout << "[ calibration ] gate at α = " << alpha << ": " << failed << " of " << seeds
              << " right engines failed, " << failed_half << " in half (bound " << bound << ")\n";
    EXPECT_LE(failed, bound) << "α = " << alpha;
    EXPECT_LE(failed_half, bound) << "α = " << alpha << ", half";
  }
}

// The reused-random-number check alone over 240 right surfaces from the synthesizer
// in fp32: 64² and 128² grids, 8 frames and a single frame at t = 0 (the two ways amplitudes are
// recovered), 60 seeds each. Its false alarms stay within the binomial bound of α at α = 0.05
// and 10⁻³; the count of coinciding pairs is printed with its Poisson mean.
TEST(RandomnessCalibration, ReusedNumbersFalseAlarmRateOverTwoHundredFortySurfaces) {
  int surfaces = 0, failed_05 = 0, failed_001 = 0;
  double worst_lambda = 0;
  long long coinciding = 0;
  for (int n : {64, 128}) {
    for (int frames : {8, 1}) {
      for (int s = 0; s < 60; ++s) {
        OceanCase c = catalogue_case();
        c.grid = Grid::create(n, n, 400.0 * n / 64, 400.0 * n / 64);
        c.frames = frames;
        c.seed = 900000 + 1000 * n + 10 * frames + s;
        const auto rendered =
            swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f32}).frames();
        swell::validation::OceanCheckOptions options;
        options.alpha = 0.05;
        const auto report = swell::validation::run_ocean_checks(c, rendered, options, {"randomness"});
        ASSERT_EQ(report.results.size(), 1u);
        const auto& r = report.results.front();
        ++surfaces;
        failed_05 += r.p_value < 0.05;
        failed_001 += r.p_value < 1e-3;
        worst_lambda = std::max(worst_lambda, r.expected);
        coinciding += (long long)r.measured;
      }
    }
  }
  for (const auto& [alpha, failed] : {std::pair{0.05, failed_05}, std::pair{1e-3, failed_001}}) {
    const boost::math::binomial_distribution<double> law(surfaces, alpha);
    const int bound = int(boost::math::quantile(boost::math::complement(law, 1e-3)));
    std::cout << "[ calibration ] randomness.reused_numbers at α = " << alpha << ": " << failed
              << " of " << surfaces << " right surfaces failed (bound " << bound
              << "); coinciding pairs in all: " << coinciding << ", largest Poisson mean "
              << worst_lambda << "\n";
    EXPECT_LE(failed, bound) << "α = " << alpha;
  }
}

// The same right engines through 16-bit PNG frames: the quantization noise (u = q/√(12 mean v²))
// must not raise the false-alarm rate above α. Frames of height and the two
// displacements (R, G, B), value range ±1.05 × the largest value of the first seed's frames.
TEST(GateCalibration, SixteenBitPngFalseAlarmRateOverTwoHundredSeeds) {
  namespace fs = std::filesystem;
  OceanCase base = catalogue_case();
  base.grid = Grid::create(64, 64, 400, 400);
  base.spreading.numbers["s"] = 10.0;
  const fs::path directory =
      fs::temp_directory_path() / ("swell_png_calibration_" + std::to_string(::getpid()));
  const int seeds = 200;
  const double alpha = 0.05;
  int failed = 0;
  double largest_roundoff = 0;
  swell::validation::FrameWriteOptions write;
  write.format = swell::validation::FrameFormat::png;
  for (int s = 0; s < seeds; ++s) {
    OceanCase c = base;
    c.seed = 600000 + s;
    auto frames = swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f32}).frames();
    const double largest = swell::test::keep_rgb_fields(frames);
    write.png_range = {-1.05 * largest, 1.05 * largest};
    fs::remove_all(directory);
    CaseFile case_file = as_case_file(c);
    case_file.input = swell::validation::write_frames(directory, frames, write);
    swell::validation::write_case_file(directory / "case.toml", case_file);
    GateOptions options;
    options.alpha = alpha;
    options.power = false;  // verdicts only
    const auto report = swell::validation::run_gate(directory / "case.toml", options);
    failed += !report.passed();
    largest_roundoff = std::max(largest_roundoff, report.unit_roundoff);
  }
  fs::remove_all(directory);
  const boost::math::binomial_distribution<double> law(seeds, alpha);
  const int bound = int(boost::math::quantile(boost::math::complement(law, 1e-3)));
  std::cout << "[ calibration ] gate on 16-bit PNG at α = " << alpha << ": " << failed << " of "
            << seeds << " right engines failed (bound " << bound << "); unit roundoff up to "
            << largest_roundoff << "\n";
  EXPECT_LE(failed, bound);
}

}  // namespace
