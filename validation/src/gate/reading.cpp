// What the gate asks of the machine before it reads any frame (memory, per surface and per
// cascade set), and a cascade's own case file.
#include "gate/judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>
#include <vector>
#include <cstdint>

#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/io/frame_io.hpp"

namespace swell::validation::gate_path {

using reference::Field;

namespace {

double streamed_bytes_per_sample(std::size_t ocean_fields, int threads, bool power_table) {
  // Per sample, whatever the frame count: the analysis — μ and τ (16 bytes), frame 0's spectrum
  // (16), the half plane's wave vectors (40) and the resolved ones' positions among them (4),
  // their fit sums and ω groups (24), the pass's spectrum (16, the forward transform's input
  // and output) and the derived check's |k| (8); per thread the FFTW plan's padded rows (16,
  // the forward transform's shared with a derived unit's) and a derived unit's array, which
  // its spectrum is written into and transformed over, where its fields are judged (16); and
  // per field two frames' values (8 bytes each: the one judged and the one read ahead) and
  // the float channels being decoded (4). The power table, made beside the passes: the half
  // plane's energy weights (4), pointers to the resolved waves by |k| (4), their sort keys
  // while it sorts (8) and its energy law's terms (4). An upper bound (docs/gate.md §6): the
  // derived units of three fields are fewer than the threads.
  const double fields = double(std::max<std::size_t>(1, ocean_fields));
  return 16 + 16 + 40 + 4 + 24 + 16 + 8 + (16.0 + 16) * threads + (2 * 8.0 + 4) * fields +
         (power_table ? 20 : 0);
}

}  // namespace

void require_streamed_gate_memory(const reference::OceanCase& ocean, std::size_t ocean_fields, int threads,
                                  bool power_table) {
  const auto sampling = ocean.sampling();
  const double fields = double(std::max<std::size_t>(1, ocean_fields));
  const double per_sample = streamed_bytes_per_sample(ocean_fields, threads, power_table);
  const double bytes = double(sampling.size()) * per_sample;
  const std::uint64_t available = reference::available_memory_bytes();
  if (available == 0 || bytes <= double(available)) return;
  throw InvalidInput(fmt::format(
      "swell gate needs about {} for the analysis of the {} ({} bytes per sample: the "
      "accumulators per wave vector, the spectra{} and two frames of {} field{}), whatever the "
      "frame count, and the machine has {} available: use a smaller grid ([grid] n), fewer "
      "fields ([input]) or fewer threads (--threads {})",
      reference::human_bytes(bytes), sampling.describe(), int(per_sample),
      power_table ? ", the power table" : "", int(fields), fields == 1 ? "" : "s",
      reference::human_bytes(double(available)), threads));
}

void require_cascade_set_memory(const CaseFile& set, int threads) {
  // Per sample of each cascade: frame 0's spectral view (power, μ of the case and of the sea,
  // |k|, kx, ky: 48 bytes) and its spectrum (16), the recovered amplitudes (17) and their fit's
  // sums (64 per entry); with three frames or more, per patch length of the set, the patch
  // fit's sums, amplitudes and residuals over the half plane (about 60). Beside them, the
  // largest surface's own analysis (require_streamed_gate_memory's figure).
  std::size_t lengths = 0;
  std::vector<std::pair<double, double>> seen;
  for (std::size_t c = 0; c < set.cascades.size(); ++c) {
    const auto grid = set.cascade_case(c).grid;
    if (std::find(seen.begin(), seen.end(), std::make_pair(grid.lx, grid.ly)) == seen.end()) {
      seen.emplace_back(grid.lx, grid.ly);
      ++lengths;
    }
  }
  double bytes = 0, largest_surface = 0;
  for (std::size_t c = 0; c < set.cascades.size(); ++c) {
    if (set.cascades[c].input.files.empty()) continue;
    const auto ocean = set.cascade_case(c);
    const double samples = double(ocean.sampling().size());
    bytes += samples * (48 + 16 + 17 + 64 + (ocean.frames >= 3 ? 60.0 * double(lengths) : 0.0));
    largest_surface = std::max(
        largest_surface, samples * streamed_bytes_per_sample(set.cascades[c].input.channels.size(), threads, false));
  }
  const std::uint64_t available = reference::available_memory_bytes();
  if (available == 0 || bytes + largest_surface <= double(available)) return;
  throw InvalidInput(fmt::format(
      "swell gate needs about {} for a cascade set: the set checks' sums over the wave vectors "
      "of every cascade ({}), whatever the frame counts, beside the largest surface's own "
      "analysis ({}), and the machine has {} available: use smaller cascade grids, or fewer "
      "threads (--threads {})",
      reference::human_bytes(bytes + largest_surface), reference::human_bytes(bytes),
      reference::human_bytes(largest_surface), reference::human_bytes(double(available)), threads));
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
