#include "context.hpp"

#include <algorithm>
#include <bit>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <new>

#include <fmt/format.h>

#include "swell/impls/vulkan.hpp"

namespace swell::impls {
namespace {

std::mutex handler_mutex;
std::function<void(const std::string&)> message_handler;
std::atomic<std::size_t> message_count{0};

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  ++message_count;
  const std::string text = fmt::format(
      "Vulkan validation {}: {}",
      severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
      data && data->pMessage ? data->pMessage : "(no message)");
  std::lock_guard lock(handler_mutex);
  if (message_handler) message_handler(text); else std::cerr << text << '\n';
  return VK_FALSE;
}

bool validation_requested() {
  const char* value = std::getenv("SWELL_VULKAN_VALIDATION");
  return value && *value && std::string(value) != "0";
}

}  // namespace

void set_vulkan_message_handler(std::function<void(const std::string&)> handler) {
  std::lock_guard lock(handler_mutex);
  message_handler = std::move(handler);
}

std::size_t vulkan_validation_message_count() { return message_count.load(); }

}  // namespace swell::impls

namespace swell::impls::vk {
namespace {

const char* result_name(VkResult result) {
  switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    default: return "VkResult";
  }
}

std::string version_text(std::uint32_t v) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v),
                     VK_API_VERSION_PATCH(v));
}

const char* type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

// Lower is preferred: discrete, integrated, virtual, CPU, other.
int preference(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

[[noreturn]] void unavailable(const std::string& why) {
  throw UnsupportedTransform("vulkan: " + why);
}

}  // namespace

void check(VkResult result, const char* call) {
  if (result == VK_SUCCESS) return;
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) {
    throw std::bad_alloc();
  }
  throw InternalError(fmt::format("vulkan: {} failed: {} ({})", call, result_name(result),
                                  int(result)));
}

std::shared_ptr<Context> Context::get(int index) {
  if (index < 0) {
    if (const char* chosen = std::getenv("SWELL_VULKAN_DEVICE"); chosen && *chosen) {
      char* end = nullptr;
      const long value = std::strtol(chosen, &end, 10);
      if (*end != '\0' || value < 0 || value > 255) {
        throw InvalidInput(std::string("SWELL_VULKAN_DEVICE='") + chosen +
                           "' must be a device index 0…255 (see `vulkaninfo --summary`)");
      }
      index = int(value);
    }
  }
  static std::mutex mutex;
  static std::map<int, std::weak_ptr<Context>> cache;
  std::lock_guard lock(mutex);
  if (auto existing = cache[index].lock()) return existing;
  std::shared_ptr<Context> context(new Context);
  context->open(index);
  cache[index] = context;
  return context;
}

void Context::open(int requested) {
  const bool validation = validation_requested();
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "swell";
  // 1.3 where the loader offers it (computeFullSubgroups for fft_lines_shuffle); 1.1 suffices
  // for everything else.
  std::uint32_t loader_version = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&loader_version);
  app.apiVersion = loader_version >= VK_API_VERSION_1_3 ? VK_API_VERSION_1_3 : VK_API_VERSION_1_1;
  std::vector<const char*> layers, extensions;
  VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = on_message;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  if (validation) {
    std::uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> available(count);
    vkEnumerateInstanceLayerProperties(&count, available.data());
    const bool found = std::any_of(available.begin(), available.end(), [](const auto& layer) {
      return std::strcmp(layer.layerName, "VK_LAYER_KHRONOS_validation") == 0;
    });
    if (!found) {
      unavailable("SWELL_VULKAN_VALIDATION is set but VK_LAYER_KHRONOS_validation is not "
                  "installed (Debian: vulkan-validationlayers)");
    }
    layers.push_back("VK_LAYER_KHRONOS_validation");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    features.pNext = &messenger_info;
    info.pNext = &features;
  }
  info.enabledLayerCount = std::uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = std::uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  const VkResult created = vkCreateInstance(&info, nullptr, &instance_);
  if (created != VK_SUCCESS) {
    unavailable(fmt::format("no Vulkan driver (vkCreateInstance: {}); for a CPU device install "
                            "lavapipe (Debian: mesa-vulkan-drivers)",
                            result_name(created)));
  }
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) check(create(instance_, &messenger_info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }

  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  if (count == 0) {
    unavailable("the Vulkan loader found no device; for a CPU device install lavapipe (Debian: "
                "mesa-vulkan-drivers)");
  }
  // A device qualifies with a compute queue; the preferred type wins, then the lower index.
  auto compute_family = [](VkPhysicalDevice device) -> int {
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &families, nullptr);
    std::vector<VkQueueFamilyProperties> properties(families);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &families, properties.data());
    for (std::uint32_t f = 0; f < families; ++f) {
      if (properties[f].queueFlags & VK_QUEUE_COMPUTE_BIT) return int(f);
    }
    return -1;
  };
  int chosen = -1;
  if (requested >= 0) {
    if (requested >= int(count)) {
      throw InvalidInput(fmt::format("vulkan: device {} requested, this machine has {} (0…{}; "
                                     "see `vulkaninfo --summary`)",
                                     requested, count, count - 1));
    }
    if (compute_family(devices[requested]) < 0) unavailable(fmt::format("device {} has no compute queue", requested));
    chosen = requested;
  } else {
    for (std::uint32_t d = 0; d < count; ++d) {
      if (compute_family(devices[d]) < 0) continue;
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(devices[d], &p);
      if (chosen < 0) { chosen = int(d); continue; }
      VkPhysicalDeviceProperties best;
      vkGetPhysicalDeviceProperties(devices[chosen], &best);
      if (preference(p.deviceType) < preference(best.deviceType)) chosen = int(d);
    }
    if (chosen < 0) unavailable("no Vulkan device has a compute queue");
  }
  index_ = chosen;
  physical_ = devices[chosen];
  queue_family_ = std::uint32_t(compute_family(physical_));
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  if (properties_.apiVersion < VK_API_VERSION_1_1) {
    unavailable(fmt::format("device {} ({}) offers Vulkan {}, swell needs 1.1", chosen,
                            properties_.deviceName, version_text(properties_.apiVersion)));
  }
  {
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, nullptr);
    std::vector<VkQueueFamilyProperties> properties(families);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, properties.data());
    timestamp_bits_ = properties[queue_family_].timestampValidBits;
  }
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical_, &supported);
  float64_ = supported.shaderFloat64 == VK_TRUE;
  // Subgroup shuffles with full subgroups (Vulkan 1.3) for fft_lines_shuffle.
  VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  if (properties_.apiVersion >= VK_API_VERSION_1_3 && app.apiVersion >= VK_API_VERSION_1_3) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceVulkan13Properties properties13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
    subgroup.pNext = &properties13;
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties2.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(physical_, &properties2);
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.pNext = &features13;
    vkGetPhysicalDeviceFeatures2(physical_, &features2);
    const bool shuffles = (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                          (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_SHUFFLE_BIT);
    const std::uint32_t size = subgroup.subgroupSize;
    if (shuffles && features13.computeFullSubgroups && size >= 8 && std::has_single_bit(size)) {
      shuffle_subgroup_size_ = size;
      max_subgroup_size_ = std::max(size, properties13.maxSubgroupSize);
    }
  }

  // The driver's name and version (Vulkan 1.2's driver properties where offered).
  std::string driver = fmt::format("driver version {:#x}", properties_.driverVersion);
  if (properties_.apiVersion >= VK_API_VERSION_1_2) {
    VkPhysicalDeviceDriverProperties driver_properties{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties2.pNext = &driver_properties;
    vkGetPhysicalDeviceProperties2(physical_, &properties2);
    driver = fmt::format("driver {} ({})", driver_properties.driverName,
                         driver_properties.driverInfo);
  }
  description_ = fmt::format("{}, {}, {}, Vulkan {}, device {} of {}", properties_.deviceName,
                             type_name(properties_.deviceType), driver,
                             version_text(properties_.apiVersion), chosen, count);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures enabled{};
  enabled.shaderFloat64 = supported.shaderFloat64;
  VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  device_info.pEnabledFeatures = &enabled;
  VkPhysicalDeviceVulkan13Features enabled13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  if (shuffle_subgroup_size_) {
    enabled13.computeFullSubgroups = VK_TRUE;
    device_info.pNext = &enabled13;
  }
  check(vkCreateDevice(physical_, &device_info, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    for (auto& slot : all_slots_) {
      if (slot.timestamps) vkDestroyQueryPool(device_, slot.timestamps, nullptr);
      vkDestroyFence(device_, slot.fence, nullptr);
      vkDestroyCommandPool(device_, slot.pool, nullptr);
    }
    for (auto& [key, p] : pipelines_) {
      vkDestroyPipeline(device_, p->pipeline, nullptr);
      vkDestroyPipelineLayout(device_, p->layout, nullptr);
      vkDestroyDescriptorSetLayout(device_, p->set_layout, nullptr);
    }
    for (auto& [name, module] : modules_) vkDestroyShaderModule(device_, module, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

namespace {

constexpr VkMemoryPropertyFlags kHostReadable = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                VK_MEMORY_PROPERTY_HOST_COHERENT_BIT |
                                                VK_MEMORY_PROPERTY_HOST_CACHED_BIT;

// The first memory type among `allowed` with every flag of each of `preferences` in turn;
// −1 when none has.
int memory_type(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t allowed,
                std::initializer_list<VkMemoryPropertyFlags> preferences) {
  for (VkMemoryPropertyFlags wanted : preferences) {
    for (std::uint32_t t = 0; t < memory.memoryTypeCount; ++t) {
      if ((allowed & (1u << t)) && (memory.memoryTypes[t].propertyFlags & wanted) == wanted) return int(t);
    }
  }
  return -1;
}

}  // namespace

Allocation Context::allocate(VkDeviceSize bytes, bool device_local) const {
  // Device-local memory for the kernels' data; host-visible, coherent (and cached, when
  // offered, for reading back) for staging, mapped.
  if (device_local) return allocate_as(bytes, {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT}, "device-local", Map::never);
  return allocate_as(bytes, {kHostReadable, kHostReadable & ~VK_MEMORY_PROPERTY_HOST_CACHED_BIT},
                     "host-visible coherent", Map::always);
}

Allocation Context::allocate_readable(VkDeviceSize bytes) const {
  return allocate_as(bytes, {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | kHostReadable, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT},
                     "device-local", Map::if_readable);
}

// A buffer in the first memory type with all flags of one of `preferences`, tried in order.
// Map::if_readable maps it only where the host reads it fast and without flushes: host visible,
// coherent and cached.
Allocation Context::allocate_as(VkDeviceSize bytes, std::initializer_list<VkMemoryPropertyFlags> preferences,
                                const char* what, Map map) const {
  Allocation a;
  a.size = std::max<VkDeviceSize>(bytes, 16);
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = a.size;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(device_, &info, nullptr, &a.buffer), "vkCreateBuffer");
  VkMemoryRequirements needs;
  vkGetBufferMemoryRequirements(device_, a.buffer, &needs);
  const int type = memory_type(memory_, needs.memoryTypeBits, preferences);
  if (type < 0) {
    vkDestroyBuffer(device_, a.buffer, nullptr);
    throw InternalError(std::string("vulkan: the device offers no ") + what + " memory");
  }
  VkMemoryAllocateInfo allocate_info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocate_info.allocationSize = needs.size;
  allocate_info.memoryTypeIndex = std::uint32_t(type);
  const VkResult allocated = vkAllocateMemory(device_, &allocate_info, nullptr, &a.memory);
  if (allocated != VK_SUCCESS) {
    vkDestroyBuffer(device_, a.buffer, nullptr);
    check(allocated, "vkAllocateMemory");
  }
  check(vkBindBufferMemory(device_, a.buffer, a.memory, 0), "vkBindBufferMemory");
  const VkMemoryPropertyFlags flags = memory_.memoryTypes[type].propertyFlags;
  if (map == Map::always || (map == Map::if_readable && (flags & kHostReadable) == kHostReadable)) {
    check(vkMapMemory(device_, a.memory, 0, VK_WHOLE_SIZE, 0, &a.mapped), "vkMapMemory");
  }
  return a;
}

void Context::free(Allocation& a) const {
  if (a.mapped) vkUnmapMemory(device_, a.memory);
  if (a.buffer) vkDestroyBuffer(device_, a.buffer, nullptr);
  if (a.memory) vkFreeMemory(device_, a.memory, nullptr);
  a = Allocation{};
}

Slot Context::acquire() const {
  {
    std::lock_guard lock(slots_mutex_);
    if (!free_slots_.empty()) {
      Slot slot = free_slots_.back();
      free_slots_.pop_back();
      return slot;
    }
  }
  Slot slot;
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = queue_family_;
  check(vkCreateCommandPool(device_, &pool_info, nullptr, &slot.pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo buffer_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  buffer_info.commandPool = slot.pool;
  buffer_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  buffer_info.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(device_, &buffer_info, &slot.commands), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(device_, &fence_info, nullptr, &slot.fence), "vkCreateFence");
  if (has_timestamps()) {
    VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = kTimestamps;
    check(vkCreateQueryPool(device_, &query_info, nullptr, &slot.timestamps), "vkCreateQueryPool");
  }
  std::lock_guard lock(slots_mutex_);
  all_slots_.push_back(slot);
  return slot;
}

void Context::release(Slot slot) const {
  std::lock_guard lock(slots_mutex_);
  free_slots_.push_back(slot);
}

void Context::submit_and_wait(const Slot& slot) const {
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &slot.commands;
  {
    std::lock_guard lock(queue_mutex_);
    check(vkQueueSubmit(queue_, 1, &submit, slot.fence), "vkQueueSubmit");
  }
  check(vkWaitForFences(device_, 1, &slot.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  check(vkResetFences(device_, 1, &slot.fence), "vkResetFences");
}

void Context::run(const std::function<void(VkCommandBuffer)>& record) const {
  Slot slot = acquire();
  struct Releaser {
    const Context* context;
    Slot slot;
    ~Releaser() { context->release(slot); }
  } releaser{this, slot};
  check(vkResetCommandBuffer(slot.commands, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(slot.commands, &begin), "vkBeginCommandBuffer");
  record(slot.commands);
  check(vkEndCommandBuffer(slot.commands), "vkEndCommandBuffer");
  submit_and_wait(slot);
}

std::vector<double> Context::timestamp_seconds(const Slot& slot, std::uint32_t count) const {
  std::vector<double> seconds(count, 0.0);
  if (!slot.timestamps) return seconds;
  std::uint64_t ticks[kTimestamps] = {};
  check(vkGetQueryPoolResults(device_, slot.timestamps, 0, count, count * sizeof(std::uint64_t),
                              ticks, sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  const std::uint64_t mask =
      timestamp_bits_ >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << timestamp_bits_) - 1;
  for (std::uint32_t q = 0; q < count; ++q) {
    seconds[q] = double((ticks[q] - ticks[0]) & mask) * timestamp_period_ns() * 1e-9;
  }
  return seconds;
}

const Pipeline& Context::pipeline(const std::string& module_name,
                                  const std::vector<std::uint32_t>& spirv,
                                  const std::vector<std::uint32_t>& specialization,
                                  const PipelineShape& shape) const {
  std::lock_guard lock(pipelines_mutex_);
  auto key = std::make_tuple(module_name, specialization);
  if (auto found = pipelines_.find(key); found != pipelines_.end()) return *found->second;
  VkShaderModule& module = modules_[module_name];
  if (!module) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size() * sizeof(std::uint32_t);
    info.pCode = spirv.data();
    check(vkCreateShaderModule(device_, &info, nullptr, &module), "vkCreateShaderModule");
  }
  auto p = std::make_unique<Pipeline>();
  p->shape = shape;
  std::vector<VkDescriptorSetLayoutBinding> bindings(shape.bindings.size());
  for (std::uint32_t b = 0; b < bindings.size(); ++b) {
    bindings[b].binding = b;
    bindings[b].descriptorType = shape.bindings[b];
    bindings[b].descriptorCount = 1;
    bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = std::uint32_t(bindings.size());
  set_info.pBindings = bindings.data();
  check(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &p->set_layout),
        "vkCreateDescriptorSetLayout");
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, shape.push_bytes};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &p->set_layout;
  layout_info.pushConstantRangeCount = shape.push_bytes ? 1 : 0;
  layout_info.pPushConstantRanges = &range;
  check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &p->layout), "vkCreatePipelineLayout");
  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (std::uint32_t i = 0; i < entries.size(); ++i) {
    entries[i] = {i, i * std::uint32_t(sizeof(std::uint32_t)), sizeof(std::uint32_t)};
  }
  VkSpecializationInfo special{std::uint32_t(entries.size()), entries.data(),
                               specialization.size() * sizeof(std::uint32_t), specialization.data()};
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  if (shape.full_subgroups) info.stage.flags = VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT;
  if (shape.dispatch_base) info.flags = VK_PIPELINE_CREATE_DISPATCH_BASE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = &special;
  info.layout = p->layout;
  check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &p->pipeline),
        "vkCreateComputePipelines");
  auto& stored = pipelines_[key];
  stored = std::move(p);
  return *stored;
}

void Context::host_barrier(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void Context::barrier(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  vkCmdPipelineBarrier(commands,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                       &barrier, 0, nullptr, 0, nullptr);
}

// ------------------------------------------------------------------ DeviceBuffer

DeviceBuffer::DeviceBuffer(std::shared_ptr<const Context> context, std::size_t bytes)
    : context_(std::move(context)), bytes_(bytes), allocation_(context_->allocate(bytes, true)) {
  // Zeroed like a HostBuffer, so that a fresh buffer never holds another run's data.
  context_->run([&](VkCommandBuffer commands) {
    vkCmdFillBuffer(commands, allocation_.buffer, 0, VK_WHOLE_SIZE, 0);
  });
}

DeviceBuffer::~DeviceBuffer() { context_->free(allocation_); }

void DeviceBuffer::upload(const void* host, std::size_t bytes) {
  if (bytes > bytes_) throw InvalidInput("upload of " + std::to_string(bytes) + " bytes into a buffer of " + std::to_string(bytes_));
  if (bytes == 0) return;
  Allocation staging = context_->allocate(bytes, false);
  std::memcpy(staging.mapped, host, bytes);
  try {
    context_->run([&](VkCommandBuffer commands) {
      const VkBufferCopy region{0, 0, bytes};
      Context::barrier(commands);
      vkCmdCopyBuffer(commands, staging.buffer, allocation_.buffer, 1, &region);
    });
  } catch (...) {
    context_->free(staging);
    throw;
  }
  context_->free(staging);
}

void DeviceBuffer::download(void* host, std::size_t bytes) const {
  if (bytes > bytes_) throw InvalidInput("download of " + std::to_string(bytes) + " bytes from a buffer of " + std::to_string(bytes_));
  if (bytes == 0) return;
  Allocation staging = context_->allocate(bytes, false);
  try {
    context_->run([&](VkCommandBuffer commands) {
      const VkBufferCopy region{0, 0, bytes};
      Context::barrier(commands);
      vkCmdCopyBuffer(commands, allocation_.buffer, staging.buffer, 1, &region);
      VkMemoryBarrier host_barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      host_barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      host_barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                           0, 1, &host_barrier, 0, nullptr, 0, nullptr);
    });
    std::memcpy(host, staging.mapped, bytes);
  } catch (...) {
    context_->free(staging);
    throw;
  }
  context_->free(staging);
}

}  // namespace swell::impls::vk
