#pragma once
// Measured 1-D wave spectra from NDBC buoys for the fit (docs/buoy_fit.md): the moments of a
// spectrum on its bands, 4√m0 against the summary's WVHT, and each spectral record paired with
// its summary by hour (spectra are stamped :50, summaries :40 of the same hour). The files'
// readers, BuoyHour and the band table live in the io room (io/ndbc_files.hpp), which this header
// includes, so that every user of the fit finds them here as well.
//
// Frequencies in this file are in Hz (NDBC's unit), labelled as such; swell's angular moments
// (docs/conventions.md) are not used here.
#include <vector>

#include "swell/validation/io/ndbc_files.hpp"

namespace swell::validation {

// Σ_j S_j f_j^n Δf_j (in m²·Hzⁿ); NaN if any band is missing.
double spectral_moment_hz(const std::vector<double>& density, const SpectralBands& bands, int n);
// 4√m0 from the bands.
double moment_significant_height(const std::vector<double>& density, const SpectralBands& bands);
// The spread of 4√m0 that rounding each printed S_j to `quantum` can cause: every S_j within
// ±quantum/2 moves m0 by at most (quantum/2) Σ Δf_j.
double moment_height_rounding(const std::vector<double>& density, const SpectralBands& bands,
                              double quantum);

// Whether 4√m0 of the bands agrees with the summary's WVHT: WVHT is printed to 0.1 m, so it
// stands for [WVHT − 0.05, WVHT + 0.05]; each S_j to `quantum`, which moves 4√m0 by up to
// moment_height_rounding. Agreement: |4√m0 − WVHT| ≤ 0.05 m + that (+1e-9 for the decimal
// representation of the printed numbers).
bool height_agrees_with_wvht(double hs_moments, double wvht, const std::vector<double>& density,
                             const SpectralBands& bands, double quantum);

// A spectrum and the summary of the same hour (if there is one).
struct PairedBuoyHour {
  const BuoySpectrumRecord* spectrum = nullptr;
  const BuoySummaryRecord* summary = nullptr;  // null when the summary lacks this hour
};

// Pairs every spectral record with the summary of its hour, chronologically. Throws
// InvalidInput when one file holds the same hour twice (naming both lines).
std::vector<PairedBuoyHour> pair_by_hour(const BuoySpectrumFile& spectra,
                                         const std::vector<BuoySummaryRecord>& summaries);

}  // namespace swell::validation
