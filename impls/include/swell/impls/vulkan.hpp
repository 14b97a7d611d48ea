#pragma once
// What the `vulkan` backend (docs/vulkan.md) offers beyond the Backend interface: the device it
// runs on, the device's own timings of a transform, and the validation layers' messages.
// Only in builds with SWELL_WITH_VULKAN (the CMake target defines SWELL_HAVE_VULKAN).
#include <cstddef>
#include <functional>
#include <string>

#include "swell/impls/transform.hpp"

namespace swell::impls {

// The device's timestamps of the three phases of one execution, in seconds: host → device
// copy, the transform's dispatches, device → host copy (0 for a phase that did not happen).
struct VulkanTimings {
  double upload_seconds = 0;
  double compute_seconds = 0;
  double download_seconds = 0;
};

// Executes a plan made by a vulkan backend and returns its timings. On host memory it uploads,
// transforms and downloads; on the backend's Buffers it only transforms. Throws InvalidInput
// for a plan of another backend.
VulkanTimings vulkan_execute_timed(const Plan& plan, const void* in, void* out);
VulkanTimings vulkan_execute_timed(const Plan& plan, const Buffer& in, Buffer& out);

// The device and driver a vulkan backend of these options ("vulkan", "vulkan:device=1") runs
// on, or why there is none (the UnsupportedTransform's message).
std::string vulkan_device_description(const std::string& backend = "vulkan");

// With SWELL_VULKAN_VALIDATION=1 every device is opened with VK_LAYER_KHRONOS_validation and
// synchronization validation, and each warning or error it reports is counted and passed to
// the handler (default: printed on stderr). Tests make each one a failure.
void set_vulkan_message_handler(std::function<void(const std::string&)> handler);
std::size_t vulkan_validation_message_count();

}  // namespace swell::impls
