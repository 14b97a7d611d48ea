#pragma once
// The gate's power (docs/gate.md §11): for a case's sampling, frames, stored precision and α,
// the smallest error of each kind that the gate detects with 90 % power, the check that detects
// it, and how that size is found — from the checks' sampling laws in closed form, or by
// simulating their statistics. No frames are needed: `swell gate --power --case FILE`.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "swell/validation/checks/case_samples.hpp"

namespace swell::validation {

struct CaseFile;

struct PowerLine {
  std::string error;     // the kind of error: "energy factor", "ω (relative, every wave)", …
  std::string smallest;  // the smallest error detected with the table's power, in words
  double below = 0, above = 0;  // its sizes: the factor or offset below and above the case's (NaN: none)
  std::string check;     // the check that detects it first
  std::string method;    // "closed form" or "simulation (M draws)"
  std::string note;      // what else makes that error (g and depth at the peak, …)
};

struct PowerTable {
  double power = 0.9;
  double alpha = 0;            // the gate's family-wise α
  double alpha_per_check = 0;  // its share per statistical check
  std::string precision;       // "half", "float" or "double": the stored values' rounding floor
  std::vector<PowerLine> lines;
};

// The table for one surface's case at family-wise `alpha`. `unit_roundoff` and
// `storage_roundoff` are the frames' (FrameSequence's): those read, or, without frames, those of
// [input] precision (float when it is not declared). `travelling_power`: τ(k) of the case on its
// samples (ocean_checks.hpp's expected_travelling_power). Its pieces run on up to `threads`
// threads; the table is the same on any number.
PowerTable gate_power(const CaseFile& case_file, double alpha, double unit_roundoff,
                      double storage_roundoff, const std::vector<double>& travelling_power,
                      int threads = 1);
// The same from what the gate's analysis holds of the case (its τ, μ and half plane, as the
// case gives them): the same table, without evaluating μ, |k|, ω and θ on every sample again.
PowerTable gate_power(const CaseFile& case_file, double alpha, double unit_roundoff,
                      double storage_roundoff, const CaseSamples& samples, int threads = 1);
// The same from the case alone: its [input] precision, float when not declared.
PowerTable gate_power(const CaseFile& case_file, double alpha, int threads = 1);

std::string render_power(const PowerTable& table);  // one line per kind of error, for the terminal
// {"power", "alpha", "alpha_per_check", "precision", "lines": [{"error", "smallest", "below",
// "above", "check", "method", "note"}]}; non-finite sizes null.
nlohmann::json power_json(const PowerTable& table);

}  // namespace swell::validation
