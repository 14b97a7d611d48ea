// A property test of the command line: a seeded generator draws cases — sizes,
// patch lengths, every spectrum model with parameters over many decades, every spreading,
// depths from centimetres to infinity, choppiness, t0, dt, loop periods, precisions, backends
// and formats — and runs `swell synth` then `swell gate` on each. The properties:
//
//   synth exit 0  ⇒ every field of every frame file is finite (the reader refuses non-finite
//                   values), and swell's own gate accepts the case (exit 0 or 1, never 2) and
//                   passes every exact check; statistical failures stay within the binomial
//                   bound of the gate's family-wise α over the gated runs;
//   synth exit 2  ⇒ one "swell: error: …" message that says what was wrong (no bare
//                   std::exception text, no internal error);
//   anything else — exit 1 or 3, a signal, a sanitizer report, a command past its time limit —
//                   fails, printing the seed and the command line that reproduces it.
//
// SWELL_PROPERTY_CASES (default 40) and SWELL_PROPERTY_SEED (default 20261201) choose the run,
// the same cases on every run of the suite. The soak run (ctest label soak, scripts/test --full)
// draws 400 cases from a fresh first seed each time (SWELL_PROPERTY_LONG_SEED fixes it) and
// prints it; every problem found prints the one command that replays its case.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <boost/math/distributions/binomial.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

// A small portable generator (splitmix64): the same draws on every compiler and library,
// unlike std::uniform_real_distribution.
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : state_(seed) {}
  std::uint64_t bits() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform(double lo = 0, double hi = 1) { return lo + (hi - lo) * double(bits() >> 11) * 0x1p-53; }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  bool chance(double p) { return uniform() < p; }
  template <typename T>
  const T& pick(const std::vector<T>& items) { return items[bits() % items.size()]; }

 private:
  std::uint64_t state_;
};

std::string number(double x) { return fmt::format("{:.6g}", x); }

struct DrawnCase {
  std::string arguments;  // everything after `swell synth`, less --out
  std::string format;
};

// One case. Parameters are drawn over the ranges users give and, one time in ten per
// parameter, over many decades beyond them, where swell must refuse with a message.
DrawnCase draw_case(std::uint64_t seed) {
  Draw d(seed);
  std::vector<std::string> a;
  auto add = [&](const std::string& flag, const std::string& value) { a.push_back(flag + " " + value); };
  auto wide = [&](double lo, double hi, double wide_lo, double wide_hi) {
    return d.chance(0.1) ? d.log_uniform(wide_lo, wide_hi) : d.log_uniform(lo, hi);
  };

  const std::string model =
      d.pick<std::string>({"phillips", "pierson-moskowitz", "bretschneider", "jonswap", "tma",
                           "gaussian", "ochi-hubble", "torsethaugen"});
  add("--model", model);
  if (model == "phillips") {
    add("--amplitude", number(wide(1e-4, 10, 1e-30, 1e30)));
    add("--wind-speed", number(wide(1, 40, 1e-3, 1e4)));
    add("--exponent", d.pick<std::string>({"2", "4", "6"}));
    if (d.chance(0.4)) add("--small-wave-cutoff", number(wide(1e-3, 1, 1e-8, 1e4)));
    if (d.chance(0.3)) add("--against-wind-factor", number(d.uniform()));
  } else if (model == "pierson-moskowitz") {
    add("--u19-5", number(wide(2, 35, 1e-3, 1e4)));
  } else if (model == "gaussian") {
    add("--hs", number(wide(0.05, 15, 1e-12, 1e6)));
    add("--tp", number(wide(1.5, 25, 1e-2, 1e4)));
    add("--sigma", number(wide(0.01, 0.5, 1e-6, 1e3)));
  } else if (model == "ochi-hubble") {
    for (const char* part : {"1", "2"}) {
      add(std::string("--hs") + part, number(wide(0.05, 10, 1e-12, 1e6)));
      add(std::string("--tp") + part, number(wide(2, 25, 1e-2, 1e4)));
      add(std::string("--lambda") + part, number(wide(0.5, 8, 1e-3, 1e3)));
    }
  } else if (model == "torsethaugen") {
    add("--hs", number(wide(0.5, 15, 1e-12, 1e6)));
    add("--tp", number(wide(3, 25, 1e-2, 1e4)));
  } else {
    const bool jonswap_like = model != "bretschneider";
    const double form = d.uniform();
    if (model == "jonswap" && form < 0.15) {
      add("--alpha", number(wide(1e-3, 3e-2, 1e-12, 10)));
      add("--omega-p", number(wide(0.3, 3, 1e-4, 1e3)));
    } else if (model == "jonswap" && form < 0.3) {
      add("--u10", number(wide(3, 30, 1e-2, 1e3)));
      add("--fetch", number(wide(1e3, 5e5, 1, 1e9)));
    } else {
      add("--hs", number(wide(0.05, 15, 1e-12, 1e6)));
      add("--tp", number(wide(1.5, 25, 1e-2, 1e4)));
      if (model == "jonswap" && d.chance(0.2)) add("--normalization", "dnv");
    }
    if (jonswap_like) {
      add("--gamma", number(d.chance(0.1) ? d.log_uniform(1, 1e3) : d.uniform(1, 7)));
      if (d.chance(0.2)) add("--sigma-a", number(d.uniform(0.02, 0.2)));
      if (d.chance(0.2)) add("--sigma-b", number(d.uniform(0.02, 0.2)));
    }
    if (model == "tma" && d.chance(0.3)) add("--depth-factor", "thompson-vincent");
  }
  if (model != "phillips") {
    const std::string spreading = d.pick<std::string>(
        {"cos2s", "mitsuyasu", "hasselmann", "donelan-banner", "cos-power", "horvath"});
    add("--spreading", spreading);
    if (spreading == "cos2s") add("--s", number(wide(0.5, 80, 1e-3, 1e4)));
    if (spreading == "mitsuyasu") add("--s-max", number(wide(2, 80, 1e-2, 1e4)));
    if ((spreading == "hasselmann" || spreading == "horvath") && d.chance(0.5)) {
      add("--wave-age", number(d.uniform(0.8, 5)));
    }
    if (spreading == "cos-power") {
      add("--p", number(wide(1, 30, 1e-2, 1e3)));
      if (d.chance(0.2)) add("--one-sided", "yes");
    }
    if (spreading == "horvath") {
      if (d.chance(0.5)) add("--swell", number(d.uniform(0, 1.5)));
      if (d.chance(0.5)) add("--spread-blend", number(d.uniform()));
    }
  }
  if (model == "tma" || d.chance(0.5)) {
    add("--depth", number(d.log_uniform(0.01, 1e4)));  // centimetres to 10 km
  } else if (d.chance(0.3)) {
    add("--depth", "inf");
  }
  if (d.chance(0.1)) add("--gravity", number(d.uniform(1, 30)));
  add("--wind-dir", number(d.uniform(-180, 360)));

  const std::vector<int> sizes = {16, 32, 64, 128};
  const std::vector<int> odd_sizes = {12, 24, 48, 50, 96};
  const int nx = d.chance(0.8) ? d.pick(sizes) : d.pick(odd_sizes);
  const int ny = d.chance(0.7) ? nx : d.pick(sizes);
  add("--n", std::to_string(nx));
  if (ny != nx) add("--ny", std::to_string(ny));
  const double length = d.log_uniform(0.1, 1e4);
  add("--length", number(length));
  if (d.chance(0.3)) add("--length-y", number(length * d.log_uniform(0.5, 2)));

  const double chop = d.uniform();
  if (chop < 0.55) add("--choppiness", number(d.uniform(0, 2.5)));
  else if (chop < 0.7) add("--choppiness", number(-d.uniform(0, 2)));
  else if (chop < 0.8) add("--choppiness", "0");
  else if (chop < 0.95) add("--choppiness", number((d.chance(0.5) ? 1 : -1) * d.log_uniform(1e-30, 1e30)));

  const double start = d.uniform();
  if (start < 0.3) add("--t0", number(d.log_uniform(1, 1e6)));
  else if (start < 0.4) add("--t0", number((d.chance(0.8) ? 1 : -1) * d.log_uniform(1e6, 1e18)));
  const int frames = d.chance(0.3) ? 1 : 2 + int(d.bits() % 4);
  if (frames > 1) {
    add("--frames", std::to_string(frames));
    add("--dt", number(d.log_uniform(0.05, 5)));
  }
  if (d.chance(0.15)) add("--loop-period", number(d.uniform(20, 200)));
  add("--seed", std::to_string(d.bits() % 1000000));

  add("--precision", d.chance(0.5) ? "fp32" : "fp64");
  const bool small = nx * ny <= 64 * 64;
  const double backend = d.uniform();
  add("--impl", backend < 0.5 ? "fftw" : backend < 0.85 || !small ? "radix2" : "naive");
  DrawnCase out;
  const double format = d.uniform();
  out.format = format < 0.4 ? "exr" : format < 0.7 ? "npy" : format < 0.85 ? "tiff" : "png";
  add("--format", out.format);
  if (out.format == "png") {
    const double range = d.log_uniform(0.1, 100);
    add("--value-range", fmt::format("{},{}", number(-range), number(range)));
  }
  for (const auto& part : a) out.arguments += (out.arguments.empty() ? "" : " ") + part;
  return out;
}

struct Tally {
  int cases = 0, accepted = 0, refused = 0, gate_passed = 0, gate_statistical_failures = 0;
  std::map<std::string, int> refusals;  // by the first words of the message
  std::vector<std::string> problems;    // each with its seed and command line
};

bool has_sanitizer_report(const std::string& output) {
  return output.find("AddressSanitizer") != std::string::npos ||
         output.find("runtime error:") != std::string::npos ||
         output.find("LeakSanitizer") != std::string::npos;
}

// What a refusal is about, from its message: the rule of reference/sampling_validity.hpp it
// applies, or the first words of any other message (numbers and paths dropped). Empty when the
// output has no "swell: error:" message.
std::string refusal_topic(const std::string& output) {
  const auto at = output.find("swell: error: ");
  if (at == std::string::npos) return "";
  const std::string message = output.substr(at + 14, output.find('\n', at) - at - 14);
  const std::vector<std::pair<std::string, std::string>> rules = {
      {"of the spectrum's m0", "energy: the grid carries < 1e-6 of m0"},
      {"cannot be evaluated", "energy: Ψ not finite on the grid"},
      {"[time]", "times: a phase beyond 2^50 rad"},
      {"values can hold", "range: a field's rms above the format's"},
      {"lose precision to underflow", "range: a field's rms below the format's"},
      {"needs about", "memory"},
      {"hides every wave vector", "png: quantization hides every wave vector"},
      {"outside the PNG", "png: a value outside --value-range"},
      {"powers of two", "backend: size not supported"},
  };
  for (const auto& [needle, topic] : rules) {
    if (message.find(needle) != std::string::npos) return topic;
  }
  std::istringstream words(message);
  std::string topic, word;
  for (int i = 0; i < 6 && words >> word; ++i) {
    if (word.find_first_of("0123456789/") != std::string::npos) continue;
    topic += (topic.empty() ? "" : " ") + word;
  }
  return topic.empty() ? "other" : topic;
}

// Seconds a command may take: the largest grid here is 128², a few frames, a naive DFT at
// 64²; 60 s is ten times the slowest seen, under sanitizers too.
constexpr int kCommandSeconds = 120;

// The command that runs the one drawn case `seed` again, as the suite's property test.
std::string replay_command(std::uint64_t seed) {
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  return fmt::format("SWELL_PROPERTY_SEED={} SWELL_PROPERTY_CASES=1 {} "
                     "--gtest_filter=CliProperty.SynthThenGateOnDrawnCases",
                     seed, error ? "swell_property_tests" : program.string());
}

void run_case(std::uint64_t seed, const fs::path& root, Tally& tally) {
  const DrawnCase c = draw_case(seed);
  const fs::path dir = root / fmt::format("case_{}", seed);
  fs::remove_all(dir);
  const std::string synth = c.arguments + " --out " + dir.string();
  const std::string reproduce = fmt::format("seed {}: swell synth {}\n  replay: {}", seed, synth,
                                            replay_command(seed));
  ++tally.cases;
  const auto made = test::swell(fmt::format("synth {}", synth), kCommandSeconds);
  if (has_sanitizer_report(made.output)) {
    tally.problems.push_back(reproduce + "\n  sanitizer report:\n" + made.output);
    return;
  }
  if (made.exit_code == 2) {
    ++tally.refused;
    const std::string topic = refusal_topic(made.output);
    if (topic.empty() || made.output.find("std::") != std::string::npos ||
        made.output.size() < 40) {
      tally.problems.push_back(reproduce + "\n  exit 2 without a message that says what was wrong:\n" +
                               made.output);
    } else {
      ++tally.refusals[topic];
    }
    fs::remove_all(dir);
    return;
  }
  if (made.exit_code != 0) {
    tally.problems.push_back(fmt::format("{}\n  synth exit {}{}:\n{}", reproduce, made.exit_code,
                                         made.exit_code == 124 ? " (past its time limit)" : "",
                                         made.output));
    return;
  }
  ++tally.accepted;
  // Every field of every frame is finite: the reader checks each value and refuses non-finite
  // ones, naming the file, the field and the sample.
  try {
    const auto case_file = validation::read_case_file(dir / "case.toml");
    (void)validation::read_frames(case_file);
  } catch (const std::exception& e) {
    tally.problems.push_back(reproduce + "\n  synth exit 0 but its frames do not read back: " + e.what());
    return;
  }
  const fs::path report = dir / "gate.json";
  const auto gate = test::swell(
      fmt::format("gate --case {} --json {}", (dir / "case.toml").string(), report.string()),
      kCommandSeconds);
  const std::string gate_line = fmt::format("  then: swell gate --case {}", (dir / "case.toml").string());
  if (has_sanitizer_report(gate.output) || (gate.exit_code != 0 && gate.exit_code != 1)) {
    tally.problems.push_back(fmt::format("{}\n{}\n  gate exit {}{}:\n{}", reproduce, gate_line,
                                         gate.exit_code,
                                         gate.exit_code == 2 ? " (refuses what synth accepted)" : "",
                                         gate.output));
    return;
  }
  if (gate.exit_code == 0) {
    ++tally.gate_passed;
    fs::remove_all(dir);
    return;
  }
  std::ifstream file(report);
  const auto json = nlohmann::json::parse(file, nullptr, false);
  if (json.is_discarded()) {
    tally.problems.push_back(reproduce + "\n" + gate_line + "\n  gate exit 1 without a JSON report");
    return;
  }
  std::string exact, statistical;
  for (const auto& check : json["checks"]) {
    if (check["pass"].get<bool>()) continue;
    const std::string line = fmt::format("    {}: {}", check["check"].get<std::string>(),
                                         check["reason"].get<std::string>());
    (check["alpha"].is_null() ? exact : statistical) += line + "\n";
  }
  if (!exact.empty()) {
    tally.problems.push_back(reproduce + "\n" + gate_line +
                             "\n  an exact check failed on swell's own frames:\n" + exact);
    return;
  }
  ++tally.gate_statistical_failures;
  std::cout << "statistical failure (counted against the bound): " << reproduce << "\n" << statistical;
  fs::remove_all(dir);
}

// The most statistical failures of `runs` independent gate runs at family-wise α that a right
// swell shows with probability ≥ 1 − kFalseAlarm: the smallest k with P(X > k) ≤ kFalseAlarm,
// X ~ Binomial(runs, α).
constexpr double kFalseAlarm = 1e-3;
int statistical_failure_bound(int runs, double alpha) {
  if (runs == 0) return 0;
  boost::math::binomial law(runs, alpha);
  int k = 0;
  while (k < runs && boost::math::cdf(boost::math::complement(law, k)) > kFalseAlarm) ++k;
  return k;
}

std::uint64_t environment_number(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  return text && *text ? std::strtoull(text, nullptr, 10) : fallback;
}

void run_property(std::uint64_t first_seed, int cases) {
  const fs::path root = fs::temp_directory_path() /
                        fmt::format("swell_property_{}_{}", first_seed, ::getpid());
  fs::create_directories(root);
  Tally tally;
  for (int i = 0; i < cases; ++i) run_case(first_seed + std::uint64_t(i), root, tally);
  const int gated = tally.gate_passed + tally.gate_statistical_failures;
  const double gate_alpha = 1e-3;  // swell gate's default family-wise α
  const int bound = statistical_failure_bound(gated, gate_alpha);
  std::cout << fmt::format(
      "property test, seeds {}…{}: {} cases; synth exit 0: {}, exit 2: {}; gate passed {}, "
      "statistical failures {} (bound {} at a false-alarm rate {:g} for {} runs at α = {:g}); "
      "problems {}\n",
      first_seed, first_seed + cases - 1, tally.cases, tally.accepted, tally.refused,
      tally.gate_passed, tally.gate_statistical_failures, bound, kFalseAlarm, gated, gate_alpha,
      tally.problems.size());
  std::cout << "refusals by topic:\n";
  for (const auto& [topic, count] : tally.refusals) std::cout << fmt::format("  {:4d}  {}\n", count, topic);
  for (const auto& problem : tally.problems) ADD_FAILURE() << problem;
  EXPECT_LE(tally.gate_statistical_failures, bound)
      << "more of swell's own surfaces fail its gate than its false-alarm rate allows";
  // The generator must exercise both outcomes, or the test proves nothing.
  EXPECT_GT(tally.accepted, cases / 5) << "too few drawn cases were accepted";
  EXPECT_GT(tally.refused, 0) << "no drawn case was refused";
  std::error_code ignored;
  if (tally.problems.empty()) fs::remove_all(root, ignored);
}

TEST(CliProperty, SynthThenGateOnDrawnCases) {
  run_property(environment_number("SWELL_PROPERTY_SEED", 20261201),
               int(environment_number("SWELL_PROPERTY_CASES", 40)));
}

// A first seed no earlier run is likely to have drawn: 400 cases from a random 48-bit number.
std::uint64_t fresh_seed() {
  std::random_device device;
  const std::uint64_t bits = (std::uint64_t(device()) << 32) ^ device() ^
                             std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
  return 1 + bits % (std::uint64_t(1) << 48);
}

TEST(CliPropertySoak, SynthThenGateOnFourHundredDrawnCases) {
  const std::uint64_t seed = environment_number("SWELL_PROPERTY_LONG_SEED", 0);
  const std::uint64_t first = seed ? seed : fresh_seed();
  std::cout << fmt::format("soak property test: first seed {} ({}; replay the whole run with "
                           "SWELL_PROPERTY_LONG_SEED={})\n",
                           first, seed ? "from SWELL_PROPERTY_LONG_SEED" : "fresh", first);
  run_property(first, 400);
}

}  // namespace
}  // namespace swell
