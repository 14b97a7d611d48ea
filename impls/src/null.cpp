// null: copies the input to the output and transforms nothing. Timing it measures the harness's
// own overhead (buffers, dispatch, memory traffic of one read and one write).
#include <algorithm>
#include <cstring>

#include "backends.hpp"

namespace swell::impls {
namespace {

class NullPlan final : public Plan {
 public:
  using Plan::Plan;
  void execute(const void* in, void* out) const override {
    const std::size_t in_bytes = spec().input_bytes(), out_bytes = spec().output_bytes();
    const std::size_t copied = std::min(in_bytes, out_bytes);
    if (in != out) std::memmove(out, in, copied);
    if (out_bytes > copied) std::memset(static_cast<char*>(out) + copied, 0, out_bytes - copied);
  }
  using Plan::execute;
};

class NullBackend final : public Backend {
 public:
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
    return std::make_unique<NullPlan>(spec);
  }
};

}  // namespace

std::unique_ptr<Backend> make_null_backend(const BackendOptions&) {
  return std::make_unique<NullBackend>();
}

}  // namespace swell::impls
