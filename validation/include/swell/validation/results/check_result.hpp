#pragma once
// A check returns a value, not a printout: what was checked, on what, the measured and expected
// numbers, the criterion, the verdict and a one-line reason. Text, JSON and Markdown are
// renderings of it (report.hpp).
#include <limits>
#include <string>
#include <vector>

namespace swell::validation {

struct CheckResult {
  std::string check;      // dotted name: "dispersion.round_trip"
  std::string subject;    // what it was applied to: "finite depth h = 10 m"
  double measured = 0;
  double expected = 0;
  double tolerance = 0;   // the bound in the criterion
  std::string criterion;  // how measured is judged: "|rel err| ≤ 1e-12"
  bool passed = false;
  std::string reason;     // one line: why it passed or failed, in the user's terms
  // Statistical checks: the p-value of the measurement under the hypothesis that the surface is
  // right, and the false-alarm rate α it was judged at (passed ⇔ p ≥ α). NaN for exact checks.
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha = std::numeric_limits<double>::quiet_NaN();
};

// Why a check did not run: what it needed and did not get.
enum class SkipReason {
  free_scale,            // the case declares a free spectrum scale: no energy to judge
  too_few_frames,        // the check needs more frames than were given
  too_few_cascades,      // the set's checks need the frames of two or more cascades
  unidentifiable_times,  // 2ω dt ≈ 0 mod 2π: no wave vector's two waves can be told apart
  above_nyquist,         // every energetic ω is above the frames' Nyquist frequency π/dt
  too_few_wave_vectors,  // too few wave vectors carry energy for the statistic
  ambiguous_phase,       // one frame at t ≠ 0 cannot tell h̃0(k) from conj h̃0(−k)
  no_field,              // none of the fields the check judges was given
  no_wave_motion,        // every energetic wave has ω = 0: no period, no motion to measure
  scheme_not_judged,     // probes: the declared synthesis scheme's law is not one swell judges yet
};

// A check that did not run, and why, in the user's terms.
struct Skipped {
  std::string check;  // dotted name: "dispersion", "statistics.hs_steady", "cascade1.direction"
  SkipReason reason = SkipReason::too_few_frames;
  std::string why;    // "needs ≥ 3 frames (the fit has 2 complex unknowns per k)"
  // "check: why", as reports print it.
  std::string text() const { return check + ": " + why; }
  bool operator==(const Skipped&) const = default;
};

// |measured − expected| ≤ tolerance · |expected|.
CheckResult relative_check(std::string check, std::string subject, double measured,
                           double expected, double tolerance, std::string what);
// An exact result with its own criterion and reason: `measured` against `bound` (expected 0).
CheckResult exact_check(std::string check, std::string subject, double measured, double bound,
                        bool passed, std::string criterion, std::string reason);
// The same, passed ⇔ error ≤ bound (false for NaN).
CheckResult bounded_check(std::string check, std::string subject, double error, double bound,
                          std::string criterion, std::string reason);
// A measured error (already relative or absolute) that must not exceed a bound.
CheckResult error_bound_check(std::string check, std::string subject, double error, double bound,
                              std::string what);
// lower ≤ measured ≤ upper.
CheckResult range_check(std::string check, std::string subject, double measured, double lower,
                        double upper, std::string what);

// A statistical result with its own reason: passed ⇔ p ≥ α (false for a NaN p), tolerance = α.
CheckResult statistical_check(std::string check, std::string subject, double measured,
                              double expected, double p_value, double alpha,
                              std::string criterion, std::string reason);

bool all_passed(const std::vector<CheckResult>& results);

}  // namespace swell::validation
