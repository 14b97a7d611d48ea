// The vulkan backend (docs/vulkan.md): plans as programs of line-FFT passes on the device.
#include "fft.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <complex>
#include <cstring>

#include <fmt/format.h>

#include "../backends/backends.hpp"
#include "swell/impls/vulkan.hpp"

namespace swell::impls::vk {
namespace {

// Flags of impls/shaders/fft_lines.comp.
constexpr std::uint32_t kInverse = 1, kRealInput = 2, kHermitian = 4, kRealOutput = 8,
                        kLimit = 16, kSplitTwiddle = 32, kSplitByHi = 64,
                        kSourceLineFastest = 128, kDestinationLineFastest = 256,
                        kFrameSource = 512, kFrameFields = 1024, kFrameJacobian = 2048;

// Positions in a pass's specialization constants (fft_lines.comp's constant_id): the five of
// the shape, then PassConstants (5 … 19), PING_PONG and RADIX8_STAGES; a frame pass appends
// FRAME_NY, PAIRS, JACOBIAN_FIRST and BATCH_IN_X (22 … 25).
constexpr std::size_t kInBatchConstant = 9, kFlagsConstant = 16, kJacobianFirstConstant = 24;

// Bindings of fft_lines.comp: source, destination (dynamic: a batch beyond one binding is
// bound one transform at a time), the two twiddle tables; a frame pass adds the probe and the
// frame's constants (uniform).
PipelineShape line_shape(bool shuffle, bool frame) {
  PipelineShape shape;
  shape.bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC,
                    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  if (frame) {
    shape.bindings.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    shape.bindings.push_back(VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    shape.dispatch_base = true;
  }
  shape.full_subgroups = shuffle;
  return shape;
}

std::uint32_t log2_of(std::uint32_t n) { return std::uint32_t(std::countr_zero(n)); }

// The longest line one pass holds: its complex numbers in shared memory, 16 per invocation.
std::uint32_t shared_points(const Context& context, Precision precision) {
  const auto& limits = context.limits();
  const std::uint32_t invocations =
      std::min(limits.maxComputeWorkGroupInvocations, limits.maxComputeWorkGroupSize[0]);
  return std::bit_floor(std::min(limits.maxComputeSharedMemorySize /
                                     std::uint32_t(2 * real_size(precision)),
                                 16 * invocations));
}

}  // namespace

FftProgram::FftProgram(std::shared_ptr<const Context> context, const TransformSpec& spec,
                       bool subgroups, const FrameIo* frame)
    : context_(std::move(context)), spec_(spec), subgroups_(subgroups) {
  if (frame) frame_ = *frame;
  const auto& limits = context_->limits();
  const std::size_t real = real_size(spec.precision);
  const std::uint32_t nx = std::uint32_t(spec.nx), ny = std::uint32_t(spec.ny);
  const std::uint32_t half = nx / 2 + 1;
  const auto refuse = [&](const std::string& rule) {
    throw UnsupportedTransform("vulkan: " + spec.describe() + ": " + rule + " on " +
                               context_->properties().deviceName);
  };
  if (spec.precision == Precision::f64 && !context_->float64()) {
    refuse("fp64 needs shaderFloat64, which this device does not offer");
  }
  // One binding of a storage buffer reaches maxStorageBufferRange bytes: each transform of the
  // batch (and, for one dispatch for the whole batch, the batch) must fit.
  const VkDeviceSize range = limits.maxStorageBufferRange;
  const VkDeviceSize largest_transform =
      std::max<VkDeviceSize>(std::size_t(nx) * ny * 2 * real, std::max(spec.input_bytes(), spec.output_bytes()) / spec.howmany);
  if (largest_transform > range) {
    refuse(fmt::format("one transform's array of {} bytes exceeds the device's "
                       "maxStorageBufferRange of {} bytes", largest_transform, range));
  }
  per_batch_ = largest_transform * VkDeviceSize(spec.howmany) > range;
  if (!per_batch_ && std::uint32_t(spec.howmany) > limits.maxComputeWorkGroupCount[2]) {
    refuse(fmt::format("a batch of {} exceeds maxComputeWorkGroupCount[2] = {}", spec.howmany,
                       limits.maxComputeWorkGroupCount[2]));
  }
  const std::uint32_t inverse = spec.direction == Direction::inverse ? kInverse : 0;
  // Plans, by kind (docs/vulkan.md §Kernels): x axis then y axis for c2c and r2c, y then x for
  // c2r (its x pass reads the half spectrum as Hermitian and writes reals).
  switch (spec.kind) {
    case Kind::c2c:
      add_axis(true, nx, nx, Target::input, Target::output, nx, nx, false, false, inverse, inverse);
      if (ny > 1) add_axis(false, ny, nx, Target::output, Target::output, nx, nx, false, false, inverse, inverse);
      break;
    case Kind::r2c:
      add_axis(true, nx, nx, Target::input, Target::output, nx, half, true, false, kRealInput, kLimit);
      if (ny > 1) add_axis(false, ny, half, Target::output, Target::output, half, half, false, false, 0, 0);
      break;
    case Kind::c2r:
      if (ny > 1) {
        add_axis(false, ny, half, Target::input, Target::temp_a, half, half, false, false, kInverse, kInverse);
        temp_a_bytes_ = std::max<VkDeviceSize>(temp_a_bytes_, VkDeviceSize(half) * ny * 2 * real * spec.howmany);
        add_axis(true, nx, nx, Target::temp_a, Target::output, half, nx, false, true, kInverse | kHermitian, kInverse | kRealOutput);
      } else {
        add_axis(true, nx, nx, Target::input, Target::output, half, nx, false, true, kInverse | kHermitian, kInverse | kRealOutput);
      }
      break;
  }
  make_pipelines();
  if (per_batch_) {
    // Dynamic offsets (uint32) of every transform of the batch, on every array a pass binds.
    for (const Pass& pass : passes_) {
      for (VkDeviceSize stride : {pass.source_stride_bytes, pass.destination_stride_bytes}) {
        if (stride % limits.minStorageBufferOffsetAlignment != 0 ||
            stride * VkDeviceSize(spec.howmany) > 0xffffffffull) {
          refuse(fmt::format("a batch beyond maxStorageBufferRange ({} bytes) is bound one "
                             "transform at a time: each array of {} bytes must be a multiple of "
                             "minStorageBufferOffsetAlignment ({}) and the batch within 4 GiB",
                             range, stride, limits.minStorageBufferOffsetAlignment));
        }
      }
    }
  }
}

FftProgram::~FftProgram() {
  for (auto& w : workspaces_) {
    for (auto* a : {&w->temp_a, &w->temp_b, &w->device_in, &w->device_out, &w->staging_in, &w->staging_out}) {
      if (a->buffer) context_->free(*a);
    }
    if (w->pool) vkDestroyDescriptorPool(context_->device(), w->pool, nullptr);
  }
  for (auto& [n, table] : twiddles_) context_->free(table);
}

int FftProgram::twiddle_table(std::uint32_t n) {
  for (std::size_t i = 0; i < twiddles_.size(); ++i) {
    if (twiddles_[i].first == n) return int(i);
  }
  // e^(−2πij/n) in long double, then rounded once to the precision (drivers' sin and cos
  // differ, and a table read is as fast as a sincos on every device).
  const std::size_t real = real_size(spec_.precision);
  std::vector<unsigned char> bytes(std::size_t(n) * 2 * real);
  const long double two_pi = 6.283185307179586476925286766559005768L;
  for (std::uint32_t j = 0; j < n; ++j) {
    const long double angle = -two_pi * (long double)j / (long double)n;
    const long double c = std::cos(angle), s = std::sin(angle);
    if (spec_.precision == Precision::f32) {
      const float v[2] = {float(c), float(s)};
      std::memcpy(bytes.data() + j * 2 * real, v, sizeof v);
    } else {
      const double v[2] = {double(c), double(s)};
      std::memcpy(bytes.data() + j * 2 * real, v, sizeof v);
    }
  }
  Allocation table = context_->allocate(bytes.size(), true);
  Allocation staging = context_->allocate(bytes.size(), false);
  std::memcpy(staging.mapped, bytes.data(), bytes.size());
  context_->run([&](VkCommandBuffer commands) {
    const VkBufferCopy region{0, 0, bytes.size()};
    vkCmdCopyBuffer(commands, staging.buffer, table.buffer, 1, &region);
  });
  context_->free(staging);
  twiddles_.emplace_back(n, table);
  return int(twiddles_.size() - 1);
}

// One axis of every transform of the batch: n points along x (rows of `columns` positions) or
// along y (columns 0 … columns − 1), from `source` to `destination`, whose rows hold
// source_row and destination_row elements. Within shared memory one pass; beyond it two
// (four-step: N = N1·N2, N1-point transforms, twiddles, N2-point transforms into place),
// through temp_b.
void FftProgram::add_axis(bool x_axis, std::uint32_t n, std::uint32_t columns, Target source,
                          Target destination, std::uint32_t source_row,
                          std::uint32_t destination_row, bool source_real,
                          bool destination_real, std::uint32_t source_flags,
                          std::uint32_t destination_flags) {
  const std::size_t real = real_size(spec_.precision);
  const std::size_t in_bytes = source_real ? real : 2 * real;
  const std::size_t out_bytes = destination_real ? real : 2 * real;
  const std::uint32_t ny = std::uint32_t(spec_.ny), nx = std::uint32_t(spec_.nx);
  const std::uint32_t in_batch = source_row * ny, out_batch = destination_row * ny;
  const std::uint32_t capacity = shared_points(*context_, spec_.precision);
  // Lines beyond the subgroup kernel's 2048 points split into two passes of it where it runs:
  // at 4096 (16·16·16 in one Stockham pass, 96 memory operations a point) two 64-point passes
  // take 2 × 32 and one more trip through memory — 4096² in 0.74× VkFFT's time against 1.19×
  // (paired device times on lavapipe, 2026-12-02).
  const bool split_for_subgroups = subgroups_ && context_->shuffle_subgroup_size() != 0 && n > 2048;
  if (n <= capacity && !split_for_subgroups) {
    PassConstants c;
    c.flags = source_flags | destination_flags;
    c.row = nx;
    c.limit = destination_row;
    if (x_axis) {  // lo counts rows — of the whole batch, which lies row after row
      c.in_lo = source_row;
      c.out_lo = destination_row;
      c.in_element = c.out_element = 1;
      // A frame program keeps each plane's rows in its own workgroups (z = plane): its last
      // pass dispatches the plane that makes J after the others (fft_lines.comp, SWELL_FRAME).
      const bool fold = !per_batch_ && !frame_;
      const std::uint32_t rows = fold ? ny * std::uint32_t(spec_.howmany) : ny;
      add_line_pass(n, rows, 1, c, source, destination, in_bytes, out_bytes, in_batch, out_batch, -1);
      passes_.back().whole_batch_in_lines = fold;
    } else {  // lo counts columns, read and written row by row
      c.in_lo = c.out_lo = 1;
      c.in_element = source_row;
      c.out_element = destination_row;
      c.flags |= kSourceLineFastest | kDestinationLineFastest;
      add_line_pass(n, columns, 1, c, source, destination, in_bytes, out_bytes, in_batch, out_batch, -1);
    }
    return;
  }
  const std::uint32_t n1 = 1u << (log2_of(n) / 2), n2 = n / n1;  // n1 ≤ n2
  if (n2 > capacity) {
    throw UnsupportedTransform(fmt::format(
        "vulkan: {}: {} points along {} exceed the {}² a two-pass transform reaches with {} "
        "points in shared memory (maxComputeSharedMemorySize {} bytes) on {}",
        spec_.describe(), n, x_axis ? "x" : "y", capacity, capacity,
        context_->limits().maxComputeSharedMemorySize, context_->properties().deviceName));
  }
  const int split = twiddle_table(n);
  const std::uint32_t temp_row = x_axis ? nx : columns;
  temp_b_bytes_ = std::max<VkDeviceSize>(temp_b_bytes_, VkDeviceSize(temp_row) * ny * 2 * real * spec_.howmany);
  PassConstants first, second;
  first.flags = source_flags | kSplitTwiddle | kSourceLineFastest | kDestinationLineFastest;
  second.flags = destination_flags | kDestinationLineFastest;
  first.row = second.row = nx;
  first.limit = temp_row;
  second.limit = destination_row;
  first.split_n = second.split_n = n;
  if (x_axis) {
    // First: line n2 (lo) of row r (hi), element n1 at position n1·N2 + n2.
    first.in_lo = first.in_lo_position = 1;
    first.in_hi = source_row;
    first.in_element = n2;
    first.out_lo = first.out_lo_position = 1;
    first.out_hi = temp_row;
    first.out_element = n2;
    add_line_pass(n1, n2, ny, first, source, Target::temp_b, in_bytes, 2 * real, in_batch, temp_row * ny, split);
    // Second: line k1 (lo) of row r, element n2 at k1·N2 + n2, written to k1 + N1·k2.
    second.in_lo = second.in_lo_position = n2;
    second.in_hi = temp_row;
    second.in_element = 1;
    second.out_lo = second.out_lo_position = 1;
    second.out_hi = destination_row;
    second.out_element = n1;
    second.flags &= ~kSourceLineFastest;
    add_line_pass(n2, n1, ny, second, Target::temp_b, destination, 2 * real, out_bytes, temp_row * ny, out_batch, -1);
  } else {
    // First: line (column c (lo), n2 (hi)), element n1 at row n1·N2 + n2.
    first.flags |= kSplitByHi;
    first.in_lo = first.out_lo = 1;
    first.in_hi = source_row;
    first.in_element = n2 * source_row;
    first.out_hi = temp_row;
    first.out_element = n2 * temp_row;
    add_line_pass(n1, columns, n2, first, source, Target::temp_b, in_bytes, 2 * real, in_batch, temp_row * ny, split);
    // Second: line (c, k1), element n2 at row k1·N2 + n2, written to row k1 + N1·k2.
    second.flags |= kSourceLineFastest;
    second.in_lo = second.out_lo = 1;
    second.in_hi = n2 * temp_row;
    second.in_element = temp_row;
    second.out_hi = destination_row;
    second.out_element = n1 * destination_row;
    add_line_pass(n2, columns, n1, second, Target::temp_b, destination, 2 * real, out_bytes, temp_row * ny, out_batch, -1);
  }
}

void FftProgram::add_line_pass(std::uint32_t n, std::uint32_t lines_lo, std::uint32_t lines_hi,
                               PassConstants c, Target source, Target destination,
                               std::size_t source_element_bytes,
                               std::size_t destination_element_bytes, std::uint32_t source_batch,
                               std::uint32_t destination_batch, int split_twiddles) {
  const auto& limits = context_->limits();
  const std::uint32_t capacity = shared_points(*context_, spec_.precision);
  // Lines per workgroup: as many as shared memory holds (measured on lavapipe against 1024
  // points a workgroup: 0.9× at 512² and 1024², the same within noise elsewhere; the column
  // passes then read 8 or more adjacent columns, a cache line per SIMD group), never more than
  // the pass has, at least 16 points (a thread's registers).
  std::uint32_t lines = std::max(1u, capacity / n);
  lines = std::min(lines, std::bit_ceil(lines_lo));
  lines = std::max(lines, std::max(1u, 16u / n));
  // Threads: 16 points each (one radix-16 butterfly a stage).
  const std::uint32_t threads = n * lines / 16;
  const std::uint32_t max_threads =
      std::min(limits.maxComputeWorkGroupInvocations, limits.maxComputeWorkGroupSize[0]);
  if (threads > max_threads || threads == 0) {
    throw InternalError(fmt::format("vulkan: {}: a {}-point line would need {} invocations, the "
                                    "device allows {}", spec_.describe(), n, threads, max_threads));
  }
  // n = first_radix · 8^radix8_stages · 16^m. Measured on lavapipe (docs/vulkan.md): a first
  // stage of radix 2 or 4 (eight or four butterflies a thread, read from the array) cost more
  // than one radix-8 stage in its place, and two radix-8 stages more than 8·16 — so
  // 32 = 4·8, 64 = 8·8, 128 = 16·8, 512 = 4·8·16, 1024 = 8·8·16, 2048 = 16·8·16.
  constexpr std::uint32_t kFirstRadix[4] = {16, 4, 8, 16};
  const std::uint32_t log2n = log2_of(n);
  const std::uint32_t first_radix = n == 1 ? 1 : (n <= 16 ? n : kFirstRadix[log2n % 4]);
  const std::uint32_t radix8_stages = (n > 16 && log2n % 4 != 0) ? 1 : 0;
  c.lines_lo = lines_lo;
  c.in_batch = per_batch_ ? 0 : source_batch;
  c.out_batch = per_batch_ ? 0 : destination_batch;
  // The shape, then the pass's addressing and flags: all specialization constants (the
  // shader's constant_id order), so each pass is its own pipeline with its strides folded in.
  std::vector<std::uint32_t> specialization = {threads, n, lines, first_radix, n * lines};
  static_assert(sizeof(PassConstants) == 15 * sizeof(std::uint32_t));
  const auto* words = reinterpret_cast<const std::uint32_t*>(&c);
  specialization.insert(specialization.end(), words, words + 15);
  // The subgroup variant where the device allows it (docs/vulkan.md §Kernels): lines of 16 to
  // 2048 points, and workgroups of whole subgroups.
  const std::uint32_t subgroup = context_->shuffle_subgroup_size();
  const bool shuffle = subgroup != 0 && n >= 16 && n <= 2048 &&
                       threads % context_->max_subgroup_size() == 0 && subgroups_;
  // Two copies of the lines in shared memory when they fit: one barrier a stage, not two (the
  // subgroup variant exchanges through shared memory once).
  const bool ping_pong = !shuffle && 2 * std::size_t(n) * lines * 2 * real_size(spec_.precision) <=
                         limits.maxComputeSharedMemorySize;
  specialization.push_back(ping_pong ? 1 : 0);
  specialization.push_back(radix8_stages);
  Pass pass;
  pass.specialization = std::move(specialization);
  pass.shuffle = shuffle;
  pass.source_batch = source_batch;
  pass.destination_batch = destination_batch;
  pass.source = source;
  pass.destination = destination;
  pass.groups_x = (lines_lo + lines - 1) / lines;
  pass.groups_y = lines_hi;
  if (pass.groups_x > limits.maxComputeWorkGroupCount[0] || pass.groups_y > limits.maxComputeWorkGroupCount[1]) {
    throw UnsupportedTransform(fmt::format("vulkan: {}: {}×{} workgroups exceed the device's "
                                           "maxComputeWorkGroupCount {}×{}",
                                           spec_.describe(), pass.groups_x, pass.groups_y,
                                           limits.maxComputeWorkGroupCount[0],
                                           limits.maxComputeWorkGroupCount[1]));
  }
  pass.line_twiddles = twiddle_table(std::max(n, 1u));
  pass.split_twiddles = split_twiddles < 0 ? pass.line_twiddles : split_twiddles;
  pass.source_stride_bytes = VkDeviceSize(source_batch) * source_element_bytes;
  pass.destination_stride_bytes = VkDeviceSize(destination_batch) * destination_element_bytes;
  passes_.push_back(pass);
}

// Each pass's pipeline, once the passes are known: in a frame program the first pass reads
// the table (FRAME_SOURCE) and the last leaves the fields in its destination (FRAME_FIELDS),
// each through the fft_frame variant, with the frame's constants. The table is not an array of
// the batch: IN_BATCH then gives the virtual spectra's plane size, and a dispatch's base
// workgroup z (or BATCH_IN_X) the plane.
void FftProgram::make_pipelines() {
  const std::string precision = spec_.precision == Precision::f32 ? "_fp32" : "_fp64";
  for (std::size_t i = 0; i < passes_.size(); ++i) {
    Pass& pass = passes_[i];
    std::vector<std::uint32_t> constants = pass.specialization;
    if (frame_) {
      pass.reads_table = pass.source == Target::input;
      pass.writes_fields = i + 1 == passes_.size();
    }
    const std::string module = (pass.frame() ? "fft_frame" : "fft_lines") +
                               std::string(pass.shuffle ? "_shuffle" : "") + precision;
    const auto& spirv = pass.frame() ? (pass.shuffle ? fft_frame_shuffle_spirv(spec_.precision)
                                                     : fft_frame_spirv(spec_.precision))
                                     : (pass.shuffle ? fft_lines_shuffle_spirv(spec_.precision)
                                                     : fft_lines_spirv(spec_.precision));
    const PipelineShape shape = line_shape(pass.shuffle, pass.frame());
    if (!pass.frame()) {
      pass.pipeline = &context_->pipeline(module, spirv, constants, shape);
      continue;
    }
    if (pass.reads_table) {
      constants[kFlagsConstant] |= kFrameSource;
      constants[kInBatchConstant] = pass.source_batch;
      pass.source_stride_bytes = 0;  // every plane reads the one table
    }
    if (pass.writes_fields) constants[kFlagsConstant] |= kFrameFields;
    // The first pass reads the one table for every plane: with the planes interleaved along x,
    // the workgroups of the same rows of every plane run one after the other and find the
    // table's rows in the cache (each read from memory about once, not once a plane: 1.3× the
    // bare pass's time at 1024² on lavapipe without, 1.0× with).
    if (pass.reads_table && !pass.writes_fields && !per_batch_ &&
        std::uint64_t(pass.groups_x) * spec_.howmany <= context_->limits().maxComputeWorkGroupCount[0]) {
      pass.batch_in_x = std::uint32_t(spec_.howmany);
      pass.groups_x *= pass.batch_in_x;
    }
    constants.push_back(std::uint32_t(spec_.ny));
    constants.push_back(frame_->pairs ? 1 : 0);
    constants.push_back(0);  // JACOBIAN_FIRST
    constants.push_back(pass.batch_in_x);
    pass.pipeline = &context_->pipeline(module, spirv, constants, shape);
    if (pass.writes_fields) {
      // The last plane's own pipeline: it makes J from the planes before it (fft_lines.comp,
      // SWELL_FRAME), which are, dispatched one transform at a time, its destination binding's
      // window (record()).
      constants[kFlagsConstant] |= kFrameJacobian;
      constants[kJacobianFirstConstant] = per_batch_ ? jacobian_first_plane() : 0;
      pass.jacobian_pipeline = &context_->pipeline(module, spirv, constants, shape);
    }
  }
}

Workspace* FftProgram::acquire() const {
  {
    std::lock_guard lock(workspaces_mutex_);
    if (!free_workspaces_.empty()) {
      Workspace* w = free_workspaces_.back();
      free_workspaces_.pop_back();
      return w;
    }
  }
  auto w = std::make_unique<Workspace>();
  if (temp_a_bytes_) w->temp_a = context_->allocate(temp_a_bytes_, true);
  if (temp_b_bytes_) w->temp_b = context_->allocate(temp_b_bytes_, true);
  const std::uint32_t sets = std::uint32_t(passes_.size());
  std::vector<VkDescriptorPoolSize> sizes;
  for (const Pass& pass : passes_) {
    for (VkDescriptorType type : pass.pipeline->shape.bindings) {
      auto same = std::find_if(sizes.begin(), sizes.end(), [&](const auto& s) { return s.type == type; });
      if (same == sizes.end()) sizes.push_back({type, 1});
      else ++same->descriptorCount;
    }
  }
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = sets;
  pool_info.poolSizeCount = std::uint32_t(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  check(vkCreateDescriptorPool(context_->device(), &pool_info, nullptr, &w->pool), "vkCreateDescriptorPool");
  std::vector<VkDescriptorSetLayout> layouts;
  for (const auto& pass : passes_) layouts.push_back(pass.pipeline->set_layout);
  VkDescriptorSetAllocateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  set_info.descriptorPool = w->pool;
  set_info.descriptorSetCount = sets;
  set_info.pSetLayouts = layouts.data();
  w->sets.resize(sets);
  check(vkAllocateDescriptorSets(context_->device(), &set_info, w->sets.data()), "vkAllocateDescriptorSets");
  std::lock_guard lock(workspaces_mutex_);
  workspaces_.push_back(std::move(w));
  return workspaces_.back().get();
}

void FftProgram::release(Workspace* workspace) const {
  std::lock_guard lock(workspaces_mutex_);
  free_workspaces_.push_back(workspace);
}

// The bytes a pass's binding covers: the whole batch, or one transform when dispatched per
// transform.
VkDeviceSize FftProgram::window(const Pass& pass, bool source) const {
  const VkDeviceSize stride = source ? pass.source_stride_bytes : pass.destination_stride_bytes;
  if (!per_batch_) return stride * VkDeviceSize(spec_.howmany);
  // A frame's J plane reads the planes from jacobian_first_plane() on through its destination.
  return !source && pass.writes_fields ? stride * (spec_.howmany - 1 - jacobian_first_plane()) : stride;
}

// The first plane a frame's J is made from: the plane before the last (pairs: λ∂Dx/∂x beside
// λDy), or the two before it (c2r: λ∂Dx/∂x and λ∂Dy/∂y).
std::uint32_t FftProgram::jacobian_first_plane() const {
  return std::uint32_t(spec_.howmany) - (frame_->pairs ? 2 : 3);
}

void FftProgram::record(VkCommandBuffer commands, Workspace& w, VkBuffer in, VkBuffer out) const {
  const auto buffer_of = [&](Target t) {
    switch (t) {
      case Target::input: return in;
      case Target::output: return out;
      case Target::temp_a: return w.temp_a.buffer;
      case Target::temp_b: return w.temp_b.buffer;
    }
    return VkBuffer(VK_NULL_HANDLE);
  };
  if (w.bound_in != in || w.bound_out != out) {
    // The sets are this workspace's alone, and no submission that uses them is in flight.
    std::vector<std::vector<Window>> bindings;
    for (const Pass& pass : passes_) {
      std::vector<Window> b = {
          pass.reads_table ? frame_->table : Window{buffer_of(pass.source), 0, window(pass, true)},
          {buffer_of(pass.destination), 0, window(pass, false)},
          {twiddles_[pass.line_twiddles].second.buffer, 0, VK_WHOLE_SIZE},
          {twiddles_[pass.split_twiddles].second.buffer, 0, VK_WHOLE_SIZE}};
      if (pass.frame()) {
        b.push_back(frame_->probe);
        b.push_back(frame_->constants);
      }
      bindings.push_back(std::move(b));
    }
    std::vector<VkDescriptorBufferInfo> infos;
    for (const auto& b : bindings) {
      for (const Window& window : b) infos.push_back({window.buffer, window.offset, window.range});
    }
    std::vector<VkWriteDescriptorSet> writes;
    for (std::size_t p = 0, next = 0; p < passes_.size(); ++p) {
      const PipelineShape& shape = passes_[p].pipeline->shape;
      for (std::uint32_t b = 0; b < shape.bindings.size(); ++b) {
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstSet = w.sets[p];
        write.dstBinding = b;
        write.descriptorCount = 1;
        write.descriptorType = shape.bindings[b];
        write.pBufferInfo = &infos[next++];
        writes.push_back(write);
      }
    }
    vkUpdateDescriptorSets(context_->device(), std::uint32_t(writes.size()), writes.data(), 0, nullptr);
    w.bound_in = in;
    w.bound_out = out;
  }
  const std::uint32_t howmany = std::uint32_t(spec_.howmany);
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    const Pass& pass = passes_[p];
    Context::barrier(commands);
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline->pipeline);
    const auto bind = [&](std::uint32_t b, std::uint32_t destination_b) {
      const std::uint32_t offsets[2] = {std::uint32_t(b * pass.source_stride_bytes),
                                        std::uint32_t(destination_b * pass.destination_stride_bytes)};
      vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline->layout, 0,
                              1, &w.sets[p], 2, offsets);
    };
    // The last plane of a frame makes J from what the plane before left in the fields: it runs
    // after the others, behind a barrier, with its own pipeline.
    const auto jacobian_plane = [&] {
      vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pass.jacobian_pipeline->pipeline);
    };
    if (per_batch_) {
      for (std::uint32_t b = 0; b < howmany; ++b) {
        // The transforms of a batch touch disjoint windows, but synchronization validation
        // (1.3.239) reports the dispatches on one buffer as hazards; a barrier between them
        // costs nothing next to a transform this large.
        if (b > 0) Context::barrier(commands);
        const bool jacobian = pass.writes_fields && b + 1 == howmany;
        if (jacobian) jacobian_plane();
        bind(b, jacobian ? jacobian_first_plane() : b);
        // A frame pass learns its plane from the base workgroup z.
        if (pass.frame()) vkCmdDispatchBase(commands, 0, 0, b, pass.groups_x, pass.groups_y, 1);
        else vkCmdDispatch(commands, pass.groups_x, pass.groups_y, 1);
      }
      continue;
    }
    bind(0, 0);
    if (pass.writes_fields) {
      vkCmdDispatchBase(commands, 0, 0, 0, pass.groups_x, pass.groups_y, howmany - 1);
      Context::barrier(commands);
      jacobian_plane();
      bind(0, 0);
      vkCmdDispatchBase(commands, 0, 0, howmany - 1, pass.groups_x, pass.groups_y, 1);
      continue;
    }
    vkCmdDispatch(commands, pass.groups_x, pass.groups_y,
                  pass.whole_batch_in_lines || pass.batch_in_x > 1 ? 1u : howmany);
  }
  Context::barrier(commands);
}

namespace {

struct SlotGuard {
  const Context& context;
  Slot slot;
  explicit SlotGuard(const Context& c) : context(c), slot(c.acquire()) {}
  ~SlotGuard() { context.release(slot); }
};

struct WorkspaceGuard {
  const FftProgram& program;
  Workspace* workspace;
  explicit WorkspaceGuard(const FftProgram& p) : program(p), workspace(p.acquire()) {}
  ~WorkspaceGuard() { program.release(workspace); }
};

void begin(const Slot& slot, std::uint32_t timestamps = kTimestamps) {
  check(vkResetCommandBuffer(slot.commands, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(slot.commands, &info), "vkBeginCommandBuffer");
  if (slot.timestamps) vkCmdResetQueryPool(slot.commands, slot.timestamps, 0, timestamps);
}

void stamp(const Slot& slot, std::uint32_t query) {
  if (slot.timestamps) {
    vkCmdWriteTimestamp(slot.commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, slot.timestamps, query);
  }
}

}  // namespace

std::vector<double> FftProgram::execute_host(const void* in, void* out) const {
  const bool in_place = spec_.placement == Placement::in_place;
  WorkspaceGuard guard(*this);
  Workspace& w = *guard.workspace;
  const VkDeviceSize in_bytes = spec_.input_bytes(), out_bytes = spec_.output_bytes();
  if (!w.device_in.buffer) {
    w.device_in = context_->allocate(std::max(in_bytes, in_place ? out_bytes : 0), true);
    w.staging_in = context_->allocate(in_bytes, false);
    if (!in_place) w.device_out = context_->allocate(out_bytes, true);
    w.staging_out = context_->allocate(out_bytes, false);
  }
  const VkBuffer device_out = in_place ? w.device_in.buffer : w.device_out.buffer;
  std::memcpy(w.staging_in.mapped, in, in_bytes);
  SlotGuard slot_guard(*context_);
  const Slot& slot = slot_guard.slot;
  begin(slot);
  Context::barrier(slot.commands);
  stamp(slot, 0);
  const VkBufferCopy upload{0, 0, in_bytes};
  vkCmdCopyBuffer(slot.commands, w.staging_in.buffer, w.device_in.buffer, 1, &upload);
  Context::barrier(slot.commands);
  stamp(slot, 1);
  record(slot.commands, w, w.device_in.buffer, device_out);
  stamp(slot, 2);
  const VkBufferCopy download{0, 0, out_bytes};
  vkCmdCopyBuffer(slot.commands, device_out, w.staging_out.buffer, 1, &download);
  VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(slot.commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       0, 1, &host, 0, nullptr, 0, nullptr);
  stamp(slot, 3);
  check(vkEndCommandBuffer(slot.commands), "vkEndCommandBuffer");
  context_->submit_and_wait(slot);
  std::memcpy(out, w.staging_out.mapped, out_bytes);
  const auto t = context_->timestamp_seconds(slot);
  return {t[1] - t[0], t[2] - t[1], t[3] - t[2]};
}

double FftProgram::execute_device(VkBuffer in, VkBuffer out) const {
  WorkspaceGuard guard(*this);
  SlotGuard slot_guard(*context_);
  const Slot& slot = slot_guard.slot;
  // Two timestamps around the passes, and no barrier of its own (record puts one before each
  // pass and after the last): each command costs lavapipe time a small transform notices.
  begin(slot, 2);
  stamp(slot, 0);
  record(slot.commands, *guard.workspace, in, out);
  stamp(slot, 1);
  check(vkEndCommandBuffer(slot.commands), "vkEndCommandBuffer");
  context_->submit_and_wait(slot);
  return context_->timestamp_seconds(slot, 2)[1];
}

// ------------------------------------------------------------------ backend and plan

namespace {

class VulkanPlan final : public Plan {
 public:
  VulkanPlan(std::shared_ptr<const Context> context, const TransformSpec& spec, bool subgroups)
      : Plan(spec), program_(std::move(context), spec, subgroups) {}

  void execute(const void* in, void* out) const override { program_.execute_host(in, out); }

  void execute(const Buffer& in, Buffer& out) const override { execute_buffers(in, out); }

  double execute_buffers(const Buffer& in, Buffer& out) const {
    const auto* device_in = dynamic_cast<const DeviceBuffer*>(&in);
    auto* device_out = dynamic_cast<DeviceBuffer*>(&out);
    if (!device_in || !device_out) {
      throw InvalidInput(spec().describe() + ": a vulkan plan runs on buffers from the vulkan "
                         "backend's allocate(), or on host pointers");
    }
    if (&device_in->context() != &program_.context() || &device_out->context() != &program_.context()) {
      throw InvalidInput(spec().describe() + ": buffers from another Vulkan device");
    }
    if (in.bytes() < spec().input_bytes() || out.bytes() < spec().output_bytes()) {
      throw InvalidInput(spec().describe() + ": buffers of " + std::to_string(in.bytes()) + " and " +
                         std::to_string(out.bytes()) + " bytes, need " +
                         std::to_string(spec().input_bytes()) + " and " +
                         std::to_string(spec().output_bytes()));
    }
    const bool same = device_in->handle() == device_out->handle();
    if (same != (spec().placement == Placement::in_place)) {
      throw InvalidInput(spec().describe() + (same ? ": input and output are the same memory"
                                                   : ": in-place plan given two buffers"));
    }
    return program_.execute_device(device_in->handle(), device_out->handle());
  }

  std::vector<double> execute_host_timed(const void* in, void* out) const {
    return program_.execute_host(in, out);
  }

  const FftProgram& program() const { return program_; }

 private:
  FftProgram program_;
};

class VulkanBackend final : public Backend {
 public:
  explicit VulkanBackend(const BackendOptions& options)
      : context_(Context::get(options.device)), subgroups_(options.subgroups) {
    if (options.threads != 1) {
      throw InvalidInput("backend option threads is for fftw and radix2; vulkan runs on its device");
    }
    if (!options.planner.empty()) throw InvalidInput("backend option planner is for fftw");
  }
  std::string name() const override { return "vulkan"; }
  Capabilities capabilities() const override {
    Capabilities caps;
    caps.precisions = {Precision::f32};
    if (context_->float64()) caps.precisions.push_back(Precision::f64);
    caps.any_size = false;
    caps.real_transforms = true;
    caps.in_place = true;
    caps.multi_threaded = false;
    caps.device_resident = true;
    const std::uint32_t f32 = shared_points(*context_, Precision::f32);
    caps.size_rule = fmt::format(
        "powers of two per axis, up to {} in one pass and {} in two (fp32; half that in fp64), "
        "each transform within the device's maxStorageBufferRange of {} bytes",
        f32, std::uint64_t(f32) * f32, context_->limits().maxStorageBufferRange);
    return caps;
  }
  std::unique_ptr<Plan> plan(const TransformSpec& spec) const override {
    validate(spec);
    return std::make_unique<VulkanPlan>(context_, spec, subgroups_);
  }
  std::unique_ptr<Buffer> allocate(std::size_t bytes) const override {
    return std::make_unique<DeviceBuffer>(context_, bytes);
  }
  const Context& context() const { return *context_; }
  const std::shared_ptr<const Context>& shared_context() const { return context_; }
  bool subgroups() const { return subgroups_; }

 private:
  std::shared_ptr<const Context> context_;
  bool subgroups_ = true;
};

const VulkanPlan& vulkan_plan(const Plan& plan) {
  const auto* p = dynamic_cast<const VulkanPlan*>(&plan);
  if (!p) throw InvalidInput(plan.spec().describe() + ": not a plan of the vulkan backend");
  return *p;
}

}  // namespace

std::shared_ptr<const Context> context_of(const Backend& backend) {
  const auto* b = dynamic_cast<const VulkanBackend*>(&backend);
  return b ? b->shared_context() : nullptr;
}

bool subgroups_of(const Backend& backend) {
  const auto* b = dynamic_cast<const VulkanBackend*>(&backend);
  return b && b->subgroups();
}

}  // namespace swell::impls::vk

namespace swell::impls {

std::unique_ptr<Backend> make_vulkan_backend(const BackendOptions& options) {
  return std::make_unique<vk::VulkanBackend>(options);
}

VulkanTimings vulkan_execute_timed(const Plan& plan, const void* in, void* out) {
  const auto t = vk::vulkan_plan(plan).execute_host_timed(in, out);
  return {t[0], t[1], t[2]};
}

VulkanTimings vulkan_execute_timed(const Plan& plan, const Buffer& in, Buffer& out) {
  VulkanTimings timings;
  timings.compute_seconds = vk::vulkan_plan(plan).execute_buffers(in, out);
  return timings;
}

std::string vulkan_device_description(const std::string& backend) {
  try {
    const auto made = make_backend(backend);
    const auto* vulkan = dynamic_cast<const vk::VulkanBackend*>(made.get());
    if (!vulkan) return backend + " is not a vulkan backend";
    return vulkan->context().description();
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace swell::impls
