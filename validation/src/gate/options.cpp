#include "swell/validation/gate/options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "swell/reference/errors.hpp"

namespace swell::validation {

void GateOptions::validate() const {
  if (!(alpha > 0 && alpha < 1)) {
    throw InvalidInput(fmt::format("alpha (the gate's family-wise false-alarm rate) must be in "
                                   "(0, 1) (got {:g})",
                                   alpha));
  }
  if (threads < 0) throw InvalidInput(fmt::format("threads must be ≥ 0 (got {})", threads));
}

int GateOptions::resolved_threads() const {
  if (threads < 0) throw InvalidInput(fmt::format("threads must be ≥ 0 (got {})", threads));
  if (threads > 0) return threads;
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

void GateOptions::report_progress(const std::string& message) const {
  if (progress) progress(message);
}

}  // namespace swell::validation
