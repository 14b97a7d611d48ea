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
  // of one frame per thread (96).
  const auto sampling = ocean.sampling();
  const double fields = double(std::max<std::size_t>(1, ocean_fields));
  const double per_sample = (8.0 * fields + 16) * ocean.frames + 64 + (24.0 + 96) * threads;
  const double bytes = double(sampling.size()) * per_sample;
  reference::require_memory(std::uint64_t(std::min(bytes, 1.8e19)), "swell gate",
                            fmt::format("{} frame{} on a {}", ocean.frames,
                                        ocean.frames == 1 ? "" : "s", sampling.describe()));
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
