#pragma once
// Runs the built `swell` binary (SWELL_BINARY, set by CMake) and captures what it prints.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace swell::test {

struct Run {
  int exit_code;
  std::string output;  // stdout and stderr together
};

// With timeout_seconds > 0 the command runs under coreutils' timeout: past it, exit code 124.
inline Run swell(const std::string& arguments, int timeout_seconds = 0) {
  const std::string limit =
      timeout_seconds > 0 ? "timeout --kill-after=5 " + std::to_string(timeout_seconds) + " " : "";
  const std::string command = limit + std::string(SWELL_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  std::array<char, 4096> buffer;
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace swell::test
