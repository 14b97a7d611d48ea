#pragma once
// The grid synthesizer (Tessendorf's method) following docs/conventions.md §Amplitudes to the
// letter, over any registered transform backend, in fp32 or fp64:
//
//   h̃0(k) = (ξ1 + i ξ2)/√2 · √(Ψ(k) Δkx Δky / 2)       ξ from wave_noise(seed, n, m)
//   h̃(k, t) = h̃0(k) e^(−iωt) + conj(h̃0(−k)) e^(+iωt)
//   field(x, t) = Σk multiplier(k) h̃(k, t) e^(ik·x)     (one inverse transform per field)
//
// k = 0 and the Nyquist row and column carry zero. The eight real fields the six outputs need
// (h, ∂h/∂x, ∂h/∂y, λDx, λDy and the three λ∂D/∂x terms of J) are computed either as four
// complex transforms, two real fields packed per transform (a + ib), or as eight c2r transforms;
// docs/synthesis.md records which is faster on which backend.
#include <array>
#include <complex>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "swell/impls/transform.hpp"
#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"

namespace swell::impls {

enum class Packing {
  complex_pairs,  // 4 c2c inverse transforms, two real fields in each
  real,           // 8 c2r inverse transforms
  automatic,      // the faster for the backend (complex_pairs unless the backend lacks c2c)
};
std::string to_string(Packing packing);
Packing packing_from_string(const std::string& name);

// The initial amplitude h̃0 at signed wave-number indices (n, m) of a case — the definition,
// in double precision; 0 where the grid carries no energy.
std::complex<double> initial_amplitude(const reference::OceanCase& ocean_case, int n, int m);
// The same over the case's grid, in FFT order (entry j·nx + i at (n, m) of (i, j)), building the
// spectrum once (initial_amplitude builds it per call).
std::vector<std::complex<double>> initial_amplitudes(const reference::OceanCase& ocean_case);

// Where one frame's time went, by the device's own clock: the evolution and the transforms
// together (device_seconds, before the fields reach the host), the evolution kernel alone
// (h̃ at t), and the transforms' passes alone, whose first makes the packed spectra and whose
// last writes the six fields (docs/synthesis.md §vulkan). Zeros for host backends, and on a
// device without timestamps.
struct FrameTimings {
  double device_seconds = 0;
  double evolve_seconds = 0;
  double transforms_seconds = 0;
};

// How a lattice frame computes its 1-D transforms of size N (docs/lattice.md §Synthesis):
// one_pass is the backend's own 1-D plan; four_step factors N = n1·n2 and runs n1 transforms
// of n2 (with the twiddles e^(2πi m1 p2 / N) applied in cache), then n2 transforms of n1 —
// Bailey's four-step FFT, whose passes over memory are a 2-D transform's; automatic chooses
// four_step from 2^17 points on, where N factors into two sizes the backend plans, on a host
// backend with complex pairs whose own large 1-D plans are not blocked already
// (Capabilities::blocked_large_1d: FFTW's are). Grids ignore it.
enum class LatticeTransform { automatic, one_pass, four_step };
std::string to_string(LatticeTransform transform);
LatticeTransform lattice_transform_from_string(const std::string& name);

struct SynthesizerOptions {
  std::string backend = "fftw";  // any registered backend, with options ("fftw:threads=2")
  Precision precision = Precision::f32;
  Packing packing = Packing::automatic;
  int threads = 1;               // for the spectrum assembly (OpenMP)
  LatticeTransform lattice_transform = LatticeTransform::automatic;
};

class Synthesizer {
 public:
  Synthesizer(reference::OceanCase ocean_case, SynthesizerOptions options = {});
  ~Synthesizer();
  Synthesizer(const Synthesizer&) = delete;
  Synthesizer& operator=(const Synthesizer&) = delete;

  const reference::OceanCase& ocean_case() const;
  const SynthesizerOptions& options() const;
  Packing packing() const;  // the packing actually used
  // A lattice frame's factorization N = n1·n2 of the four-step transform; {0, 0} when its
  // transforms are the backend's one-pass 1-D plans (and on grids).
  std::array<int, 2> four_step_factors() const;
  // The transforms of one frame (for benchmarks: frame time over bare transform time).
  std::vector<TransformSpec> transforms_per_frame() const;

  // All six fields at time t into `fields`: 6 consecutive arrays of nx·ny reals of the
  // synthesizer's precision (float or double), in reference::kAllFields order.
  //
  // With a device-resident backend (vulkan) the waves live on the device from construction on
  // and a frame is one submission there: the spectra at t, the transforms and the six fields,
  // copied back only because `fields` is host memory (docs/synthesis.md §vulkan); frames are
  // then serialized, so several threads may call evaluate() on one synthesizer. The host
  // backends assemble into one spectrum buffer per synthesizer: give each thread its own.
  void evaluate(double t, std::span<std::byte> fields) const;
  // The same, with the device's timings of the frame (benchmarks).
  FrameTimings evaluate_timed(double t, std::span<std::byte> fields) const;
  std::size_t frame_bytes() const;  // bytes `fields` must hold
  // About the memory a synthesizer of this grid and precision holds, with one frame converted
  // to double (frame()): what a command checks against the machine before building one.
  static std::uint64_t bytes_needed(const reference::Grid& grid, Precision precision);

  // The same, converted to double: one frame at time t, and the case's frames.
  reference::FieldFrame frame(double t) const;
  reference::FrameSequence frames() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace swell::impls
