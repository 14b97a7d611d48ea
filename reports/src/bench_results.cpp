#include "swell/reports/bench_results.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <sstream>

#include "swell/reference/errors.hpp"

namespace swell::reports {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, separator);) parts.push_back(part);
  return parts;
}

bool parse_long(const std::string& text, long& value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
  try {
    value = std::stol(text);
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

bool is_precision(const std::string& part) {
  return part == "fp32" || part == "fp64" || part == "fp80";
}

double seconds_per_unit(const std::string& unit) {
  if (unit == "ns") return 1e-9;
  if (unit == "us") return 1e-6;
  if (unit == "ms") return 1e-3;
  if (unit == "s") return 1.0;
  throw InvalidInput("benchmark JSON: unknown time_unit '" + unit + "'");
}

}  // namespace

double BenchmarkName::points() const {
  if (family.rfind("lattice", 0) == 0) return double(size);
  const double square = double(size) * double(size);
  return family.rfind("gate", 0) == 0 ? square * double(frames) : square;
}

// The parts Google Benchmark appends to a name for its own settings ("min_warmup_time:0.050",
// "repeats:3", "real_time", …): not part of swell's scheme. A backend's options use '='
// ("fftw:threads=2"), these ':' alone.
bool is_benchmark_setting(const std::string& part) {
  if (part == "real_time" || part == "process_time" || part == "manual_time") return true;
  static const std::vector<std::string> keys = {"min_warmup_time", "min_time", "iterations",
                                                "repeats", "threads"};
  const auto colon = part.find(':');
  return colon != std::string::npos && part.find('=') == std::string::npos &&
         std::find(keys.begin(), keys.end(), part.substr(0, colon)) != keys.end();
}

BenchmarkName parse_benchmark_name(const std::string& run_name) {
  auto all = split(run_name, '/');
  BenchmarkName name;
  std::vector<std::string> parts;
  for (const auto& part : all) {
    if (part == "real_time") name.real_time = true;
    if (!is_benchmark_setting(part)) parts.push_back(part);
  }
  const auto refuse = [&](const std::string& why) {
    return InvalidInput(fmt::format("benchmark '{}': {} (bench/*.cpp name the schemes)", run_name, why));
  };
  if (parts.size() < 3) throw refuse("too few parts for any of swell's naming schemes");
  name.family = parts[0];
  // gate/<N>/<frames>: one surface; gate_cascades/<N>/<frames>: a set of three cascades of N².
  if (name.family == "gate" || name.family == "gate_cascades") {
    name.suite = "gate";
    if (parts.size() != 3 || !parse_long(parts[1], name.size) || !parse_long(parts[2], name.frames)) {
      throw refuse("expected " + name.family + "/<N>/<frames>");
    }
    return name;
  }
  if (name.family == "fft2d") {
    name.suite = "fft";
    if (parts.size() != 5) throw refuse("expected fft2d/<kind>/<impl>/<precision>/<N>");
    name.kind = parts[1];
    parts.erase(parts.begin() + 1);
  } else if (name.family.rfind("frame", 0) == 0) {
    name.suite = "frame";
  } else if (name.family.rfind("lattice", 0) == 0) {
    name.suite = "lattice";
  } else {
    throw refuse("unknown family '" + name.family + "'");
  }
  // <family>/<impl>/<precision>[/<kind>]/<N>
  if (parts.size() < 4 || !is_precision(parts[2]) || !parse_long(parts.back(), name.size)) {
    throw refuse("expected " + name.family + "/<impl>/<precision>/…/<N>");
  }
  name.impl = parts[1];
  name.precision = parts[2];
  if (parts.size() == 5) name.kind = parts[3];
  if (parts.size() > 5) throw refuse("too many parts");
  return name;
}

BenchmarkFile load_benchmark_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InvalidInput("cannot read benchmark results " + file.string());
  // Google Benchmark writes a non-finite statistic as a bare NaN or inf (the coefficient of
  // variation of a counter that is 0 in every repetition), which JSON has no word for: null.
  const std::string raw((std::istreambuf_iterator<char>(in)), {});
  static const std::regex non_finite(R"((:\s*)-?(NaN|nan|inf|Infinity)\b)");
  const std::string text = std::regex_replace(raw, non_finite, "$1null");
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw InvalidInput("benchmark results " + file.string() + " are not JSON: " + e.what());
  }
  if (!document.is_object() || !document.contains("benchmarks") || !document["benchmarks"].is_array()) {
    throw InvalidInput("benchmark results " + file.string() +
                       " hold no \"benchmarks\" array (is it Google Benchmark's --benchmark_out?)");
  }
  BenchmarkFile out;
  out.context = document.value("context", nlohmann::json::object());
  std::map<std::string, std::size_t> index;
  for (const auto& row : document["benchmarks"]) {
    if (row.value("run_type", "iteration") != "iteration") continue;
    const std::string run_name = row.value("run_name", row.value("name", ""));
    if (run_name.empty()) continue;
    auto found = index.find(run_name);
    if (found == index.end()) {
      BenchmarkRun run;
      run.run_name = run_name;
      run.name = parse_benchmark_name(run_name);
      found = index.emplace(run_name, out.runs.size()).first;
      out.runs.push_back(std::move(run));
    }
    BenchmarkRun& run = out.runs[found->second];
    if (row.value("error_occurred", false) || row.contains("error_message")) {
      run.error = row.value("error_message", std::string("skipped"));
      continue;
    }
    const double unit = seconds_per_unit(row.value("time_unit", std::string("ns")));
    const double time = row.value(run.name.real_time ? "real_time" : "cpu_time", std::numeric_limits<double>::quiet_NaN());
    if (!std::isfinite(time)) {
      throw InvalidInput(fmt::format("benchmark results {}: {} has no finite time", file.string(), run_name));
    }
    run.seconds.push_back(time * unit);
    run.label = row.value("label", std::string());
    // Counters are the numeric fields Google Benchmark does not define itself.
    static const std::vector<std::string> own = {
        "real_time", "cpu_time", "iterations", "repetitions", "repetition_index", "threads",
        "family_index", "per_family_instance_index"};
    for (const auto& [key, value] : row.items()) {
      if (!value.is_number() || std::find(own.begin(), own.end(), key) != own.end()) continue;
      run.counters[key].push_back(value.get<double>());
    }
  }
  return out;
}

std::vector<BenchmarkRun> merge_runs(const std::vector<BenchmarkFile>& files) {
  std::vector<BenchmarkRun> merged;
  std::map<std::string, std::size_t> index;
  for (const auto& file : files) {
    for (const auto& run : file.runs) {
      const auto found = index.find(run.run_name);
      if (found == index.end()) {
        index.emplace(run.run_name, merged.size());
        merged.push_back(run);
        continue;
      }
      BenchmarkRun& into = merged[found->second];
      into.seconds.insert(into.seconds.end(), run.seconds.begin(), run.seconds.end());
      for (const auto& [key, values] : run.counters) {
        auto& target = into.counters[key];
        target.insert(target.end(), values.begin(), values.end());
      }
      if (into.error.empty()) into.error = run.error;
    }
  }
  return merged;
}

}  // namespace swell::reports
