#pragma once
// Progress on stderr for long commands (swell bench, swell sweep): on a terminal a bar rewritten
// in place with the time left, otherwise a plain line every few seconds (logs and CI keep
// readable output); "none" is silent. The time left is estimated from the pace so far.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

#include <fmt/format.h>

namespace swell::cli {

inline std::string duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  return s >= 3600 ? fmt::format("{}h{:02}m", s / 3600, s / 60 % 60)
         : s >= 60 ? fmt::format("{}m{:02}s", s / 60, s % 60)
                   : fmt::format("{}s", s);
}

class Progress {
 public:
  // mode: auto (bar on a terminal, plain lines otherwise) | bar | plain | none. `done` counts
  // work finished before this process started (a resumed sweep): shown, but not in the pace.
  Progress(std::string label, const std::string& mode, long total, long done = 0)
      : label_(std::move(label)), total_(total), done_(done), first_(done) {
    terminal_ = mode == "bar" || (mode == "auto" && isatty(STDERR_FILENO));
    quiet_ = mode == "none";
  }
  void step(const std::string& what) {
    ++done_;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const long here = done_ - first_;
    const double left = here > 0 ? elapsed / double(here) * double(total_ - done_) : NAN;
    const double share = total_ > 0 ? double(done_) / double(total_) : 1.0;
    if (quiet_) return;
    if (terminal_) {
      constexpr int kWidth = 24;
      const int filled = int(std::floor(share * kWidth));
      const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
      std::cerr << fmt::format("\r\033[K{}: [{}] {}/{} ({:.0f} %), {} elapsed, about {} left — {}",
                               label_, bar, done_, total_, 100 * share, duration(elapsed),
                               duration(left), what)
                << std::flush;
    } else if (elapsed - last_line_ >= 5 || done_ == total_) {
      std::cerr << fmt::format("{}: {}/{} ({:.0f} %), {} elapsed, about {} left — {}\n", label_,
                               done_, total_, 100 * share, duration(elapsed), duration(left), what);
      last_line_ = elapsed;
    }
  }
  void finish() {
    if (terminal_ && !quiet_) std::cerr << "\n";
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  long total_ = 0, done_ = 0, first_ = 0;
  bool terminal_ = false, quiet_ = false;
  double last_line_ = -1e9;
  Clock::time_point start_ = Clock::now();
};

}  // namespace swell::cli
