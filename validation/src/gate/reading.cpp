// Reading a surface's frames for the gate: the memory asked for first, then what the checks
// keep of every field of every frame.
#include "gate/judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/io/frame_io.hpp"

namespace swell::validation::gate_path {

using reference::Field;

void require_gate_memory(const reference::OceanCase& ocean, std::size_t ocean_fields, int threads) {
  // Per sample: every frame's fields (8 bytes each, up to six) and its two complex waves in the
  // dispersion fit (16), the analysis' spectra and expected powers (64), one frame of float
  // channels being decoded per reading thread (24), and the derived check's spectra and fields
  // of one frame per thread (96). A cascade set's surfaces are held whole (cascade_gate.cpp).
  const auto sampling = ocean.sampling();
  const double fields = double(std::max<std::size_t>(1, ocean_fields));
  const double per_sample = (8.0 * fields + 16) * ocean.frames + 64 + (24.0 + 96) * threads;
  const double bytes = double(sampling.size()) * per_sample;
  reference::require_memory(std::uint64_t(std::min(bytes, 1.8e19)), "swell gate",
                            fmt::format("{} frame{} on a {}", ocean.frames,
                                        ocean.frames == 1 ? "" : "s", sampling.describe()));
}

void require_streamed_gate_memory(const reference::OceanCase& ocean, std::size_t ocean_fields, int threads) {
  // Per sample, whatever the frame count: the analysis — μ and τ (16 bytes), frame 0's spectrum
  // and height (24), the half plane's wave vectors twice, all and resolved (80), their fit sums
  // and fits (48), the pass's spectrum and each thread's transform scratch (16 + 16 per thread),
  // the derived check's wave numbers (24) and its spectra and fields of one field per thread
  // (64) — and three frames' fields (8 bytes each): the one judged, the one read ahead, and
  // frame 0's until the pass passes it.
  const auto sampling = ocean.sampling();
  const double fields = double(std::max<std::size_t>(1, ocean_fields));
  const double per_sample = 16 + 24 + 80 + 48 + 16 + 24 + (16.0 + 64) * threads + 3 * 8.0 * fields;
  const double bytes = double(sampling.size()) * per_sample;
  const std::uint64_t available = reference::available_memory_bytes();
  if (available == 0 || bytes <= double(available)) return;
  throw InvalidInput(fmt::format(
      "swell gate needs about {} for the analysis of the {} ({} bytes per sample: the "
      "accumulators per wave vector, the spectra and three frames of {} field{}), whatever the "
      "frame count, and the machine has {} available: use a smaller grid ([grid] n), fewer "
      "fields ([input]) or fewer threads (--threads {})",
      reference::human_bytes(bytes), sampling.describe(), int(per_sample), int(fields),
      fields == 1 ? "" : "s", reference::human_bytes(double(available)), threads));
}

reference::FrameSequence read_gate_frames(const CaseFile& case_file,
                                          const std::string& pattern_override, int threads) {
  return read_frames(case_file, pattern_override, {}, threads);
}

CaseFile surface_case_file(const CaseFile& set, const reference::OceanCase& ocean,
                           const InputSpec& input) {
  CaseFile out;
  out.ocean = ocean;
  out.input = input;
  out.scale = set.scale;
  out.directory = set.directory;
  return out;
}

}  // namespace swell::validation::gate_path
