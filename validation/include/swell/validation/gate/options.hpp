#pragma once
// What `swell gate` is asked to do, checked before any frame is read.
#include <functional>
#include <string>

namespace swell::validation {

struct GateOptions {
  double alpha = 1e-3;        // family-wise false-alarm rate of the whole gate, in (0, 1)
  std::string input_pattern;  // replaces the case's [input] files when not empty
  // Threads that read frames and run the checks (0: every hardware thread); the verdict does
  // not depend on it.
  int threads = 0;
  // Called with a one-line message ("reading 64 frames of 512×512…") as the gate goes; unset:
  // silent. The CLI prints them on standard error.
  std::function<void(const std::string&)> progress;
  // Whether a single surface's report carries the gate's power table (power.hpp; about 0.3 s of
  // simulation whatever the grid). Loops that judge many surfaces only for their verdicts (a
  // false-alarm calibration) turn it off.
  bool power = true;

  // Throws InvalidInput naming the option when α is outside (0, 1) or threads is negative.
  void validate() const;
  // The threads the gate runs on: `threads`, or every hardware thread when 0.
  int resolved_threads() const;
  // Passes a message to `progress` when set.
  void report_progress(const std::string& message) const;
};

}  // namespace swell::validation
