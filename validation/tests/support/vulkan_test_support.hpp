#pragma once
// Vulkan tests: a test that finds no Vulkan device skips, saying why — unless
// SWELL_REQUIRE_VULKAN=1 (scripts/test sets it, with lavapipe installed), where a missing device
// is a failure, so that a green CI means the Vulkan tests ran. Validation-layer messages fail
// the test that caused them in binaries that link vulkan_validation_environment.cpp.
//
//   TEST(Foo, OnVulkan) {
//     SWELL_VULKAN_OR_SKIP();  // returns from the test when make_backend("vulkan") cannot start
//     …
//   }
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "swell/impls/transform.hpp"

namespace swell::test {

inline bool vulkan_required() {
  const char* value = std::getenv("SWELL_REQUIRE_VULKAN");
  return value && std::string(value) == "1";
}

// The backend `name` ("vulkan", "vulkan:device=1"), or nullptr when it cannot start here
// (UnsupportedTransform: no driver, no device; or a build without SWELL_WITH_VULKAN): the test
// is then marked skipped with the reason (failed under SWELL_REQUIRE_VULKAN=1), and the caller
// returns. Bad options (InvalidInput) propagate: they are the test's mistake, not the machine's.
inline std::unique_ptr<impls::Backend> vulkan_or_skip(const std::string& name = "vulkan") {
  std::string why;
#ifdef SWELL_HAVE_VULKAN
  try {
    return impls::make_backend(name);
  } catch (const impls::UnsupportedTransform& e) {
    why = e.what();
  }
#else
  why = "this build has no vulkan backend (configured with SWELL_WITH_VULKAN=OFF)";
#endif
  if (vulkan_required()) {
    ADD_FAILURE() << "SWELL_REQUIRE_VULKAN=1: " << why;
  } else {
    [&] { GTEST_SKIP() << why; }();
  }
  return nullptr;
}

}  // namespace swell::test

// Skips the test with `reason` (fails it where SWELL_REQUIRE_VULKAN=1).
#define SWELL_SKIP_WITHOUT_VULKAN(reason)                                              \
  do {                                                                                 \
    if (swell::test::vulkan_required()) FAIL() << "SWELL_REQUIRE_VULKAN=1: " << (reason); \
    GTEST_SKIP() << (reason);                                                          \
  } while (0)

// Returns from the test (skipped, or failed where required) when the vulkan backend cannot start.
#define SWELL_VULKAN_OR_SKIP()                      \
  do {                                              \
    if (!::swell::test::vulkan_or_skip()) return;   \
  } while (false)
