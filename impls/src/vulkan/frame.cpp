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

// The push constants of frame_evolve.comp and frame_unpack.comp, in their std430 layout.
struct EvolveConstants {
  double t = 0;
  std::uint32_t nx = 0, ny = 0, half_columns = 0, spectrum_columns = 0;
  std::uint32_t base[kRealFields] = {};
};
static_assert(sizeof(EvolveConstants) == 56 && offsetof(EvolveConstants, base) == 24);
struct UnpackConstants {
  std::uint32_t count = 0;
  std::uint32_t input_base[kRealFields] = {};
  std::uint32_t field_base[kFields] = {};
};
static_assert(sizeof(UnpackConstants) == 60 && offsetof(UnpackConstants, field_base) == 36);

// Storage buffers each kernel binds (frame_evolve.comp: 4 tables and 8 planes; frame_unpack.comp:
// the tables, the probe, 8 input planes, 6 fields).
constexpr std::uint32_t kEvolveBuffers = 4 + kRealFields;
constexpr std::uint32_t kUnpackBuffers = 2 + kRealFields + kFields;

// A binding of `bytes` bytes from `start` in a buffer: the offset rounded down to the device's
// minStorageBufferOffsetAlignment, and the element where the data starts inside the window
// (0 whenever a plane's size is a multiple of the alignment, as on every grid past a few
// samples; a tiny grid's planes share a window).
struct Window {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, range = 0;
  std::uint32_t base = 0;
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
  // unpack (the caller's next use decides which one it needs). The caller holds mutex_ until
  // the submission has completed: the buffers and the transform's workspace are this
  // program's alone.
  void record_frame(VkCommandBuffer commands, double t) const;
  Window window(const Allocation& allocation, VkDeviceSize start, VkDeviceSize bytes) const;
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
  Allocation waves_, lambda_over_k_, omega_, tables_, spectra_, transformed_storage_, fields_,
      probe_;
  Allocation staging_;  // host visible: the six fields, then the probe's count
  const Allocation& transformed() const { return pairs_ ? spectra_ : transformed_storage_; }
  const Pipeline* evolve_ = nullptr;
  const Pipeline* unpack_ = nullptr;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet evolve_set_ = VK_NULL_HANDLE, unpack_set_ = VK_NULL_HANDLE;
  EvolveConstants evolve_constants_;
  UnpackConstants unpack_constants_;
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

Window FrameProgram::window(const Allocation& allocation, VkDeviceSize start,
                            VkDeviceSize bytes) const {
  const VkDeviceSize alignment = std::max<VkDeviceSize>(1, context_->limits().minStorageBufferOffsetAlignment);
  Window w;
  w.buffer = allocation.buffer;
  w.offset = start / alignment * alignment;
  w.range = start + bytes - w.offset;
  w.base = std::uint32_t((start - w.offset) / real_);
  if (w.range > context_->limits().maxStorageBufferRange) {
    refuse(fmt::format("an array of {} bytes exceeds the device's maxStorageBufferRange of {} bytes",
                       w.range, context_->limits().maxStorageBufferRange));
  }
  return w;
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

  // The tables, in the shaders' layouts: (a, b) interleaved per entry, then λ/|k|, ω, and the
  // scales with kx and ky.
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
  std::vector<std::byte> table_bytes((2 * kRealFields + nx_ + ny_) * real_);
  std::memcpy(&table_bytes[0], tables.field_scale, kRealFields * real_);
  std::memcpy(&table_bytes[kRealFields * real_], tables.inverse_scale, kRealFields * real_);
  std::memcpy(&table_bytes[2 * kRealFields * real_], tables.kx, nx_ * real_);
  std::memcpy(&table_bytes[(2 * kRealFields + nx_) * real_], tables.ky, ny_ * real_);
  struct Upload {
    Allocation* target;
    const void* data;
    std::size_t bytes;
  };
  const std::vector<Upload> uploads = {
      {&waves_, waves.data(), waves.size()},
      {&lambda_over_k_, tables.lambda_over_k, entries * real_},
      {&omega_, tables.omega, entries * sizeof(double)},
      {&tables_, table_bytes.data(), table_bytes.size()}};

  const VkDeviceSize count = VkDeviceSize(nx_) * ny_;
  const VkDeviceSize spectrum_plane = VkDeviceSize(spectrum_columns_) * ny_ * 2 * real_;
  const VkDeviceSize transformed_plane = pairs_ ? count * 2 * real_ : count * real_;
  fields_bytes_ = kFields * count * real_;
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

    // The bindings. Evolution: tables 0–3, then the eight output planes (pairs: four, bound
    // twice over so that every binding the shader declares is valid).
    std::vector<Window> evolve_windows = {
        window(waves_, 0, waves_.size), window(lambda_over_k_, 0, lambda_over_k_.size),
        window(omega_, 0, omega_.size), window(tables_, 0, tables_.size)};
    std::vector<Window> unpack_windows = {window(tables_, 0, tables_.size),
                                          window(probe_, 0, probe_.size)};
    const int planes = pairs_ ? 4 : kRealFields;
    for (int p = 0; p < kRealFields; ++p) {
      const Window s = window(spectra_, VkDeviceSize(p % planes) * spectrum_plane, spectrum_plane);
      evolve_windows.push_back(s);
      evolve_constants_.base[p] = s.base;
      const Window d = window(transformed(), VkDeviceSize(p % planes) * transformed_plane, transformed_plane);
      unpack_windows.push_back(d);
      unpack_constants_.input_base[p] = d.base;
    }
    for (int f = 0; f < kFields; ++f) {
      const Window w = window(fields_, VkDeviceSize(f) * count * real_, count * real_);
      unpack_windows.push_back(w);
      unpack_constants_.field_base[f] = w.base;
    }
    evolve_constants_.nx = nx_;
    evolve_constants_.ny = ny_;
    evolve_constants_.half_columns = half_columns_;
    evolve_constants_.spectrum_columns = spectrum_columns_;
    unpack_constants_.count = std::uint32_t(count);

    const std::vector<std::uint32_t> specialization = {kLocalSize, pairs_ ? 1u : 0u};
    const bool f64 = precision_ == Precision::f64;
    evolve_ = &context_->pipeline(f64 ? "frame_evolve_fp64" : "frame_evolve_fp32",
                                  frame_evolve_spirv(precision_), specialization, kEvolveBuffers,
                                  0, sizeof(EvolveConstants));
    unpack_ = &context_->pipeline(f64 ? "frame_unpack_fp64" : "frame_unpack_fp32",
                                  frame_unpack_spirv(precision_), specialization, kUnpackBuffers,
                                  0, sizeof(UnpackConstants));
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
  for (Allocation* a : {&waves_, &lambda_over_k_, &omega_, &tables_, &spectra_,
                        &transformed_storage_, &fields_, &probe_, &staging_}) {
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

void FrameProgram::record_frame(VkCommandBuffer commands, double t) const {
  // After whatever the queue ran before (the previous frame read these buffers): a barrier,
  // then the probe's count back to 0. The evolution does not touch the probe; the barriers
  // FftProgram::record puts before its passes order the fill before the unpack.
  Context::barrier(commands);
  vkCmdFillBuffer(commands, probe_.buffer, 0, VK_WHOLE_SIZE, 0);
  EvolveConstants constants = evolve_constants_;
  constants.t = t;
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, evolve_->pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, evolve_->layout, 0, 1,
                          &evolve_set_, 0, nullptr);
  vkCmdPushConstants(commands, evolve_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof constants,
                     &constants);
  dispatch(commands, std::uint64_t(half_columns_) * ny_);
  // A barrier before each pass (the evolution's writes before the first) and after the last.
  transform_.record(commands, *workspace_, spectra_.buffer, transformed().buffer);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, unpack_->pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, unpack_->layout, 0, 1,
                          &unpack_set_, 0, nullptr);
  vkCmdPushConstants(commands, unpack_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                     sizeof unpack_constants_, &unpack_constants_);
  dispatch(commands, std::uint64_t(nx_) * ny_);
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
  record_frame(slot.commands, t);
  Context::barrier(slot.commands);  // the unpack's writes before the copies read them
  stamp(slot, 1);
  const VkBufferCopy frame{0, 0, fields_bytes_};
  vkCmdCopyBuffer(slot.commands, fields_.buffer, staging_.buffer, 1, &frame);
  const VkBufferCopy probe{0, fields_bytes_, sizeof(std::uint32_t)};
  vkCmdCopyBuffer(slot.commands, probe_.buffer, staging_.buffer, 1, &probe);
  VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(slot.commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       0, 1, &host, 0, nullptr, 0, nullptr);
  stamp(slot, 2);
  stamp(slot, 3);
  check(vkEndCommandBuffer(slot.commands), "vkEndCommandBuffer");
  context_->submit_and_wait(slot);
  const auto* staged = static_cast<const std::byte*>(staging_.mapped);
  std::memcpy(fields.data(), staged, fields_bytes_);
  std::uint32_t non_finite = 0;
  std::memcpy(&non_finite, staged + fields_bytes_, sizeof non_finite);
  const auto seconds = context_->timestamp_seconds(slot);
  timings.device_seconds = seconds[1] - seconds[0];
  timings.download_seconds = seconds[2] - seconds[1];
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
