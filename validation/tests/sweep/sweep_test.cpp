// swell sweep (docs/sweeps.md): the --vary grammar and its refusals, the statistics each run
// measures against the spectrum's own expectations, and reproducibility whatever the split —
// threads, mpirun with 1 and 2 ranks, shards merged, an interrupted sweep resumed — down to the
// bytes of the rows.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/validation/sweep/sweep.hpp"

namespace {

namespace fs = std::filesystem;
namespace sweep = swell::validation::sweep;
using swell::test::swell;

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

// A small deep-water JONSWAP case: 32² over 200 m (Tp = 6 s: λp ≈ 56 m, 3.6 peak wavelengths),
// one frame, choppy enough to fold in places.
const char* kCase = R"([grid]
n = [32, 32]
length = [200.0, 200.0]
[spectrum]
model = "jonswap"
hs = 2.0
tp = 6.0
gamma = 3.3
[spreading]
model = "cos2s"
s = 8.0
wind_dir_deg = 20.0
[synthesis]
choppiness = 1.0
seed = 11
)";

class Sweep : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("swell_sweep_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "case.toml") << kCase;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  sweep::SweepSpec spec(const std::vector<std::string>& vary, int seeds) const {
    sweep::SweepSpec s;
    s.case_path = dir_ / "case.toml";
    s.case_text = kCase;
    for (const auto& v : vary) s.variations.push_back(sweep::parse_variation(v, s.case_text, s.case_path));
    s.seeds = seeds;
    s.sweep_seed = 11;
    return s;
  }
  fs::path dir_;
};

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// runs.csv without its last column (seconds: wall time, the one column that differs between
// runs of the same sweep).
std::string rows_without_seconds(const fs::path& csv) {
  std::stringstream in(read(csv)), out;
  for (std::string line; std::getline(in, line);) out << line.substr(0, line.rfind(',')) << "\n";
  return out.str();
}

TEST_F(Sweep, RangesAndListsGiveTheValuesAsWritten) {
  const auto range = sweep::parse_variation("gamma=1:7:7", kCase, "case.toml");
  EXPECT_EQ(range.section, "spectrum");
  EXPECT_EQ(range.key, "gamma");
  ASSERT_EQ(range.numbers.size(), 7u);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(range.numbers[i], 1.0 + i);
  const auto fractions = sweep::parse_variation("hs=1:2:3", kCase, "case.toml");
  EXPECT_EQ(fractions.labels, (std::vector<std::string>{"1", "1.5", "2"}));
  const auto grid = sweep::parse_variation("n=16,32", kCase, "case.toml");
  EXPECT_EQ(grid.section, "grid");
  EXPECT_EQ(grid.toml_values, (std::vector<std::string>{"16", "32"}));
  // Keys the base case does not hold, found in the sections' vocabularies.
  EXPECT_EQ(sweep::parse_variation("depth=10,inf", kCase, "c").section, "physics");
  EXPECT_EQ(sweep::parse_variation("sigma_a=0.05,0.09", kCase, "c").section, "spectrum");
  EXPECT_EQ(sweep::parse_variation("frames=1,2", kCase, "c").section, "time");
  EXPECT_EQ(sweep::parse_variation("spreading.s=2,20", kCase, "c").key, "s");
}

TEST_F(Sweep, BadSpecsAreRefusedNamingTheKey) {
  auto refused = [&](const std::string& vary, const std::string& fragment) {
    try {
      auto s = spec({vary}, 1);
      sweep::validate(s);
      ADD_FAILURE() << vary << " was accepted";
    } catch (const swell::InvalidInput& e) {
      EXPECT_TRUE(contains(e.what(), fragment)) << vary << ": " << e.what();
    }
  };
  refused("gama=1:2:2", "unknown key 'gama'");
  refused("gamma=1:7:0", "gamma=1:7:0");          // n < 1
  refused("gamma=1:7:1", "empty range");           // one value cannot span 1…7
  refused("gamma=", "no values");
  refused("gamma=1,,2", "empty value");
  refused("gamma=2,2", "given twice");
  refused("n=16:32:4", "must be an integer");     // 16, 21.3, …
  refused("seed=1,2", "--seeds");                  // replicates are --seeds
  refused("gamma=0.5,2", "gamma = 0.5");           // the case rules: γ ≥ 1
  refused("hs=-1,2", "hs = -1");
  refused("n=24,32", "powers of two");             // radix2 takes powers of two
  refused("length=1e-6,200", "at length = 1e-6");  // the validity rule: no energy on the grid
  try {
    sweep::validate(spec({"gamma=1:7:100000", "hs=1:3:1000"}, 1));
    ADD_FAILURE() << "10⁸ points were accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_TRUE(contains(e.what(), "split it")) << e.what();
  }
}

TEST_F(Sweep, RunSeedsDependOnTheRunAloneAndDoNotCollide) {
  std::set<std::uint64_t> seen;
  for (std::size_t p = 0; p < 300; ++p) {
    for (int r = 0; r < 300; ++r) seen.insert(sweep::run_seed(7, p, r));
  }
  EXPECT_EQ(seen.size(), 90000u);
  EXPECT_EQ(sweep::run_seed(7, 3, 4), sweep::run_seed(7, 3, 4));
  EXPECT_NE(sweep::run_seed(7, 3, 4), sweep::run_seed(8, 3, 4));
  EXPECT_NE(sweep::run_seed(7, 3, 4), sweep::run_seed(7, 4, 3));
}

// Hs² / 16 is the surface's variance about its mean, Σ over k ≠ 0 of I(k) exactly, whose
// expectation is Σ μ(k) (docs/conventions.md; conventions §Amplitudes): over S seeds, the
// t statistic of the mean against it has a false-alarm rate of 1e-3 at |t| > 3.88 (S = 24,
// Student's t with 23 dof). The excess kurtosis of a Gaussian surface has mean 0 (same rate).
// Tm01 over seeds is judged by the same t law against 2π Σμ / Σμω: the ratio estimator's bias
// is O(Σμ²/(Σμ)²) ≈ 1/(effective waves) ≈ 1e-2 of one seed's spread/…, far below the t bound.
TEST_F(Sweep, StatisticsMatchTheSpectrumsExpectations) {
  auto s = spec({"gamma=1,5"}, 24);
  sweep::validate(s);
  for (std::size_t p = 0; p < s.point_count(); ++p) {
    const sweep::Point point = sweep::make_point(s, p);
    const auto& ocean = point.case_file.ocean;
    const auto mu = swell::validation::expected_periodogram(*ocean.directional_spectrum(), ocean.grid);
    double m0 = 0, m1 = 0;
    const auto& g = ocean.grid;
    for (int m = 0; m < g.ny; ++m) {
      for (int i = 0; i < g.nx; ++i) {
        const int wx = i <= g.nx / 2 ? i : i - g.nx, wy = m <= g.ny / 2 ? m : m - g.ny;
        const double mu_k = mu[std::size_t(m) * g.nx + i];
        m0 += mu_k;
        m1 += mu_k * ocean.omega(std::hypot(wx * 2 * M_PI / g.lx, wy * 2 * M_PI / g.ly));
      }
    }
    std::vector<double> variance, kurtosis, tm01;
    for (int r = 0; r < s.seeds; ++r) {
      const auto row = sweep::run(s, point, r);
      variance.push_back(row.statistics.at("hs") * row.statistics.at("hs") / 16);
      kurtosis.push_back(row.statistics.at("excess_kurtosis"));
      tm01.push_back(row.statistics.at("tm01"));
      EXPECT_GE(row.statistics.at("foam_fraction"), 0.0);
      EXPECT_LE(row.statistics.at("min_jacobian"), 1.0);
    }
    auto t_statistic = [](const std::vector<double>& x, double expected) {
      double mean = 0, sq = 0;
      for (double v : x) mean += v / x.size();
      for (double v : x) sq += (v - mean) * (v - mean);
      return (mean - expected) / std::sqrt(sq / (x.size() - 1) / x.size());
    };
    EXPECT_LT(std::abs(t_statistic(variance, m0)), 3.88) << "point " << p;
    EXPECT_LT(std::abs(t_statistic(kurtosis, 0.0)), 3.88) << "point " << p;
    EXPECT_LT(std::abs(t_statistic(tm01, 2 * M_PI * m0 / m1)), 3.88) << "point " << p;
  }
}

// --------------------------------------------------------------- the command line

const std::string kVary = "--vary gamma=1:3:3 --vary hs=1,2 --seeds 3 --progress none";

TEST_F(Sweep, CliRefusesBadSpecsBeforeAnyWork) {
  for (const auto& [args, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"--vary gama=1:2:2 --seeds 2", "gama"},
           {"--vary gamma=1:2:0 --seeds 2", "gamma=1:2:0"},
           {"--vary gamma=0.5,2 --seeds 2", "gamma"},
           {"--vary gamma=1,2 --seeds 0", "--seeds"},
           {"--vary gamma=1,2 --seeds 2 --shard 2/2", "--shard 2/2"}}) {
    const auto out = path("out");
    const auto run = swell("sweep --case " + path("case.toml") + " " + args + " --out " + out);
    EXPECT_EQ(run.exit_code, 2) << args << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, fragment)) << args << "\n" << run.output;
    EXPECT_FALSE(fs::exists(fs::path(out) / "rows.jsonl")) << args;
  }
  const auto missing = swell("sweep --case " + path("nope.toml") + " --seeds 1 --out " + path("o"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(contains(missing.output, "nope.toml")) << missing.output;
}

TEST_F(Sweep, JsonToStandardOutputIsTheDocumentAlone) {
  const auto run = swell("sweep --case " + path("case.toml") + " --vary gamma=1,2 --seeds 1 "
                         "--progress none --gnuplot '' --json - --out " + path("j"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // stderr (the gnuplot note) comes first in the captured output; the document follows.
  const auto document = nlohmann::json::parse(run.output.substr(run.output.find('{')));
  EXPECT_EQ(document["runs"], 2);
  EXPECT_EQ(document["complete"], true);
}

TEST_F(Sweep, CliWritesRowsSummariesAndPlots) {
  const auto run = swell("sweep --case " + path("case.toml") + " " + kVary + " --fit --out " + path("a"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto runs = nlohmann::json::parse(read(path("a/runs.json")));
  ASSERT_EQ(runs["runs"].size(), 18u);
  const auto& first = runs["runs"][0];
  EXPECT_EQ(first["parameters"]["gamma"], 1.0);
  EXPECT_EQ(first["parameters"]["hs"], 1.0);
  EXPECT_TRUE(first["fit"]["gamma"]["ci95"].is_array());
  const auto points = nlohmann::json::parse(read(path("a/points.json")));
  ASSERT_EQ(points["points"].size(), 6u);
  // The fit's truth is each point's own case: γ = 2 at point 2 (gamma varies slowest).
  EXPECT_EQ(points["points"][2]["fit"]["gamma"]["truth"], 2.0);
  EXPECT_EQ(points["points"][2]["runs"], 3);
  // The point summary is the runs' own mean.
  double mean = 0;
  for (int r = 0; r < 3; ++r) mean += runs["runs"][3 * 2 + r]["statistics"]["hs"].get<double>() / 3;
  EXPECT_NEAR(points["points"][2]["statistics"]["hs"]["mean"].get<double>(), mean, 1e-12 * mean);
  EXPECT_TRUE(fs::exists(path("a/runs.csv")));
  EXPECT_TRUE(fs::exists(path("a/points.csv")));
  EXPECT_TRUE(fs::exists(path("a/plots/hs_vs_gamma.dat")));
  EXPECT_TRUE(fs::exists(path("a/plots/fit_gamma_vs_gamma.gp")));
  // A second sweep into the same folder is refused, not mixed in.
  const auto again = swell("sweep --case " + path("case.toml") + " " + kVary + " --out " + path("a"));
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_TRUE(contains(again.output, "--resume")) << again.output;
}

// The same rows whatever the split: threads, mpirun -np 1 and -np 2, and two shards merged.
TEST_F(Sweep, RowsAreIdenticalWhateverTheSplit) {
  const std::string base = "sweep --case " + path("case.toml") + " " + kVary;
  ASSERT_EQ(swell(base + " --threads 1 --out " + path("one")).exit_code, 0);
  ASSERT_EQ(swell(base + " --threads 2 --out " + path("two")).exit_code, 0);
  const auto shard0 = swell(base + " --shard 0/2 --out " + path("s0"));
  const auto shard1 = swell(base + " --shard 1/2 --out " + path("s1"));
  ASSERT_EQ(shard0.exit_code, 0) << shard0.output;
  ASSERT_EQ(shard1.exit_code, 0) << shard1.output;
  const auto merged = swell("sweep --merge " + path("s0") + " " + path("s1") + " --out " + path("merged"));
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const std::string reference = rows_without_seconds(path("one/runs.csv"));
  EXPECT_EQ(std::count(reference.begin(), reference.end(), '\n'), 19);
  EXPECT_EQ(rows_without_seconds(path("two/runs.csv")), reference);
  EXPECT_EQ(rows_without_seconds(path("merged/runs.csv")), reference);
  EXPECT_EQ(read(path("merged/points.csv")), read(path("one/points.csv")));
#ifdef SWELL_MPIEXEC
  // Open MPI refuses root without these (the CI machine runs as root).
  const std::string mpirun = std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ") +
                             SWELL_MPIEXEC + " --oversubscribe -np ";
  for (const int ranks : {1, 2}) {
    const std::string out = path("mpi" + std::to_string(ranks));
    const std::string command = mpirun + std::to_string(ranks) + " " + SWELL_BINARY + " " + base +
                                " --out " + out + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = pclose(pipe);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command << "\n" << output;
    EXPECT_EQ(rows_without_seconds(fs::path(out) / "runs.csv"), reference) << ranks << " ranks";
    EXPECT_EQ(read(fs::path(out) / "points.csv"), read(path("one/points.csv"))) << ranks << " ranks";
  }
#else
  GTEST_SKIP() << "built without MPI (SWELL_WITH_MPI=OFF): mpirun not tested";
#endif
}

TEST_F(Sweep, MergeRefusesMissingAndForeignShards) {
  const std::string base = "sweep --case " + path("case.toml") + " " + kVary;
  ASSERT_EQ(swell(base + " --shard 0/2 --out " + path("s0")).exit_code, 0);
  const auto missing = swell("sweep --merge " + path("s0") + " --out " + path("m"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(contains(missing.output, "1/2 missing")) << missing.output;
  ASSERT_EQ(swell("sweep --case " + path("case.toml") + " --vary gamma=1:3:3 --vary hs=1,2 --seeds 4 "
                  "--progress none --shard 1/2 --out " + path("s1")).exit_code, 0);
  const auto foreign = swell("sweep --merge " + path("s0") + " " + path("s1") + " --out " + path("m"));
  EXPECT_EQ(foreign.exit_code, 2);
  EXPECT_TRUE(contains(foreign.output, "seeds")) << foreign.output;
}

// Ctrl-C (SIGINT) keeps the finished rows; --resume finishes the sweep with the rows an
// uninterrupted sweep gives. 48 runs of about 30 ms each: the signal comes after the second.
TEST_F(Sweep, InterruptedSweepsResumeToTheSameRows) {
  const std::string options = "sweep --case " + path("case.toml") +
                              " --vary gamma=1:4:4 --vary n=32,64 --threads 1 --fit --progress none";
  const std::string base = options + " --seeds 6";
  ASSERT_EQ(swell(base + " --out " + path("whole")).exit_code, 0);
  // SIGINT once the journal holds two rows (as Ctrl-C would): exit 130, the finished rows kept.
  const std::string command = "exec " + std::string(SWELL_BINARY) + " " + base + " --out " +
                              path("cut") + " >/dev/null 2>&1";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  auto journal_rows = [&] {
    const std::string journal = read(path("cut/rows.jsonl"));
    return std::count(journal.begin(), journal.end(), '\n');
  };
  int status = 0;
  for (int waited_ms = 0; journal_rows() < 2 && waited_ms < 60000; ++waited_ms) {
    if (waitpid(child, &status, WNOHANG) == child) FAIL() << "the sweep ended before it was interrupted";
    usleep(1000);
  }
  kill(child, SIGINT);
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const long kept = journal_rows();
  EXPECT_GE(kept, 2);
  EXPECT_LT(kept, 48);
  EXPECT_FALSE(fs::exists(path("cut/runs.csv")));
  const auto resumed = swell(base + " --out " + path("cut") + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(rows_without_seconds(path("cut/runs.csv")), rows_without_seconds(path("whole/runs.csv")));
  // Resuming with another sweep's options is refused.
  const auto other = swell(options + " --seeds 7 --out " + path("cut") + " --resume");
  EXPECT_EQ(other.exit_code, 2) << other.output;
}

}  // namespace
