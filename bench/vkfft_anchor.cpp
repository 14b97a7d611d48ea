// The VkFFT anchor: fft2d/c2c/vkfft/fp32/<N>, VkFFT's (libvkfft-dev 1.2.26) 2-D N×N complex
// inverse in fp32, unnormalized like FFTW_BACKWARD. Out of place, as swell's plans run: with
// isInputFormatted set, VkFFT 1.2.26 reads `inputBuffer` and writes `buffer` (checked against
// FFTW, the input left intact), so every iteration transforms the same input (in place, the
// unnormalized repeats would grow by about N each and overflow to inf).
//
// Device: SWELL_VULKAN_DEVICE (an index into vkEnumeratePhysicalDevices) when set, else the first
// discrete GPU, integrated GPU, virtual GPU, CPU (lavapipe), in that order. Each iteration records
// one command buffer (two timestamps around VkFFTAppend), submits it and waits on a fence.
// Counters as fft_bench.cpp's (GFLOP/s, bytes/s, plan_seconds = initializeVkFFT's wall time) and
// device_seconds: the mean over the iterations of the GPU time between the two timestamps.
#include "vkfft_anchor.hpp"

#include <benchmark/benchmark.h>

#include <string>

#ifdef SWELL_HAVE_VKFFT
#include <vkFFT.h>

#include <chrono>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <vector>
#endif

// Vulkan's create-info structs are written with designated initializers naming only the fields
// that matter; the rest are meant to be zero, which is what -Wextra would flag.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace {

constexpr int kMinN = 16, kMaxN = 4096;

std::string benchmark_name(int n) { return "fft2d/c2c/vkfft/fp32/" + std::to_string(n); }

#ifdef SWELL_HAVE_VKFFT

// A failed Vulkan or VkFFT call; its message becomes the benchmark's skip reason.
struct VulkanError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) {
    throw VulkanError(std::string(what) + " failed: VkResult " + std::to_string(int(result)));
  }
}

VkPhysicalDevice choose_device(VkInstance instance) {
  uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
  if (devices.empty()) throw VulkanError("no Vulkan device (lavapipe: apt-get install mesa-vulkan-drivers)");
  if (const char* chosen = std::getenv("SWELL_VULKAN_DEVICE"); chosen && *chosen) {
    char* end = nullptr;
    const unsigned long index = std::strtoul(chosen, &end, 10);
    if (*end || index >= devices.size()) {
      throw VulkanError("SWELL_VULKAN_DEVICE=" + std::string(chosen) + " is not a device index (" +
                        std::to_string(devices.size()) + " devices)");
    }
    return devices[index];
  }
  for (VkPhysicalDeviceType type :
       {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
        VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU, VK_PHYSICAL_DEVICE_TYPE_CPU}) {
    for (VkPhysicalDevice device : devices) {
      VkPhysicalDeviceProperties properties;
      vkGetPhysicalDeviceProperties(device, &properties);
      if (properties.deviceType == type) return device;
    }
  }
  return devices.front();
}

// The instance, device, compute queue, command pool and fence all sizes share. VkFFT keeps
// pointers to these handles, so they live at a fixed address for the whole run.
struct Context {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  uint32_t family = 0;
  uint32_t timestamp_bits = 0;  // of the queue family; 0: no timestamps
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  std::string error;  // why there is no device; empty when ready

  Context() {
    try {
      create();
    } catch (const VulkanError& e) {
      error = e.what();
    }
  }
  ~Context() {
    if (device) {
      vkDestroyFence(device, fence, nullptr);
      vkDestroyCommandPool(device, pool, nullptr);
      vkDestroyDevice(device, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  void create() {
    const VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                                .pApplicationName = "swell_fft_bench",
                                .apiVersion = VK_API_VERSION_1_1};
    const VkInstanceCreateInfo instance_info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                             .pApplicationInfo = &app};
    check(vkCreateInstance(&instance_info, nullptr, &instance), "vkCreateInstance");
    physical = choose_device(instance);
    vkGetPhysicalDeviceProperties(physical, &properties);

    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (family = 0; family < count && !(families[family].queueFlags & VK_QUEUE_COMPUTE_BIT);) {
      ++family;
    }
    if (family == count) throw VulkanError(std::string(properties.deviceName) + " has no compute queue");
    timestamp_bits = families[family].timestampValidBits;

    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queue_info{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                             .queueFamilyIndex = family,
                                             .queueCount = 1,
                                             .pQueuePriorities = &priority};
    const VkDeviceCreateInfo device_info{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                         .queueCreateInfoCount = 1,
                                         .pQueueCreateInfos = &queue_info};
    check(vkCreateDevice(physical, &device_info, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, family, 0, &queue);

    const VkCommandPoolCreateInfo pool_info{
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,  // re-recorded each iteration
        .queueFamilyIndex = family};
    check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
    const VkFenceCreateInfo fence_info{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(device, &fence_info, nullptr, &fence), "vkCreateFence");
  }

  // Submits `commands` and waits for them; the fence is left unsignalled for the next user.
  void submit_and_wait(VkCommandBuffer commands) const {
    const VkSubmitInfo submit{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
                              .commandBufferCount = 1,
                              .pCommandBuffers = &commands};
    check(vkQueueSubmit(queue, 1, &submit, fence), "vkQueueSubmit");
    check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(device, 1, &fence), "vkResetFences");
  }
};

// Created by the first vkfft benchmark that runs, so listing or filtering them out costs nothing.
Context& context() {
  static Context instance;
  return instance;
}

struct Buffer {
  VkDevice device = VK_NULL_HANDLE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;

  Buffer(const Context& vk, VkDeviceSize bytes, VkBufferUsageFlags usage, VkMemoryPropertyFlags flags)
      : device(vk.device) {
    const VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                                  .size = bytes,
                                  .usage = usage,
                                  .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    check(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(device, buffer, &needs);
    VkPhysicalDeviceMemoryProperties memory_types;
    vkGetPhysicalDeviceMemoryProperties(vk.physical, &memory_types);
    VkMemoryAllocateInfo allocate{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                  .allocationSize = needs.size,
                                  .memoryTypeIndex = memory_types.memoryTypeCount};
    for (uint32_t i = 0; i < memory_types.memoryTypeCount; ++i) {
      if ((needs.memoryTypeBits & (1u << i)) &&
          (memory_types.memoryTypes[i].propertyFlags & flags) == flags) {
        allocate.memoryTypeIndex = i;
        break;
      }
    }
    if (allocate.memoryTypeIndex == memory_types.memoryTypeCount) {
      throw VulkanError("no memory type with flags " + std::to_string(flags));
    }
    check(vkAllocateMemory(device, &allocate, nullptr, &memory), "vkAllocateMemory");
    check(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
  }
  ~Buffer() {
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
  }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
};

// One size's plan and buffers: `source` holds fft_bench.cpp's input, `result` the inverse.
struct Transform {
  static constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                               VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                               VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  const Context& vk;
  uint64_t bytes;
  Buffer source, result;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkQueryPool timestamps = VK_NULL_HANDLE;
  VkFFTApplication app{};
  bool planned = false;
  double plan_seconds = 0;

  Transform(const Context& context, int n)
      : vk(context),
        bytes(uint64_t(n) * n * sizeof(std::complex<float>)),
        source(vk, bytes, kUsage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
        result(vk, bytes, kUsage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) {
    const VkCommandBufferAllocateInfo allocate{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                               .commandPool = vk.pool,
                                               .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                               .commandBufferCount = 1};
    check(vkAllocateCommandBuffers(vk.device, &allocate, &commands), "vkAllocateCommandBuffers");
    if (vk.timestamp_bits) {
      const VkQueryPoolCreateInfo query{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                        .queryType = VK_QUERY_TYPE_TIMESTAMP,
                                        .queryCount = 2};
      check(vkCreateQueryPool(vk.device, &query, nullptr, &timestamps), "vkCreateQueryPool");
    }
    upload(n);

    VkFFTConfiguration config{};
    config.FFTdim = 2;
    config.size[0] = config.size[1] = uint64_t(n);
    config.physicalDevice = const_cast<VkPhysicalDevice*>(&vk.physical);
    config.device = const_cast<VkDevice*>(&vk.device);
    config.queue = const_cast<VkQueue*>(&vk.queue);
    config.commandPool = const_cast<VkCommandPool*>(&vk.pool);
    config.fence = const_cast<VkFence*>(&vk.fence);
    config.isInputFormatted = 1;  // out of place: read inputBuffer, write buffer
    config.inputBuffer = &source.buffer;
    config.inputBufferSize = &bytes;
    config.buffer = &result.buffer;
    config.bufferSize = &bytes;
    config.makeInversePlanOnly = 1;  // the forward plan would only lengthen plan_seconds
    const auto start = std::chrono::steady_clock::now();
    const VkFFTResult status = initializeVkFFT(&app, config);
    plan_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (status != VKFFT_SUCCESS) {
      throw VulkanError("initializeVkFFT failed: VkFFTResult " + std::to_string(int(status)));
    }
    planned = true;
  }
  ~Transform() {
    if (planned) deleteVkFFT(&app);
    if (timestamps) vkDestroyQueryPool(vk.device, timestamps, nullptr);
    vkFreeCommandBuffers(vk.device, vk.pool, 1, &commands);
  }
  Transform(const Transform&) = delete;
  Transform& operator=(const Transform&) = delete;

  // fft_bench.cpp's input (mt19937(7), uniform in [-0.5, 0.5)), through a staging buffer.
  void upload(int n) {
    Buffer staging(vk, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    void* mapped = nullptr;
    check(vkMapMemory(vk.device, staging.memory, 0, bytes, 0, &mapped), "vkMapMemory");
    std::mt19937 engine(7);
    auto* x = static_cast<float*>(mapped);
    for (std::size_t i = 0; i < 2 * std::size_t(n) * n; ++i) x[i] = float(engine()) / 4294967296.0f - 0.5f;
    vkUnmapMemory(vk.device, staging.memory);

    begin();
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(commands, staging.buffer, source.buffer, 1, &region);
    // The copy's writes must be visible to the transform's shaders in the later submissions.
    const VkMemoryBarrier barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                  .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                  .dstAccessMask = VK_ACCESS_SHADER_READ_BIT};
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
    end_and_wait();
  }

  void begin() {
    const VkCommandBufferBeginInfo info{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    check(vkBeginCommandBuffer(commands, &info), "vkBeginCommandBuffer");
  }
  void end_and_wait() {
    check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
    vk.submit_and_wait(commands);
  }

  // One inverse transform, recorded, submitted and waited for. Returns its GPU seconds from the
  // timestamps, 0 when the queue has none.
  double execute() {
    begin();
    if (timestamps) {
      vkCmdResetQueryPool(commands, timestamps, 0, 2);
      vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
    }
    VkFFTLaunchParams launch{};
    launch.commandBuffer = &commands;
    const VkFFTResult status = VkFFTAppend(&app, 1, &launch);
    if (status != VKFFT_SUCCESS) {
      throw VulkanError("VkFFTAppend failed: VkFFTResult " + std::to_string(int(status)));
    }
    if (timestamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, 1);
    end_and_wait();
    if (!timestamps) return 0;
    uint64_t ticks[2];
    check(vkGetQueryPoolResults(vk.device, timestamps, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    // Only the low timestampValidBits count; the difference is taken modulo that width.
    const uint64_t mask = vk.timestamp_bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << vk.timestamp_bits) - 1;
    return double((ticks[1] - ticks[0]) & mask) * vk.properties.limits.timestampPeriod * 1e-9;
  }
};

void run(benchmark::State& state, int n) {
  Context& vk = context();
  if (!vk.error.empty()) {
    state.SkipWithError(vk.error.c_str());
    return;
  }
  try {
    Transform transform(vk, n);
    // One untimed transform first: on lavapipe a plan's first submission took about 3 ms more
    // than the next at 64² and 130 ms more at 4096², which would dominate the single iteration
    // a short --benchmark_min_time allows at large N.
    transform.execute();
    double device_seconds = 0;
    for (auto _ : state) device_seconds += transform.execute();
    state.SetLabel(vk.properties.deviceName);
    const double n2 = double(n) * n;
    state.counters["GFLOP/s"] =
        benchmark::Counter(5.0 * n2 * std::log2(n2) * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["plan_seconds"] = transform.plan_seconds;
    if (vk.timestamp_bits) state.counters["device_seconds"] = device_seconds / double(state.iterations());
    state.SetBytesProcessed(state.iterations() * int64_t(2 * transform.bytes));
  } catch (const VulkanError& e) {
    state.SkipWithError(e.what());
  }
}

#else

void skip(benchmark::State& state) { state.SkipWithError("VkFFT anchor not built: " SWELL_VKFFT_REASON); }

#endif

}  // namespace

namespace swell::bench {

void register_vkfft_benchmarks() {
#ifdef SWELL_HAVE_VKFFT
  benchmark::AddCustomContext("vkfft_version", std::to_string(VkFFTGetVersion()));
#endif
  for (int n = kMinN; n <= kMaxN; n *= 2) {
#ifdef SWELL_HAVE_VKFFT
    // Real time: the thread sleeps on the fence, so its CPU time misses the transform (and the
    // GFLOP/s and bytes/s rates, taken over the benchmark's time, would be far too high).
    benchmark::RegisterBenchmark(benchmark_name(n).c_str(), run, n)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        // Warm-up (untimed) before each: the first benchmarks of a run were up to 2× slower
        // than the same ones later (lavapipe's threads and the CPU's clocks waking up).
        ->MinWarmUpTime(0.05);
#else
    benchmark::RegisterBenchmark(benchmark_name(n).c_str(), skip);
#endif
  }
}

}  // namespace swell::bench
