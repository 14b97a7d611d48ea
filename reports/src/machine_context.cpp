#include "swell/reports/machine_context.hpp"

#include <fftw3.h>
#include <sys/utsname.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/chrono.h>
#include <fmt/format.h>

namespace swell::reports {
namespace {

namespace fs = std::filesystem;

std::string read_first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  if (in) std::getline(in, line);
  return line;
}

std::string trimmed(std::string s) {
  const auto first = s.find_first_not_of(" \t\n");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\n");
  return s.substr(first, last - first + 1);
}

// "value" of the first "key : value" line of /proc/cpuinfo.
std::string cpuinfo(const std::string& key) {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    const auto colon = line.find(':');
    if (colon != std::string::npos && trimmed(line.substr(0, colon)) == key) {
      return trimmed(line.substr(colon + 1));
    }
  }
  return "";
}

// The first line a command prints, or "" (git may be missing or the tree not a repository).
std::string command_line(const std::string& command) {
  std::array<char, 512> buffer{};
  FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return "";
  std::string out;
  if (std::fgets(buffer.data(), buffer.size(), pipe)) out = buffer.data();
  pclose(pipe);
  return trimmed(out);
}

nlohmann::json or_unknown(const std::string& value, const std::string& why) {
  return value.empty() ? nlohmann::json("unknown (" + why + ")") : nlohmann::json(value);
}

nlohmann::json caches() {
  nlohmann::json list = nlohmann::json::array();
  const fs::path root = "/sys/devices/system/cpu/cpu0/cache";
  std::error_code error;
  for (int i = 0; i < 8; ++i) {
    const fs::path index = root / ("index" + std::to_string(i));
    if (!fs::exists(index, error)) break;
    list.push_back({{"level", read_first_line(index / "level")},
                    {"type", read_first_line(index / "type")},
                    {"size", read_first_line(index / "size")}});
  }
  return list;
}

nlohmann::json frequency_scaling() {
  const fs::path root = "/sys/devices/system/cpu/cpu0/cpufreq";
  const std::string why = "no " + root.string() + ": frequency scaling not exposed (a VM?)";
  return {{"governor", or_unknown(read_first_line(root / "scaling_governor"), why)},
          {"driver", or_unknown(read_first_line(root / "scaling_driver"), why)},
          {"min_khz", or_unknown(read_first_line(root / "cpuinfo_min_freq"), why)},
          {"max_khz", or_unknown(read_first_line(root / "cpuinfo_max_freq"), why)}};
}

double meminfo_bytes(const std::string& key) {
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key + ":", 0) != 0) continue;
    std::istringstream fields(line.substr(key.size() + 1));
    double kib = 0;
    fields >> kib;
    return kib * 1024;
  }
  return 0;
}

std::string os_name() {
  std::ifstream in("/etc/os-release");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("PRETTY_NAME=", 0) == 0) {
      std::string value = line.substr(12);
      if (value.size() >= 2 && value.front() == '"') value = value.substr(1, value.size() - 2);
      return value;
    }
  }
  return "";
}

}  // namespace

const std::vector<std::string>& machine_context_keys() {
  static const std::vector<std::string> keys = {"cpu", "memory", "os", "load_average",
                                                "build", "libraries", "date"};
  return keys;
}

nlohmann::json machine_context(const std::string& vulkan_loader, const std::string& vulkan_device) {
  nlohmann::json context;
  const std::string flags = cpuinfo("flags");
  std::string simd;
  for (const char* flag : {"sse2", "sse4_2", "avx", "avx2", "fma", "avx512f", "avx512dq",
                           "avx512bw", "avx512vl", "neon", "asimd", "sve"}) {
    if ((" " + flags + " ").find(std::string(" ") + flag + " ") != std::string::npos) {
      simd += (simd.empty() ? "" : " ") + std::string(flag);
    }
  }
  context["cpu"] = {{"model", or_unknown(cpuinfo("model name"), "no model name in /proc/cpuinfo")},
                    {"logical_cores", std::thread::hardware_concurrency()},
                    {"flags", or_unknown(flags, "no flags in /proc/cpuinfo")},
                    {"simd", simd},
                    {"caches", caches()},
                    {"mhz", or_unknown(cpuinfo("cpu MHz"), "no cpu MHz in /proc/cpuinfo")},
                    {"frequency_scaling", frequency_scaling()}};
  context["memory"] = {{"total_bytes", meminfo_bytes("MemTotal")},
                       {"available_bytes", meminfo_bytes("MemAvailable")}};
  utsname names{};
  uname(&names);
  context["os"] = {{"name", or_unknown(os_name(), "no /etc/os-release")},
                   {"kernel", std::string(names.sysname) + " " + names.release},
                   {"machine", names.machine}};
  std::array<double, 3> load{};
  if (getloadavg(load.data(), 3) != 3) load = {-1, -1, -1};
  context["load_average"] = load;
  const std::string source = SWELL_SOURCE_DIR;
  const std::string commit = command_line("git -C '" + source + "' rev-parse HEAD");
  const std::string status = command_line("git -C '" + source + "' status --porcelain --untracked-files=no");
  context["build"] = {{"compiler", std::string(__VERSION__)},
                      {"flags", std::string(SWELL_CXX_FLAGS)},
                      {"build_type", std::string(SWELL_BUILD_TYPE)},
                      {"git_commit", or_unknown(commit, "git or the repository is missing")},
                      {"git_dirty", !status.empty()}};
  context["libraries"] = {{"fftw", std::string(fftw_version)},
                          {"openimageio", std::string(SWELL_OPENIMAGEIO_VERSION)},
                          {"ceres", std::string(SWELL_CERES_VERSION)},
                          {"google_benchmark", std::string(SWELL_BENCHMARK_VERSION)},
                          {"vulkan_loader", vulkan_loader},
                          {"vulkan_device", vulkan_device}};
  const auto now = std::chrono::system_clock::now();
  context["date"] = fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(now)));
  return context;
}

}  // namespace swell::reports
