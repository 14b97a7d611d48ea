// NDBC's spectral-density, summary and directional-parameter files, and the band table
// (ndbc_files.hpp, docs/buoy_fit.md §1 and §4, docs/ndbc_directional.md §1).
#include "swell/validation/io/ndbc_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "swell/reference/errors.hpp"

namespace swell::validation {
namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
// NDBC's missing value in the directional-parameter files (printed 999.0, 999.00).
constexpr double kNdbcMissing = 999.0;

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

// Where a value came from, for messages: "FILE line N, field NAME".
struct Place {
  const std::string& path;
  int line;
  std::string where(const std::string& field) const {
    return fmt::format("{} line {}, field {}", path, line, field);
  }
};

double parse_number(const std::string& token, const Place& place, const std::string& field,
                    bool missing_allowed) {
  if (token == "MM") {
    if (missing_allowed) return kMissing;
    throw InvalidInput(place.where(field) + ": 'MM' (missing) is not allowed here");
  }
  double value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) {
    throw InvalidInput(place.where(field) + ": '" + token + "' is not a number");
  }
  return value;
}

int parse_integer(const std::string& token, const Place& place, const std::string& field, int lo,
                  int hi) {
  int value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) {
    throw InvalidInput(place.where(field) + ": '" + token + "' is not an integer");
  }
  if (value < lo || value > hi) {
    throw InvalidInput(
        fmt::format("{}: {} is outside [{}, {}]", place.where(field), value, lo, hi));
  }
  return value;
}

BuoyHour parse_time(const std::vector<std::string>& t, std::size_t yy, std::size_t mo,
                    std::size_t dd, std::size_t hh, const Place& place) {
  BuoyHour time;
  time.year = parse_integer(t[yy], place, "YY", 0, 9999);
  if (time.year < 100) time.year += time.year < 50 ? 2000 : 1900;  // NDBC's 2-digit years
  time.month = parse_integer(t[mo], place, "MM", 1, 12);
  time.day = parse_integer(t[dd], place, "DD", 1, 31);
  time.hour = parse_integer(t[hh], place, "hh", 0, 23);
  return time;
}

// A band's frequency as printed after its value: "(0.033)", in Hz, > 0.
double parse_frequency(const std::string& f, const Place& place, std::size_t band) {
  const std::string field = fmt::format("freq_{}", band);
  if (f.size() < 3 || f.front() != '(' || f.back() != ')') {
    throw InvalidInput(place.where(field) + ": '" + f + "' is not a frequency in parentheses");
  }
  const double hz = parse_number(f.substr(1, f.size() - 2), place, field, false);
  if (!(hz > 0)) {
    throw InvalidInput(place.where(field) + fmt::format(": {} Hz is not positive", hz));
  }
  return hz;
}

std::ifstream open(const std::string& path, const char* what) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(fmt::format("cannot open the {} {}", what, path));
  return in;
}

// NDBC's WPM band table (https://www.ndbc.noaa.gov/faq/wavespectra.shtml): band 1 at 0.0200 Hz
// (0.010 wide, not in the FM 65 reports), 13 bands of 0.005 Hz centred 0.0325…0.0925, 26 of
// 0.010 Hz centred 0.100…0.350, 7 of 0.020 Hz centred 0.365…0.485.
std::vector<std::pair<double, double>> wpm_table() {
  std::vector<std::pair<double, double>> table{{0.0200, 0.010}};
  for (int i = 0; i < 13; ++i) table.push_back({0.0325 + 0.005 * i, 0.005});
  for (int i = 0; i < 26; ++i) table.push_back({0.100 + 0.010 * i, 0.010});
  for (int i = 0; i < 7; ++i) table.push_back({0.365 + 0.020 * i, 0.020});
  return table;
}

// Every record of one file lists the same bands: the first record's frequencies become the
// file's, a later record with others is refused naming both.
template <typename File>
void keep_one_set_of_bands(File& file, const std::vector<double>& frequency, const std::string& path,
                           int line) {
  if (file.records.empty()) {
    file.frequency = frequency;
  } else if (frequency != file.frequency) {
    throw InvalidInput(fmt::format(
        "{} line {}: {} frequencies from {} to {} Hz; the first record (line {}) has {} from "
        "{} to {} Hz — one file must keep one set of bands",
        path, line, frequency.size(), frequency.front(), frequency.back(), file.records.front().line,
        file.frequency.size(), file.frequency.front(), file.frequency.back()));
  }
}

}  // namespace

std::string BuoyHour::iso() const {
  return fmt::format("{:04d}-{:02d}-{:02d}T{:02d}:00Z", year, month, day, hour);
}

double BuoyHour::hours_since_2000() const {
  // Days from civil (H. Hinnant's algorithm), relative to 2000-01-01.
  const int y = year - (month <= 2);
  const int era = (y >= 0 ? y : y - 399) / 400;
  const int yoe = y - era * 400;
  const int doy = (153 * (month + (month > 2 ? -3 : 9)) + 2) / 5 + day - 1;
  const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  const long days = long(era) * 146097 + doe - 719468 - 10957;
  return double(days) * 24.0 + hour;
}

BuoySpectrumFile read_ndbc_spectral_density(const std::string& path) {
  auto in = open(path, "spectral-density file");
  BuoySpectrumFile file;
  file.path = path;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto t = tokens(line);
    if (t.empty() || t[0][0] == '#') continue;
    const Place place{path, number};
    if (t.size() < 8 || (t.size() - 6) % 2 != 0) {
      throw InvalidInput(fmt::format(
          "{} line {}: {} fields; a record is YY MM DD hh mm Sep_Freq followed by pairs "
          "'S (f)'",
          path, number, t.size()));
    }
    BuoySpectrumRecord r;
    r.line = number;
    r.time = parse_time(t, 0, 1, 2, 3, place);
    r.minute = parse_integer(t[4], place, "mm", 0, 59);
    r.separation_frequency = parse_number(t[5], place, "Sep_Freq", true);
    std::vector<double> frequency;
    for (std::size_t i = 6; i < t.size(); i += 2) {
      const std::size_t band = (i - 6) / 2 + 1;
      const std::string name = fmt::format("spec_{}", band);
      const double s = parse_number(t[i], place, name, true);
      if (s < 0) throw InvalidInput(place.where(name) + fmt::format(": {} m²/Hz is negative", s));
      r.density.push_back(s);
      frequency.push_back(parse_frequency(t[i + 1], place, band));
    }
    keep_one_set_of_bands(file, frequency, path, number);
    file.records.push_back(std::move(r));
  }
  if (file.records.empty()) {
    throw InvalidInput(path + ": no spectral records (only headers or blank lines)");
  }
  return file;
}

std::vector<BuoySummaryRecord> read_ndbc_summary(const std::string& path) {
  auto in = open(path, "summary file");
  std::map<std::string, std::size_t> column;
  std::vector<BuoySummaryRecord> out;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    auto t = tokens(line);
    if (t.empty()) continue;
    if (t[0][0] == '#') {
      if (column.empty()) {  // the first header names the columns; the second gives units
        t[0] = t[0].substr(1);
        for (std::size_t i = 0; i < t.size(); ++i) column.emplace(t[i], i);
        for (const char* required : {"YY", "MM", "DD", "hh", "mm", "WVHT"}) {
          if (!column.count(required)) {
            throw InvalidInput(fmt::format(
                "{} line {}: the header names no column '{}' (expected #YY MM DD hh mm WVHT …)",
                path, number, required));
          }
        }
      }
      continue;
    }
    if (column.empty()) {
      throw InvalidInput(fmt::format(
          "{} line {}: a record before the header line (#YY MM DD hh mm WVHT …)", path, number));
    }
    const Place place{path, number};
    const std::size_t needed = std::max_element(column.begin(), column.end(), [](auto& a, auto& b) {
                                 return a.second < b.second;
                               })->second + 1;
    if (t.size() != needed) {
      throw InvalidInput(fmt::format("{} line {}: {} fields, the header names {}", path, number,
                                     t.size(), needed));
    }
    BuoySummaryRecord r;
    r.line = number;
    r.time = parse_time(t, column["YY"], column["MM"], column["DD"], column["hh"], place);
    r.minute = parse_integer(t[column["mm"]], place, "mm", 0, 59);
    auto number_of = [&](const char* name) {
      const auto it = column.find(name);
      return it == column.end() ? kMissing : parse_number(t[it->second], place, name, true);
    };
    auto text_of = [&](const char* name) -> std::string {
      const auto it = column.find(name);
      return it == column.end() || t[it->second] == "MM" ? "" : t[it->second];
    };
    r.wvht = number_of("WVHT");
    r.swell_height = number_of("SwH");
    r.swell_period = number_of("SwP");
    r.wind_sea_height = number_of("WWH");
    r.wind_sea_period = number_of("WWP");
    r.average_period = number_of("APD");
    r.mean_direction = number_of("MWD");
    r.swell_direction = text_of("SwD");
    r.wind_sea_direction = text_of("WWD");
    r.steepness = text_of("STEEPNESS");
    out.push_back(std::move(r));
  }
  if (out.empty()) throw InvalidInput(path + ": no summary records (only headers or blank lines)");
  return out;
}

const char* ndbc_directional_parameter_name(NdbcDirectionalParameter parameter) {
  switch (parameter) {
    case NdbcDirectionalParameter::alpha1: return "alpha1";
    case NdbcDirectionalParameter::alpha2: return "alpha2";
    case NdbcDirectionalParameter::r1: return "r1";
    case NdbcDirectionalParameter::r2: return "r2";
  }
  return "?";
}

NdbcParameterFile read_ndbc_directional_parameter(const std::string& path,
                                                  NdbcDirectionalParameter parameter) {
  const std::string name = ndbc_directional_parameter_name(parameter);
  const bool angle = parameter == NdbcDirectionalParameter::alpha1 ||
                     parameter == NdbcDirectionalParameter::alpha2;
  auto in = open(path, (name + " file").c_str());
  NdbcParameterFile file;
  file.path = path;
  file.parameter = parameter;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto t = tokens(line);
    if (t.empty()) continue;
    if (t[0][0] == '#') {
      // "#YY  MM DD hh mm alpha1_1 (freq_1) …": the first value column names the parameter.
      if (t.size() > 5 && t[0] == "#YY") {
        const std::string& column = t[5];
        const auto underscore = column.rfind('_');
        const std::string named = column.substr(0, underscore);
        if (underscore != std::string::npos && named != name) {
          throw InvalidInput(fmt::format(
              "{} line {}: the header names {} values ('{}'), but the file was given as the {} "
              "file",
              path, number, named, column, name));
        }
      }
      continue;
    }
    const Place place{path, number};
    if (t.size() < 7 || (t.size() - 5) % 2 != 0) {
      throw InvalidInput(fmt::format(
          "{} line {}: {} fields; a record is YY MM DD hh mm followed by pairs '{} (f)'", path,
          number, t.size(), name));
    }
    NdbcParameterRecord r;
    r.line = number;
    r.time = parse_time(t, 0, 1, 2, 3, place);
    r.minute = parse_integer(t[4], place, "mm", 0, 59);
    std::vector<double> frequency;
    for (std::size_t i = 5; i < t.size(); i += 2) {
      const std::size_t band = (i - 5) / 2 + 1;
      const std::string field = fmt::format("{}_{}", name, band);
      double v = parse_number(t[i], place, field, true);
      // NDBC's missing value, printed where a band has no energy (e.g. 999.0, 999.00).
      if (v == kNdbcMissing) v = kMissing;
      if (angle && !(std::isnan(v) || (v >= 0 && v <= 360))) {
        throw InvalidInput(place.where(field) +
                           fmt::format(": {}° is outside [0, 360] (and not 999, missing)", v));
      }
      if (!angle && !(std::isnan(v) || (v >= 0 && v <= 1))) {
        throw InvalidInput(
            place.where(field) +
            fmt::format(": {} is outside [0, 1] (and not 999, missing){}", v,
                        v > 1 && v <= 100 ? "; NDBC's historical files print r × 100, the "
                                            "realtime files read here r itself"
                                          : ""));
      }
      r.value.push_back(v);
      frequency.push_back(parse_frequency(t[i + 1], place, band));
    }
    keep_one_set_of_bands(file, frequency, path, number);
    file.records.push_back(std::move(r));
  }
  if (file.records.empty()) {
    throw InvalidInput(fmt::format("{}: no {} records (only headers or blank lines)", path, name));
  }
  return file;
}

const char* band_convention_name(BandConvention convention) {
  return convention == BandConvention::ndbc_wpm_table ? "ndbc-wpm-table" : "midpoints";
}

SpectralBands spectral_bands(const std::vector<double>& printed,
                             std::optional<BandConvention> convention) {
  if (printed.size() < 2) {
    throw InvalidInput(fmt::format("band widths need at least 2 frequencies, got {}", printed.size()));
  }
  for (std::size_t j = 1; j < printed.size(); ++j) {
    if (!(printed[j] > printed[j - 1])) {
      throw InvalidInput(fmt::format("band frequencies must increase: {} Hz follows {} Hz",
                                     printed[j], printed[j - 1]));
    }
  }
  SpectralBands bands;
  // The table applies when the printed centres are its centres to their rounding: NDBC prints
  // 3 decimals, so 0.0325 appears as 0.033 (±0.0005, and a little more for binary rounding).
  const auto table = wpm_table();
  auto table_match = [&]() -> std::optional<std::size_t> {
    for (std::size_t first : {std::size_t(0), std::size_t(1)}) {
      if (table.size() - first != printed.size()) continue;
      bool all = true;
      for (std::size_t j = 0; j < printed.size() && all; ++j) {
        all = std::abs(table[first + j].first - printed[j]) <= 0.0006;
      }
      if (all) return first;
    }
    return std::nullopt;
  }();
  const BandConvention use =
      convention.value_or(table_match ? BandConvention::ndbc_wpm_table : BandConvention::midpoints);
  if (use == BandConvention::ndbc_wpm_table) {
    if (!table_match) {
      throw InvalidInput(fmt::format(
          "the {} frequencies from {} to {} Hz are not NDBC's WPM bands (46 or 47 centres "
          "0.0200/0.0325…0.485 Hz)",
          printed.size(), printed.front(), printed.back()));
    }
    for (std::size_t j = 0; j < printed.size(); ++j) {
      bands.centre.push_back(table[*table_match + j].first);
      bands.width.push_back(table[*table_match + j].second);
    }
  } else {
    const std::size_t n = printed.size();
    bands.centre = printed;
    for (std::size_t j = 0; j < n; ++j) {
      const double lo = j == 0 ? printed[0] - 0.5 * (printed[1] - printed[0])
                               : 0.5 * (printed[j - 1] + printed[j]);
      const double hi = j + 1 == n ? printed[n - 1] + 0.5 * (printed[n - 1] - printed[n - 2])
                                   : 0.5 * (printed[j] + printed[j + 1]);
      bands.width.push_back(hi - lo);
    }
  }
  bands.convention = use;
  return bands;
}

}  // namespace swell::validation
