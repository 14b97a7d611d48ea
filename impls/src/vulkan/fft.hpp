#pragma once
// Internal: the vulkan backend's plan as a program of passes (docs/vulkan.md §Kernels) that can
// be recorded into any command buffer — its own execute() and the synthesizer's frame
// submission both record it.
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "context.hpp"

namespace swell::impls::vk {

// The specialization constants 5 … 19 of impls/shaders/fft_lines.comp, in its order.
struct PassConstants {
  std::uint32_t in_lo = 0, in_lo_position = 0, in_hi = 0, in_element = 0, in_batch = 0;
  std::uint32_t out_lo = 0, out_lo_position = 0, out_hi = 0, out_element = 0, out_batch = 0;
  std::uint32_t lines_lo = 1, flags = 0, row = 0, limit = 0, split_n = 1;
};

// Which buffer a pass reads or writes.
enum class Target { input, output, temp_a, temp_b };

// The synthesizer's frame program (frame.cpp): the batch of inverse transforms whose first pass
// reads the evolution's half spectrum and makes the packed spectra, and whose last pass leaves
// the six fields in its destination (fft_lines.comp, SWELL_FRAME: bindings 4 and 5).
struct FrameIo {
  bool pairs = true;  // 4 c2c of field pairs, or 8 c2r of one field each
  Window table;       // the evolution's half spectrum h̃ (the first pass's source)
  Window probe;       // the count of non-finite field values
  Window constants;   // uniform: the field scales, inverse scales, Δkx, Δky, λ
};

struct Pass {
  const Pipeline* pipeline = nullptr;  // its addressing and flags are specialization constants
  const Pipeline* jacobian_pipeline = nullptr;  // a frame's last pass: for the last plane
  std::vector<std::uint32_t> specialization;
  bool shuffle = false;                // the subgroup variant of the line kernel
  Target source = Target::input, destination = Target::output;
  std::uint32_t groups_x = 1, groups_y = 1;
  int line_twiddles = 0, split_twiddles = 0;   // indices into FftProgram::twiddles
  std::uint32_t source_batch = 0, destination_batch = 0;  // elements of one transform
  VkDeviceSize source_stride_bytes = 0;        // one transform of the batch, on each side
  VkDeviceSize destination_stride_bytes = 0;
  bool whole_batch_in_lines = false;  // lines run through the batch: one workgroup layer (z = 1)
  std::uint32_t batch_in_x = 1;       // transforms interleaved along x (fft_lines.comp BATCH_IN_X)
  bool reads_table = false;           // frame: the first pass (FRAME_SOURCE)
  bool writes_fields = false;         // frame: the last pass (FRAME_FIELDS)
  bool frame() const { return reads_table || writes_fields; }
};

// What one execution owns: scratch arrays, descriptor sets, and (for host memory) device
// copies and staging buffers.
struct Workspace {
  Allocation temp_a, temp_b;
  Allocation device_in, device_out, staging_in, staging_out;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets;  // one per pass
  VkBuffer bound_in = VK_NULL_HANDLE, bound_out = VK_NULL_HANDLE;
};

class FftProgram {
 public:
  // Throws UnsupportedTransform naming the rule when the device cannot run `spec`. subgroups:
  // use fft_lines_shuffle where the device and the pass allow it (else the portable kernel).
  // frame: the synthesizer's frame program (spec: its batch of inverse transforms).
  FftProgram(std::shared_ptr<const Context> context, const TransformSpec& spec, bool subgroups = true,
             const FrameIo* frame = nullptr);
  ~FftProgram();
  FftProgram(const FftProgram&) = delete;
  FftProgram& operator=(const FftProgram&) = delete;

  const TransformSpec& spec() const { return spec_; }
  bool subgroups() const { return subgroups_; }
  const Context& context() const { return *context_; }
  // A workspace for one execution at a time (created when none is free).
  Workspace* acquire() const;
  void release(Workspace* workspace) const;
  // Records the passes on `in` → `out` (device buffers of the spec's sizes) into `commands`,
  // with a barrier before each pass and after the last. A frame program reads the table for
  // `in` and writes the fields for its last pass's destination.
  void record(VkCommandBuffer commands, Workspace& workspace, VkBuffer in, VkBuffer out) const;
  // Host memory: upload, record, download, with the device's timestamps of the three phases.
  std::vector<double> execute_host(const void* in, void* out) const;
  // Device buffers: the transform alone; returns its device seconds (0 without timestamps).
  double execute_device(VkBuffer in, VkBuffer out) const;

 private:
  void add_axis(bool x_axis, std::uint32_t n, std::uint32_t columns, Target source,
                Target destination, std::uint32_t source_row, std::uint32_t destination_row,
                bool source_real, bool destination_real, std::uint32_t source_flags,
                std::uint32_t destination_flags);
  void add_line_pass(std::uint32_t n, std::uint32_t lines_lo, std::uint32_t lines_hi,
                     PassConstants constants, Target source, Target destination,
                     std::size_t source_element_bytes, std::size_t destination_element_bytes,
                     std::uint32_t source_batch, std::uint32_t destination_batch,
                     int split_twiddles);
  int twiddle_table(std::uint32_t n);
  void make_pipelines();
  std::uint32_t jacobian_first_plane() const;
  VkDeviceSize window(const Pass& pass, bool source) const;

  std::shared_ptr<const Context> context_;
  TransformSpec spec_;
  std::vector<Pass> passes_;
  std::vector<std::pair<std::uint32_t, Allocation>> twiddles_;  // (N, table of N complex)
  VkDeviceSize temp_a_bytes_ = 0, temp_b_bytes_ = 0;
  bool per_batch_ = false;  // one dispatch per transform of the batch (arrays beyond the range)
  bool subgroups_ = true;   // fft_lines_shuffle allowed (backend option subgroups)
  std::optional<FrameIo> frame_;
  mutable std::mutex workspaces_mutex_;
  mutable std::vector<std::unique_ptr<Workspace>> workspaces_;
  mutable std::vector<Workspace*> free_workspaces_;
};

// A vulkan backend's context (nullptr for another backend's) and its subgroups option: for the
// synthesizer's frame, which builds its own program.
std::shared_ptr<const Context> context_of(const Backend& backend);
bool subgroups_of(const Backend& backend);

}  // namespace swell::impls::vk
