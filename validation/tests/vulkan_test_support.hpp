#pragma once
// Vulkan tests: a test that finds no Vulkan device skips, saying why — unless
// SWELL_REQUIRE_VULKAN=1 (scripts/test sets it, with lavapipe installed), where a missing device
// is a failure, so that a green CI means the Vulkan tests ran.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace swell::test {

inline bool vulkan_required() {
  const char* value = std::getenv("SWELL_REQUIRE_VULKAN");
  return value && std::string(value) == "1";
}

}  // namespace swell::test

// Skips the test with `reason` (fails it where SWELL_REQUIRE_VULKAN=1).
#define SWELL_SKIP_WITHOUT_VULKAN(reason)                                              \
  do {                                                                                 \
    if (swell::test::vulkan_required()) FAIL() << "SWELL_REQUIRE_VULKAN=1: " << (reason); \
    GTEST_SKIP() << (reason);                                                          \
  } while (0)
