// `swell bench` and `swell report` (reports/README.md): a small bench run of the fft
// suite feeds the report; its tables are checked against the Google Benchmark JSON they came
// from (medians recomputed here from the repetitions, GFLOP/s from benchFFT's formula), the
// figures' PNG signatures when gnuplot is present, the machine context's keys, and the
// comparison of a run with itself (no significant change) and with a run of a deliberately
// slowed backend (null spinning 2 ms per transform: significantly slower, and the other way
// faster). Bad options exit 2 naming what was wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using swell::test::swell;

json read(const fs::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << file;
  return json::parse(in);
}

std::string text(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool gnuplot_present() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

class ReportCli : public ::testing::Test {
 protected:
  static fs::path root;
  static void SetUpTestSuite() {
    root = fs::temp_directory_path() / ("swell_report_test_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
    // 9 repetitions (what the U test needs), tiny sizes, and 20 ms per repetition: an unslowed
    // null repetition is then ≈ 4000 iterations of ≈ 5 µs, which a scheduler stall cannot lift to
    // the slowed 2 ms mean (with 2 ms per repetition, Google Benchmark ran a loaded machine's
    // repetitions with a handful of iterations, and one stall of a few ms mixed the samples).
    const std::string common = " --suite fft --sizes 64:128 --precision fp32 --repetitions 9 "
                               "--min-time 0.02 --progress none";
    auto a = swell("bench --impl fftw,null" + common + " --out " + (root / "a").string(), 600);
    ASSERT_EQ(a.exit_code, 0) << a.output;
    auto slow = swell("bench --impl null" + common + " --out " + (root / "slow").string(), 600);
    ASSERT_EQ(slow.exit_code, 0) << slow.output;
    // The same benchmark names, slowed: null spins 2 ms per transform. A repetition of the
    // unslowed null would have to lose more than 8 s to the scheduler to look as slow.
    ::setenv("SWELL_NULL_DELAY_US", "2000", 1);
    auto slowed = swell("bench --impl null" + common + " --out " + (root / "slowed").string(), 600);
    ::unsetenv("SWELL_NULL_DELAY_US");
    ASSERT_EQ(slowed.exit_code, 0) << slowed.output;
    auto report = swell("report " + (root / "a").string(), 300);
    ASSERT_EQ(report.exit_code, 0) << report.output;
  }
  static void TearDownTestSuite() { fs::remove_all(root); }
};
fs::path ReportCli::root;

// Each table row against the raw JSON: the median of its repetitions' times (real time, as the
// fft suite's names say), benchFFT's GFLOP/s, FFTW's ratio, and its line in README.md.
TEST_F(ReportCli, TablesMatchTheBenchmarkJson) {
  const json raw = read(root / "a" / "bench" / "fft.json");
  std::map<std::string, std::vector<double>> seconds;
  for (const auto& row : raw["benchmarks"]) {
    if (row["run_type"] != "iteration") continue;
    const std::map<std::string, double> unit = {{"ns", 1e-9}, {"us", 1e-6}, {"ms", 1e-3}, {"s", 1.0}};
    seconds[row["run_name"]].push_back(row["real_time"].get<double>() * unit.at(row["time_unit"]));
  }
  const json report = read(root / "a" / "report" / "report.json");
  const std::string readme = text(root / "a" / "report" / "README.md");
  ASSERT_EQ(report["fft"].size(), seconds.size());
  ASSERT_EQ(report["fft"].size(), 8u);  // {fftw, null} × {c2c, c2r} × {64, 128}
  std::map<std::string, double> fftw;
  for (const auto& row : report["fft"]) {
    if (row["impl"] == "fftw") fftw[row["kind"].get<std::string>() + std::to_string(row["n"].get<int>())] = row["median_s"];
  }
  for (const auto& row : report["fft"]) {
    auto values = seconds.at(row["name"]);
    ASSERT_EQ(values.size(), 9u);
    std::sort(values.begin(), values.end());
    EXPECT_DOUBLE_EQ(row["median_s"].get<double>(), values[4]) << row["name"];
    EXPECT_DOUBLE_EQ(row["iqr_s"].get<double>(), values[6] - values[2]) << row["name"];  // numpy linear, n = 9
    const double points = std::pow(row["n"].get<double>(), 2);
    const bool real = row["kind"] == "c2r";
    if (row["impl"] == "fftw") {
      const double gflops = (real ? 2.5 : 5.0) * points * std::log2(points) / values[4] * 1e-9;
      EXPECT_NEAR(row["gflops"].get<double>(), gflops, 1e-9 * gflops);
      EXPECT_DOUBLE_EQ(row["ratio_to_fftw"].get<double>(), 1.0);
      EXPECT_LE(row["rel_l2"].get<double>(), row["bound"].get<double>());
      EXPECT_GT(row["rel_l2"].get<double>(), 0.0);
    } else {
      EXPECT_TRUE(row["gflops"].is_null()) << "null copies: no flop rate";
      const double ratio = values[4] / fftw.at(row["kind"].get<std::string>() + std::to_string(row["n"].get<int>()));
      EXPECT_NEAR(row["ratio_to_fftw"].get<double>(), ratio, 1e-12 * ratio);
    }
    const std::string line = "| " + std::to_string(row["n"].get<int>()) + "² | " +
                             row["impl"].get<std::string>() + " | fp32 | " + row["kind"].get<std::string>() + " | ";
    EXPECT_NE(readme.find(line), std::string::npos) << line;
  }
}

TEST_F(ReportCli, FiguresAreWrittenAndRenderedWhenGnuplotIsPresent) {
  const json report = read(root / "a" / "report" / "report.json");
  ASSERT_EQ(report["figures"].size(), 4u);  // time, GFLOP/s, ratio to FFTW, error
  for (const auto& figure : report["figures"]) {
    const fs::path dir = root / "a" / "report" / "figures";
    EXPECT_TRUE(fs::exists(dir / figure["data"].get<std::string>()));
    EXPECT_TRUE(fs::exists(dir / figure["script"].get<std::string>()));
    if (!gnuplot_present()) continue;
    EXPECT_TRUE(figure["rendered"].get<bool>()) << figure["png"];
    std::ifstream png(dir / figure["png"].get<std::string>(), std::ios::binary);
    char signature[8] = {};
    png.read(signature, 8);
    EXPECT_EQ(std::string(signature, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << figure["png"];
  }
  // Without gnuplot: data and scripts, no PNG, and the report says so.
  const auto run = swell("report " + (root / "a").string() + " --out " + (root / "no_gnuplot").string() +
                         " --gnuplot /nonexistent/gnuplot");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_FALSE(fs::exists(root / "no_gnuplot" / "figures" / "fft_time.png"));
  EXPECT_TRUE(fs::exists(root / "no_gnuplot" / "figures" / "fft_time.gp"));
  EXPECT_NE(text(root / "no_gnuplot" / "README.md").find("was not found"), std::string::npos);
}

TEST_F(ReportCli, MachineContextHasEveryKey) {
  const json context = read(root / "a" / "context.json");
  for (const char* key : {"cpu", "memory", "os", "load_average", "build", "libraries", "date"}) {
    EXPECT_TRUE(context.contains(key)) << key;
  }
  for (const char* key : {"model", "logical_cores", "flags", "simd", "caches", "mhz", "frequency_scaling"}) {
    EXPECT_TRUE(context["cpu"].contains(key)) << key;
  }
  for (const char* key : {"compiler", "flags", "build_type", "git_commit", "git_dirty"}) {
    EXPECT_TRUE(context["build"].contains(key)) << key;
  }
  for (const char* key : {"fftw", "openimageio", "ceres", "google_benchmark", "vulkan_loader", "vulkan_device"}) {
    EXPECT_TRUE(context["libraries"].contains(key)) << key;
  }
  EXPECT_GT(context["cpu"]["logical_cores"].get<int>(), 0);
  EXPECT_NE(context["libraries"]["fftw"].get<std::string>().find("fftw-3"), std::string::npos);
  const json run = read(root / "a" / "run.json");
  EXPECT_EQ(run["repetitions"], 9);
  EXPECT_EQ(run["benchmarks"]["fft"].size(), 8u);
}

TEST_F(ReportCli, ARunAgainstItselfHasNoSignificantChange) {
  const auto run = swell("report " + (root / "a").string() + " --against " + (root / "a").string() +
                         " --out " + (root / "self").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const json c = read(root / "self" / "report.json")["comparison"];
  ASSERT_EQ(c["rows"].size(), 8u);
  for (const auto& row : c["rows"]) {
    EXPECT_EQ(row["verdict"], "no significant change") << row["name"];
    EXPECT_DOUBLE_EQ(row["ratio"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(row["p_value"].get<double>(), 1.0);  // identical samples
  }
  EXPECT_EQ(c["faster"], 0);
  EXPECT_EQ(c["slower"], 0);
  EXPECT_DOUBLE_EQ(c["geometric_mean_ratio"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(c["threshold"].get<double>(), 0.35);  // separately made runs
}

// null takes well under 10 µs at 64² and 128²; spinning 2 ms makes it 200× slower or more,
// and 9 against 9 completely separated repetitions give p = 4.1e-4 (the U test's smallest).
TEST_F(ReportCli, ASlowedBackendIsSignificantlySlowerAndTheOtherWayFaster) {
  auto run = swell("report " + (root / "slowed").string() + " --against " + (root / "slow").string() +
                   " --out " + (root / "slower").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  json c = read(root / "slower" / "report.json")["comparison"];
  ASSERT_EQ(c["rows"].size(), 4u);  // null × {c2c, c2r} × {64, 128}
  for (const auto& row : c["rows"]) {
    EXPECT_EQ(row["verdict"], "slower") << row["name"] << " ratio " << row["ratio"] << " p " << row["p_value"];
    EXPECT_GT(row["ratio"].get<double>(), 10.0);
    EXPECT_LT(row["p_value"].get<double>(), 1e-3);
  }
  EXPECT_EQ(c["slower"], 4);
  EXPECT_GT(c["geometric_mean_ratio"].get<double>(), 10.0);
  run = swell("report " + (root / "slow").string() + " --against " + (root / "slowed").string() +
              " --out " + (root / "faster").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  c = read(root / "faster" / "report.json")["comparison"];
  EXPECT_EQ(c["faster"], 4);
  if (gnuplot_present()) {
    EXPECT_TRUE(fs::exists(root / "faster" / "figures" / "comparison_ratios.png"));
  }
}

// Interleaved runs: one repetition of each build in turn, a round file per repetition on
// both sides, merged by the report; the pair is judged with the interleaved threshold (0.10).
TEST_F(ReportCli, InterleavedRunsAlternateAndUseTheirThreshold) {
  const std::string bench_dir = SWELL_BENCH_BINARY_DIR;
  const auto run = swell("bench --suite fft --impl null --sizes 64 --precision fp32 --repetitions 3 "
                         "--min-time 0.002 --progress none --no-accuracy --out " + (root / "ia").string() +
                         " --interleave " + bench_dir + " --other-out " + (root / "ib").string(), 300);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* side : {"ia", "ib"}) {
    for (int round = 1; round <= 3; ++round) {
      EXPECT_TRUE(fs::exists(root / side / "bench" / ("fft.round000" + std::to_string(round) + ".json"))) << side;
    }
  }
  const auto report = swell("report " + (root / "ia").string() + " --against " + (root / "ib").string() +
                            " --out " + (root / "interleaved").string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const json c = read(root / "interleaved" / "report.json")["comparison"];
  EXPECT_DOUBLE_EQ(c["threshold"].get<double>(), 0.10);
  ASSERT_EQ(c["rows"].size(), 2u);  // null × {c2c, c2r} at 64²
  for (const auto& row : c["rows"]) {
    EXPECT_EQ(row["repetitions"], 3);
    EXPECT_NE(row["warning"].get<std::string>(), "") << "3 repetitions must be warned about";
  }
}

TEST_F(ReportCli, BadOptionsExit2NamingWhatWasWrong) {
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {"bench --suite nope", "--suite 'nope'"},
      {"bench --sizes 9:3", "--sizes '9:3'"},
      {"bench --sizes 64:x", "--sizes '64:x'"},
      {"bench --precision fp16", "--precision 'fp16'"},
      {"bench --impl nosuch", "nosuch"},
      {"bench --repetitions 0", "--repetitions 0"},
      {"bench --interleave /tmp", "--other-out"},
      {"bench --suite fft --sizes 3:5", "no fft benchmark matches"},
      {"report /nonexistent/folder", "/nonexistent/folder"},
      {"report " + (root / "a").string() + " --threshold 0", "--threshold"},
      {"report " + (root / "a").string() + " --against /nonexistent/other", "/nonexistent/other"},
  };
  for (const auto& c : cases) {
    const auto run = swell(c.arguments + " --out " + (root / "bad").string());
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.output;
    EXPECT_NE(run.output.find(c.expected), std::string::npos) << c.arguments << "\n" << run.output;
  }
}

}  // namespace
