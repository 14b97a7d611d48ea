#pragma once
// Helpers for tests that write files and expect refusals: a scratch directory of the running
// test's own, and an InvalidInput whose message must name what was wrong.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "swell/reference/errors.hpp"

namespace swell::test {

// A directory under the temporary folder named for `prefix`, the process and the running test,
// removed with everything in it at the end.
struct Scratch {
  std::filesystem::path dir;
  explicit Scratch(const std::string& prefix) {
    dir = std::filesystem::temp_directory_path() /
          (prefix + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  // Writes `text` to dir/name and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
};

// Expects InvalidInput whose message holds every one of `parts`.
template <typename F>
void expect_invalid(F&& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    for (const auto& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message lacks '" << part << "': " << e.what();
    }
  }
}

}  // namespace swell::test
