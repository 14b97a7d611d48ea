#pragma once
// A buoy record fitted hour by hour and summarized: what `swell fit --spectrum` reports
// (docs/buoy_fit.md). An NDBC spectral-density file is fitted hour by hour
// (fit_buoy_spectrum); with a summary file each hour is paired with the summary's (by hour:
// spectra at :50, summaries at :40) and 4√m0 compared with WVHT.
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "swell/validation/fit/buoy_fit.hpp"
#include "swell/validation/fit/buoy_spectrum.hpp"

namespace swell::validation {

// One hour of the record: what was measured, what was fitted.
struct BuoyRecordHour {
  BuoyHour time;
  const BuoySpectrumRecord* spectrum = nullptr;  // in BuoyRecordFit::spectra
  const BuoySummaryRecord* summary = nullptr;    // in BuoyRecordFit::summaries; null: unpaired
  double hs_moments = NAN, hs_rounding = NAN, tp_peak = NAN;
  double wvht = NAN, dominant_period = NAN, apd = NAN;
  std::string dominant_source;  // "SwP" or "WWP": the period of the larger of SwH and WWH
  std::optional<bool> wvht_agrees;
  std::optional<BuoyFit> fit;
  std::string fit_error;        // why an hour has no fit (no energy, too few bands)
};

// The record as a whole.
struct BuoyRecordSummary {
  int paired_hours = 0, wvht_compared = 0, wvht_agree = 0;
  double wvht_largest_difference = 0;  // m, |4√m0 − WVHT| over the compared hours
  std::string wvht_largest_at;         // its hour
  int fitted = 0, flagged = 0, second_peaks = 0, energy_misfits = 0, deviance_rejects = 0;
  int not_converged = 0;
  std::vector<double> dispersions;     // φ = deviance/dof of every fitted hour, ascending
};

struct BuoyRecordFit {
  std::string spectrum_file, summary_file;  // summary_file "" when none was given
  BuoyFitOptions options;
  BuoySpectrumFile spectra;
  std::vector<BuoySummaryRecord> summaries;
  SpectralBands bands;
  std::vector<BuoyRecordHour> hours;
  BuoyRecordSummary summary;
};

// Reads and fits the record. Bad files throw InvalidInput naming the file and line; an hour
// without energy is reported in its fit_error, not thrown.
BuoyRecordFit fit_buoy_record(const std::string& spectrum_file, const std::string& summary_file,
                              const BuoyFitOptions& options);

// {"spectrum_file", "summary_file", "band_convention", "dof_per_0_01_hz", "quantum", "sigma_a",
//  "sigma_b", "deviance_alpha", "shape_alpha", "hours": [...], "summary": {...}}
// (docs/buoy_fit.md §8).
nlohmann::json buoy_record_json(const BuoyRecordFit& record);
// The table of hours and the summary's lines, for the terminal.
std::string render_buoy_record(const BuoyRecordFit& record);

}  // namespace swell::validation
