#pragma once
// What the frame and lattice benchmarks share: the two clocks they read and the bare
// transforms of a frame, timed beside the frame itself.
#include <time.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "swell/impls/transform.hpp"
#ifdef SWELL_HAVE_VULKAN
#include "swell/impls/vulkan.hpp"
#endif

namespace swell::bench {

// CPU seconds of the calling thread, as Google Benchmark's cpu_time column.
inline double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

// Wall-clock seconds, as the real_time column: for device-resident backends, whose work the
// benchmark thread only waits for.
inline double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The transforms of one frame on buffers of their own. Their input is zeros: transform time
// does not depend on the values (no backend branches on data; zeros are not subnormal), and an
// in-place inverse transform repeated on random data would grow by about N per repetition
// until fp32 overflows.
struct BareTransforms {
  std::unique_ptr<impls::Backend> backend;
  std::vector<std::unique_ptr<impls::Plan>> plans;
  std::vector<std::unique_ptr<impls::Buffer>> inputs, outputs;

  BareTransforms(const std::string& impl, const std::vector<impls::TransformSpec>& specs)
      : backend(impls::make_backend(impl)) {
    for (const auto& spec : specs) {
      plans.push_back(backend->plan(spec));
      inputs.push_back(backend->allocate(spec.input_bytes()));
      const std::vector<unsigned char> zeros(spec.input_bytes(), 0);
      inputs.back()->upload(zeros.data(), zeros.size());  // touches every page
      if (spec.placement == impls::Placement::out_of_place) {
        outputs.push_back(backend->allocate(spec.output_bytes()));
      } else {
        outputs.push_back(nullptr);
      }
    }
    run();  // first touch of the outputs, outside the timing
  }
  // Runs them; returns the device's seconds for a device-resident backend (0 otherwise).
  double run() const {
    double device_seconds = 0;
    for (std::size_t i = 0; i < plans.size(); ++i) {
      impls::Buffer& out = outputs[i] ? *outputs[i] : *inputs[i];
#ifdef SWELL_HAVE_VULKAN
      if (backend->name() == "vulkan") {
        device_seconds += impls::vulkan_execute_timed(*plans[i], *inputs[i], out).compute_seconds;
        continue;
      }
#endif
      plans[i]->execute(*inputs[i], out);
    }
    return device_seconds;
  }
};

}  // namespace swell::bench
