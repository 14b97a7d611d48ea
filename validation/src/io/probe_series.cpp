#include "swell/validation/io/probe_series.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "swell/reference/errors.hpp"
#include "swell/validation/io/npy.hpp"

namespace swell::validation {
namespace {

namespace fs = std::filesystem;

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t\r\n");
  std::string out = s.substr(begin, end - begin + 1);
  if (out.size() >= 2 && out.front() == '"' && out.back() == '"') out = out.substr(1, out.size() - 2);
  return out;
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(trim(field));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

std::vector<std::string> split_spaces(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string token;
  while (in >> token) out.push_back(token);
  return out;
}

// A printed number and half its last digit's place: "1.234E+00" → (1.234, 5e-4); "12.50" →
// (12.5, 5e-3); "3" → (3, 0.5).
struct Printed {
  double value = 0, half_quantum = 0;
};

bool parse_printed(const std::string& token, Printed& out) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;
  const auto result = std::from_chars(begin, end, out.value);
  if (result.ec != std::errc() || result.ptr != end || !std::isfinite(out.value)) return false;
  const auto point = token.find('.');
  const auto exponent_at = token.find_first_of("eEdD");
  int decimals = 0;
  if (point != std::string::npos) {
    const auto stop = exponent_at == std::string::npos ? token.size() : exponent_at;
    decimals = int(stop - point - 1);
  }
  int exponent = 0;
  if (exponent_at != std::string::npos) exponent = std::atoi(token.c_str() + exponent_at + 1);
  out.half_quantum = 0.5 * std::pow(10.0, exponent - decimals);
  return true;
}

// The columns a table names for the time and each probe, by name, in the positions' order.
struct Columns {
  int time = -1;
  std::vector<int> probes;
};

Columns find_columns(const std::vector<std::string>& names, const ProbeInput& input, const std::string& where) {
  Columns out;
  auto index_of = [&](const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) {
      std::string listed;
      for (const auto& n : names) listed += (listed.empty() ? "" : ", ") + n;
      throw InvalidInput(fmt::format("{}: no column '{}' (the columns are {})", where, name, listed));
    }
    return int(it - names.begin());
  };
  if (!input.time_column.empty()) out.time = index_of(input.time_column);
  for (const auto& name : input.probes) out.probes.push_back(index_of(name));
  return out;
}

// The rows of a table read into the series, each checked.
struct TableReader {
  const fs::path& path;
  const Columns& columns;
  const reference::ProbeLayout& layout;
  ProbeSeries& series;
  std::size_t row = 0;

  void add(const std::vector<std::string>& fields, std::size_t width, int line) {
    if (fields.size() != width) {
      throw InvalidInput(fmt::format("{}:{}: {} values where the header names {}", path.string(), line,
                                     fields.size(), width));
    }
    if (row >= layout.samples) {
      throw InvalidInput(fmt::format("{}:{}: more rows than the case's samples = {}", path.string(), line,
                                     layout.samples));
    }
    auto value = [&](int column, const char* what) {
      Printed printed;
      if (!parse_printed(fields[std::size_t(column)], printed)) {
        throw InvalidInput(fmt::format("{}:{}: column {} ({}): '{}' is not a finite number", path.string(), line,
                                       column + 1, what, fields[std::size_t(column)]));
      }
      return printed;
    };
    if (columns.time >= 0) {
      const Printed t = value(columns.time, "time");
      const double expected = layout.time(row);
      const double tolerance = t.half_quantum + 1e-9 * std::max(std::abs(expected), layout.dt);
      if (std::abs(t.value - expected) > tolerance) {
        throw InvalidInput(fmt::format("{}:{}: time {:.12g} s where the case's t0 + n dt is {:.12g} s "
                                       "(sample {}; t0 = {:g} s, dt = {:g} s)",
                                       path.string(), line, t.value, expected, row, layout.t0, layout.dt));
      }
    }
    for (std::size_t p = 0; p < columns.probes.size(); ++p) {
      const Printed v = value(columns.probes[p], "probe");
      series.elevation[p].push_back(v.value);
      series.rounding[p] = std::max(series.rounding[p], v.half_quantum);
    }
    ++row;
  }
};

// A series per probe, empty, its rounding 0: what a table's rows fill.
ProbeSeries no_samples_yet(const reference::ProbeLayout& layout) {
  ProbeSeries series;
  series.elevation.resize(layout.positions.size());
  series.rounding.assign(layout.positions.size(), 0.0);
  return series;
}

void require_probe_names(const ProbeInput& input, std::size_t probes, const std::string& where) {
  if (input.probes.size() != probes) {
    throw InvalidInput(fmt::format("{}: [input] probes must name one column per probe ({} positions; "
                                   "got {} names)",
                                   where, probes, input.probes.size()));
  }
}

ProbeSeries read_csv(const fs::path& path, const ProbeInput& input, const reference::ProbeLayout& layout) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(path.string() + ": cannot open the series file");
  require_probe_names(input, layout.positions.size(), path.string());
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!trim(line).empty()) break;
  }
  if (trim(line).empty()) throw InvalidInput(path.string() + ": empty (a header line of column names first)");
  const auto names = split_commas(line);
  const Columns columns = find_columns(names, input, fmt::format("{}:{}", path.string(), number));
  ProbeSeries series = no_samples_yet(layout);
  TableReader reader{path, columns, layout, series};
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty()) continue;
    reader.add(split_commas(line), names.size(), number);
  }
  if (reader.row != layout.samples) {
    throw InvalidInput(fmt::format("{}: {} rows of samples where the case has samples = {}", path.string(),
                                   reader.row, layout.samples));
  }
  return series;
}

// OpenFAST's .out: the names line is the first whose tokens include the time column and every
// probe column; the next line holds the units.
ProbeSeries read_openfast(const fs::path& path, const ProbeInput& input, const reference::ProbeLayout& layout) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(path.string() + ": cannot open the series file");
  require_probe_names(input, layout.positions.size(), path.string());
  if (input.time_column.empty()) {
    throw InvalidInput(path.string() + ": an OpenFAST .out table needs [input] time_column (its \"Time\")");
  }
  std::string line;
  int number = 0, time_line = 0;
  std::vector<std::string> names, with_time;
  while (std::getline(in, line)) {
    ++number;
    const auto tokens = split_spaces(line);
    if (time_line == 0 && std::find(tokens.begin(), tokens.end(), input.time_column) != tokens.end()) {
      time_line = number, with_time = tokens;
    }
    const bool has_all = std::find(tokens.begin(), tokens.end(), input.time_column) != tokens.end() &&
                         std::all_of(input.probes.begin(), input.probes.end(), [&](const std::string& name) {
                           return std::find(tokens.begin(), tokens.end(), name) != tokens.end();
                         });
    if (has_all) {
      names = tokens;
      break;
    }
  }
  if (names.empty() && time_line > 0) {
    (void)find_columns(with_time, input, fmt::format("{}:{}", path.string(), time_line));  // names the missing one
  }
  if (names.empty()) {
    throw InvalidInput(fmt::format("{}: no line names the time column '{}' and every probe column; an "
                                   "OpenFAST .out table has a line of names, then a line of units",
                                   path.string(), input.time_column));
  }
  const Columns columns = find_columns(names, input, fmt::format("{}:{}", path.string(), number));
  if (!std::getline(in, line)) throw InvalidInput(path.string() + ": no units line after the names line");
  ++number;
  const auto units = split_spaces(line);
  if (units.empty() || units.front().front() != '(') {
    throw InvalidInput(fmt::format("{}:{}: expected the units line, e.g. \"(s) (m)\", after the names", path.string(),
                                   number));
  }
  if (columns.time >= 0 && std::size_t(columns.time) < units.size() && units[std::size_t(columns.time)] != "(s)") {
    throw InvalidInput(fmt::format("{}:{}: the time column's unit is {}, not (s)", path.string(), number,
                                   units[std::size_t(columns.time)]));
  }
  for (std::size_t p = 0; p < columns.probes.size(); ++p) {
    const auto c = std::size_t(columns.probes[p]);
    if (c < units.size() && units[c] != "(m)") {
      throw InvalidInput(fmt::format("{}:{}: probe column '{}' is in {}, not (m)", path.string(), number,
                                     input.probes[p], units[c]));
    }
  }
  ProbeSeries series = no_samples_yet(layout);
  TableReader reader{path, columns, layout, series};
  while (std::getline(in, line)) {
    ++number;
    const auto tokens = split_spaces(line);
    if (tokens.empty()) continue;
    reader.add(tokens, names.size(), number);
  }
  if (reader.row != layout.samples) {
    throw InvalidInput(fmt::format("{}: {} rows of samples where the case has samples = {}", path.string(),
                                   reader.row, layout.samples));
  }
  return series;
}

// `path` names the array in messages: the .npy file, or the array handed over in memory.
ProbeSeries npy_series(const NpyArray& array, const fs::path& path, const reference::ProbeLayout& layout) {
  const std::size_t probes = layout.positions.size();
  const bool one_column = array.shape.size() == 1 && probes == 1;
  if (!(one_column || (array.shape.size() == 2 && array.shape[1] == probes))) {
    throw InvalidInput(fmt::format("{}: shape {} where the case needs (samples, probes) = ({}, {})",
                                   path.string(), shape_string(array.shape), layout.samples, probes));
  }
  if (array.shape[0] != layout.samples) {
    throw InvalidInput(fmt::format("{}: {} samples where the case has samples = {}", path.string(),
                                   array.shape[0], layout.samples));
  }
  std::vector<double> values;
  double unit = 0;
  bool float_valued = false;
  if (array.dtype == NpyArray::Dtype::f4) {
    const auto floats = array.values<float>();
    values.assign(floats.begin(), floats.end());
    unit = std::numeric_limits<float>::epsilon() / 2;
  } else if (array.dtype == NpyArray::Dtype::f8) {
    values = array.values<double>();
    unit = std::numeric_limits<double>::epsilon() / 2;
    // Doubles that are all floats were computed (or stored) in single precision: their rounding
    // is a float's, which the exact checks must allow.
    if (std::all_of(values.begin(), values.end(), [](double v) { return double(float(v)) == v; })) {
      unit = std::numeric_limits<float>::epsilon() / 2;
      float_valued = true;
    }
  } else {
    throw InvalidInput(fmt::format("{}: dtype '{}'; probe series are float32 or float64", path.string(),
                                   to_descr(array.dtype)));
  }
  ProbeSeries series;
  series.elevation.assign(probes, std::vector<double>(layout.samples));
  series.rounding.assign(probes, 0.0);
  for (std::size_t n = 0; n < layout.samples; ++n) {
    for (std::size_t p = 0; p < probes; ++p) {
      const double v = values[n * probes + p];
      if (!std::isfinite(v)) {
        throw InvalidInput(fmt::format("{}: sample {} of probe {} is not finite", path.string(), n, p));
      }
      series.elevation[p][n] = v;
      series.rounding[p] = std::max(series.rounding[p], unit * std::abs(v));
    }
  }
  if (float_valued) {
    series.notes.push_back(fmt::format("{}: float64 values that are all float32 values: judged with a float's "
                                       "rounding", path.string()));
  }
  return series;
}

ProbeSeries read_npy_series(const fs::path& path, const reference::ProbeLayout& layout) {
  return npy_series(read_npy(path), path, layout);
}

}  // namespace

ProbeSeries probe_series_from_array(const NpyArray& array, const std::string& source,
                                    const reference::ProbeLayout& layout) {
  ProbeSeries series = npy_series(array, source, layout);
  series.source = source;
  return series;
}

ProbeSeries read_probe_series(const fs::path& path, const ProbeInput& input, const reference::ProbeLayout& layout) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw InvalidInput(path.string() + ": no such series file (or not a regular file)");
  }
  std::string ext = path.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  ProbeSeries series = ext == ".npy" ? read_npy_series(path, layout)
                       : ext == ".out" ? read_openfast(path, input, layout)
                                       : read_csv(path, input, layout);
  series.source = path.string();
  return series;
}

ProbeSeries read_probe_series(const CaseFile& case_file) {
  if (!case_file.is_probe_case()) throw InvalidInput(case_file.origin.string() + ": not a probes case");
  const auto& input = case_file.probes->input;
  if (input.files.empty()) {
    throw InvalidInput(case_file.origin.string() + ": [input] needs files (the series: .csv, .out or .npy)");
  }
  const fs::path file = fs::path(input.files).is_absolute() ? fs::path(input.files) : case_file.directory / input.files;
  return read_probe_series(file, input, case_file.probes->layout);
}

void write_probe_series_csv(const fs::path& path, const reference::ProbeLayout& layout,
                            const std::vector<std::vector<double>>& elevation,
                            const std::vector<std::string>& names, const std::string& time_column) {
  if (names.size() != elevation.size()) throw InternalError("write_probe_series_csv: a name per probe");
  std::ofstream out(path);
  if (!out) throw InvalidInput(path.string() + ": cannot write the series file");
  out << time_column;
  for (const auto& name : names) out << ',' << name;
  out << '\n';
  char buffer[64];
  auto put = [&](double v) {
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    out.write(buffer, result.ptr - buffer);
  };
  for (std::size_t n = 0; n < layout.samples; ++n) {
    put(layout.time(n));
    for (const auto& series : elevation) {
      out << ',';
      put(series[n]);
    }
    out << '\n';
  }
  if (!out) throw InvalidInput(path.string() + ": writing the series failed (disk full?)");
}

}  // namespace swell::validation
