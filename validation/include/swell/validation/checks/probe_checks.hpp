#pragma once
// The checks of a probes case (docs/probes.md): the elevation series at points judged against
// the sea and the synthesis scheme the case declares (reference/probe_sea.hpp).
//
// Over a record of whole repeat periods of uniform lines (record T = m · repeat_period), line i
// falls on DFT bin q = m i, and with X_q = (1/N) Σ η_n e^(−2πi q n/N) its periodogram
// I_q = 2|X_q|² has E I_q = S(ω_q) Δω:
//   series.spectrum      deterministic amplitudes with one direction per frequency (or a
//                        long-crested sea): I_q = S Δω exactly, to the stored values' rounding;
//                        Rayleigh amplitudes: I_q/(S Δω) independent Exp(1) — rings of bins,
//                        Σ ~ Gamma(n, 1), Fisher's method, per probe, Bonferroni over probes;
//   series.energy        Σ_q I_q over the lines' bins: Σ S Δω exactly, or the weighted sum of
//                        exponentials (saddlepoint law) for Rayleigh amplitudes;
//   series.stray_energy  bins no line falls on (and the mean level) hold only rounding:
//                        Σ I ≤ 2 r² by Parseval, r the bound on a value's rounding;
//   series.phase         long-crested: conj X_q at probe p over probe 0's is e^(i k(ω) ê·Δx)
//                        exactly, k of the case's depth — a deep-water k in finite depth is named.
//   series.moments       Hs, Tm01 and Tm02 of the line powers (checks/probes/spectral_moments.cpp);
//   series.repeat_period a record longer than repeat_period/dt samples repeats exactly;
//   series.skewness, series.kurtosis against simulated nulls (checks/probes/skewness_kurtosis.hpp).
// Any other record (equal-energy or random frequencies, or not whole repeat periods) is judged by
// Welch estimates and its mean square against their exact moments over the declared lines
// (checks/probes/welch_spectrum.cpp). Exact checks allow the stored rounding plus a double
// engine's own arithmetic. Checks whose law the scheme does not give yet are skipped, saying so.
#include <vector>

#include "swell/reference/probe_sea.hpp"
#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

struct ProbeCheckReport {
  std::vector<CheckResult> results;
  std::vector<Skipped> skipped;
  std::vector<std::string> notes;
};

// The statistical checks the case's scheme runs (they share the gate's family-wise α).
int probe_statistical_check_count(const reference::ProbeCase& probe_case);

// `elevation[p][n]` and `rounding[p]` (m, the bound on each stored value's rounding) of every
// probe; each statistical check at `alpha`.
ProbeCheckReport run_probe_checks(const reference::ProbeCase& probe_case,
                                  const std::vector<std::vector<double>>& elevation,
                                  const std::vector<double>& rounding, double alpha);

}  // namespace swell::validation
