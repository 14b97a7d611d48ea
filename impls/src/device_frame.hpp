#pragma once
// Internal: the synthesizer's frame on a device (docs/synthesis.md §vulkan). The synthesizer
// hands over, once, what does not change from frame to frame; each frame is then one
// submission on the device: the spectra at time t (evolution), the batch of inverse
// transforms, the six fields (unpack) and their copy for the host. No Vulkan type shows here,
// so synthesizer.cpp builds the same with and without SWELL_WITH_VULKAN.
#include <cstddef>
#include <memory>
#include <span>

#include "swell/impls/synthesizer.hpp"
#include "swell/impls/transform.hpp"

namespace swell::impls {

// What does not change from frame to frame, as Synthesizer::State holds it on the host, in the
// synthesis precision's Real (float for fp32, double for fp64) except ω, which is double for
// both (the phase ωt is computed in double). Read during the construction only.
struct DeviceFrameTables {
  Precision precision = Precision::f32;
  bool pairs = true;  // Packing::complex_pairs (4 c2c) or Packing::real (8 c2r)
  int nx = 0, ny = 0;
  // Per half-spectrum entry: ny rows of nx/2 + 1 columns, FFT order, row-major.
  const void *a_re = nullptr, *a_im = nullptr, *b_re = nullptr, *b_im = nullptr;
  const double* omega = nullptr;
  double dkx = 0, dky = 0;   // Δkx, Δky: the kernels form kx and ky as the host's tables do
  double choppiness = 0;     // λ: the kernels form λ/|k| from it
  const void* field_scale = nullptr;    // [8], packing order (synthesizer.cpp)
  const void* inverse_scale = nullptr;  // [8]
};

class DeviceFrame {
 public:
  virtual ~DeviceFrame() = default;
  // All six fields at time t into `fields` (Synthesizer::frame_bytes() bytes, the layout of
  // Synthesizer::evaluate), with the device's timings. Returns how many samples hold a
  // non-finite value (0 for every frame of a valid case); `fields` is written either way, so
  // the caller can name the first one. Safe to call from several threads (serialized).
  virtual std::size_t evaluate(double t, std::span<std::byte> fields,
                               FrameTimings& timings) const = 0;
};

#ifdef SWELL_HAVE_VULKAN
// The frame of a vulkan backend for `spec`, the synthesizer's batch of inverse transforms (which
// the backend's rules must allow: it is validated as a plan is). Throws UnsupportedTransform
// naming the device and the missing feature, InvalidInput when `backend` is not vulkan.
// (vulkan/frame.cpp)
std::unique_ptr<DeviceFrame> make_vulkan_frame(const Backend& backend, const TransformSpec& spec,
                                               const DeviceFrameTables& tables);
#endif

}  // namespace swell::impls
