// null: copies the input to the output and transforms nothing. Timing it measures the harness's
// own overhead (buffers, dispatch, memory traffic of one read and one write). With
// SWELL_NULL_DELAY_US=D every execute also spins D µs on the steady clock: a backend known to be
// slower under the same benchmark names, for the comparison tests of `swell report --against`.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>

#include "backends.hpp"

namespace swell::impls {
namespace {

class NullPlan final : public Plan {
 public:
  NullPlan(const TransformSpec& spec, long delay_us) : Plan(spec), delay_us_(delay_us) {}
  void execute(const void* in, void* out) const override {
    if (delay_us_ > 0) {  // a spin, not a sleep: the delay then shows in CPU time too
      const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(delay_us_);
      while (std::chrono::steady_clock::now() < until) {
      }
    }
    const std::size_t in_bytes = spec().input_bytes(), out_bytes = spec().output_bytes();
    const std::size_t copied = std::min(in_bytes, out_bytes);
    if (in != out) std::memmove(out, in, copied);
    if (out_bytes > copied) std::memset(static_cast<char*>(out) + copied, 0, out_bytes - copied);
  }
  using Plan::execute;

 private:
  long delay_us_;
};

class NullBackend final : public Backend {
 public:
  explicit NullBackend(long delay_us) : delay_us_(delay_us) {}
  std::string name() const override { return "null"; }
  Capabilities capabilities() const override {
    Capabilities c;
    c.precisions = {Precision::f32, Precision::f64, Precision::f80};
    c.any_size = true;
    c.size_rule = "any N ≥ 1";
    c.exact = false;
    c.blocked_large_1d = true;
    return c;
  }
  std::unique_ptr<Plan> plan(const TransformSpec& spec) const override {
    validate(spec);
    return std::make_unique<NullPlan>(spec, delay_us_);
  }

 private:
  long delay_us_;
};

}  // namespace

std::unique_ptr<Backend> make_null_backend(const BackendOptions&) {
  long delay = 0;
  if (const char* env = std::getenv("SWELL_NULL_DELAY_US"); env && *env) {
    char* end = nullptr;
    delay = std::strtol(env, &end, 10);
    if (*end != '\0' || delay < 0 || delay > 10'000'000) {
      throw InvalidInput(std::string("SWELL_NULL_DELAY_US='") + env +
                         "' must be a whole number of microseconds 0…10000000");
    }
  }
  return std::make_unique<NullBackend>(delay);
}

}  // namespace swell::impls
