#pragma once
// The test engine: a second, independent implementation of docs/conventions.md §5 (amplitudes,
// synthesis, derived fields), in fp64 and as plainly as possible, that renders the surfaces of an
// ocean case right — and, on request, wrong in one named way. The synthesizer (impls/) is
// compared with it, and every ocean check is shown to fail on the bugs it is meant to catch.
//
// It shares with the synthesizer only what defines the contract: reference::wave_noise (the
// Philox draws), the case's Ψ(k) and ω(k), the Grid helpers, and validation::field_from_spectrum
// (an fp64 FFTW inverse, Σk X(k) e^(ik·x)) for the transforms. No code of impls::Synthesizer.
//
//   h̃0(k)   = (ξ1 + i ξ2)/√2 · √(Ψ(k) Δkx Δky / 2)   (ξ1, ξ2) = wave_noise(seed, n, m)
//   h̃(k, t) = h̃0(k) e^(−iωt) + conj(h̃0(−k)) e^(+iωt)    ω = ocean_case.omega(|k|)
//   height ↔ h̃, slope_x ↔ i kx h̃, slope_y ↔ i ky h̃, disp_x ↔ λ i kx/|k| h̃, disp_y ↔ λ i ky/|k| h̃,
//   J = (1 + λ Dxx)(1 + λ Dyy) − λ² Dxy²,  Dxx ↔ −kx²/|k| h̃, Dyy ↔ −ky²/|k| h̃, Dxy ↔ −kx ky/|k| h̃
//
// k = 0 and the Nyquist row and column carry zero; frame f is at ocean_case.time(f).
#include <complex>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"

namespace swell::test {

// One deliberate departure from the conventions each. "Amplitude" below is h̃0; a factor on the
// amplitude scales every linear field (height, slopes, displacements) by it.
enum class EngineBug {
  none,
  // Amplitudes × √2: twice the energy (mean h² exactly doubled).
  energy_doubled,
  // h̃(k, t) = h̃0(k) e^(−iωt) + conj(g(−k)) e^(+iωt) with g drawn independently (wave_noise
  // stream 1) instead of h̃0(−k): the spectrum is not Hermitian, the complex inverse transform
  // has an imaginary part (FieldFrame::imaginary with EngineOptions::keep_imaginary) and only
  // its real part is kept. That real part is a valid-looking surface with half the energy.
  independent_minus_k_real_part,
  // h̃0(−k) draws the same (ξ1, ξ2) as h̃0(k) (the half-plane representative's pair).
  same_pair_for_minus_k,
  // ω = √(g k) in the time evolution and Ψ(k) built through deep-water dispersion (S(ω) and D
  // unchanged, TMA's depth factor included) although the case has finite depth. The loop period
  // still quantizes ω. No effect on a deep-water case.
  deep_water_dispersion,
  // h̃(k, t) = h̃0(k) e^(+iωt) + conj(h̃0(−k)) e^(−iωt): the surface of time −t; waves run
  // against θw.
  reversed_time,
  // J computed with λ = 1 while the displacements use the case's λ.
  jacobian_without_choppiness,
  // ξ = √3 (2u − 1), u uniform on (0, 1] (reference::wave_uniforms): unit variance, not Gaussian.
  uniform_noise,
  // Every transform output (the five linear fields and the three ∂D terms J is formed from)
  // multiplied by (−1)^(i+j): a "centred FFT" fix-up applied to FFT-ordered data.
  checkerboard_sign,
  // h̃0 = (ξ1 + i ξ2)/√2 · √(Ψ/2) without Δkx Δky: amplitudes × 1/√(Δkx Δky), so Hs changes
  // with the patch size.
  amplitude_without_dk,
  // JONSWAP σa = σb = 0.7 instead of the case's (default 0.07/0.09): the case is copied with
  // sigma_a, sigma_b set in its spectrum parameters and Ψ built from that (with hs/tp the
  // exact normalization keeps m0; the shape broadens). Only for jonswap and tma cases.
  sigma_wrong,
  // S scaled by √g/g² (α√g instead of α g², as in Blender's ocean_spectrum.cc): Ψ × g^(−3/2),
  // amplitudes × g^(−3/4).
  alpha_sqrt_g,
  // ω = g k in the time evolution (loop period quantization still applied).
  omega_equals_gk,
  // D without its normalization: the spreading's shape scaled to 1 in the mean direction,
  // D(ω, θ)/D(ω, 0) — cos^(2s)(θ/2) for cos-2s (Ψ × 1/G(s)), sech²(βθ) for Donelan–Banner,
  // |cos θ|^p for cos-power. Ψ × 1/D(ω(k), 0), ω(k) the case's unquantized dispersion. Not for
  // phillips, which has no spreading model.
  spreading_not_normalized,
  // Tessendorf's −i in the displacement with λ > 0, applied consistently: D ↔ −i k/|k| h̃ and
  // its derivatives flip too, so disp and J equal the right ones for choppiness −λ.
  displacement_sign_flipped,
  // Two overlapping cascades: wave vectors with |k| in the middle third of the grid's |k| range
  // [kmin + (kmax − kmin)/3, kmin + 2(kmax − kmin)/3), kmin = min(Δkx, Δky), kmax the largest
  // |k| carrying energy, get amplitude × √2.
  band_counted_twice,
  // h̃(k, t) = (h̃0(k) + conj(h̃0(−k))) cos(ωt): standing, not travelling, waves.
  standing_waves,
  // Amplitudes × (1 + 0.2 (t − t0)/(frames·dt)) (× 1 when frames·dt = 0): Hs grows over frames.
  time_drift,
  // Issue 16's engines. The FFT input written x-major and read y-major: the height field is
  // transposed (kx along rows), the displacement and slope channels are not. Square grids only.
  transposed_height,
  // The displacement channels swapped: disp_x holds λDy and disp_y holds λDx.
  swapped_displacements,
  // A plugin core's lattice: bin (n, m) evaluates Ψ, ω and the derived multipliers at
  // K' = ((2n + 1) Δkx, (2m + 1) Δky) and pairs with bin (−n − 1, −m − 1) without the conjugate:
  // h̃(k, t) = h̃0'(k) e^(−iω't) + h̃0'(−k − 1) e^(+iω't); the real part of the complex inverse is
  // kept, so each output bin holds the frequencies ω(|2K ± Δk|).
  half_bin_offset_lattice,
  // Each wave vector seeded from a 16-bit hash of its index: (ξ1, ξ2) = wave_noise(seed, h, 0)
  // with h a mixed hash of (n, m) in 2¹⁶ buckets: on the catalogue's 128² grid 46 % of the wave
  // vectors draw the same pair as another one (the gate's count). Otherwise right.
  hash_collisions,
  // The k = 0 coefficient moves: the mean level rises and falls as 0.8·√(2 m0) cos(2π t/8 s)
  // (m0 the waves' mean h² at t = 0; 0.64 m0 of variance over a period, about 39 % of the
  // total) and the displacements sway by the same amount along x and y. Otherwise right.
  heave,
};

std::string to_string(EngineBug bug);                       // "energy_doubled", …
EngineBug engine_bug_from_string(const std::string& name);  // throws InvalidInput
// Every bug, none excluded, in declaration order.
std::vector<EngineBug> all_engine_bugs();
// False where a bug cannot be rendered for a case (sigma_wrong needs jonswap or tma,
// spreading_not_normalized a spreading model); render_surface then throws InvalidInput.
// (deep_water_dispersion applies to a deep case too, where it changes nothing.)
bool engine_bug_applies(EngineBug bug, const reference::OceanCase& ocean_case);

struct EngineOptions {
  // Also fill FieldFrame::imaginary: the imaginary parts of the complex inverse transforms
  // (≈ 0 unless the bug makes the spectrum non-Hermitian). For the Jacobian, the imaginary
  // part of J evaluated in complex arithmetic from the complex ∂D fields.
  bool keep_imaginary = false;
};

// h̃0 over the grid as the engine with `bug` draws it, in FFT order (element j·nx + i holds
// signed (n, m) = (signed_index(i, nx), signed_index(j, ny)); 0 where the grid carries no
// energy). Exposed so tests can tie a rendered spectrum to its amplitudes.
std::vector<std::complex<double>> engine_initial_amplitudes(const reference::OceanCase& ocean_case,
                                                            EngineBug bug = EngineBug::none);

// All six fields at the case's frame times, fp64 (unit_roundoff 2⁻⁵³). Validates the case.
reference::FrameSequence render_surface(const reference::OceanCase& ocean_case,
                                        EngineBug bug = EngineBug::none,
                                        EngineOptions options = {});

// Keeps what an RGB heightmap holds — height, disp_x, disp_y (PNG channels R, G, B) — and
// returns the largest |value| among them, to size a PNG value range from.
double keep_rgb_fields(reference::FrameSequence& frames);

}  // namespace swell::test
