// Golden behaviour of the `swell` command: what it prints and writes for good input, and exit
// code 2 with a message naming the problem for bad input (docs/conventions.md §8).
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include <sys/wait.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <ostream>
#include <set>
#include <string>

namespace {

using swell::test::Run;
using swell::test::swell;

// Bretschneider written out here, independently of reference/.
double bretschneider(double hs, double tp, double omega) {
  const double wp = 2 * std::numbers::pi / tp;
  return 5.0 / 16.0 * hs * hs * std::pow(wp, 4) / std::pow(omega, 5) *
         std::exp(-1.25 * std::pow(wp / omega, 4));
}

TEST(CliSpectrum, BretschneiderValuesAndMomentsAsJson) {
  const auto run = swell("spectrum --model bretschneider --hs 6.5 --tp 10 --omega 1,2,3 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto doc = nlohmann::json::parse(run.output);
  EXPECT_EQ(doc.at("model"), "bretschneider");
  EXPECT_DOUBLE_EQ(doc.at("params").at("hs").get<double>(), 6.5);
  ASSERT_EQ(doc.at("omega").size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const double omega = doc.at("omega")[i].get<double>();
    EXPECT_DOUBLE_EQ(omega, i + 1.0);
    // Same formula, different rounding order: a few ulps.
    EXPECT_NEAR(doc.at("S")[i].get<double>(), bretschneider(6.5, 10, omega),
                1e-14 * bretschneider(6.5, 10, omega));
  }
  const auto& m = doc.at("moments");
  for (const char* key : {"m0", "m1", "m2", "m4", "m_1", "hs", "tp", "tm01", "tm02", "te"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  EXPECT_NEAR(m.at("m0").get<double>(), 6.5 * 6.5 / 16, 1e-9 * 6.5 * 6.5 / 16);
  EXPECT_NEAR(m.at("hs").get<double>(), 6.5, 1e-8);
  EXPECT_NEAR(m.at("tp").get<double>(), 10.0, 1e-7);
  EXPECT_TRUE(m.at("m4").is_null()) << "m4 of an ω⁻⁵ tail diverges";
  // Tm02 in closed form: 2π √(m0/m2) with m2 = (Hs²/16) ωp² √(5/4) Γ(1/2).
  const double wp = 2 * std::numbers::pi / 10;
  const double tm02 = 2 * std::numbers::pi / (wp * std::sqrt(std::sqrt(1.25) * std::sqrt(std::numbers::pi)));
  EXPECT_NEAR(m.at("tm02").get<double>(), tm02, 1e-8 * tm02);
}

TEST(CliSpectrum, OmegaRangeSamplesEvenly) {
  const auto run = swell("spectrum --model jonswap --hs 2 --tp 7 --omega 0.5:2.5:5 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto omega = nlohmann::json::parse(run.output).at("omega").get<std::vector<double>>();
  EXPECT_EQ(omega, (std::vector<double>{0.5, 1.0, 1.5, 2.0, 2.5}));
}

TEST(CliSpectrum, TextOutputNamesUnits) {
  const auto run = swell("spectrum --model tma --hs 2 --tp 7 --depth 15");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("omega [rad/s]"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Hs ="), std::string::npos) << run.output;
}

struct BadInput {
  std::string arguments;
  std::string must_mention;
};

void PrintTo(const BadInput& input, std::ostream* os) { *os << "swell " << input.arguments; }

class CliBadInput : public testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, ExitsTwoNamingTheProblem) {
  const auto run = swell(GetParam().arguments);
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find(GetParam().must_mention), std::string::npos)
      << "message should mention '" << GetParam().must_mention << "':\n" << run.output;
}

INSTANTIATE_TEST_SUITE_P(
    Spectrum, CliBadInput,
    testing::Values(
        BadInput{"spectrum --model jonswapp --hs 1 --tp 5", "pierson-moskowitz"},  // lists valid
        BadInput{"spectrum --model bretschneider --hs 1 --tp 5 --gamma 2", "gamma"},
        BadInput{"spectrum --model jonswap --hs 1", "tp"},
        BadInput{"spectrum --model bretschneider --hs 0 --tp 5", "hs"},
        BadInput{"spectrum --model bretschneider --hs -1 --tp 5", "hs"},
        BadInput{"spectrum --model bretschneider --hs nan --tp 5", "hs"},
        BadInput{"spectrum --model jonswap --hs 1 --tp 5 --gamma 0.5", "gamma"},
        BadInput{"spectrum --model tma --hs 1 --tp 5 --depth -3", "depth"},
        BadInput{"spectrum --model tma --hs 1 --tp 5", "depth"},
        // Each value in range, the whole outside any sea: bad input, not a numerical failure.
        BadInput{"spectrum --model tma --hs 3 --tp 4e65 --depth 10", "cannot be evaluated"},
        BadInput{"spectrum --model jonswap --hs 1e300 --tp 8", "cannot be evaluated"},
        BadInput{"spectrum --model jonswap --hs 1 --tp 5 --alpha 0.01", "exactly one of"},
        BadInput{"spectrum --model jonswap --hs 1 --tp 5 --normalization dvn", "dnv"},
        BadInput{"spectrum --model jonswap --hs 1 --tp 5 --omega 1:2", "a:b:n"},
        BadInput{"spectrum --model jonswap --hs 1 --tp 5 --omega 1,x", "'x'"},
        BadInput{"spectrum --model jonswap --hs 1 --tp 5 --omega 2:1:4", "b > a"},
        BadInput{"spectrum --model jonswap --hs one --tp 5", "hs"},
        BadInput{"spectrum --hs 1 --tp 5", "model"},
        BadInput{"check transforms --impl fftx --report-dir /tmp/swell-cli-test", "fftx"},
        BadInput{"frobnicate", "frobnicate"},
        BadInput{"check ocean --impl fftx --report-dir /tmp/swell-cli-test", "fftx"},
        BadInput{"check ocean --alpha 0 --report-dir /tmp/swell-cli-test", "alpha"},
        BadInput{"check ocean --n 8 --report-dir /tmp/swell-cli-test", "--n"}),
    [](const testing::TestParamInfo<BadInput>& info) {
      std::string name = std::to_string(info.index) + "_";
      for (char c : info.param.arguments) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

TEST(CliCheck, AllPassesAndWritesReports) {
  const auto dir = std::filesystem::temp_directory_path() / "swell_cli_check_test";
  std::filesystem::remove_all(dir);
  const auto run = swell("check all --report-dir " + dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(" 0 failed"), std::string::npos) << run.output;
  std::ifstream json_file(dir / "check_all.json");
  ASSERT_TRUE(json_file) << "no check_all.json";
  const auto doc = nlohmann::json::parse(json_file);
  EXPECT_EQ(doc.at("failed"), 0);
  EXPECT_EQ(doc.at("pass"), true);
  EXPECT_GT(doc.at("passed").get<int>(), 40);
  // Every exact backend's accuracy rows are there and pass.
  // Every exact backend that can start here: naive, radix2, fftw, and vulkan where the build
  // has it and a device runs it (check all then names the device; a backend it leaves out is
  // in unavailable_backends, which SWELL_REQUIRE_VULKAN=1 does not accept for vulkan).
  std::set<std::string> expected = {"naive", "radix2", "fftw"};
  if (doc.contains("vulkan_device")) {
    expected.insert("vulkan");
  } else if (const char* required = std::getenv("SWELL_REQUIRE_VULKAN");
             required && std::string(required) == "1") {
    ADD_FAILURE() << "SWELL_REQUIRE_VULKAN=1, but check all ran no vulkan: "
                  << doc.value("unavailable_backends", nlohmann::json::object()).dump();
  }
  std::set<std::string> impls;
  for (const auto& row : doc.at("transforms")) {
    impls.insert(row.at("impl").get<std::string>());
    EXPECT_TRUE(row.at("pass").get<bool>()) << row.dump();
    EXPECT_LE(row.at("rel_l2").get<double>(), row.at("bound").get<double>()) << row.dump();
  }
  EXPECT_EQ(impls, expected);
  EXPECT_EQ(doc.at("checks").size(), doc.at("passed").get<std::size_t>());
  for (const auto& row : doc.at("checks")) {
    for (const char* key : {"check", "subject", "measured", "expected", "tolerance", "pass"}) {
      EXPECT_TRUE(row.contains(key)) << key;
    }
  }
  // The ocean matrix: every exact backend × fp32/fp64 × the 4 built-in cases, all passing
  // (vulkan's frames synthesized on the device); then the lattice rows: the 4 cases on a
  // Korobov and a Fibonacci lattice × fp32/fp64 through lattice:fft=fftw.
  std::set<std::string> ocean_backends, ocean_cases, lattice_cases;
  ASSERT_EQ(doc.at("ocean").size(), expected.size() * 2u * 4u + 2u * 2u * 4u);
  for (const auto& row : doc.at("ocean")) {
    const auto backend = row.at("backend").get<std::string>();
    const auto name = row.at("case").get<std::string>();
    if (backend == "lattice:fft=fftw") {
      lattice_cases.insert(name);
    } else {
      ocean_backends.insert(backend);
      ocean_cases.insert(name);
    }
    EXPECT_TRUE(row.at("pass").get<bool>()) << row.dump();
    EXPECT_EQ(row.at("failed"), 0) << row.dump();
    EXPECT_GE(row.at("checks").size(), 20u);
  }
  EXPECT_EQ(ocean_backends, expected);
  EXPECT_EQ(ocean_cases, (std::set<std::string>{"jonswap_deep", "tma_10m", "phillips",
                                                 "pierson_moskowitz_cos2s"}));
  EXPECT_EQ(lattice_cases.size(), 8u);  // 4 cases × {korobov, fibonacci}
  for (const auto& name : lattice_cases) {
    EXPECT_TRUE(name.find("@ korobov N=") != std::string::npos ||
                name.find("@ fibonacci N=") != std::string::npos)
        << name;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "check_all.md"));
  std::filesystem::remove_all(dir);
}

// The ocean matrix of one backend, small and fast, with its table and JSON on stdout.
TEST(CliCheck, OceanForOneBackendPrintsTheMatrix) {
  const auto run = swell("check ocean --impl radix2 --n 32 --json - --report-dir /tmp/swell-cli-ocean");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto doc = nlohmann::json::parse(run.output.substr(run.output.find('{')));
  ASSERT_EQ(doc.at("ocean").size(), 8u);
  for (const auto& row : doc.at("ocean")) {
    EXPECT_EQ(row.at("backend"), "radix2");
    EXPECT_TRUE(row.at("pass").get<bool>()) << row.dump();
  }
  const auto text = swell("check ocean --impl fftw --n 32 --report-dir /tmp/swell-cli-ocean");
  EXPECT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("dispersion"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("jonswap_deep"), std::string::npos) << text.output;
}

TEST(CliCheck, UnreadableDataDirectoryIsBadInput) {
  const auto run = swell("check all --data-dir /nonexistent --report-dir /tmp/swell-cli-test");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("/nonexistent"), std::string::npos) << run.output;
}

TEST(Cli, HelpExitsZero) {
  const auto run = swell("spectrum --help");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("--sigma-a"), std::string::npos) << run.output;
  // Every model with its parameters and units, the spreadings too.
  for (const char* line : {"gaussian: hs [m], tp [s], sigma [rad/s]",
                           "ochi-hubble: hs1 [m], tp1 [s], lambda1, hs2 [m], tp2 [s], lambda2",
                           "torsethaugen: hs [m], tp [s]", "horvath: wave_age, swell, spread_blend",
                           "short_wave_fade [m]"}) {
    EXPECT_NE(run.output.find(line), std::string::npos) << line << "\n" << run.output;
  }
}

}  // namespace
