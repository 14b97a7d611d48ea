// The synthesizer's frame on a Vulkan device (docs/synthesis.md §vulkan: a device
// backend's frame is one submission). At construction the tables of the waves go to device
// memory once; each frame is then one command buffer and one fence wait:
//
//   evolution (impls/shaders/frame_evolve.comp)    h̃(k, t) of the half spectrum, one phase a wave
//   the frame program (FftProgram with FrameIo)    the batch of inverse transforms, whose first
//                                                  pass makes the packed spectra from h̃ and whose
//                                                  last pass leaves the six fields in its
//                                                  destination and counts non-finite values
//                                                  (fft_lines.comp, SWELL_FRAME)
//   the fields to the host                         read where they are when the device's memory
//                                                  is host-readable (lavapipe, integrated GPUs),
//                                                  else copied through a staging buffer
//
// On lavapipe a frame costs what its storage-buffer accesses cost (docs/vulkan.md §Kernels):
// a kernel that wrote the eight packed spectra and one that read the transforms back to make
// the fields cost 1.4–1.6× the transforms themselves; fused into the passes, the frame reads
// and writes little more than the bare transforms do (1.1–1.3× from 512², docs/synthesis.md).
//
// record_frame() records the first two alone and leaves the fields in device memory: a
// device-only evaluation (a renderer that samples the fields where they are) is that call into
// its own command buffer, without the host ever touching the frame.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "../device_frame.hpp"
#include "fft.hpp"

namespace swell::impls::vk {
namespace {

constexpr int kRealFields = 8;  // packing order of synthesizer.cpp
constexpr int kFields = 6;      // reference::kAllFields

// Invocations per workgroup of the evolution kernel. It uses no shared memory and no barrier,
// so the size only sets how work is handed out: 128 is a multiple of every GPU's subgroup
// (32, 64) and of lavapipe's 8 lanes, and few enough that the padding of the last workgroup
// costs little.
constexpr std::uint32_t kLocalSize = 128;

// frame_evolve.comp takes four entries an invocation, and the tables are padded to whole
// workgroups of it.
constexpr std::uint32_t kEntriesPerGroup = 4 * kLocalSize;

class FrameProgram final : public DeviceFrame {
 public:
  FrameProgram(std::shared_ptr<const Context> context, const TransformSpec& spec, bool subgroups,
               const DeviceFrameTables& tables);
  ~FrameProgram() override;
  FrameProgram(const FrameProgram&) = delete;
  FrameProgram& operator=(const FrameProgram&) = delete;

  std::size_t evaluate(double t, std::span<std::byte> fields, FrameTimings& timings) const override;

 private:
  // Records the frame at t — evolution, then the frame program — into `commands`, leaving the
  // six fields in field_memory() and the count of non-finite values in probe_, with a barrier after
  // the last pass. With `stamps`, timestamp 1 of that pool is written after the evolution and
  // timestamp 2 after the last pass. The caller holds mutex_ until the submission has
  // completed: the buffers and the program's workspace are this frame's alone.
  void record_frame(VkCommandBuffer commands, double t, VkQueryPool stamps) const;
  Window whole(const Allocation& allocation) const;
  [[noreturn]] void refuse(const std::string& rule) const;
  void release();
  // Where the fields are on the device: pairs, the packed spectra's first three planes; c2r,
  // the output's first six.
  const Allocation& field_memory() const { return pairs_ ? planes_ : fields_; }
  // The three pair planes of the device's fields into the six fields of the frame's layout.
  template <typename Real>
  void split_pairs(const std::byte* pairs, std::byte* fields) const;

  std::shared_ptr<const Context> context_;
  Precision precision_;
  bool pairs_;
  std::uint32_t nx_, ny_;
  std::uint32_t entries_ = 0;  // of the half spectrum, (nx/2 + 1) · ny, padded to whole workgroups
  std::uint32_t evolve_groups_x_ = 0, evolve_groups_y_ = 0;
  std::size_t real_;
  VkDeviceSize fields_bytes_ = 0;    // the six fields the caller gets
  // Device memory: the waves and ω (written once), the evolution's table (h̃, each frame), the
  // packed spectra (pairs: the in-place c2c batch, where the fields end), the c2r packing's
  // output (the fields, then two scratch planes), the probe, the frame's constants
  // (host-visible uniform), and staging where the fields or the probe are not host-readable.
  Allocation waves_, omega_, table_, planes_, fields_, probe_, constants_, staging_;
  std::optional<FftProgram> program_;
  const Pipeline* evolve_ = nullptr;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet evolve_set_ = VK_NULL_HANDLE;
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

FrameProgram::FrameProgram(std::shared_ptr<const Context> context, const TransformSpec& spec,
                           bool subgroups, const DeviceFrameTables& tables)
    : context_(std::move(context)),
      precision_(tables.precision),
      pairs_(tables.pairs),
      nx_(std::uint32_t(tables.nx)),
      ny_(std::uint32_t(tables.ny)),

      real_(real_size(tables.precision)) {
  const auto& limits = context_->limits();
  // The evolution's workgroups, along x and, beyond maxComputeWorkGroupCount[0], y (the kernel
  // counts x fastest, then y); the tables are padded to as many entries as they take.
  const std::uint64_t entries = std::uint64_t(tables.nx / 2 + 1) * std::uint64_t(tables.ny);
  const std::uint64_t groups = (entries + kEntriesPerGroup - 1) / kEntriesPerGroup;
  evolve_groups_x_ = std::uint32_t(std::min<std::uint64_t>(groups, limits.maxComputeWorkGroupCount[0]));
  evolve_groups_y_ = std::uint32_t((groups + evolve_groups_x_ - 1) / evolve_groups_x_);
  if (evolve_groups_y_ > limits.maxComputeWorkGroupCount[1]) {
    refuse(fmt::format("{} workgroups exceed the device's maxComputeWorkGroupCount {}×{}", groups,
                       limits.maxComputeWorkGroupCount[0], limits.maxComputeWorkGroupCount[1]));
  }
  entries_ = evolve_groups_x_ * evolve_groups_y_ * kEntriesPerGroup;
  // The phases ωt reach 2⁵⁰ rad (reference::kLargestPhase) and must come out right to the
  // synthesis precision: the kernel reduces them in double (frame_evolve.comp). A device without
  // shaderFloat64 is refused; a float-float (two-float) reduction would serve it and is not
  // built yet.
  if (!context_->float64()) {
    refuse("the phases ω t are reduced in double precision on the device (|ωt| up to 2⁵⁰ rad), "
           "which needs shaderFloat64, and this device does not offer it (a float-float "
           "reduction is not implemented)");
  }
  if (limits.maxPerStageDescriptorStorageBuffers < 5) {
    refuse(fmt::format("the frame's first and last passes bind 5 storage buffers, beyond the "
                       "device's maxPerStageDescriptorStorageBuffers of {}",
                       limits.maxPerStageDescriptorStorageBuffers));
  }
  const bool expected = spec.nx == tables.nx && spec.ny == tables.ny &&
                        spec.precision == precision_ && spec.direction == Direction::inverse &&
                        (pairs_ ? spec.kind == Kind::c2c && spec.howmany == 4 &&
                                      spec.placement == Placement::in_place
                                : spec.kind == Kind::c2r && spec.howmany == kRealFields &&
                                      spec.placement == Placement::out_of_place);
  if (!expected) {
    throw InternalError("vulkan frame: the transform " + spec.describe() +
                        " is not the synthesizer's batch of inverse transforms");
  }

  // The tables, in frame_evolve.comp's layouts: (a, b) per half-spectrum entry (in fp32 two
  // complex words), and ω.
  const auto* a_re = static_cast<const std::byte*>(tables.a_re);
  const auto* a_im = static_cast<const std::byte*>(tables.a_im);
  const auto* b_re = static_cast<const std::byte*>(tables.b_re);
  const auto* b_im = static_cast<const std::byte*>(tables.b_im);
  std::vector<std::byte> waves(entries_ * 4 * real_);  // the padding: zeros (h̃ = 0 there)
  std::vector<double> omega(entries_, 0.0);
  std::copy(tables.omega, tables.omega + entries, omega.begin());
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
  const std::vector<Upload> uploads = {{&waves_, waves.data(), waves.size()},
                                       {&omega_, omega.data(), omega.size() * sizeof(double)}};

  // The fields on the device (fft_lines.comp, FRAME_FIELDS) are where the last pass stores:
  // pairs, in place over the packed spectra, whose first three planes then hold (h, slope_x),
  // (slope_y, disp_x), (disp_y, J), which evaluate() splits into the six fields; c2r, the eight
  // real planes of the output, the first six of them the six fields.
  const VkDeviceSize count = VkDeviceSize(nx_) * ny_;
  fields_bytes_ = kFields * count * real_;
  try {
    std::size_t staged = 0;
    for (const auto& u : uploads) {
      *u.target = context_->allocate(u.bytes, true);
      staged += u.bytes;
    }
    table_ = context_->allocate(entries_ * 2 * real_, true);  // h̃, written by every frame's evolution
    if (pairs_) planes_ = context_->allocate_readable(spec.input_bytes());
    else fields_ = context_->allocate_readable(spec.output_bytes());
    probe_ = context_->allocate_readable(sizeof(std::uint32_t));
    if (!field_memory().mapped || !probe_.mapped) {
      staging_ = context_->allocate(fields_bytes_ + sizeof(std::uint32_t), false);
    }

    // The frame's constants (fft_lines.comp's FrameConstants, std140): the eight field scales,
    // the eight inverse scales, Δkx, Δky and λ. Host-visible and written once, before any
    // submission reads them.
    constants_ = context_->allocate(16 * real_ + 3 * sizeof(double), false);
    auto* constants = static_cast<std::byte*>(constants_.mapped);
    std::memcpy(constants, tables.field_scale, kRealFields * real_);
    std::memcpy(constants + kRealFields * real_, tables.inverse_scale, kRealFields * real_);
    const double numbers[3] = {tables.dkx, tables.dky, tables.choppiness};
    std::memcpy(constants + 16 * real_, numbers, sizeof numbers);

    // One upload for the waves and ω, through a staging buffer freed at once.
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

    FrameIo io;
    io.pairs = pairs_;
    io.table = whole(table_);
    io.probe = whole(probe_);
    io.constants = {constants_.buffer, 0, constants_.size};
    program_.emplace(context_, spec, subgroups, &io);

    const bool f64 = precision_ == Precision::f64;
    PipelineShape shape;
    shape.bindings.assign(3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);  // the waves, ω, the table
    shape.push_bytes = sizeof(double);  // t
    evolve_ = &context_->pipeline(f64 ? "frame_evolve_fp64" : "frame_evolve_fp32",
                                  frame_evolve_spirv(precision_), {kLocalSize}, shape);
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    check(vkCreateDescriptorPool(context_->device(), &pool_info, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    set_info.descriptorPool = pool_;
    set_info.descriptorSetCount = 1;
    set_info.pSetLayouts = &evolve_->set_layout;
    check(vkAllocateDescriptorSets(context_->device(), &set_info, &evolve_set_), "vkAllocateDescriptorSets");
    const Window windows[3] = {whole(waves_), whole(omega_), whole(table_)};
    VkDescriptorBufferInfo infos[3];
    VkWriteDescriptorSet writes[3];
    for (std::uint32_t b = 0; b < 3; ++b) {
      infos[b] = {windows[b].buffer, windows[b].offset, windows[b].range};
      writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[b].dstSet = evolve_set_;
      writes[b].dstBinding = b;
      writes[b].descriptorCount = 1;
      writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[b].pBufferInfo = &infos[b];
    }
    vkUpdateDescriptorSets(context_->device(), 3, writes, 0, nullptr);
    workspace_ = program_->acquire();
  } catch (...) {
    release();  // what was made so far; every handle starts null
    throw;
  }
}

FrameProgram::~FrameProgram() { release(); }

template <typename Real>
void FrameProgram::split_pairs(const std::byte* pairs, std::byte* fields) const {
  const std::size_t count = std::size_t(nx_) * ny_;
  if (reinterpret_cast<std::uintptr_t>(fields) % alignof(Real) != 0) {
    // The caller's bytes need not be aligned for Real: then the values go through memcpy.
    for (std::size_t p = 0; p < kFields / 2; ++p) {
      const std::byte* in = pairs + 2 * p * count * sizeof(Real);
      std::byte* first = fields + 2 * p * count * sizeof(Real);
      for (std::size_t s = 0; s < count; ++s) {
        std::memcpy(first + s * sizeof(Real), in + 2 * s * sizeof(Real), sizeof(Real));
        std::memcpy(first + (count + s) * sizeof(Real), in + (2 * s + 1) * sizeof(Real), sizeof(Real));
      }
    }
    return;
  }
  for (std::size_t p = 0; p < kFields / 2; ++p) {
    const Real* __restrict in = reinterpret_cast<const Real*>(pairs) + 2 * p * count;
    Real* __restrict first = reinterpret_cast<Real*>(fields) + 2 * p * count;
    Real* __restrict second = first + count;
    for (std::size_t s = 0; s < count; ++s) {
      first[s] = in[2 * s];
      second[s] = in[2 * s + 1];
    }
  }
}

void FrameProgram::release() {
  if (workspace_) program_->release(workspace_);
  workspace_ = nullptr;
  program_.reset();
  if (pool_) vkDestroyDescriptorPool(context_->device(), pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
  for (Allocation* a : {&waves_, &omega_, &table_, &planes_, &fields_, &probe_, &constants_, &staging_}) {
    if (a->buffer) context_->free(*a);
  }
}

void FrameProgram::record_frame(VkCommandBuffer commands, double t, VkQueryPool stamps) const {
  // After whatever the queue ran before (the previous frame read these buffers): a barrier,
  // then the probe's count back to 0. The evolution does not touch the probe; the barrier the
  // program puts before its first pass orders the fill before the last pass's counts.
  Context::barrier(commands);
  vkCmdFillBuffer(commands, probe_.buffer, 0, VK_WHOLE_SIZE, 0);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, evolve_->pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, evolve_->layout, 0, 1,
                          &evolve_set_, 0, nullptr);
  vkCmdPushConstants(commands, evolve_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof t, &t);
  vkCmdDispatch(commands, evolve_groups_x_, evolve_groups_y_, 1);
  if (stamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, stamps, 1);
  // A barrier before each pass (the evolution's writes before the first) and after the last.
  // The table stands for the program's input (its first pass reads the table); its output is
  // where the fields are.
  program_->record(commands, *workspace_, table_.buffer, field_memory().buffer);
  if (stamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, stamps, 2);
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
  if (slot.timestamps) vkCmdResetQueryPool(slot.commands, slot.timestamps, 0, 3);
  stamp(slot, 0);
  record_frame(slot.commands, t, slot.timestamps);  // ends with a barrier
  // Where the fields or the probe are not host-readable, a copy to the staging buffer.
  if (!field_memory().mapped) {
    const VkBufferCopy frame{0, 0, fields_bytes_};
    vkCmdCopyBuffer(slot.commands, field_memory().buffer, staging_.buffer, 1, &frame);
  }
  if (!probe_.mapped) {
    const VkBufferCopy probe{0, fields_bytes_, sizeof(std::uint32_t)};
    vkCmdCopyBuffer(slot.commands, probe_.buffer, staging_.buffer, 1, &probe);
  }
  Context::host_barrier(slot.commands);
  check(vkEndCommandBuffer(slot.commands), "vkEndCommandBuffer");
  context_->submit_and_wait(slot);
  const auto* staged = static_cast<const std::byte*>(staging_.mapped);
  const std::byte* device = field_memory().mapped ? static_cast<const std::byte*>(field_memory().mapped) : staged;
  if (pairs_) {
    if (precision_ == Precision::f32) split_pairs<float>(device, fields.data()); else split_pairs<double>(device, fields.data());
  } else {
    std::memcpy(fields.data(), device, fields_bytes_);
  }
  std::uint32_t non_finite = 0;
  std::memcpy(&non_finite, probe_.mapped ? probe_.mapped : staged + fields_bytes_, sizeof non_finite);
  const auto seconds = context_->timestamp_seconds(slot, 3);
  timings.device_seconds = seconds[2] - seconds[0];
  timings.evolve_seconds = seconds[1] - seconds[0];
  timings.transforms_seconds = seconds[2] - seconds[1];
  return non_finite;
}

}  // namespace

}  // namespace swell::impls::vk

namespace swell::impls {

std::unique_ptr<DeviceFrame> make_vulkan_frame(const Backend& backend, const TransformSpec& spec,
                                               const DeviceFrameTables& tables) {
  auto context = vk::context_of(backend);
  if (!context) {
    throw InvalidInput("the vulkan frame needs a vulkan backend, not " + backend.name());
  }
  backend.validate(spec);
  return std::make_unique<vk::FrameProgram>(std::move(context), spec, vk::subgroups_of(backend), tables);
}

}  // namespace swell::impls
