#pragma once
// A gate's verdict: what was judged, at which α, each check's result and what was skipped.
#include <optional>
#include <string>
#include <vector>

#include "swell/validation/gate/power.hpp"
#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

struct GateReport {
  std::string case_path;               // the case file judged ("" when given in memory)
  std::string subject;                 // the case's one-line description
  int frames = 0, nx = 0, ny = 0;  // a lattice: nx = N points, ny = 1
  std::string samples;             // "512×512", or the lattice ("korobov N=4096 g=(1,671) over …")
  std::vector<std::string> fields;     // field names present
  double alpha = 0;                    // family-wise
  double alpha_per_check = 0;          // what each statistical check ran at
  int statistical_checks = 0;          // how many share α
  std::vector<CheckResult> results;
  std::vector<Skipped> skipped;        // checks that could not run, with the reason
  double fitted_scale = 1;             // free-scale cases: the engine's spectrum over the case's
  double unit_roundoff = 0;            // of the values read (FrameSequence::unit_roundoff)
  double storage_roundoff = 0;         // half frames' one ulp, 2⁻¹⁰ (FrameSequence::storage_roundoff)
  // The gate's power on this case (power.hpp): a single surface's gate; empty for a probes case
  // or a cascade set.
  std::optional<PowerTable> power;
  double seconds = 0;                  // wall time of reading and judging
  double read_seconds = 0;             // of which reading the case and its frames
  // What the case's sea is, where a table made it: the share of the table's m0 the sampling
  // carries, and what its reader did to it (clipped, renormalized). Empty for parametric seas.
  std::vector<std::string> notes;
  bool passed() const;
};

}  // namespace swell::validation
