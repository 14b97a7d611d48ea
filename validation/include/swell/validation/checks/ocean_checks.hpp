#pragma once
// The checks that judge a sampled ocean surface against its case (docs/checks.md,
// docs/checks.md). Each consumes only frames and the case — never a synthesizer's internals —
// so the same code judges swell's own backends and another engine's files.
//
// Every statistical check has a false-alarm rate α (default 1e-3): on a right surface it fails
// with probability α, derived from the sampling distribution of its statistic. A check with
// several parts splits its α among them (Bonferroni), so each check as a whole keeps α. Exact
// checks (Hermitian, Parseval, dispersion, derived fields) are judged against rounding bounds.
//
//   hermitian   imaginary residue of complex fields; Hermitian symmetry of real ones
//   parseval    Σ h² = N Σ |ĥ|² through the analysis transform
//   energy      mean h² against the band-limited m0 (exact sampling law of Σ I)
//   spectrum    periodogram against μ(k) in rings of |k| (exact Gamma laws, Fisher's method);
//               energy where the case puts none
//   moments     Hs, Tp, Tm01, Tm02 against the band-limited spectrum
//   dispersion  per wave vector, frames fit a e^(−iωt) + b e^(iωt) at the case's ω(k): residual
//               energy fraction; ω measured per wave vector against ω(k)
//   direction   energy travelling along +k against −k: mean direction and spread against D;
//               waves at k and −k independent (travelling, not standing)
//   randomness  the recovered initial amplitudes, normalized, do not repeat across distinct
//               wave vectors beyond chance (reused random numbers)
//   statistics  skewness and kurtosis of heights; Gaussian amplitudes (Anderson–Darling);
//               Hs steady across frames
//   derived     slopes, displacements and Jacobian consistent with the height field
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "swell/validation/checks/case_samples.hpp"

#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/validation/io/frame_source.hpp"
#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

struct OceanCheckOptions {
  double alpha = 1e-3;                    // false-alarm rate of each check
  std::string analysis_backend = "fftw";  // transform the Parseval check runs (fp64)
  // The engine scales its spectrum by an unknown constant: fit it (reported as
  // "scale"), judge everything else up to it, and do not judge the energy.
  bool free_scale = false;
  // Told of each frame as the passes over the frames go (the gate's progress), when set.
  std::function<void(const std::string&)> progress;
};

struct OceanCheckReport {
  std::vector<CheckResult> results;
  std::vector<Skipped> skipped;      // checks, or parts of checks, that could not run
  double fitted_scale = 1;           // Σ I / Σ μ when free_scale, else 1
};

// Throws the InvalidInput the checks throw for frames whose rounding (unit roundoff u relative
// to the height's rms, mean_square_height = mean h²) hides every wave vector of the case: what
// swell synth asks before writing a PNG the gate could not judge.
void require_judgeable_rounding(const reference::OceanCase& ocean_case, double unit_roundoff,
                                double mean_square_height);

// The name of the result that reports the fitted scale of a free-scale case (not judged).
inline constexpr std::string_view kFittedScaleCheck = "scale";

// The names of the checks, in the order they run (ocean_check_table.hpp).
std::vector<std::string> ocean_check_names();
// The position of a result's check ("moments.tp" → moments') in that order; the table's size
// for a result of no check of the table (the fitted scale).
std::size_t ocean_check_position(const std::string& check);

// τ(k) of the case's directional spectrum on the case's own samples (stats/periodogram.hpp), on
// up to `threads` threads: what an analysis of the case's frames starts from.
std::vector<double> expected_travelling_power(const reference::OceanCase& ocean_case,
                                              int threads = 1);

// Groups of checks run concurrently on `threads` threads (the gate): every group judges one
// analysis of `frames`, made once. Reports in the groups' order (with a free scale the first begins with the fitted
// scale); the first group's error is thrown. `travelling_power`: τ(k) of the case on its samples
// (expected_travelling_power(ocean_case, threads), and no other), which the gate evaluates once
// before reading for its sampling rule and hands to the analysis.
struct OceanCheckGroup {
  std::vector<std::string> checks;
};
// One group per check, the longest first (ocean_check_table.hpp's cost ranks), for whichever
// thread is free: what the gate runs.
std::vector<OceanCheckGroup> ocean_check_groups_longest_first();
std::vector<OceanCheckReport> run_ocean_check_groups(const reference::OceanCase& ocean_case,
                                                     const reference::FrameSequence& frames,
                                                     const OceanCheckOptions& options,
                                                     const std::vector<OceanCheckGroup>& groups,
                                                     std::vector<double> travelling_power,
                                                     int threads);

// Work that runs beside the analysis (the gate's power table): on a thread of its own through
// the passes over the frames, which leave the cores idle while frames are decoded (with one
// thread, after them, before the checks). Given the precision the frames show (frame 0's; run
// again in the rare case that every frame, once read, shows another), and the case's τ(k), μ(k)
// and half plane while the analysis holds them as the case gives them (null with a free scale,
// whose analysis scales them).
using BesideChecks = std::function<void(const FramePrecision& precision, const CaseSamples* samples)>;

// The same on frames streamed from a source (io/frame_source.hpp): what the gate runs on a
// case's files, whose memory is then a few frames', whatever their number. `beside`, when
// given, runs as BesideChecks says; its error is thrown before the groups'.
std::vector<OceanCheckReport> run_ocean_check_groups(const reference::OceanCase& ocean_case,
                                                     const FrameSource& frames,
                                                     const OceanCheckOptions& options,
                                                     const std::vector<OceanCheckGroup>& groups,
                                                     std::vector<double> travelling_power,
                                                     int threads, const BesideChecks& beside = {});
// Runs the checks named (all when empty) on `frames`, which must match the case's grid.
// Throws InvalidInput for an unknown check name, mismatched grids or frames without height.
OceanCheckReport run_ocean_checks(const reference::OceanCase& ocean_case,
                                  const reference::FrameSequence& frames,
                                  const OceanCheckOptions& options = {},
                                  const std::vector<std::string>& checks = {});

}  // namespace swell::validation
