// Linked into every test binary that runs Vulkan: each message of the validation layers
// (SWELL_VULKAN_VALIDATION=1: VK_LAYER_KHRONOS_validation with synchronization validation,
// impls/src/vulkan/context.cpp) fails the test that caused it, and any message at all fails
// the run — including those from destroying a device after the last test.
#include <gtest/gtest.h>

#include "swell/impls/vulkan.hpp"

namespace {

class VulkanValidation : public testing::Environment {
 public:
  void SetUp() override {
    swell::impls::set_vulkan_message_handler(
        [](const std::string& message) { ADD_FAILURE() << message; });
  }
  void TearDown() override {
    EXPECT_EQ(swell::impls::vulkan_validation_message_count(), 0u)
        << "the Vulkan validation layers reported problems (above)";
  }
};

[[maybe_unused]] testing::Environment* const registered =
    testing::AddGlobalTestEnvironment(new VulkanValidation);

}  // namespace
