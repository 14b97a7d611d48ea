// Probes from the command line (docs/probes.md): swell synth writes series that swell gate
// passes, for each amplitude law and direction scheme the gate judges; a deep-water dispersion
// in finite depth and an energy factor are named; OpenFAST's .out tables are read; bad cases
// exit 2 naming what is wrong.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/impls/probe_synthesis.hpp"
#include "swell/validation/io/probe_series.hpp"

namespace {

namespace fs = std::filesystem;
using swell::test::swell;

class ProbeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("swell_probe_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  fs::path dir_;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The OpenFAST sea, shortened: JONSWAP Hs 3 m, Tp 10 s, γ 3.3 in 30 m of water, three
// probes, 4096 samples at 0.25 s — one repeat period of 1024 s.
std::string probes_case(const std::string& synthesis, const std::string& spreading = "wind_dir_deg = 30.0\n",
                        const std::string& depth = "30.0") {
  return "[sampling]\nkind = \"probes\"\npositions = [[0.0, 0.0], [10.0, 0.0], [0.0, 10.0]]\n"
         "[time]\nt0 = 0.0\ndt = 0.25\nsamples = 4096\n"
         "[physics]\ndepth = " + depth + "\n"
         "[spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 10.0\ngamma = 3.3\n"
         "[spreading]\n" + spreading +
         "[synthesis]\nseed = 7\nrepeat_period = 1024.0\nomega_cutoff = [0.0, 6.0]\n" + synthesis;
}

TEST_F(ProbeCli, SynthThenGatePassForEachSchemeTheGateJudges) {
  const std::pair<const char*, std::string> schemes[] = {
      {"deterministic_long_crested", probes_case("amplitudes = \"deterministic\"\ndirections = \"long_crested\"\n")},
      {"rayleigh_long_crested", probes_case("amplitudes = \"rayleigh\"\ndirections = \"long_crested\"\n")},
      {"rayleigh_double_summation",
       probes_case("amplitudes = \"rayleigh\"\ndirections = \"double_summation\"\nn_directions = 15\n",
                   "model = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n")},
      {"deterministic_double_summation",
       probes_case("amplitudes = \"deterministic\"\ndirections = \"double_summation\"\nn_directions = 15\n",
                   "model = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n")},
      {"deterministic_single",
       probes_case("amplitudes = \"deterministic\"\ndirections = \"single_per_frequency\"\n",
                   "model = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n")},
  };
  for (const auto& [name, text] : schemes) {
    SCOPED_TRACE(name);
    write(std::string(name) + ".toml", text);
    const auto synth = swell("synth --case " + path(std::string(name) + ".toml") + " --out " + path(name));
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    const auto gate = swell("gate --case " + path(std::string(name) + "/case.toml"));
    EXPECT_EQ(gate.exit_code, 0) << gate.output;
    EXPECT_TRUE(contains(gate.output, "PASS  series.spectrum")) << gate.output;
    EXPECT_TRUE(contains(gate.output, "PASS  series.stray_energy")) << gate.output;
  }
}

// Series made in deep water, judged as the 30 m case: the exact phase check names the
// dispersion; series scaled by 2π (amplitudes × 2π): the energy check names × 4π².
TEST_F(ProbeCli, ADeepWaterDispersionAndAScaledAmplitudeAreNamed) {
  const std::string scheme = "amplitudes = \"deterministic\"\ndirections = \"long_crested\"\n";
  write("deep.toml", probes_case(scheme, "wind_dir_deg = 30.0\n", "\"inf\""));
  ASSERT_EQ(swell("synth --case " + path("deep.toml") + " --out " + path("deep")).exit_code, 0);
  // The same series judged against the 30 m case, its [input] the deep run's file.
  write("deep/shallow.toml", probes_case(scheme) + "[input]\nfiles = \"elevation.csv\"\ntime_column = \"time\"\n"
                                                   "probes = [\"probe0\", \"probe1\", \"probe2\"]\n");
  const auto gate = swell("gate --case " + path("deep/shallow.toml"));
  EXPECT_EQ(gate.exit_code, 1) << gate.output;
  EXPECT_TRUE(contains(gate.output, "FAIL  series.phase")) << gate.output;
  EXPECT_TRUE(contains(gate.output, "deep-water k = ω²/g where the case's depth is 30 m")) << gate.output;

  write("right.toml", probes_case(scheme));
  ASSERT_EQ(swell("synth --case " + path("right.toml") + " --out " + path("right")).exit_code, 0);
  auto c = swell::validation::read_case_file(dir_ / "right" / "case.toml");
  auto series = swell::validation::read_probe_series(c);
  for (auto& probe : series.elevation) {
    for (double& v : probe) v *= 2 * 3.141592653589793;
  }
  swell::validation::write_probe_series_csv(dir_ / "right" / "elevation.csv", c.probes->layout, series.elevation,
                                            c.probes->input.probes);
  const auto scaled = swell("gate --case " + path("right/case.toml"));
  EXPECT_EQ(scaled.exit_code, 1) << scaled.output;
  EXPECT_TRUE(contains(scaled.output, "FAIL  series.energy")) << scaled.output;
  EXPECT_TRUE(contains(scaled.output, "× 4π²")) << scaled.output;
}

// Two engine bugs on a right case: amplitudes ∝ S Δω (a = 2 S Δω, the √ of √(2 S Δω) missing) —
// named by the spectrum check's slope; and probe 1 repeating probe 0's series (a probe clamped to
// the domain's edge) — named by the phase check. For each amplitude law the gate judges.
TEST_F(ProbeCli, AMissingSquareRootAndAClampedProbeAreNamed) {
  for (const char* amplitudes : {"deterministic", "rayleigh"}) {
    SCOPED_TRACE(amplitudes);
    const std::string scheme = std::string("amplitudes = \"") + amplitudes + "\"\ndirections = \"long_crested\"\n";
    write("case.toml", probes_case(scheme));
    ASSERT_EQ(swell("synth --case " + path("case.toml") + " --out " + path(amplitudes)).exit_code, 0);
    const auto c = swell::validation::read_case_file(dir_ / amplitudes / "case.toml");
    const auto probe_case = c.probe_case();
    auto lines = swell::reference::probe_wave_lines(probe_case, c.ocean.seed);
    for (auto& line : lines) line.amplitude = line.amplitude * line.amplitude;  // √(2 S Δω) → 2 S Δω
    const auto buggy = swell::impls::synthesize_probe_series(probe_case, lines);
    swell::validation::write_probe_series_csv(dir_ / amplitudes / "elevation.csv", probe_case.layout, buggy,
                                              c.probes->input.probes);
    const auto root = swell("gate --case " + path(std::string(amplitudes) + "/case.toml"));
    EXPECT_EQ(root.exit_code, 1) << root.output;
    EXPECT_TRUE(contains(root.output, "a missing √")) << root.output;

    auto series = swell::impls::synthesize_probe_series(probe_case, swell::reference::probe_wave_lines(probe_case, c.ocean.seed));
    series[1] = series[0];
    swell::validation::write_probe_series_csv(dir_ / amplitudes / "elevation.csv", probe_case.layout, series,
                                              c.probes->input.probes);
    const auto clamped = swell("gate --case " + path(std::string(amplitudes) + "/case.toml"));
    EXPECT_EQ(clamped.exit_code, 1) << clamped.output;
    EXPECT_TRUE(contains(clamped.output, "probe 1 moves in phase with probe 0")) << clamped.output;
  }
}

// Series that repeat after half the declared period (lines 2 Δω apart) are named so; a record
// shorter than the declared repeat period is judged by Welch estimates, saying so.
TEST_F(ProbeCli, ASeriesRepeatingSoonerThanDeclaredIsNamed) {
  const std::string scheme = "amplitudes = \"deterministic\"\ndirections = \"long_crested\"\n";
  std::string half = probes_case(scheme);
  half.replace(half.find("repeat_period = 1024.0"), 22, "repeat_period = 512.0");
  write("half.toml", half);
  ASSERT_EQ(swell("synth --case " + path("half.toml") + " --out " + path("half")).exit_code, 0);
  write("half/declared.toml", probes_case(scheme) + "[input]\nfiles = \"elevation.csv\"\ntime_column = \"time\"\n"
                                                    "probes = [\"probe0\", \"probe1\", \"probe2\"]\n");
  const auto gate = swell("gate --case " + path("half/declared.toml"));
  EXPECT_EQ(gate.exit_code, 1) << gate.output;
  EXPECT_TRUE(contains(gate.output, "the series repeats after repeat_period/2")) << gate.output;
  std::string longer = probes_case(scheme);
  longer.replace(longer.find("repeat_period = 1024.0"), 22, "repeat_period = 2048.0");
  write("half/longer.toml", longer + "[input]\nfiles = \"elevation.csv\"\ntime_column = \"time\"\n"
                                     "probes = [\"probe0\", \"probe1\", \"probe2\"]\n");
  // Judged by Welch estimates, whose bins cannot tell the declared lines from the engine's, saying so.
  const auto shorter = swell("gate --case " + path("half/longer.toml"));
  EXPECT_EQ(shorter.exit_code, 0) << shorter.output;
  EXPECT_TRUE(contains(shorter.output, "shorter than the declared repeat period")) << shorter.output;
}

// An engine that interpolates its probes from a wave grid of 4 m spacing (OpenFAST's SeaState
// does): probes off the nodes lose variance, more at the shorter waves. The exact check of one
// amplitude per line names it, for each scheme with one direction per frequency.
TEST_F(ProbeCli, ProbesInterpolatedFromAGridAreNamed) {
  for (const char* directions : {"long_crested", "single_per_frequency"}) {
    SCOPED_TRACE(directions);
    const std::string scheme = std::string("amplitudes = \"rayleigh\"\ndirections = \"") + directions + "\"\n";
    write("case.toml", probes_case(scheme, "model = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n"));
    ASSERT_EQ(swell("synth --case " + path("case.toml") + " --out " + path(directions)).exit_code, 0);
    const auto c = swell::validation::read_case_file(dir_ / directions / "case.toml");
    const auto probe_case = c.probe_case();
    const auto lines = swell::reference::probe_wave_lines(probe_case, c.ocean.seed);
    // The probes (0, 0), (10, 0), (0, 10): probe 0 on a node, the others halfway between nodes
    // 8 and 12 m, bilinear.
    auto nodes = probe_case;
    nodes.layout.positions = {{0.0, 0.0}, {8.0, 0.0}, {12.0, 0.0}, {0.0, 8.0}, {0.0, 12.0}};
    const auto at_nodes = swell::impls::synthesize_probe_series(nodes, lines);
    std::vector<std::vector<double>> series = {at_nodes[0], at_nodes[1], at_nodes[3]};
    for (std::size_t n = 0; n < series[1].size(); ++n) {
      series[1][n] = 0.5 * (at_nodes[1][n] + at_nodes[2][n]);
      series[2][n] = 0.5 * (at_nodes[3][n] + at_nodes[4][n]);
    }
    swell::validation::write_probe_series_csv(dir_ / directions / "elevation.csv", probe_case.layout, series,
                                              c.probes->input.probes);
    const auto gate = swell("gate --case " + path(std::string(directions) + "/case.toml"));
    EXPECT_EQ(gate.exit_code, 1) << gate.output;
    EXPECT_TRUE(contains(gate.output, "FAIL  series.same_amplitude")) << gate.output;
    EXPECT_TRUE(contains(gate.output, "values interpolated between grid nodes")) << gate.output;
  }
}

// An OpenFAST SeaState .out table: preamble, names, units, whitespace-separated rows printed
// to ES-style precision; the gate reads it, its rounding bounding the exact checks.
TEST_F(ProbeCli, AnOpenFastOutTableIsRead) {
  const std::string scheme = "amplitudes = \"deterministic\"\ndirections = \"long_crested\"\n";
  write("case.toml", probes_case(scheme));
  ASSERT_EQ(swell("synth --case " + path("case.toml") + " --out " + path("made")).exit_code, 0);
  auto c = swell::validation::read_case_file(dir_ / "made" / "case.toml");
  const auto series = swell::validation::read_probe_series(c);
  std::ofstream out(dir_ / "made" / "driver.out");
  out << "\n Predictions were generated on 06-Dec-2026 at 10:00:00 using SeaState\n linked with OpenFAST\n\n"
         " Description from the driver input file: a test\n\n";
  out << "Time      Wave1Elev Wave2Elev Wave3Elev\n(s)       (m)       (m)       (m)\n";
  for (std::size_t n = 0; n < c.probes->layout.samples; ++n) {
    out << fmt::format("{:.4f}", c.probes->layout.time(n));
    for (const auto& probe : series.elevation) out << fmt::format("  {:.9E}", probe[n]);
    out << "\n";
  }
  out.close();
  write("made/openfast.toml", probes_case(scheme) + "[input]\nfiles = \"driver.out\"\ntime_column = \"Time\"\n"
                                                    "probes = [\"Wave1Elev\", \"Wave2Elev\", \"Wave3Elev\"]\n");
  const auto gate = swell("gate --case " + path("made/openfast.toml"));
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
  // A missing column is named.
  write("made/missing.toml", probes_case(scheme) + "[input]\nfiles = \"driver.out\"\ntime_column = \"Time\"\n"
                                                   "probes = [\"Wave1Elev\", \"Wave2Elev\", \"Wave9Elev\"]\n");
  const auto missing = swell("gate --case " + path("made/missing.toml"));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_TRUE(contains(missing.output, "Wave9Elev")) << missing.output;
}

TEST_F(ProbeCli, BadProbeCasesExitTwoNamingTheProblem) {
  const std::pair<std::string, std::string> cases[] = {
      {probes_case("amplitudes = \"gaussian\"\n"), "amplitudes"},
      {probes_case("directions = \"double_summation\"\nn_directions = 5\n"), "spreading model"},
      {probes_case("n_directions = 5\n"), "n_directions"},
      {probes_case("choppiness = 1.0\n"), "choppiness"},
  };
  int i = 0;
  for (const auto& [text, part] : cases) {
    write("bad" + std::to_string(i) + ".toml", text);
    const auto run = swell("synth --case " + path("bad" + std::to_string(i) + ".toml") + " --out " + path("o"));
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_TRUE(contains(run.output, part)) << part << "\n" << run.output;
    ++i;
  }
  // Above the Nyquist frequency π/dt = 12.6 rad/s.
  std::string high = probes_case("");
  high.replace(high.find("omega_cutoff = [0.0, 6.0]"), 25, "omega_cutoff = [0.0, 20.0]");
  write("high.toml", high);
  const auto run = swell("synth --case " + path("high.toml") + " --out " + path("o"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "Nyquist")) << run.output;
  // A record that is not whole repeat periods, or non-uniform lines, is judged by Welch
  // estimates, saying why.
  for (const auto& [scheme, part] :
       {std::pair<std::string, std::string>{"repeat_period = 1000.0\n", "whole number of repeat periods"},
        std::pair<std::string, std::string>{"frequencies = \"equal_energy\"\nn_frequencies = 200\n", "equal_energy"}}) {
    std::string text = probes_case("");
    if (scheme.rfind("repeat", 0) == 0) {
      text.replace(text.find("repeat_period = 1024.0"), 22, "repeat_period = 1000.0");
    } else {
      text.replace(text.find("repeat_period = 1024.0"), 22, "repeat_period = 0.0");
      text += scheme;
    }
    write("unjudged.toml", text);
    ASSERT_EQ(swell("synth --case " + path("unjudged.toml") + " --out " + path("unjudged")).exit_code, 0);
    const auto gate = swell("gate --case " + path("unjudged/case.toml"));
    EXPECT_EQ(gate.exit_code, 0) << gate.output;
    EXPECT_TRUE(contains(gate.output, part)) << part << "\n" << gate.output;
    EXPECT_TRUE(contains(gate.output, "judged by Welch estimates")) << gate.output;
    EXPECT_TRUE(contains(gate.output, "PASS  series.spectrum")) << gate.output;
  }
  // swell spectrum takes a probes case, a long-crested one without a spreading model too: its
  // m0 is the JONSWAP's Hs²/16.
  write("long.toml", probes_case(""));
  const auto spectrum = swell("spectrum --case " + path("long.toml") + " --json -");
  ASSERT_EQ(spectrum.exit_code, 0) << spectrum.output;
  EXPECT_NEAR(nlohmann::json::parse(spectrum.output)["moments"]["m0"].get<double>(), 9.0 / 16, 1e-8);
  // swell fit takes grids, and names what this case is.
  write("good.toml", probes_case(""));
  const auto fit = swell("fit --case " + path("good.toml") + " --input " + path("frame_%04d.exr"));
  EXPECT_EQ(fit.exit_code, 2) << fit.output;
  EXPECT_TRUE(contains(fit.output, "probes")) << fit.output;
}

}  // namespace
