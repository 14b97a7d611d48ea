#pragma once
// A run's peak resident memory, from Linux's own high-water mark: writing 5 to
// /proc/self/clear_refs resets VmHWM to the present resident set (Linux ≥ 4.0), so the mark
// read after a run is that run's peak; malloc_trim first returns what earlier runs freed, so that
// the baseline is what the process holds, not what the allocator kept.
#include <malloc.h>

#include <fstream>
#include <string>

namespace swell::bench {

// VmHWM or VmRSS of this process in bytes (0 where /proc is not readable).
inline double proc_status_bytes(const std::string& key) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.compare(0, key.size() + 1, key + ":") == 0) return 1024.0 * std::stod(line.substr(key.size() + 1));
  }
  return 0;
}

class PeakMemory {
 public:
  // Resets the high-water mark to the present resident set.
  PeakMemory() {
    malloc_trim(0);
    std::ofstream("/proc/self/clear_refs") << "5";
    baseline_ = proc_status_bytes("VmRSS");
  }
  double baseline_bytes() const { return baseline_; }
  // The peak since construction, and its rise over the baseline.
  double peak_bytes() const { return proc_status_bytes("VmHWM"); }
  double rise_bytes() const { return peak_bytes() - baseline_; }

 private:
  double baseline_ = 0;
};

}  // namespace swell::bench
