#pragma once
// Internal: the Vulkan side of swell (docs/vulkan.md) — one instance and logical device per
// chosen physical device, shared by every backend, plan, buffer and synthesizer that uses it.
//
// Thread safety: vkQueueSubmit and command pools need external synchronization. The queue is
// guarded by a mutex; command buffers, fences and query pools come from a pool of Slots that a
// caller owns between acquire() and release(), so any number of host threads can record and
// submit at once.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "swell/impls/transform.hpp"

namespace swell::impls::vk {

// Throws InternalError naming the call and the VkResult unless result is VK_SUCCESS.
void check(VkResult result, const char* call);

// A buffer and its own memory. Host-visible buffers stay mapped.
struct Allocation {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;
};

// What one submission needs: a command buffer, its pool, a fence, and four timestamps.
struct Slot {
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkQueryPool timestamps = VK_NULL_HANDLE;  // kTimestamps queries, or null without timestamps
};
constexpr std::uint32_t kTimestamps = 4;

// A binding's window of a buffer.
struct Window {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, range = 0;
};

// What a pipeline's layout holds: set 0's bindings 0, 1, … (one descriptor each, of these
// types), and `push_bytes` bytes of push constants.
struct PipelineShape {
  std::vector<VkDescriptorType> bindings;
  std::uint32_t push_bytes = 0;
  bool full_subgroups = false;  // VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT
  bool dispatch_base = false;   // dispatched with a base workgroup (vkCmdDispatchBase)
};

// A compiled compute pipeline with its layout.
struct Pipeline {
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  PipelineShape shape;
};

class Context {
 public:
  // The context of device `index` (−1: SWELL_VULKAN_DEVICE when set, else the first discrete
  // GPU, then integrated, virtual, CPU). Cached while anything holds it. Throws
  // UnsupportedTransform saying why when there is no loader, no device or no compute queue.
  static std::shared_ptr<Context> get(int index = -1);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkDevice device() const { return device_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  bool float64() const { return float64_; }
  // The subgroup size when compute shaders may shuffle within subgroups and require them full
  // (subgroup shuffles in compute, Vulkan 1.3's computeFullSubgroups, a power of two ≥ 8);
  // 0 otherwise. Pipelines that require full subgroups need a workgroup width that is a
  // multiple of max_subgroup_size().
  std::uint32_t shuffle_subgroup_size() const { return shuffle_subgroup_size_; }
  std::uint32_t max_subgroup_size() const { return max_subgroup_size_; }
  bool has_timestamps() const { return timestamp_bits_ > 0; }
  double timestamp_period_ns() const { return properties_.limits.timestampPeriod; }
  bool is_cpu() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  int index() const { return index_; }
  // "llvmpipe (LLVM 15.0.6, 256 bits), CPU, driver llvmpipe (Mesa 22.3.6 (LLVM 15.0.6)),
  // Vulkan 1.3.230, device 0 of 1"
  const std::string& description() const { return description_; }

  // device_local: for the data the kernels work on; otherwise host visible and coherent,
  // mapped (staging). Throws std::bad_alloc when the device is out of memory.
  Allocation allocate(VkDeviceSize bytes, bool device_local) const;
  // Device-local memory the host can read directly where the device has such memory that is
  // also coherent and cached (a CPU device, integrated GPUs; mapped is set), so results need
  // no copy through staging; else plain device-local memory (mapped is null) — a discrete
  // GPU's host-visible device memory is uncached, and reading it from the host is slow.
  Allocation allocate_readable(VkDeviceSize bytes) const;
  void free(Allocation& allocation) const;

  Slot acquire() const;
  void release(Slot slot) const;
  // Submits `slot`'s recorded command buffer and waits for it.
  void submit_and_wait(const Slot& slot) const;
  // Records `record` into a slot, submits it and waits: for uploads, downloads and set-up.
  void run(const std::function<void(VkCommandBuffer)>& record) const;
  // Seconds between timestamps `from` and `to` of a slot that ran.
  // `count`: the slot's first `count` timestamps were written (at most kTimestamps).
  std::vector<double> timestamp_seconds(const Slot& slot, std::uint32_t count = kTimestamps) const;

  // The pipeline of an embedded SPIR-V module with these specialization constants (cached;
  // a module's pipelines all have the same shape).
  const Pipeline& pipeline(const std::string& module_name, const std::vector<std::uint32_t>& spirv,
                           const std::vector<std::uint32_t>& specialization,
                           const PipelineShape& shape) const;

  // Barrier: compute (or transfer) writes before compute and transfer reads and writes.
  static void barrier(VkCommandBuffer commands);
  // Barrier: compute and transfer writes before the host reads (after the fence).
  static void host_barrier(VkCommandBuffer commands);

 private:
  Context() = default;
  void open(int index);
  enum class Map { never, always, if_readable };
  Allocation allocate_as(VkDeviceSize bytes, std::initializer_list<VkMemoryPropertyFlags> preferences,
                         const char* what, Map map) const;

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  std::uint32_t timestamp_bits_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  bool float64_ = false;
  std::uint32_t shuffle_subgroup_size_ = 0, max_subgroup_size_ = 0;
  int index_ = 0;
  std::string description_;

  mutable std::mutex queue_mutex_;
  mutable std::mutex slots_mutex_;
  mutable std::vector<Slot> free_slots_;
  mutable std::vector<Slot> all_slots_;
  mutable std::mutex pipelines_mutex_;
  mutable std::map<std::tuple<std::string, std::vector<std::uint32_t>>, std::unique_ptr<Pipeline>>
      pipelines_;
  mutable std::map<std::string, VkShaderModule> modules_;
};

// A Buffer in device-local memory; upload and download go through a staging buffer.
class DeviceBuffer final : public Buffer {
 public:
  DeviceBuffer(std::shared_ptr<const Context> context, std::size_t bytes);
  ~DeviceBuffer() override;
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  std::size_t bytes() const override { return bytes_; }
  void upload(const void* host, std::size_t bytes) override;
  void download(void* host, std::size_t bytes) const override;
  void* host_data() override { return nullptr; }
  const void* host_data() const override { return nullptr; }
  VkBuffer handle() const { return allocation_.buffer; }
  const Context& context() const { return *context_; }

 private:
  std::shared_ptr<const Context> context_;
  std::size_t bytes_;
  Allocation allocation_;
};

// The SPIR-V of the shaders in impls/shaders, compiled by glslc at build time.
const std::vector<std::uint32_t>& fft_lines_spirv(Precision precision);
// fft_lines built with SWELL_SHUFFLE: needs subgroup shuffles and full subgroups.
const std::vector<std::uint32_t>& fft_lines_shuffle_spirv(Precision precision);
// fft_lines built with SWELL_FRAME (and SWELL_SHUFFLE): the frame program's first and last
// passes, which make the packed spectra and write the six fields (frame.cpp).
const std::vector<std::uint32_t>& fft_frame_spirv(Precision precision);
const std::vector<std::uint32_t>& fft_frame_shuffle_spirv(Precision precision);
// The synthesizer's evolution kernel: h̃(k, t) of the half spectrum.
const std::vector<std::uint32_t>& frame_evolve_spirv(Precision precision);

}  // namespace swell::impls::vk
