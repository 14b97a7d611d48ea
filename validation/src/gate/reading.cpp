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

void require_gate_memory(const reference::OceanCase& ocean, int threads) {
  // Per sample: every frame's height (8 bytes) and its two complex waves in the dispersion fit
  // (16), the two end frames' six fields (96), the analysis' spectra and expected powers (64),
  // and one frame of float channels being decoded per reading thread (24).
  const auto sampling = ocean.sampling();
  const double per_sample = 24.0 * ocean.frames + 96 + 64 + 24.0 * threads;
  const double bytes = double(sampling.size()) * per_sample;
  reference::require_memory(std::uint64_t(std::min(bytes, 1.8e19)), "swell gate",
                            fmt::format("{} frame{} on a {}", ocean.frames,
                                        ocean.frames == 1 ? "" : "s", sampling.describe()));
}

GateFrames read_gate_frames(const CaseFile& case_file, const std::string& pattern_override,
                            int threads) {
  const int count = case_file.ocean.frames;
  const bool has_height = case_file.input.channels.count(Field::height) > 0;
  GateFrames out;
  const auto keep = [&](int frame, Field field) {
    return !has_height || field == Field::height || frame == 0 || frame == count - 1;
  };
  out.all = read_frames(case_file, pattern_override, keep, threads);
  out.ends.grid = out.all.grid;
  out.ends.lattice = out.all.lattice;
  out.ends.unit_roundoff = out.all.unit_roundoff;
  out.ends.frames.push_back(out.all.frames.front());
  if (count > 1) out.ends.frames.push_back(out.all.frames.back());
  return out;
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
