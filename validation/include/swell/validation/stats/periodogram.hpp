#pragma once
// The spectral view of sampled frames that the checks and the fit share
// (docs/conventions.md §Transforms): ĥ(k) = (1/(Nx Ny)) Σx h(x) e^(−ik·x) in FFT order, the
// periodogram I(k) = |ĥ(k)|² (Σ I = mean h²), and what a right surface makes of it:
//   E I(k) = μ(k) = ½ (Ψ(k) + Ψ(−k)) Δkx Δky   for k carrying energy, 0 elsewhere,
// with, in one realization, I(k) exponentially distributed with mean μ(k) and independent
// over a half plane of k (I(−k) = I(k)).
#include <complex>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "swell/reference/directional.hpp"
#include "swell/reference/grid.hpp"
#include "swell/reference/sampling.hpp"

namespace swell::impls {
class HostBuffer;
}

namespace swell::validation {

// The backend every analysis transform goes through: fp64 FFTW with estimate plans (a MEASURE
// plan is chosen by timing, so its rounding, and the reports, would change from run to run).
inline constexpr const char* kAnalysisBackend = "fftw:planner=estimate";

// ĥ of a real field of grid.nx·grid.ny values (fp64 FFTW).
std::vector<std::complex<double>> field_spectrum(const std::vector<double>& field,
                                                 const reference::Grid& grid);
// The inverse: Σk ĥ(k) e^(ik·x), real part (ĥ Hermitian up to rounding).
std::vector<double> field_from_spectrum(const std::vector<std::complex<double>>& spectrum,
                                        const reference::Grid& grid);

// μ(k) over the grid, in FFT order.
std::vector<double> expected_periodogram(const reference::DirectionalSpectrum& spectrum,
                                         const reference::Grid& grid);
// E|h̃0(k)|² = ½ Ψ(k) Δkx Δky: the mean power of the wave travelling along +k (rows on up to
// `threads` threads; the values do not depend on it).
std::vector<double> expected_travelling_power(const reference::DirectionalSpectrum& spectrum,
                                              const reference::Grid& grid, int threads = 1);
// μ(k) = τ(k) + τ(−k) from the travelling power τ above, without evaluating Ψ again.
std::vector<double> expected_periodogram(const std::vector<double>& travelling,
                                         const reference::Grid& grid);

// The same on any sampling (docs/conventions.md §2.1): a grid as above; a lattice's analysis is
// one forward 1-D FFT of its N samples over n, divided by N, coefficient m at k_m.
std::vector<std::complex<double>> field_spectrum(const std::vector<double>& field,
                                                 const reference::Sampling& sampling);
// The same into `spectrum` (resized), reusing its memory: for loops over many frames, where a
// fresh multi-megabyte vector per frame costs its page faults again.
// With `energy`, also Σ|X(k)|² / N of the transform X = N ĥ before its division by N (summed in
// long double in FFT order): the spectral side of Parseval's identity for kAnalysisBackend,
// exactly as the parseval check computes it, from the transform made here anyway.
void field_spectrum(const std::vector<double>& field, const reference::Sampling& sampling,
                    std::vector<std::complex<double>>& spectrum, long double* energy = nullptr);
// X = N ĥ, the transform field_spectrum divides by N (ĥ(k) = X(k) · (1/N) bit for bit), in the
// calling thread's scratch array: valid until this thread's next analysis transform. For loops
// that need a few entries of many frames' spectra without writing each whole spectrum out;
// release_analysis_scratch() afterwards frees the scratch when it is larger than it keeps.
std::span<const std::complex<double>> analysis_transform(const std::vector<double>& field,
                                                         const reference::Sampling& sampling,
                                                         long double* energy = nullptr);
void release_analysis_scratch();
// While one lives on a thread, that thread's scratch is kept however large: a pass over many
// frames reuses it, where a fresh array costs its page faults and the kernel's zeroing every
// frame (over 64 MiB, from 2048²). release_analysis_scratch() after the pass frees it; a pool
// thread's goes with the thread.
class KeepAnalysisScratch {
 public:
  KeepAnalysisScratch();
  ~KeepAnalysisScratch();
  KeepAnalysisScratch(const KeepAnalysisScratch&) = delete;
  KeepAnalysisScratch& operator=(const KeepAnalysisScratch&) = delete;
};
std::vector<double> field_from_spectrum(const std::vector<std::complex<double>>& spectrum,
                                        const reference::Sampling& sampling);
// The same into `field` (resized), reusing its memory: for loops over many frames.
void field_from_spectrum(const std::vector<std::complex<double>>& spectrum,
                         const reference::Sampling& sampling, std::vector<double>& field);
// The same for a spectrum `fill` writes straight into the transform's input (all
// sampling.size() entries, FFT order): no spectrum array of the caller's own.
void field_from_spectrum(const reference::Sampling& sampling,
                         const std::function<void(std::span<std::complex<double>>)>& fill,
                         std::vector<double>& field);
// Two real fields from one inverse transform: `fill` writes A + iB, where A and B are each the
// spectrum of a real field (Hermitian); the real part of the result is A's field, the imaginary
// part B's. Each carries the transform's rounding of the other besides its own (a few fp64 ulps
// of the other's size, log₂N-fold at most).
void fields_from_spectrum(const reference::Sampling& sampling,
                          const std::function<void(std::span<std::complex<double>>)>& fill,
                          std::vector<double>& real_field, std::vector<double>& imaginary_field);
// An aligned complex array for an inverse analysis transform (inverse_transform), held by the
// caller and kept between calls, not zeroed (each call writes every entry it reads): the
// spectrum is written into it and transformed over itself. A pass whose units of work each
// transform once keeps one per unit running at a time, where the threads' own scratch
// (field_from_spectrum) holds one on every thread that ever ran one.
class InverseTransformArrays {
 public:
  InverseTransformArrays();
  ~InverseTransformArrays();
  InverseTransformArrays(const InverseTransformArrays&) = delete;
  InverseTransformArrays& operator=(const InverseTransformArrays&) = delete;

 private:
  friend std::span<const std::complex<double>> inverse_transform(
      const reference::Sampling&, InverseTransformArrays&,
      const std::function<void(std::span<std::complex<double>>)>&);
  std::unique_ptr<impls::HostBuffer> data_;
};
// Σk s(k) e^(ik·x) of the spectrum s `fill` writes (all sampling.size() entries, FFT order),
// complex, in `arrays` (over the spectrum): valid until their next use. For s = A + iB with A
// and B each the spectrum of a real field, the real part is A's field and the imaginary part
// B's, bit for bit what fields_from_spectrum gives.
std::span<const std::complex<double>> inverse_transform(
    const reference::Sampling& sampling, InverseTransformArrays& arrays,
    const std::function<void(std::span<std::complex<double>>)>& fill);
std::vector<double> expected_travelling_power(const reference::DirectionalSpectrum& spectrum,
                                              const reference::Sampling& sampling, int threads = 1);
std::vector<double> expected_periodogram(const std::vector<double>& travelling,
                                         const reference::Sampling& sampling);
std::vector<double> expected_periodogram(const reference::DirectionalSpectrum& spectrum,
                                         const reference::Sampling& sampling);
// True for the representative of each ±k pair carrying energy: exactly one of k, −k.
bool in_half_plane(int n, int m);

}  // namespace swell::validation
