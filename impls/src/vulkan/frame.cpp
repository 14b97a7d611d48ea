// The synthesizer's frame on a Vulkan device (docs/synthesis.md §vulkan; DESIGN §3: "a device
// backend's frame is one submission"). At construction the tables of the waves go to device
// memory once; each frame is then one command buffer and one fence wait:
//
//   evolution (impls/shaders/frame_evolve.comp)   the packed spectra at t, as assemble() does
//   the plan's passes (FftProgram::record)        the batch of inverse transforms, in place
//   unpack (impls/shaders/frame_unpack.comp)      the six fields and the non-finite probe
//   copy to a host-visible staging buffer         only because evaluate() returns host memory
//
// record_frame() records the first three alone and leaves the fields in a device buffer: a
// device-only evaluation (a renderer that samples the fields where they are) is that call into
// its own command buffer, without the copy and without the host ever touching the frame.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <mutex>
#include <vector>

#include <fmt/format.h>

#include "../device_frame.hpp"
#include "fft.hpp"

namespace swell::impls::vk {
namespace {

constexpr int kRealFields = 8;  // packing order of synthesizer.cpp
constexpr int kFields = 6;      // reference::kAllFields

// Invocations per workgroup of both kernels. They use no shared memory and no barrier, so the
// size only sets how work is handed out: 128 is a multiple of every GPU's subgroup (32, 64) and
// of lavapipe's 8 lanes, and few enough that the last, partial workgroup of a row costs little.
constexpr std::uint32_t kLocalSize = 128;

// The push constants of frame_evolve.comp and frame_unpack.comp, in their std430 layout: these
// headers, then the eight (inverse) field scales in the synthesis precision.
struct EvolveHeader {
  double t = 0, dkx = 0, dky = 0;
  std::uint32_t nx = 0, ny = 0, half_columns = 0, spectrum_columns = 0, plane_stride = 0,
                reserved = 0;
};
static_assert(sizeof(EvolveHeader) == 48);
struct UnpackHeader {
  std::uint32_t count = 0, input_stride = 0, field_stride = 0, reserved = 0;
};
static_assert(sizeof(UnpackHeader) == 16);

// Storage buffers each kernel binds (frame_evolve.comp: the waves, λ/|k|, ω and 8 planes;
// frame_unpack.comp: the probe, 8 input planes, 6 fields).
constexpr std::uint32_t kEvolveBuffers = 3 + kRealFields;
constexpr std::uint32_t kUnpackBuffers = 1 + kRealFields + kFields;

// A binding: a buffer's window (offset, range).
struct Window {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, range = 0;
};

// The bindings of `planes` planes of `plane_bytes` each from the start of `buffer`, in words of
// `word_bytes`: one window per plane, or — when a plane's size is not a multiple of the
// device's minStorageBufferOffsetAlignment (a grid of a few samples) — the whole buffer for
// every one, plane p then starting at word p · stride.
struct Planes {
  std::vector<Window> windows;
  std::uint32_t stride = 0;
};

class FrameProgram final : public DeviceFrame {
 public:
  FrameProgram(std::shared_ptr<const Context> context, const FftProgram& transform,
               const DeviceFrameTables& tables);
  ~FrameProgram() override;
  FrameProgram(const FrameProgram&) = delete;
  FrameProgram& operator=(const FrameProgram&) = delete;

  std::size_t evaluate(double t, std::span<std::byte> fields, FrameTimings& timings) const override;

 private:
  // Records the frame at t — evolution, transforms, unpack — into `commands`, leaving the six
  // fields in fields_ and the count of non-finite samples in probe_, with no barrier after the
  // unpack (the caller's next use decides which one it needs). With `stamps`, timestamps 1 and
  // 2 of that pool are written after the evolution and after the transforms. The caller holds mutex_ until
  // the submission has completed: the buffers and the transform's workspace are this
  // program's alone.
  void record_frame(VkCommandBuffer commands, double t, VkQueryPool stamps) const;
  Window whole(const Allocation& allocation) const;
  Planes planes(const Allocation& allocation, int count, int bound, VkDeviceSize plane_bytes,
                VkDeviceSize word_bytes) const;
  void dispatch(VkCommandBuffer commands, std::uint64_t invocations) const;
  [[noreturn]] void refuse(const std::string& rule) const;
  void release();

  std::shared_ptr<const Context> context_;
  const FftProgram& transform_;  // the synthesizer's plan, which outlives this
  Precision precision_;
  bool pairs_;
  std::uint32_t nx_, ny_, half_columns_, spectrum_columns_;
  std::size_t real_;
  VkDeviceSize fields_bytes_ = 0;
  // Device memory: the waves' tables (written once), the spectra and their transforms (the
  // same buffer for the in-place c2c batch), the six fields and the probe.
  Allocation waves_, lambda_over_k_, omega_, spectra_, transformed_storage_, fields_, probe_;
  Allocation staging_;  // host visible: the six fields, then the probe's count
  const Allocation& transformed() const { return pairs_ ? spectra_ : transformed_storage_; }
  const Pipeline* evolve_ = nullptr;
  const Pipeline* unpack_ = nullptr;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet evolve_set_ = VK_NULL_HANDLE, unpack_set_ = VK_NULL_HANDLE;
  std::vector<std::byte> evolve_push_, unpack_push_;  // header and scales (t set per frame)
  Workspace* workspace_ = nullptr;
  // One frame in flight per program: evaluate() is const and may be called from several
  // threads; they take turns on the buffers above.
  mutable std::mutex mutex_;
};

void FrameProgram::refuse(const std::string& rule) const {
  throw UnsupportedTransform(fmt::format("vulkan: the synthesizer's frame of {}×{} in {}: {} on {}",
                                         nx_, ny_, to_string(precision_), rule,
                                         context_->properties().deviceName));
}

Window FrameProgram::whole(const Allocation& allocation) const {
  if (allocation.size > context_->limits().maxStorageBufferRange) {
    refuse(fmt::format("an array of {} bytes exceeds the device's maxStorageBufferRange of {} bytes",
                       allocation.size, context_->limits().maxStorageBufferRange));
  }
  return {allocation.buffer, 0, allocation.size};
}

// `bound` bindings for `count` planes: pairs bind their 4 planes twice over, so that every
// binding the shader declares is valid.
Planes FrameProgram::planes(const Allocation& allocation, int count, int bound,
                            VkDeviceSize plane_bytes, VkDeviceSize word_bytes) const {
  const VkDeviceSize alignment = std::max<VkDeviceSize>(1, context_->limits().minStorageBufferOffsetAlignment);
  Planes out;
  if (plane_bytes % alignment != 0) {
    out.windows.assign(std::size_t(bound), whole(allocation));
    out.stride = std::uint32_t(plane_bytes / word_bytes);
    return out;
  }
  if (plane_bytes > context_->limits().maxStorageBufferRange) {
    refuse(fmt::format("a plane of {} bytes exceeds the device's maxStorageBufferRange of {} bytes",
                       plane_bytes, context_->limits().maxStorageBufferRange));
  }
  for (int p = 0; p < bound; ++p) {
    out.windows.push_back({allocation.buffer, VkDeviceSize(p % count) * plane_bytes, plane_bytes});
  }
  return out;
}

FrameProgram::FrameProgram(std::shared_ptr<const Context> context, const FftProgram& transform,
                           const DeviceFrameTables& tables)
    : context_(std::move(context)),
      transform_(transform),
      precision_(tables.precision),
      pairs_(tables.pairs),
      nx_(std::uint32_t(tables.nx)),
      ny_(std::uint32_t(tables.ny)),
      half_columns_(std::uint32_t(tables.nx / 2 + 1)),
      spectrum_columns_(tables.pairs ? std::uint32_t(tables.nx) : std::uint32_t(tables.nx / 2 + 1)),
      real_(real_size(tables.precision)) {
  const auto& limits = context_->limits();
  // The phases ωt reach 2⁵⁰ rad (reference::kLargestPhase) and must come out right to the
  // synthesis precision: the kernel reduces them in double (frame_evolve.comp). A device without
  // shaderFloat64 is refused; a float-float (two-float) reduction would serve it and is not
  // built yet.
  if (!context_->float64()) {
    refuse("the phases ω t are reduced in double precision on the device (|ωt| up to 2⁵⁰ rad), "
           "which needs shaderFloat64, and this device does not offer it (a float-float "
           "reduction is not implemented)");
  }
  if (limits.maxPerStageDescriptorStorageBuffers < kUnpackBuffers) {
    refuse(fmt::format("the unpack kernel binds {} storage buffers, beyond the device's "
                       "maxPerStageDescriptorStorageBuffers of {}",
                       kUnpackBuffers, limits.maxPerStageDescriptorStorageBuffers));
  }
  const TransformSpec& spec = transform_.spec();
  const bool expected = spec.nx == tables.nx && spec.ny == tables.ny &&
                        spec.precision == precision_ && spec.direction == Direction::inverse &&
                        (pairs_ ? spec.kind == Kind::c2c && spec.howmany == 4 &&
                                      spec.placement == Placement::in_place
                                : spec.kind == Kind::c2r && spec.howmany == kRealFields &&
                                      spec.placement == Placement::out_of_place);
  if (!expected) {
    throw InternalError("vulkan frame: the plan " + spec.describe() +
                        " is not the synthesizer's batch of inverse transforms");
  }

  // The tables, in the shaders' layouts: (a, b) interleaved per entry (in fp32 two complex
  // words), then λ/|k| and ω.
  const std::size_t entries = std::size_t(half_columns_) * ny_;
  const auto* a_re = static_cast<const std::byte*>(tables.a_re);
  const auto* a_im = static_cast<const std::byte*>(tables.a_im);
  const auto* b_re = static_cast<const std::byte*>(tables.b_re);
  const auto* b_im = static_cast<const std::byte*>(tables.b_im);
  std::vector<std::byte> waves(entries * 4 * real_);
  for (std::size_t e = 0; e < entries; ++e) {
    std::memcpy(&waves[(4 * e + 0) * real_], a_re + e * real_, real_);
    std::memcpy(&waves[(4 * e + 1) * real_], a_im + e * real_, real_);
    std::memcpy(&waves[(4 * e + 2) * real_], b_re + e * real_, real_);
    std::memcpy(&waves[(4 * e + 3) * real_], b_im + e * real_, real_);
  }
  struct Upload {
    Allocation* target;
    const void* data;
    std::size_t bytes;
  };
  const std::vector<Upload> uploads = {
      {&waves_, waves.data(), waves.size()},
      {&lambda_over_k_, tables.lambda_over_k, entries * real_},
      {&omega_, tables.omega, entries * sizeof(double)}};

  const VkDeviceSize count = VkDeviceSize(nx_) * ny_;
  const VkDeviceSize spectrum_plane = VkDeviceSize(spectrum_columns_) * ny_ * 2 * real_;
  const VkDeviceSize transformed_plane = pairs_ ? count * 2 * real_ : count * real_;
  fields_bytes_ = kFields * count * real_;
  // fp32 unpacks two adjacent samples per invocation (frame_unpack.comp).
  if (precision_ == Precision::f32 && count % 2 != 0) {
    refuse("the fp32 unpack takes samples two at a time, and nx·ny is odd");
  }
  try {
    std::size_t staged = 0;
    for (const auto& u : uploads) {
      *u.target = context_->allocate(u.bytes, true);
      staged += u.bytes;
    }
    spectra_ = context_->allocate(spec.input_bytes(), true);
    if (!pairs_) transformed_storage_ = context_->allocate(spec.output_bytes(), true);
    fields_ = context_->allocate(fields_bytes_, true);
    probe_ = context_->allocate(sizeof(std::uint32_t), true);
    staging_ = context_->allocate(fields_bytes_ + sizeof(std::uint32_t), false);

    // One upload for all tables, through a staging buffer freed at once.
    Allocation upload = context_->allocate(staged, false);
    std::vector<VkBufferCopy> regions;
    VkDeviceSize at = 0;
    for (const auto& u : uploads) {
      std::memcpy(static_cast<std::byte*>(upload.mapped) + at, u.data, u.bytes);
      regions.push_back({at, 0, u.bytes});
      at += u.bytes;
    }
    try {
      context_->run([&](VkCommandBuffer commands) {
        for (std::size_t i = 0; i < uploads.size(); ++i) {
          vkCmdCopyBuffer(commands, upload.buffer, uploads[i].target->buffer, 1, &regions[i]);
        }
      });
    } catch (...) {
      context_->free(upload);
      throw;
    }
    context_->free(upload);

    // The bindings. Evolution: the three tables, then the eight output planes (complex words);
    // unpack: the probe, the eight input planes and the six fields (64-bit words).
    const int planes_used = pairs_ ? 4 : kRealFields;
    const Planes spectra = planes(spectra_, planes_used, kRealFields, spectrum_plane, 2 * real_);
    const Planes inputs = planes(transformed(), planes_used, kRealFields, transformed_plane, 8);
    const Planes outputs = planes(fields_, kFields, kFields, count * real_, 8);
    std::vector<Window> evolve_windows = {whole(waves_), whole(lambda_over_k_), whole(omega_)};
    evolve_windows.insert(evolve_windows.end(), spectra.windows.begin(), spectra.windows.end());
    std::vector<Window> unpack_windows = {whole(probe_)};
    unpack_windows.insert(unpack_windows.end(), inputs.windows.begin(), inputs.windows.end());
    unpack_windows.insert(unpack_windows.end(), outputs.windows.begin(), outputs.windows.end());

    EvolveHeader evolve;
    evolve.dkx = tables.dkx;
    evolve.dky = tables.dky;
    evolve.nx = nx_;
    evolve.ny = ny_;
    evolve.half_columns = half_columns_;
    evolve.spectrum_columns = spectrum_columns_;
    evolve.plane_stride = spectra.stride;
    evolve_push_.resize(sizeof evolve + kRealFields * real_);
    std::memcpy(evolve_push_.data(), &evolve, sizeof evolve);
    std::memcpy(evolve_push_.data() + sizeof evolve, tables.field_scale, kRealFields * real_);
    UnpackHeader unpack;
    unpack.count = std::uint32_t(count);
    unpack.input_stride = inputs.stride;
    unpack.field_stride = outputs.stride;
    unpack_push_.resize(sizeof unpack + kRealFields * real_);
    std::memcpy(unpack_push_.data(), &unpack, sizeof unpack);
    std::memcpy(unpack_push_.data() + sizeof unpack, tables.inverse_scale, kRealFields * real_);

    const std::vector<std::uint32_t> specialization = {kLocalSize, pairs_ ? 1u : 0u};
    const bool f64 = precision_ == Precision::f64;
    evolve_ = &context_->pipeline(f64 ? "frame_evolve_fp64" : "frame_evolve_fp32",
                                  frame_evolve_spirv(precision_), specialization, kEvolveBuffers,
                                  0, std::uint32_t(evolve_push_.size()));
    unpack_ = &context_->pipeline(f64 ? "frame_unpack_fp64" : "frame_unpack_fp32",
                                  frame_unpack_spirv(precision_), specialization, kUnpackBuffers,
                                  0, std::uint32_t(unpack_push_.size()));
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kEvolveBuffers + kUnpackBuffers};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 2;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    check(vkCreateDescriptorPool(context_->device(), &pool_info, nullptr, &pool_), "vkCreateDescriptorPool");
    const VkDescriptorSetLayout layouts[2] = {evolve_->set_layout, unpack_->set_layout};
    VkDescriptorSetAllocateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    set_info.descriptorPool = pool_;
    set_info.descriptorSetCount = 2;
    set_info.pSetLayouts = layouts;
    VkDescriptorSet sets[2];
    check(vkAllocateDescriptorSets(context_->device(), &set_info, sets), "vkAllocateDescriptorSets");
    evolve_set_ = sets[0];
    unpack_set_ = sets[1];
    std::vector<VkDescriptorBufferInfo> infos;
    infos.reserve(evolve_windows.size() + unpack_windows.size());
    std::vector<VkWriteDescriptorSet> writes;
    const auto bind = [&](VkDescriptorSet set, const std::vector<Window>& windows) {
      for (std::uint32_t b = 0; b < windows.size(); ++b) {
        infos.push_back({windows[b].buffer, windows[b].offset, windows[b].range});
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstSet = set;
        write.dstBinding = b;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        write.pBufferInfo = &infos.back();
        writes.push_back(write);
      }
    };
    bind(evolve_set_, evolve_windows);
    bind(unpack_set_, unpack_windows);
    vkUpdateDescriptorSets(context_->device(), std::uint32_t(writes.size()), writes.data(), 0, nullptr);
    workspace_ = transform_.acquire();
  } catch (...) {
    release();  // what was made so far; every handle starts null
    throw;
  }
}

FrameProgram::~FrameProgram() { release(); }

void FrameProgram::release() {
  if (workspace_) transform_.release(workspace_);
  workspace_ = nullptr;
  if (pool_) vkDestroyDescriptorPool(context_->device(), pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
  for (Allocation* a : {&waves_, &lambda_over_k_, &omega_, &spectra_, &transformed_storage_,
                        &fields_, &probe_, &staging_}) {
    if (a->buffer) context_->free(*a);
  }
}

// `invocations` one-dimensional invocations, as workgroups along x, and along y beyond
// maxComputeWorkGroupCount[0] (the kernels count x fastest, then y).
void FrameProgram::dispatch(VkCommandBuffer commands, std::uint64_t invocations) const {
  const auto& limits = context_->limits();
  const std::uint64_t groups = (invocations + kLocalSize - 1) / kLocalSize;
  const std::uint64_t x = std::min<std::uint64_t>(groups, limits.maxComputeWorkGroupCount[0]);
  const std::uint64_t y = (groups + x - 1) / x;
  if (y > limits.maxComputeWorkGroupCount[1]) {
    refuse(fmt::format("{} workgroups exceed the device's maxComputeWorkGroupCount {}×{}", groups,
                       limits.maxComputeWorkGroupCount[0], limits.maxComputeWorkGroupCount[1]));
  }
  vkCmdDispatch(commands, std::uint32_t(x), std::uint32_t(y), 1);
}

void FrameProgram::record_frame(VkCommandBuffer commands, double t, VkQueryPool stamps) const {
  // After whatever the queue ran before (the previous frame read these buffers): a barrier,
  // then the probe's count back to 0. The evolution does not touch the probe; the barriers
  // FftProgram::record puts before its passes order the fill before the unpack.
  Context::barrier(commands);
  vkCmdFillBuffer(commands, probe_.buffer, 0, VK_WHOLE_SIZE, 0);
  std::vector<std::byte> push = evolve_push_;
  std::memcpy(push.data() + offsetof(EvolveHeader, t), &t, sizeof t);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, evolve_->pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, evolve_->layout, 0, 1,
                          &evolve_set_, 0, nullptr);
  vkCmdPushConstants(commands, evolve_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                     std::uint32_t(push.size()), push.data());
  dispatch(commands, std::uint64_t(half_columns_) * ny_);
  if (stamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, stamps, 1);
  // A barrier before each pass (the evolution's writes before the first) and after the last.
  transform_.record(commands, *workspace_, spectra_.buffer, transformed().buffer);
  if (stamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, stamps, 2);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, unpack_->pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, unpack_->layout, 0, 1,
                          &unpack_set_, 0, nullptr);
  vkCmdPushConstants(commands, unpack_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                     std::uint32_t(unpack_push_.size()), unpack_push_.data());
  // fp32: two samples per invocation.
  const std::uint64_t samples = std::uint64_t(nx_) * ny_;
  dispatch(commands, precision_ == Precision::f32 ? samples / 2 : samples);
}

void stamp(const Slot& slot, std::uint32_t query) {
  if (slot.timestamps) {
    vkCmdWriteTimestamp(slot.commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, slot.timestamps, query);
  }
}

std::size_t FrameProgram::evaluate(double t, std::span<std::byte> fields,
                                   FrameTimings& timings) const {
  if (fields.size() < fields_bytes_) {
    throw InvalidInput(fmt::format("vulkan frame: output of {} bytes for a frame of {}",
                                   fields.size(), fields_bytes_));
  }
  std::lock_guard lock(mutex_);
  struct SlotGuard {
    const Context& context;
    Slot slot;
    ~SlotGuard() { context.release(slot); }
  } guard{*context_, context_->acquire()};
  const Slot& slot = guard.slot;
  check(vkResetCommandBuffer(slot.commands, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(slot.commands, &begin), "vkBeginCommandBuffer");
  if (slot.timestamps) vkCmdResetQueryPool(slot.commands, slot.timestamps, 0, kTimestamps);
  stamp(slot, 0);
  record_frame(slot.commands, t, slot.timestamps);
  stamp(slot, 3);
  Context::barrier(slot.commands);  // the unpack's writes before the copies read them
  const VkBufferCopy frame{0, 0, fields_bytes_};
  vkCmdCopyBuffer(slot.commands, fields_.buffer, staging_.buffer, 1, &frame);
  const VkBufferCopy probe{0, fields_bytes_, sizeof(std::uint32_t)};
  vkCmdCopyBuffer(slot.commands, probe_.buffer, staging_.buffer, 1, &probe);
  VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(slot.commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       0, 1, &host, 0, nullptr, 0, nullptr);
  check(vkEndCommandBuffer(slot.commands), "vkEndCommandBuffer");
  context_->submit_and_wait(slot);
  const auto* staged = static_cast<const std::byte*>(staging_.mapped);
  std::memcpy(fields.data(), staged, fields_bytes_);
  std::uint32_t non_finite = 0;
  std::memcpy(&non_finite, staged + fields_bytes_, sizeof non_finite);
  const auto seconds = context_->timestamp_seconds(slot);
  timings.device_seconds = seconds[3] - seconds[0];
  timings.evolve_seconds = seconds[1] - seconds[0];
  timings.unpack_seconds = seconds[3] - seconds[2];
  return non_finite;
}

}  // namespace

}  // namespace swell::impls::vk

namespace swell::impls {

std::unique_ptr<DeviceFrame> make_vulkan_frame(const Backend& backend, const Plan& plan,
                                               const DeviceFrameTables& tables) {
  auto context = vk::context_of(backend);
  const vk::FftProgram* program = vk::program_of(plan);
  if (!context || !program) {
    throw InvalidInput("the vulkan frame needs a vulkan backend and one of its plans, not " +
                       backend.name());
  }
  return std::make_unique<vk::FrameProgram>(std::move(context), *program, tables);
}

}  // namespace swell::impls
