#pragma once
// The elevation series of a probes case (reference/probe_sea.hpp) from its wave lines, fast:
// per probe, the lines of one frequency combine into one complex amplitude
// B_i(x) = Σ_j a_ij e^(i(k_i ê(θ_ij)·x + φ_ij)), and η(x, t_n) = Re Σ_i B_i e^(−iω_i t_n) is
//   - one forward FFT of length M = repeat_period/dt when the frequencies are uniform and the
//     repeat period is a whole number of samples (ω_i t_n = 2π q_i n/M + ω_i t0): the series
//     over one repeat period, repeated;
//   - otherwise summed frequency by frequency, e^(−iω dt) applied as a rotation and re-anchored
//     on the exactly reduced phase every 64 samples (its rounding stays near 1e-14 of a line's
//     amplitude).
// Either agrees with reference::probe_series_direct to ~1e-12 of the series' rms
// (ProbeSynthesis tests). Probes run on up to `threads` threads.
#include <vector>

#include "swell/reference/probe_sea.hpp"

namespace swell::impls {

// series[p][n]: probe p at t_n = t0 + n dt.
std::vector<std::vector<double>> synthesize_probe_series(const reference::ProbeCase& probe_case,
                                                         const std::vector<reference::WaveLine>& lines,
                                                         int threads = 1);

// Whether the FFT path applies: uniform frequencies and repeat_period/dt within 1e-9 of an
// integer M ≥ 2 (returned in `period_samples`).
bool probe_series_is_periodic(const reference::ProbeCase& probe_case, std::size_t* period_samples = nullptr);

}  // namespace swell::impls
