// Spectra from files (spectrum_table_file.hpp): CSV through the standard library, netCDF
// through Unidata's C library (Debian's libnetcdf-dev).
#include "swell/validation/io/spectrum_table_file.hpp"

#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <numeric>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "swell/reference/errors.hpp"
#include "swell/reference/table_spectrum.hpp"

namespace swell::validation {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// The factor from the file's frequency to ω in rad/s.
double omega_per_frequency_unit(const SpectrumTableDeclaration& d, const std::string& where) {
  if (d.frequency_unit.empty()) {
    throw InvalidInput(fmt::format("{}: frequency_unit is not declared ({}); swell never guesses "
                                   "a file's units", where, kFrequencyUnits));
  }
  if (d.frequency_unit == "Hz") return 2 * kPi;
  if (d.frequency_unit == "rad/s") return 1;
  throw InvalidInput(fmt::format("{}: frequency_unit \"{}\" is not one of {}", where,
                                 d.frequency_unit, kFrequencyUnits));
}

// The factor from the file's density to swell's (per rad/s, and per radian of direction).
double density_factor(const SpectrumTableDeclaration& d, bool directional, const std::string& where) {
  const char* valid = directional ? kDensityUnits2d : kDensityUnits1d;
  if (d.density_unit.empty()) {
    throw InvalidInput(fmt::format("{}: density_unit is not declared ({})", where, valid));
  }
  // Per Hz → per rad/s: S(ω) = S(f) df/dω = S(f)/(2π). Per degree → per radian: × 180/π.
  if (!directional) {
    if (d.density_unit == "m2/Hz") return 1 / (2 * kPi);
    if (d.density_unit == "m2.s/rad") return 1;
  } else {
    if (d.density_unit == "m2/Hz/deg") return 180 / kPi / (2 * kPi);
    if (d.density_unit == "m2/Hz/rad") return 1 / (2 * kPi);
    if (d.density_unit == "m2.s/rad/rad") return 1;
  }
  throw InvalidInput(fmt::format("{}: density_unit \"{}\" is not one of {}{}", where,
                                 d.density_unit, valid,
                                 directional ? " (a 2-D table's density is per direction too)"
                                             : " (a 1-D table's density is per frequency only)"));
}

reference::SpectrumTable read_csv(const SpectrumTableDeclaration& d) {
  const std::string where = d.file.string();
  if (!d.direction_convention.empty() || !d.direction_unit.empty()) {
    throw InvalidInput(fmt::format("{}: a CSV table is 1-D S(f) (frequency, density); "
                                   "direction_convention and direction_unit belong to a 2-D "
                                   "netCDF table", where));
  }
  const double to_omega = omega_per_frequency_unit(d, where);
  const double to_density = density_factor(d, false, where);
  std::ifstream in(d.file);
  if (!in) throw InvalidInput(fmt::format("{}: cannot open the spectrum table", where));
  reference::SpectrumTable t;
  t.source = where;
  std::string line;
  int number = 0;
  bool header = false;
  double previous = -1;
  while (std::getline(in, line)) {
    ++number;
    const std::string text = trim(line);
    if (text.empty() || text[0] == '#') continue;
    if (!header) {  // the first line names the columns
      header = true;
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream stream(text);
    for (std::string cell; std::getline(stream, cell, ',');) cells.push_back(trim(cell));
    if (cells.size() != 2) {
      throw InvalidInput(fmt::format("{}:{}: expected 2 columns (frequency, density), got {}",
                                     where, number, cells.size()));
    }
    double values[2];
    for (int c = 0; c < 2; ++c) {
      std::size_t used = 0;
      try {
        values[c] = std::stod(cells[c], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != cells[c].size() || cells[c].empty()) {
        throw InvalidInput(fmt::format("{}:{}: column {} ({}) '{}' is not a number", where, number,
                                       c + 1, c == 0 ? "frequency" : "density", cells[c]));
      }
      if (!std::isfinite(values[c]) || values[c] < 0 || (c == 0 && values[c] == 0)) {
        throw InvalidInput(fmt::format("{}:{}: column {} ({}) is {} (must be finite and {})", where,
                                       number, c + 1, c == 0 ? "frequency" : "density", cells[c],
                                       c == 0 ? "> 0" : "≥ 0"));
      }
    }
    if (!(values[0] > previous)) {
      throw InvalidInput(fmt::format("{}:{}: column 1 (frequency) {} does not increase (after {}): "
                                     "the rows must be sorted by frequency", where, number,
                                     values[0], previous));
    }
    previous = values[0];
    t.omega.push_back(values[0] * to_omega);
    t.density.push_back(values[1] * to_density);
  }
  if (!header) throw InvalidInput(where + ": empty file (a header, then rows of frequency, density)");
  if (t.omega.empty()) throw InvalidInput(where + ": no rows after the header");
  return t;
}

// ------------------------------------------------------------------ netCDF

struct NcFile {
  int id = -1;
  std::string where;
  ~NcFile() {
    if (id >= 0) nc_close(id);
  }
  void check(int status, const std::string& doing) const {
    if (status != NC_NOERR) {
      throw InvalidInput(fmt::format("{}: {}: {}", where, doing, nc_strerror(status)));
    }
  }
  int variable(const std::string& name, const std::string& key) const {
    int var = -1;
    if (nc_inq_varid(id, name.c_str(), &var) != NC_NOERR) {
      int count = 0;
      nc_inq_nvars(id, &count);
      std::string names;
      for (int v = 0; v < count; ++v) {
        char buffer[NC_MAX_NAME + 1] = {};
        nc_inq_varname(id, v, buffer);
        names += (names.empty() ? "" : ", ") + std::string(buffer);
      }
      throw InvalidInput(fmt::format("{}: no variable '{}' ({} = \"{}\"); the file's variables: {}",
                                     where, name, key, name, names));
    }
    return var;
  }
  std::vector<int> dimensions(int var) const {
    int count = 0;
    check(nc_inq_varndims(id, var, &count), "reading a variable's dimensions");
    std::vector<int> dims(std::size_t(count), 0);
    if (count > 0) check(nc_inq_vardimid(id, var, dims.data()), "reading a variable's dimensions");
    return dims;
  }
  std::string dimension_name(int dim) const {
    char buffer[NC_MAX_NAME + 1] = {};
    check(nc_inq_dimname(id, dim, buffer), "reading a dimension's name");
    return buffer;
  }
  std::size_t dimension_length(int dim) const {
    std::size_t length = 0;
    check(nc_inq_dimlen(id, dim, &length), "reading a dimension's length");
    return length;
  }
  // The CF packing and fill attributes of a variable: value = raw × scale + offset; raw equal
  // to the fill value is missing.
  double attribute(int var, const char* name, double fallback) const {
    double value = fallback;
    std::size_t length = 0;
    if (nc_inq_attlen(id, var, name, &length) != NC_NOERR || length != 1) return fallback;
    if (nc_get_att_double(id, var, name, &value) != NC_NOERR) return fallback;
    return value;
  }
  // A 1-D coordinate variable, whole.
  std::vector<double> coordinate(const std::string& name, const std::string& key) const {
    const int var = variable(name, key);
    const auto dims = dimensions(var);
    if (dims.size() != 1) {
      throw InvalidInput(fmt::format("{}: the coordinate variable '{}' has {} dimensions (1 "
                                     "expected)", where, name, dims.size()));
    }
    std::vector<double> values(dimension_length(dims[0]));
    if (!values.empty()) check(nc_get_var_double(id, var, values.data()), "reading '" + name + "'");
    const double scale = attribute(var, "scale_factor", 1), offset = attribute(var, "add_offset", 0);
    for (double& v : values) v = v * scale + offset;
    return values;
  }
};

reference::SpectrumTable read_netcdf(const SpectrumTableDeclaration& d) {
  const std::string where = d.file.string();
  const double to_omega = omega_per_frequency_unit(d, where);
  const double to_density = density_factor(d, true, where);
  if (d.direction_unit.empty()) {
    throw InvalidInput(fmt::format("{}: direction_unit is not declared ({})", where, kDirectionUnits));
  }
  if (d.direction_unit != "deg" && d.direction_unit != "rad") {
    throw InvalidInput(fmt::format("{}: direction_unit \"{}\" is not one of {}", where,
                                   d.direction_unit, kDirectionUnits));
  }
  if (d.direction_convention.empty()) {
    throw InvalidInput(fmt::format("{}: direction_convention is not declared ({}): whether the "
                                   "file's directions are where the waves come from, clockwise "
                                   "from north, or where they go, counter-clockwise from +x",
                                   where, kDirectionConventions));
  }
  if (d.direction_convention != "nautical_from" && d.direction_convention != "toward_ccw_from_x") {
    throw InvalidInput(fmt::format("{}: direction_convention \"{}\" is not one of {}", where,
                                   d.direction_convention, kDirectionConventions));
  }
  NcFile nc;
  nc.where = where;
  if (!fs::exists(d.file)) throw InvalidInput(where + ": no such file (the spectrum table)");
  nc.check(nc_open(d.file.c_str(), NC_NOWRITE, &nc.id), "opening the netCDF file");
  const std::vector<double> frequency = nc.coordinate(d.frequency_variable, "frequency_variable");
  const std::vector<double> direction = nc.coordinate(d.direction_variable, "direction_variable");
  const int freq_dim = nc.dimensions(nc.variable(d.frequency_variable, "frequency_variable"))[0];
  const int dir_dim = nc.dimensions(nc.variable(d.direction_variable, "direction_variable"))[0];
  const int var = nc.variable(d.variable, "variable");
  const auto dims = nc.dimensions(var);
  std::vector<std::size_t> start(dims.size(), 0), count(dims.size(), 1);
  int freq_axis = -1, dir_axis = -1;
  std::map<std::string, long> unused = d.select;
  for (std::size_t a = 0; a < dims.size(); ++a) {
    const std::string name = nc.dimension_name(dims[a]);
    const std::size_t length = nc.dimension_length(dims[a]);
    if (dims[a] == freq_dim) {
      freq_axis = int(a);
      count[a] = length;
    } else if (dims[a] == dir_dim) {
      dir_axis = int(a);
      count[a] = length;
    } else if (const auto it = d.select.find(name); it != d.select.end()) {
      if (it->second < 0 || std::size_t(it->second) >= length) {
        throw InvalidInput(fmt::format("{}: select {} = {} is outside the dimension '{}' (0 … {})",
                                       where, name, it->second, name, long(length) - 1));
      }
      start[a] = std::size_t(it->second);
      unused.erase(name);
    } else if (length != 1) {
      throw InvalidInput(fmt::format("{}: '{}' has dimension '{}' of length {}: choose one with "
                                     "select = {{{} = INDEX}} (e.g. select = {{time = 0, site = 0}})",
                                     where, d.variable, name, length, name));
    }
  }
  if (!unused.empty()) {
    throw InvalidInput(fmt::format("{}: select names '{}', which is not a dimension of '{}'", where,
                                   unused.begin()->first, d.variable));
  }
  if (freq_axis < 0 || dir_axis < 0) {
    throw InvalidInput(fmt::format("{}: '{}' is not a function of '{}' and '{}' (its dimensions do "
                                   "not include theirs)", where, d.variable, d.frequency_variable,
                                   d.direction_variable));
  }
  const std::size_t nf = frequency.size(), nd = direction.size();
  std::vector<double> raw(nf * nd);
  if (!raw.empty()) {
    nc.check(nc_get_vara_double(nc.id, var, start.data(), count.data(), raw.data()),
             "reading '" + d.variable + "'");
  }
  const double scale = nc.attribute(var, "scale_factor", 1), offset = nc.attribute(var, "add_offset", 0);
  const double fill = nc.attribute(var, "_FillValue", std::numeric_limits<double>::quiet_NaN());
  // The value at file row i (frequency) and column j (direction), whatever the axes' order.
  auto at = [&](std::size_t i, std::size_t j) {
    const double v = freq_axis < dir_axis ? raw[i * nd + j] : raw[j * nf + i];
    return v == fill ? std::numeric_limits<double>::quiet_NaN() : v * scale + offset;
  };

  // The axes: frequencies strictly increasing; directions distinct and in cyclic order (either
  // sense: WAVEWATCH III lists them descending from a start), in [0, 360) or [0, 2π).
  for (std::size_t i = 0; i < nf; ++i) {
    if (!(std::isfinite(frequency[i]) && frequency[i] > 0)) {
      throw InvalidInput(fmt::format("{}: {}[{}] = {} (frequencies must be finite and > 0)", where,
                                     d.frequency_variable, i, frequency[i]));
    }
    if (i > 0 && !(frequency[i] > frequency[i - 1])) {
      throw InvalidInput(fmt::format("{}: {} is not sorted: {}[{}] = {} after {}", where,
                                     d.frequency_variable, d.frequency_variable, i, frequency[i],
                                     frequency[i - 1]));
    }
  }
  const double turn = d.direction_unit == "deg" ? 360.0 : 2 * kPi;
  // The declared unit against the values: radians never exceed 2π, and a full circle of
  // directions in degrees spans far more than 2π.
  const auto [lowest, highest] = std::minmax_element(direction.begin(), direction.end());
  if (nd > 0 && d.direction_unit == "rad" && *highest - *lowest > 2 * kPi + 1e-9) {
    throw InvalidInput(fmt::format("{}: direction_unit = \"rad\", but {} spans {:g} to {:g}, more "
                                   "than 2π: are the directions in degrees (direction_unit = "
                                   "\"deg\")?", where, d.direction_variable, *lowest, *highest));
  }
  if (nd > 4 && d.direction_unit == "deg" && *highest - *lowest <= 2 * kPi + 1e-9) {
    throw InvalidInput(fmt::format("{}: direction_unit = \"deg\", but {} spans only {:g} to {:g}: "
                                   "{} directions within 2π degrees are radians (direction_unit = "
                                   "\"rad\")", where, d.direction_variable, *lowest, *highest, nd));
  }
  // Going once round the circle in the listed order, each step taken counter-clockwise in
  // (0, turn): one turn in all when the list ascends cyclically, n − 1 turns when it descends.
  double up = 0;
  for (std::size_t j = 0; j < nd; ++j) {
    if (!std::isfinite(direction[j])) {
      throw InvalidInput(fmt::format("{}: {}[{}] = {}", where, d.direction_variable, j, direction[j]));
    }
    const double step = std::fmod(direction[(j + 1) % nd] - direction[j] + 4 * turn, turn);
    if (nd > 1 && step == 0) {
      throw InvalidInput(fmt::format("{}: {}[{}] and [{}] are the same direction", where,
                                     d.direction_variable, j, (j + 1) % nd));
    }
    up += step;
  }
  const double turns = up / turn;
  if (nd > 2 && std::abs(turns - 1) > 1e-9 * nd && std::abs(turns - double(nd - 1)) > 1e-9 * nd) {
    throw InvalidInput(fmt::format("{}: {} is not sorted around the circle (each direction must "
                                   "follow the previous one in one sense)", where,
                                   d.direction_variable));
  }
  for (std::size_t i = 0; i < nf; ++i) {
    for (std::size_t j = 0; j < nd; ++j) {
      const double v = at(i, j);
      if (!(std::isfinite(v) && v >= 0)) {
        throw InvalidInput(fmt::format("{}: {} at {} row {} ({} = {:g}), {} column {} ({} = {:g}) "
                                       "is {} (must be finite and ≥ 0)", where, d.variable,
                                       d.frequency_variable, i, d.frequency_variable, frequency[i],
                                       d.direction_variable, j, d.direction_variable, direction[j], v));
      }
    }
  }

  // Into swell's frame: θ toward which the waves travel, counter-clockwise from +x. Nautical
  // "from" θn (clockwise from north, where they come from) travels toward θn + 180° clockwise
  // from north, which is 90° − (θn + 180°) = 270° − θn counter-clockwise from east.
  const double to_radians = d.direction_unit == "deg" ? kPi / 180 : 1.0;
  std::vector<double> theta(nd);
  for (std::size_t j = 0; j < nd; ++j) {
    double x = direction[j] * to_radians;
    if (d.direction_convention == "nautical_from") x = 1.5 * kPi - x;
    x = std::fmod(x, 2 * kPi);
    if (x < 0) x += 2 * kPi;
    if (x >= 2 * kPi) x = 0;
    theta[j] = x;
  }
  std::vector<std::size_t> order(nd);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return theta[a] < theta[b]; });
  reference::SpectrumTable t;
  t.source = fmt::format("{} ({})", where, d.variable);
  for (std::size_t i = 0; i < nf; ++i) t.omega.push_back(frequency[i] * to_omega);
  for (auto j : order) t.theta.push_back(theta[j]);
  t.density.resize(nf * nd);
  for (std::size_t i = 0; i < nf; ++i) {
    for (std::size_t c = 0; c < nd; ++c) t.density[i * nd + c] = at(i, order[c]) * to_density;
  }
  return t;
}

}  // namespace

reference::SpectrumTable read_spectrum_table(const SpectrumTableDeclaration& d) {
  const std::string extension = d.file.extension().string();
  reference::SpectrumTable table;
  if (extension == ".csv") {
    table = read_csv(d);
  } else if (extension == ".nc" || extension == ".nc4" || extension == ".cdf") {
    table = read_netcdf(d);
  } else {
    throw InvalidInput(fmt::format("{}: a spectrum table is .csv (1-D S(f)) or .nc (2-D E(f, θ), "
                                   "netCDF)", d.file.string()));
  }
  reference::validate_table(table);
  return table;
}

}  // namespace swell::validation
