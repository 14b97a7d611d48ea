#pragma once
// The ocean checks in one table (ocean_checks.hpp runs them): each row says what the check is,
// what it needs and why it can be skipped. The registry, the gate's shares of α, its run order
// and docs/checks.md's list of checks derive from it.
#include <cstddef>
#include <string_view>
#include <vector>

#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

struct OceanCheckRow {
  std::string_view name;
  // Judged by p against α (and sharing the gate's family-wise α), or against a rounding bound.
  bool statistical = false;
  // Statistical only when the case's spectrum scale is absolute (energy: a free scale leaves no
  // energy to judge).
  bool needs_absolute_scale = false;
  // The frames the statistical part needs: with fewer the check is skipped and takes no share
  // of α (direction: one frame cannot tell k from −k).
  std::size_t statistical_frames = 1;
  std::string_view needs;  // what it reads of the frames, in a few words
  // Rank by cost, 1 the longest: the gate starts the longest first (longest processing time
  // first keeps two threads within the shortest check of each other).
  int cost_rank = 0;
  std::vector<SkipReason> skipped_when;  // why it (or one of its parts) may not run
};

// The rows in the order the checks run and report.
const std::vector<OceanCheckRow>& ocean_check_table();

// The checks that share α on `frames` frames of a case (free_scale: the case's scale is free).
// A check counted here that finds nothing to judge at run time (direction when 2ω dt ≈ 0 mod 2π
// for every k) only makes the gate more conservative.
std::vector<std::string_view> statistical_ocean_checks(bool free_scale, std::size_t frames);

}  // namespace swell::validation
