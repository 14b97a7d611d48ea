// `swell bench`: runs swell's Google Benchmark suites (build/bench/swell_<suite>_bench) over the
// chosen backends, sizes and precisions, and keeps in one folder what `swell report` needs: the
// raw benchmark JSON, each fft backend's accuracy at each size against the long-double oracle,
// and the machine context (reports/README.md).
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/chrono.h>
#include <fmt/format.h>

#ifdef SWELL_HAVE_VULKAN
#include <vulkan/vulkan.h>
#endif

#include "commands.hpp"
#include "progress.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reports/bench_results.hpp"
#include "swell/reports/machine_context.hpp"
#include "swell/reports/performance_report.hpp"
#include "swell/validation/checks/transform_checks.hpp"

namespace swell::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::vector<std::string> kSuites = {"fft", "frame", "lattice", "gate"};

struct BenchOptions {
  std::string suite = "fft";
  std::string impls;       // comma separated; empty: each suite's default backends
  std::string sizes;       // "a:b" or "a" (n of n × n, √N for lattices, the gate's N)
  std::string precisions;  // comma separated; empty: all
  int repetitions = reports::kRecommendedRepetitions;
  double min_time = 0;     // s; 0: Google Benchmark's default
  std::string out;
  std::string bench_dir;   // where swell_<suite>_bench live
  std::string interleave;  // another build's bench directory: A B A B… rounds
  std::string other_out;
  bool accuracy = true;
  std::string progress = "auto";
};

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

fs::path own_directory() {
  std::error_code error;
  const auto exe = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::current_path() : exe.parent_path();
}

fs::path bench_directory(const std::string& given) {
  if (!given.empty()) return given;
  if (const char* env = std::getenv("SWELL_BENCH_DIR"); env && *env) return env;
  return own_directory().parent_path() / "bench";  // build/cli/swell → build/bench
}

// A child process with its stdout read line by line; its stderr goes to `stderr_file` (Google
// Benchmark prints its context there) or, when that is empty, passes through.
int run_child(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
              const std::function<void(const std::string&)>& on_line,
              const std::string& stderr_file = "") {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw InternalError("pipe failed");
  const pid_t child = fork();
  if (child < 0) throw InternalError("fork failed");
  if (child == 0) {
    dup2(pipe_fds[1], STDOUT_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    if (!stderr_file.empty()) {
      const int fd = open(stderr_file.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (fd >= 0) {
        dup2(fd, STDERR_FILENO);
        close(fd);
      }
    }
    for (const auto& [key, value] : env) setenv(key.c_str(), value.c_str(), 1);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    std::fprintf(stderr, "swell bench: cannot run %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  close(pipe_fds[1]);
  FILE* stream = fdopen(pipe_fds[0], "r");
  std::string line;
  for (int c; (c = std::fgetc(stream)) != EOF;) {
    if (c == '\n') {
      on_line(line);
      line.clear();
    } else {
      line += char(c);
    }
  }
  if (!line.empty()) on_line(line);
  std::fclose(stream);
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string regex_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (std::strchr("\\^$.|?*+()[]{}", c)) out += '\\';
    out += c;
  }
  return out;
}

struct Selection {
  std::string suite;
  fs::path binary;
  std::vector<std::string> names;  // run names as --benchmark_list_tests prints them
};

// Whether a listed benchmark falls in the chosen impls, precisions and sizes.
bool selected(const reports::BenchmarkName& name, const BenchOptions& o, long size_lo, long size_hi) {
  const auto impls = split_list(o.impls);
  if (!impls.empty() && !name.impl.empty() &&
      std::find(impls.begin(), impls.end(), name.impl) == impls.end()) {
    return false;
  }
  const auto precisions = split_list(o.precisions);
  if (!precisions.empty() && !name.precision.empty() &&
      std::find(precisions.begin(), precisions.end(), name.precision) == precisions.end()) {
    return false;
  }
  // Sizes bound n of an n × n transform or frame; a lattice of N points counts as √N.
  const double side = name.family.rfind("lattice", 0) == 0 ? std::sqrt(double(name.size)) : double(name.size);
  return side >= double(size_lo) - 1e-9 && side <= double(size_hi) + 1e-9;
}

std::map<std::string, std::string> child_environment(const BenchOptions& o) {
  std::map<std::string, std::string> env;
  if (!o.impls.empty()) {
    // vkfft (fft_bench's anchor) and copy (its roofline) are not backends: the suite registers
    // them on its own.
    std::string list;
    for (const auto& impl : split_list(o.impls)) {
      if (impl != "vkfft" && impl != "copy") list += (list.empty() ? "" : ",") + impl;
    }
    if (!list.empty()) env["SWELL_BENCH_IMPLS"] = list;
  }
  return env;
}

Selection select_suite(const std::string& suite, const fs::path& dir, const BenchOptions& o,
                       long size_lo, long size_hi) {
  Selection s;
  s.suite = suite;
  s.binary = dir / ("swell_" + suite + "_bench");
  if (access(s.binary.c_str(), X_OK) != 0) {
    throw InvalidInput(fmt::format("no benchmark binary {} (build with SWELL_BUILD_BENCHMARKS=ON, or "
                                   "point --bench-dir or SWELL_BENCH_DIR at build/bench)",
                                   s.binary.string()));
  }
  std::vector<std::string> listed;
  const int status = run_child({s.binary.string(), "--benchmark_list_tests=true"}, child_environment(o),
                               [&](const std::string& line) {
                                 if (!line.empty()) listed.push_back(line);
                               });
  if (status != 0) throw InvalidInput(fmt::format("{} --benchmark_list_tests failed (exit {})", s.binary.string(), status));
  for (const auto& name : listed) {
    reports::BenchmarkName parsed;
    try {
      parsed = reports::parse_benchmark_name(name);
    } catch (const InvalidInput&) {
      continue;  // a benchmark outside swell's schemes is not selectable by these options
    }
    if (selected(parsed, o, size_lo, size_hi)) s.names.push_back(name);
  }
  return s;
}

std::string filter_for(const Selection& s) {
  std::string regex = "^(";
  for (std::size_t i = 0; i < s.names.size(); ++i) regex += (i ? "|" : "") + regex_escape(s.names[i]);
  return regex + ")$";
}

// Runs one suite's selection once, writing Google Benchmark's JSON to `out`.
int run_suite(const Selection& s, const fs::path& binary, const fs::path& out, int repetitions,
              const BenchOptions& o, Progress& progress) {
  std::vector<std::string> argv = {binary.string(), "--benchmark_filter=" + filter_for(s),
                                   fmt::format("--benchmark_repetitions={}", repetitions),
                                   "--benchmark_out=" + out.string(), "--benchmark_out_format=json",
                                   "--benchmark_format=console", "--benchmark_color=false"};
  if (o.min_time > 0) argv.push_back(fmt::format("--benchmark_min_time={}", o.min_time));
  const std::set<std::string> names(s.names.begin(), s.names.end());
  const std::string log = out.string() + ".stderr.log";
  const int status = run_child(argv, child_environment(o), [&](const std::string& line) {
    const std::string first = line.substr(0, line.find(' '));
    if (names.count(first)) progress.step(s.suite + " " + first);
  }, log);
  if (status != 0) {
    std::ifstream in(log);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    std::cerr << "\n" << binary.string() << " said (" << log << "):\n"
              << (text.size() > 4000 ? text.substr(text.size() - 4000) : text) << "\n";
  }
  return status;
}

nlohmann::json measure_accuracy(const Selection& fft, Progress& progress) {
  nlohmann::json rows = nlohmann::json::array();
  std::set<std::tuple<std::string, std::string, std::string, long>> done;
  for (const auto& name : fft.names) {
    const auto n = reports::parse_benchmark_name(name);
    if (n.impl == "vkfft" || n.impl == "copy" || !done.insert({n.impl, n.precision, n.kind, n.size}).second) {
      continue;
    }
    nlohmann::json row = {{"impl", n.impl}, {"precision", n.precision}, {"kind", n.kind}, {"n", n.size}};
    try {
      const auto backend = impls::make_backend(n.impl);
      if (!backend->capabilities().exact) {
        row["note"] = "not an exact transform (null copies)";
      } else {
        impls::TransformSpec spec;
        spec.nx = spec.ny = int(n.size);
        spec.kind = n.kind == "c2r" ? impls::Kind::c2r : impls::Kind::c2c;
        spec.direction = impls::Direction::inverse;
        spec.precision = impls::precision_from_string(n.precision);
        const auto a = validation::measure_transform_accuracy(*backend, spec);
        row["rel_l2"] = a.rel_l2;
        row["rel_linf"] = a.rel_linf;
        row["bound"] = a.bound;
        row["oracle"] = a.oracle;
        row["pass"] = a.pass;
      }
    } catch (const std::exception& e) {
      row["note"] = e.what();
    }
    rows.push_back(row);
    progress.step("accuracy " + name);
  }
  return {{"transforms", rows},
          {"method", "seeded random input (uniform in [−1, 1)), relative L2 and L∞ errors against "
                     "the long-double oracle, bound c·ε·log2 N (validation/transform_checks.hpp)"}};
}

std::string vulkan_loader_version() {
#ifdef SWELL_HAVE_VULKAN
  std::uint32_t version = 0;
  if (vkEnumerateInstanceVersion(&version) != VK_SUCCESS) return "unknown (vkEnumerateInstanceVersion failed)";
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                     VK_API_VERSION_PATCH(version));
#else
  return "not built (SWELL_WITH_VULKAN=OFF or no Vulkan at configure time)";
#endif
}

void write_file(const fs::path& file, const nlohmann::json& document) {
  std::ofstream out(file);
  out << document.dump(2) << "\n";
  if (!out) throw InvalidInput("cannot write " + file.string());
}

int run_bench(const BenchOptions& o) {
  // ---- the options, all checked before any work
  std::vector<std::string> suites;
  if (o.suite == "all") {
    suites = kSuites;
  } else if (std::find(kSuites.begin(), kSuites.end(), o.suite) != kSuites.end()) {
    suites = {o.suite};
  } else {
    throw InvalidInput("--suite '" + o.suite + "': valid are fft, frame, lattice, gate, all");
  }
  long size_lo = 1, size_hi = 1L << 30;
  if (!o.sizes.empty()) {
    const auto colon = o.sizes.find(':');
    try {
      std::size_t used = 0;
      size_lo = std::stol(o.sizes.substr(0, colon), &used);
      if (used != o.sizes.substr(0, colon).size()) throw std::invalid_argument("");
      size_hi = size_lo;
      if (colon != std::string::npos) {
        const std::string high = o.sizes.substr(colon + 1);
        size_hi = std::stol(high, &used);
        if (used != high.size()) throw std::invalid_argument("");
      }
    } catch (const std::exception&) {
      throw InvalidInput("--sizes '" + o.sizes + "': expected LOW:HIGH or N, whole numbers (e.g. 64:4096)");
    }
    if (size_lo < 1 || size_hi < size_lo) {
      throw InvalidInput("--sizes '" + o.sizes + "': need 1 ≤ LOW ≤ HIGH");
    }
  }
  for (const auto& p : split_list(o.precisions)) {
    if (p != "fp32" && p != "fp64") throw InvalidInput("--precision '" + p + "': valid are fp32, fp64");
  }
  for (const auto& impl : split_list(o.impls)) {
    if (impl == "vkfft" || impl == "copy") continue;
    try {
      impls::make_backend(impl);
    } catch (const impls::UnsupportedTransform&) {
      // a backend that cannot start here (no Vulkan device): its benchmarks skip with why
    }
  }
  if (o.repetitions < 1) throw InvalidInput(fmt::format("--repetitions {}: need at least 1", o.repetitions));
  if (o.interleave.empty() != o.other_out.empty()) {
    throw InvalidInput("--interleave OTHER_BENCH_DIR and --other-out DIR go together");
  }
  if (o.repetitions < reports::kRecommendedRepetitions) {
    std::cerr << fmt::format("swell bench: warning: {} repetitions; comparisons (swell report --against) "
                             "trust the U test from {} on\n", o.repetitions, reports::kRecommendedRepetitions);
  }
  const fs::path dir = bench_directory(o.bench_dir);
  const fs::path out = o.out.empty()
                           ? fs::path(fmt::format("swell-bench-{:%Y%m%d-%H%M%S}",
                                                  fmt::localtime(std::time(nullptr))))
                           : fs::path(o.out);
  const fs::path other_dir = o.interleave;
  const fs::path other_out = o.other_out;

  std::vector<Selection> selections;
  for (const auto& suite : suites) {
    auto s = select_suite(suite, dir, o, size_lo, size_hi);
    if (!o.interleave.empty()) {
      const fs::path other = other_dir / ("swell_" + suite + "_bench");
      if (access(other.c_str(), X_OK) != 0) throw InvalidInput("--interleave: no benchmark binary " + other.string());
    }
    if (s.names.empty()) {
      if (o.suite != "all") {
        throw InvalidInput(fmt::format("no {} benchmark matches --impl '{}' --precision '{}' --sizes '{}' "
                                       "(swell_{}_bench --benchmark_list_tests lists them)",
                                       suite, o.impls, o.precisions, o.sizes, suite));
      }
      std::cerr << "swell bench: no " << suite << " benchmark matches; skipping the suite\n";
      continue;
    }
    selections.push_back(std::move(s));
  }
  if (selections.empty()) throw InvalidInput("no benchmark matches the options in any suite");

  for (const auto& folder : {out, other_out}) {
    if (folder.empty()) continue;
    std::error_code error;
    fs::create_directories(folder / "bench", error);
    if (error) throw InvalidInput("cannot create " + (folder / "bench").string() + ": " + error.message());
  }

  // ---- the runs
  long total = 0;
  for (const auto& s : selections) {
    total += long(s.names.size()) * o.repetitions * (o.interleave.empty() ? 1 : 2);
    if (s.suite == "fft" && o.accuracy) total += long(s.names.size());
  }
  const std::string started = fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::time(nullptr)));
  const nlohmann::json context = reports::machine_context(vulkan_loader_version(), vulkan_device_line());
  Progress progress("swell bench", o.progress, total);
  int failures = 0;
  for (const auto& s : selections) {
    if (o.interleave.empty()) {
      const int status = run_suite(s, s.binary, out / "bench" / (s.suite + ".json"), o.repetitions, o, progress);
      if (status != 0) {
        ++failures;
        std::cerr << fmt::format("\nswell bench: {} exited {} (a benchmark failed; its row says why)\n",
                                 s.binary.string(), status);
      }
    } else {
      // A B A B…: one repetition of each build in turn, so that a drift of the machine's speed
      // falls on both alike.
      for (int round = 1; round <= o.repetitions; ++round) {
        const std::string file = fmt::format("{}.round{:04}.json", s.suite, round);
        failures += run_suite(s, s.binary, out / "bench" / file, 1, o, progress) != 0;
        failures += run_suite(s, other_dir / ("swell_" + s.suite + "_bench"), other_out / "bench" / file, 1,
                              o, progress) != 0;
      }
    }
    if (s.suite == "fft" && o.accuracy) write_file(out / "accuracy.json", measure_accuracy(s, progress));
  }
  progress.finish();

  nlohmann::json run = {{"started", started},
                        {"finished", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::time(nullptr)))},
                        {"suites", suites}, {"impls", o.impls.empty() ? "each suite's default" : o.impls},
                        {"sizes", o.sizes.empty() ? "all" : o.sizes},
                        {"precisions", o.precisions.empty() ? "all" : o.precisions},
                        {"repetitions", o.repetitions}, {"min_time", o.min_time},
                        {"interleaved_with", o.interleave}, {"bench_dir", fs::absolute(dir).string()}};
  for (const auto& s : selections) run["benchmarks"][s.suite] = s.names;
  write_file(out / "run.json", run);
  write_file(out / "context.json", context);
  if (!other_out.empty()) {
    run["bench_dir"] = fs::absolute(other_dir).string();
    run["interleaved_with"] = fs::absolute(dir).string();
    write_file(other_out / "run.json", run);
    write_file(other_out / "context.json", context);
  }
  std::cout << fmt::format("swell bench: results in {}{}; next: swell report {}\n", out.string(),
                           other_out.empty() ? "" : " and " + other_out.string(), out.string());
  return failures ? 1 : 0;
}

}  // namespace

Action add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  app.add_option("--suite", o->suite, "fft | frame | lattice | gate | all")->capture_default_str();
  app.add_option("--impl", o->impls, "backends, comma separated (fftw,radix2,…; vkfft: fft's anchor; copy: the roofline, a copy of a 2-D transform's bytes); default each suite's");
  app.add_option("--sizes", o->sizes, "LOW:HIGH or N: n of n × n transforms and frames, √N of lattices, the gate's N");
  app.add_option("--precision", o->precisions, "fp32,fp64 (default both)");
  app.add_option("--repetitions", o->repetitions, "repetitions of each benchmark (9: what compare.py's U test trusts)")->capture_default_str();
  app.add_option("--min-time", o->min_time, "seconds each repetition runs at least (Google Benchmark's default 0.5)");
  app.add_option("--out", o->out, "results folder (default swell-bench-<date>-<time>)");
  app.add_option("--bench-dir", o->bench_dir, "where swell_<suite>_bench are (default: build/bench beside this swell, or SWELL_BENCH_DIR)");
  app.add_option("--interleave", o->interleave, "another build's bench folder: run A B A B…, one repetition each, for a fair comparison");
  app.add_option("--other-out", o->other_out, "results folder of the --interleave build");
  app.add_flag("--no-accuracy{false}", o->accuracy, "skip the fft suite's accuracy measurement");
  app.add_option("--progress", o->progress, "auto | bar | plain | none")->check(CLI::IsMember({"auto", "bar", "plain", "none"}));
  return [o] { return run_bench(*o); };
}

}  // namespace swell::cli
