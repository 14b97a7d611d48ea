#pragma once
// NDBC buoy files, read as printed (docs/buoy_fit.md §1, docs/ndbc_directional.md §1): the
// spectral-density file (`*.data_spec`: `YY MM DD hh mm Sep_Freq  S1 (f1) S2 (f2) …`, S in
// m²/Hz, one record an hour), the hourly summary (`*.spec`: WVHT, SwH, SwP, WWH, WWP, SwD, WWD,
// STEEPNESS, APD, MWD; "MM" means missing), the four directional-parameter files (`*.swdir`,
// `*.swdir2`, `*.swr1`, `*.swr2`: α1, α2, r1, r2 per band), and the bands' widths (NDBC's WPM
// table). Spectra are stamped :50 and
// summaries :40 of the same hour, so records carry the hour and the minute apart.
//
// Frequencies in this file are in Hz and directions in degrees, NDBC's units, labelled as such;
// nothing here converts into swell's conventions (docs/conventions.md): the directional reader
// (ndbc_directional.hpp) and the fit (fit/buoy_spectrum.hpp) do.
#include <optional>
#include <string>
#include <vector>

namespace swell::validation {

// The hour a record belongs to (UTC); minutes are kept apart because the two files stamp the
// same hour differently.
struct BuoyHour {
  int year = 0, month = 0, day = 0, hour = 0;
  auto operator<=>(const BuoyHour&) const = default;
  long key() const { return ((long(year) * 100 + month) * 100 + day) * 100 + hour; }
  std::string iso() const;  // "2020-06-01T03:00Z"
  // Hours since 2000-01-01T00Z (proleptic Gregorian), for plotting and differences.
  double hours_since_2000() const;
};

struct BuoySpectrumRecord {
  BuoyHour time;
  int minute = 0;
  double separation_frequency = 0;  // Hz, NDBC's swell/wind-sea split (NaN when "MM")
  std::vector<double> density;      // m²/Hz per band as printed (NaN when "MM")
  int line = 0;                     // 1-based line in the file
};

struct BuoySpectrumFile {
  std::string path;
  std::vector<double> frequency;  // Hz, the band centres as printed (3 decimals in NDBC files)
  std::vector<BuoySpectrumRecord> records;  // in file order (NDBC writes newest first)
};

// Reads an NDBC spectral-density file. Lines starting with '#' are headers. Every record must
// list the same frequencies. Throws InvalidInput naming the file, the line and the field for a
// file that cannot be opened, a malformed or negative value, a record whose frequencies differ
// from the first one's, or a file without records.
BuoySpectrumFile read_ndbc_spectral_density(const std::string& path);

struct BuoySummaryRecord {
  BuoyHour time;
  int minute = 0;
  // NaN where the file says "MM" or the column is absent.
  double wvht = 0;            // m, significant wave height (4√m0), rounded to 0.1 m
  double swell_height = 0;    // SwH, m
  double swell_period = 0;    // SwP, s
  double wind_sea_height = 0; // WWH, m
  double wind_sea_period = 0; // WWP, s
  double average_period = 0;  // APD, s
  double mean_direction = 0;  // MWD, degrees true
  std::string swell_direction, wind_sea_direction, steepness;  // as printed ("" if missing)
  int line = 0;
};

// Reads an NDBC hourly summary (`.spec`); the columns are found by the names in its first header
// line (#YY MM DD hh mm WVHT SwH SwP WWH WWP SwD WWD STEEPNESS APD MWD). Throws InvalidInput as
// the spectral reader does.
std::vector<BuoySummaryRecord> read_ndbc_summary(const std::string& path);

// How the band widths were obtained.
enum class BandConvention {
  ndbc_wpm_table,  // NDBC's WPM band table (centres 0.0325…0.0925 Hz by 0.005, 0.100…0.350 by
                   // 0.01, 0.365…0.485 by 0.02; https://www.ndbc.noaa.gov/faq/wavespectra.shtml)
  midpoints,       // edges halfway between neighbouring centres, the end bands symmetric
};
const char* band_convention_name(BandConvention convention);

struct SpectralBands {
  std::vector<double> centre;  // Hz (the table's exact centre where the table applies)
  std::vector<double> width;   // Hz, Δf_j
  BandConvention convention = BandConvention::midpoints;
  double low_edge(std::size_t j) const { return centre[j] - 0.5 * width[j]; }
  double high_edge(std::size_t j) const { return centre[j] + 0.5 * width[j]; }
};

// The bands of printed centre frequencies: NDBC's WPM table when the printed centres are the
// table's 46 (or 47, with the 0.0200 Hz band) centres to their printed rounding (±0.0006 Hz),
// else midpoints between neighbours (or the convention forced by `convention`). Throws
// InvalidInput for fewer than 2 or non-increasing frequencies.
SpectralBands spectral_bands(const std::vector<double>& printed_frequency,
                             std::optional<BandConvention> convention = std::nullopt);

// The four directional-parameter files of NDBC's realtime directional products
// (https://www.ndbc.noaa.gov/faq/measdes.shtml): per band, the mean direction α1 and the
// principal direction α2 (degrees, nautical: the direction the waves come FROM, clockwise from
// true north; α2 is defined modulo 180°), and the normalized Fourier amplitudes r1 and r2 in
// [0, 1]. NDBC's historical yearly files (`…j2019.txt`, `…k2019.txt`) print r1, r2 times 100;
// the realtime files read here print them as they are, which the range check enforces.
enum class NdbcDirectionalParameter { alpha1, alpha2, r1, r2 };
// "alpha1", "alpha2", "r1", "r2": the column names of the files' headers (alpha1_1, …).
const char* ndbc_directional_parameter_name(NdbcDirectionalParameter parameter);

struct NdbcParameterRecord {
  BuoyHour time;
  int minute = 0;
  // Per band, as printed; NaN where the file says "MM" or NDBC's missing value 999 (printed
  // 999.0 or 999.00, out of every parameter's range; NDBC prints it where the band has no energy).
  std::vector<double> value;
  int line = 0;  // 1-based line in the file
};

struct NdbcParameterFile {
  std::string path;
  NdbcDirectionalParameter parameter = NdbcDirectionalParameter::alpha1;
  std::vector<double> frequency;  // Hz, the band centres as printed
  std::vector<NdbcParameterRecord> records;  // in file order (NDBC writes newest first)
};

// Reads one directional-parameter file: `YY MM DD hh mm v1 (f1) v2 (f2) …`, lines starting with
// '#' are headers. Where a header names its columns (`alpha1_1 (freq_1) …`), the name must be
// `parameter`'s, so that files given in the wrong order are caught. Throws InvalidInput naming
// the file, the line and the field (alpha1_7, r2_12, …) for a file that cannot be opened, a
// malformed value, a value outside its range (α in [0, 360], r in [0, 1]: a file of r × 100
// is named as such), a record whose frequencies differ from the first one's, or a file without
// records.
NdbcParameterFile read_ndbc_directional_parameter(const std::string& path,
                                                  NdbcDirectionalParameter parameter);

}  // namespace swell::validation
