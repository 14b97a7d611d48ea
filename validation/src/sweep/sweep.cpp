#include "swell/validation/sweep/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>
#include <toml++/toml.h>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/reports/figures.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"
#include "swell/validation/results/report.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/validation/stats/sample_moments.hpp"

namespace swell::validation::sweep {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double number_or_nan(const json& x) { return x.is_number() ? x.get<double>() : kNaN; }

// Shortest text that reads back as the same double ("" for NaN: an empty CSV cell).
std::string text(double x) { return std::isfinite(x) ? fmt::format("{}", x) : std::string(); }

toml::table parse_toml(const std::string& case_text, const fs::path& case_path) {
  try {
    return toml::parse(case_text, case_path.string());
  } catch (const toml::parse_error& e) {
    throw InvalidInput(fmt::format("{}: not valid TOML: {}", case_path.string(), e.description()));
  }
}

// Keys a case's fixed sections accept (docs/case_files.md §2); the model sections' keys come
// from the models' own parameter lists.
const std::vector<std::pair<std::string, std::vector<std::string>>>& fixed_keys() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> keys = {
      {"grid", {"n", "length"}},
      {"time", {"t0", "dt", "frames"}},
      {"physics", {"gravity", "depth"}},
      {"synthesis", {"choppiness", "loop_period", "seed"}},
      {"sampling", {"kind", "points", "generator"}},
  };
  return keys;
}

std::vector<std::string> model_keys(const toml::table& document, const std::string& section) {
  const auto model = document[section]["model"].value<std::string>();
  std::vector<std::string> keys = {"model"};
  if (section == "spectrum") keys.push_back("scale");
  if (!model) return keys;
  // The mean direction lives in [spreading], or in [spectrum] for phillips (its own spreading).
  if (section == "spreading" || *model == "phillips") keys.push_back("wind_dir_deg");
  try {
    for (const auto& info : reference::model_parameters(*model)) {
      if (info.name == "depth" || info.name == "gravity" || info.name == "wind_dir") continue;
      keys.push_back(info.name);
    }
  } catch (const InvalidInput&) {
    // An unknown model: the case file's own check names it when the point is built.
  }
  return keys;
}

// Where a bare key goes: the base case's own key first, then the vocabulary of every section.
std::pair<std::string, std::string> resolve_key(const std::string& name, const toml::table& document,
                                                const std::string& spec) {
  const auto dot = name.find('.');
  if (dot != std::string::npos) {
    const std::string section = name.substr(0, dot), key = name.substr(dot + 1);
    if (section.empty() || key.empty()) {
      throw InvalidInput(fmt::format("--vary {}: '{}' is not a case key (write KEY or SECTION.KEY, "
                                     "such as gamma or spectrum.gamma)", spec, name));
    }
    return {section, key};
  }
  std::vector<std::string> present;
  for (auto&& [section, node] : document) {
    if (const auto* table = node.as_table(); table && table->contains(name)) {
      present.emplace_back(section.str());
    }
  }
  if (present.size() == 1) return {present[0], name};
  if (present.size() > 1) {
    throw InvalidInput(fmt::format("--vary {}: '{}' is in more than one section of the case ({}); "
                                   "write SECTION.{}", spec, name, fmt::join(present, ", "), name));
  }
  std::vector<std::string> candidates, every;
  for (const auto& [section, keys] : fixed_keys()) {
    for (const auto& key : keys) {
      every.push_back(section + "." + key);
      if (key == name) candidates.push_back(section);
    }
  }
  for (const std::string section : {"spectrum", "spreading"}) {
    for (const auto& key : model_keys(document, section)) {
      every.push_back(section + "." + key);
      if (key == name && std::find(candidates.begin(), candidates.end(), section) == candidates.end()) {
        candidates.push_back(section);
      }
    }
  }
  if (candidates.size() == 1) return {candidates[0], name};
  if (candidates.empty()) {
    throw InvalidInput(fmt::format("--vary {}: unknown key '{}'; keys of this case: {}", spec, name,
                                   fmt::join(every, ", ")));
  }
  throw InvalidInput(fmt::format("--vary {}: '{}' could be in {}; write SECTION.{}", spec, name,
                                 fmt::join(candidates, " or "), name));
}

bool integral_key(const std::string& key) {
  return key == "n" || key == "frames" || key == "points";
}

std::optional<double> parse_number(const std::string& s) {
  if (s.empty()) return std::nullopt;
  std::size_t used = 0;
  try {
    const double x = std::stod(s, &used);
    if (used != s.size()) return std::nullopt;
    return x;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

void add_value(Variation& v, const std::string& literal) {
  if (const auto x = parse_number(literal)) {
    v.labels.push_back(literal);
    v.numbers.push_back(*x);
    const bool is_integer = literal.find_first_of(".eE") == std::string::npos;
    v.toml_values.push_back(is_integer ? literal : text(*x));
    if (!std::isfinite(*x)) v.toml_values.back() = *x > 0 ? "inf" : (*x < 0 ? "-inf" : "nan");
    return;
  }
  // A string: a model name, a choice, depth = "inf".
  if (literal.find_first_of("\"\\\n") != std::string::npos) {
    throw InvalidInput(fmt::format("--vary {}={}: a value may not contain quotes or backslashes",
                                   v.name, literal));
  }
  v.labels.push_back(literal);
  v.numbers.push_back(literal == "inf" ? std::numeric_limits<double>::infinity() : kNaN);
  v.toml_values.push_back("\"" + literal + "\"");
}

// SplitMix64's finalizer (Steele, Lea & Flood 2014): a bijection of 64-bit words whose outputs
// for neighbouring inputs are unrelated.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::string point_label(const SweepSpec& spec, const Point& point) {
  std::string out;
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    out += (out.empty() ? "" : ", ") + spec.variations[v].name + " = " +
           spec.variations[v].labels[point.value_index[v]];
  }
  return out.empty() ? "the base case" : out;
}

// Frequency moments of a power spectrum over the grid's wave vectors k ≠ 0 (FFT order), each at
// ω(|k|) of the case's dispersion: m_n = Σ P(k) ω^n for n = 0, 1, 2, and the peak band of ω
// (bands 4 % wide, as the moments check) with its P-weighted ω. Used for a run's periodogram and
// for a point's expected μ(k).
struct FrequencyMoments {
  double m[3] = {0, 0, 0};
  double peak_omega = kNaN;  // P-weighted ω of the most energetic band
  double tm01() const { return m[1] > 0 ? 2 * kPi * m[0] / m[1] : kNaN; }
  double tm02() const { return m[2] > 0 ? 2 * kPi * std::sqrt(m[0] / m[2]) : kNaN; }
};

FrequencyMoments frequency_moments(const reference::OceanCase& ocean, const std::vector<double>& power) {
  const auto& grid = ocean.grid;
  FrequencyMoments out;
  std::map<int, std::pair<double, double>> bands;  // band → (Σ P, Σ P ω)
  const double dkx = 2 * kPi / grid.lx, dky = 2 * kPi / grid.ly;
  for (int row = 0; row < grid.ny; ++row) {
    const int wy = row <= grid.ny / 2 ? row : row - grid.ny;
    for (int i = 0; i < grid.nx; ++i) {
      const int wx = i <= grid.nx / 2 ? i : i - grid.nx;
      if (wx == 0 && wy == 0) continue;
      const double p = power[std::size_t(row) * grid.nx + i];
      const double omega = ocean.omega(std::hypot(wx * dkx, wy * dky));
      out.m[0] += p;
      out.m[1] += p * omega;
      out.m[2] += p * omega * omega;
      auto& band = bands[int(std::floor(std::log(omega) / std::log(1.04)))];
      band.first += p;
      band.second += p * omega;
    }
  }
  double peak = 0;
  for (const auto& [key, band] : bands) {
    if (band.first > peak) {
      peak = band.first;
      out.peak_omega = band.second / band.first;
    }
  }
  return out;
}

}  // namespace

bool Variation::numeric() const {
  return std::all_of(numbers.begin(), numbers.end(), [](double x) { return std::isfinite(x); });
}

std::size_t SweepSpec::point_count() const {
  std::size_t n = 1;
  for (const auto& v : variations) n *= v.labels.size();
  return n;
}

json SweepSpec::to_json() const {
  json variations_json = json::array();
  for (const auto& v : variations) {
    variations_json.push_back({{"name", v.name}, {"section", v.section}, {"key", v.key},
                               {"values", v.labels}, {"toml_values", v.toml_values}});
  }
  return {{"case_file", case_path.string()},
          {"case", case_text},
          {"variations", variations_json},
          {"seeds", seeds},
          {"sweep_seed", sweep_seed},
          {"fit", fit},
          {"impl", impl},
          {"precision", impls::to_string(precision)},
          {"points", point_count()},
          {"runs", run_count()}};
}

SweepSpec SweepSpec::from_json(const json& d) {
  SweepSpec spec;
  try {
    spec.case_path = d.at("case_file").get<std::string>();
    spec.case_text = d.at("case").get<std::string>();
    for (const auto& v : d.at("variations")) {
      Variation variation;
      variation.name = v.at("name").get<std::string>();
      variation.section = v.at("section").get<std::string>();
      variation.key = v.at("key").get<std::string>();
      variation.labels = v.at("values").get<std::vector<std::string>>();
      variation.toml_values = v.at("toml_values").get<std::vector<std::string>>();
      for (const auto& label : variation.labels) {
        const auto x = parse_number(label);
        variation.numbers.push_back(x ? *x : (label == "inf" ? std::numeric_limits<double>::infinity() : kNaN));
      }
      spec.variations.push_back(std::move(variation));
    }
    spec.seeds = d.at("seeds").get<int>();
    spec.sweep_seed = d.at("sweep_seed").get<std::uint64_t>();
    spec.fit = d.at("fit").get<bool>();
    spec.impl = d.at("impl").get<std::string>();
    spec.precision = impls::precision_from_string(d.at("precision").get<std::string>());
  } catch (const json::exception& e) {
    throw InvalidInput(std::string("not a sweep description (sweep.json): ") + e.what());
  }
  return spec;
}

Variation parse_variation(const std::string& spec, const std::string& case_text,
                          const fs::path& case_path) {
  const auto equals = spec.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw InvalidInput(fmt::format("--vary {}: expected NAME=a:b:n or NAME=v1,v2,… (such as "
                                   "gamma=1:7:7 or n=64,128)", spec));
  }
  Variation v;
  v.name = trim(spec.substr(0, equals));
  const std::string values = trim(spec.substr(equals + 1));
  const toml::table document = parse_toml(case_text, case_path);
  std::tie(v.section, v.key) = resolve_key(v.name, document, spec);
  if (v.section == "synthesis" && v.key == "seed") {
    throw InvalidInput(fmt::format("--vary {}: a sweep derives each run's seed from --seed, the "
                                   "point and the replicate; give the replicates with --seeds", spec));
  }
  if (v.section == "input") {
    throw InvalidInput(fmt::format("--vary {}: [input] says where frames are read from; a sweep "
                                   "synthesizes its own", spec));
  }
  if (values.empty()) throw InvalidInput(fmt::format("--vary {}: no values after '='", spec));

  if (values.find(':') != std::string::npos) {
    // a:b:n — n values from a to b inclusive.
    std::vector<std::string> parts;
    std::stringstream stream(values);
    for (std::string part; std::getline(stream, part, ':');) parts.push_back(trim(part));
    if (parts.size() != 3) {
      throw InvalidInput(fmt::format("--vary {}: a range is a:b:n (from a to b in n values)", spec));
    }
    const auto a = parse_number(parts[0]), b = parse_number(parts[1]);
    const auto n = parse_number(parts[2]);
    if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b)) {
      throw InvalidInput(fmt::format("--vary {}: the range's ends must be finite numbers", spec));
    }
    if (!n || *n != std::floor(*n) || *n < 1 || *n > 1e6) {
      throw InvalidInput(fmt::format("--vary {}: the number of values n must be an integer in "
                                     "1…1000000 (got '{}')", spec, parts[2]));
    }
    const int count = int(*n);
    if (count == 1 && *a != *b) {
      throw InvalidInput(fmt::format("--vary {}: an empty range: one value cannot span {} to {} "
                                     "(give n ≥ 2, or a = b)", spec, parts[0], parts[1]));
    }
    for (int i = 0; i < count; ++i) {
      const double x = count == 1 ? *a : *a + (*b - *a) * double(i) / double(count - 1);
      const double rounded = std::round(x);
      if (integral_key(v.key) && std::abs(x - rounded) > 1e-9 * std::max(1.0, std::abs(x))) {
        throw InvalidInput(fmt::format("--vary {}: {} must be an integer, and the range gives {}",
                                       spec, v.key, text(x)));
      }
      add_value(v, integral_key(v.key) ? fmt::format("{}", (long long)rounded) : text(x));
    }
  } else {
    std::stringstream stream(values);
    for (std::string part; std::getline(stream, part, ',');) {
      part = trim(part);
      if (part.empty()) throw InvalidInput(fmt::format("--vary {}: an empty value in the list", spec));
      add_value(v, part);
    }
  }
  std::set<std::string> seen;
  for (const auto& label : v.labels) {
    if (!seen.insert(label).second) {
      throw InvalidInput(fmt::format("--vary {}: the value {} is given twice", spec, label));
    }
  }
  return v;
}

Point make_point(const SweepSpec& spec, std::size_t index) {
  if (index >= spec.point_count()) throw InternalError("sweep point index out of range");
  Point point;
  point.index = index;
  point.value_index.resize(spec.variations.size());
  std::size_t rest = index;
  for (std::size_t v = spec.variations.size(); v-- > 0;) {
    const std::size_t n = spec.variations[v].labels.size();
    point.value_index[v] = rest % n;
    rest /= n;
  }
  toml::table document = parse_toml(spec.case_text, spec.case_path);
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    const Variation& variation = spec.variations[v];
    const std::string& literal = variation.toml_values[point.value_index[v]];
    // The value parsed by toml++ itself, so that its type is TOML's reading of the literal.
    toml::table value = toml::parse("value = " + literal);
    if (!document.contains(variation.section)) document.insert(variation.section, toml::table{});
    toml::table* section = document[variation.section].as_table();
    if (!section) {
      throw InvalidInput(fmt::format("--vary {}: '{}' in the case is not a section", variation.name,
                                     variation.section));
    }
    section->insert_or_assign(variation.key, *value.get("value"));
  }
  std::ostringstream toml_text;
  toml_text << document;
  try {
    point.case_file = parse_case_toml(toml_text.str(), spec.case_path);
    require_single_grid(point.case_file, "swell sweep");
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("--vary at {}: the case rules refuse this point: {}",
                                   point_label(spec, point), e.what()));
  }
  return point;
}

void validate(const SweepSpec& spec) {
  if (spec.seeds < 1) throw InvalidInput(fmt::format("--seeds must be ≥ 1 (got {})", spec.seeds));
  std::set<std::string> keys;
  for (const auto& v : spec.variations) {
    if (!keys.insert(v.section + "." + v.key).second) {
      throw InvalidInput(fmt::format("--vary {}: [{}] {} is varied twice", v.name, v.section, v.key));
    }
  }
  // Each point is built and checked below, before any run: a product beyond ten million points
  // is refused rather than left to overflow or to take hours before the first run.
  double points = 1;
  for (const auto& v : spec.variations) points *= double(v.labels.size());
  if (points * spec.seeds > 1e10 || points > 1e7) {
    throw InvalidInput(fmt::format("the sweep has {:.3g} points × {} seeds: more than swell sweep "
                                   "takes (10⁷ points, 10¹⁰ runs); split it into several sweeps",
                                   points, spec.seeds));
  }
  const auto backend = impls::make_backend(spec.impl);
  const auto capabilities = backend->capabilities();
  if (std::find(capabilities.precisions.begin(), capabilities.precisions.end(), spec.precision) ==
      capabilities.precisions.end()) {
    throw InvalidInput(fmt::format("--impl {} has no {} transforms", spec.impl, impls::to_string(spec.precision)));
  }
  if (!capabilities.exact) {
    throw InvalidInput(fmt::format("--impl {}: its transforms are not exact (a benchmark stand-in); "
                                   "a sweep's statistics would be meaningless", spec.impl));
  }
  for (std::size_t i = 0; i < spec.point_count(); ++i) {
    const Point point = make_point(spec, i);
    const auto& ocean = point.case_file.ocean;
    if (ocean.is_lattice()) {
      throw InvalidInput(fmt::format("at {}: a sweep synthesizes grid cases; this one samples a "
                                     "rank-1 lattice", point_label(spec, point)));
    }
    if (!capabilities.any_size && (!impls::is_power_of_two(ocean.grid.nx) ||
                                   !impls::is_power_of_two(ocean.grid.ny))) {
      throw InvalidInput(fmt::format("at {}: --impl {} takes {} only, and the grid is {}×{} (use "
                                     "--impl fftw)", point_label(spec, point), spec.impl,
                                     capabilities.size_rule, ocean.grid.nx, ocean.grid.ny));
    }
    // The validity rule every command applies to a case (reference/sampling_validity.hpp), in
    // the synthesis precision, with one run's working set: the synthesizer and the case's frames
    // of six fields in double.
    try {
      const double frame_bytes = double(ocean.grid.nx) * double(ocean.grid.ny) * 6 * 8 * ocean.frames;
      reference::require_valid_sampling(
          ocean, spec.precision == impls::Precision::f64 ? reference::kFloat64 : reference::kFloat32,
          impls::Synthesizer::bytes_needed(ocean.grid, spec.precision) +
              std::uint64_t(std::min(frame_bytes, 1e18)),
          "swell sweep");
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("at {}: {}", point_label(spec, point), e.what()));
    }
    if (point.case_file.scale == SpectrumScale::free) {
      throw InvalidInput(fmt::format("at {}: the case declares a free spectrum scale; a sweep "
                                     "synthesizes the case's spectrum as given (write scale = "
                                     "\"absolute\")", point_label(spec, point)));
    }
    if (spec.fit) {
      try {
        case_jonswap_parameters(ocean);
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("--fit at {}: {}", point_label(spec, point), e.what()));
      }
    }
  }
}

std::uint64_t run_seed(std::uint64_t sweep_seed, std::size_t point, int replicate) {
  std::uint64_t z = mix(sweep_seed + 0x9e3779b97f4a7c15ULL);
  z = mix(z ^ (std::uint64_t(point) + 0x9e3779b97f4a7c15ULL));
  z = mix(z ^ (std::uint64_t(replicate) + 0x9e3779b97f4a7c15ULL));
  return z;
}

const std::vector<std::string>& statistic_names() {
  static const std::vector<std::string> names = {"hs",       "tp",           "tm01",
                                                 "tm02",     "skewness",     "excess_kurtosis",
                                                 "foam_fraction", "min_jacobian"};
  return names;
}

RunRow run(const SweepSpec& spec, const Point& point, int replicate) {
  const auto start = std::chrono::steady_clock::now();
  RunRow row;
  row.point = point.index;
  row.replicate = replicate;
  row.seed = run_seed(spec.sweep_seed, point.index, replicate);
  reference::OceanCase ocean = point.case_file.ocean;
  ocean.seed = row.seed;
  impls::SynthesizerOptions options;
  options.backend = spec.impl;
  options.precision = spec.precision;
  const impls::Synthesizer synthesizer(ocean, options);
  const reference::FrameSequence frames = synthesizer.frames();
  const auto& grid = ocean.grid;
  const std::size_t n = std::size_t(grid.nx) * std::size_t(grid.ny);

  // Central moments of h and the Jacobian's extremes over all samples of all frames.
  long double sum = 0;
  std::size_t count = 0, folded = 0;
  double min_j = std::numeric_limits<double>::infinity();
  for (const auto& frame : frames.frames) {
    for (const double h : frame.fields.at(reference::Field::height)) sum += h;
    for (const double j : frame.fields.at(reference::Field::jacobian)) {
      min_j = std::min(min_j, j);
      folded += j < 0;
    }
    count += n;
  }
  const double mean = double(sum / (long double)count);
  stats::SampleMoments<long double> height;
  for (const auto& frame : frames.frames) {
    height.add(frame.fields.at(reference::Field::height), mean);
  }
  const long double m2 = height.variance();
  auto& s = row.statistics;
  s["hs"] = 4 * std::sqrt(double(m2));
  s["skewness"] = m2 > 0 ? double(height.skewness()) : kNaN;
  s["excess_kurtosis"] = m2 > 0 ? double(height.excess_kurtosis()) : kNaN;
  s["foam_fraction"] = double(folded) / double(count);
  s["min_jacobian"] = min_j;

  // Periods from the periodogram averaged over frames, each wave vector at ω(|k|) of the case's
  // dispersion: m_n = Σ ω^n I(k) over k ≠ 0; Tm01 = 2π m0/m1, Tm02 = 2π √(m0/m2); Tp = 2π over
  // the energy-weighted ω of the most energetic 4 % band of ω (the moments check's bins).
  std::vector<double> periodogram(n, 0.0);
  for (std::size_t f = 0; f < frames.frames.size(); ++f) {
    const auto spectrum = field_spectrum(frames.field(int(f), reference::Field::height), grid);
    for (std::size_t i = 0; i < n; ++i) periodogram[i] += std::norm(spectrum[i]);
  }
  for (double& p : periodogram) p /= double(frames.frames.size());
  const FrequencyMoments moments = frequency_moments(ocean, periodogram);
  s["tm01"] = moments.tm01();
  s["tm02"] = moments.tm02();
  s["tp"] = 2 * kPi / moments.peak_omega;

  if (spec.fit) {
    const JonswapFit fit = fit_jonswap(ocean, {frames});
    row.fitted = true;
    row.fit_converged = fit.converged;
    auto keep = [&](const char* name, const Estimate& e) {
      row.fit[name] = {e.value, e.ci95_low, e.ci95_high, e.calibrated};
    };
    keep("hs", fit.hs);
    keep("tp", fit.tp);
    keep("gamma", fit.gamma);
  }
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

json row_json(const SweepSpec& spec, const RunRow& row) {
  json parameters = json::object();
  const Point point = [&] {
    Point p;
    p.index = row.point;
    std::size_t rest = row.point;
    p.value_index.resize(spec.variations.size());
    for (std::size_t v = spec.variations.size(); v-- > 0;) {
      p.value_index[v] = rest % spec.variations[v].labels.size();
      rest /= spec.variations[v].labels.size();
    }
    return p;
  }();
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    const auto& variation = spec.variations[v];
    const double x = variation.numbers[point.value_index[v]];
    parameters[variation.name] = std::isfinite(x) ? json(x) : json(variation.labels[point.value_index[v]]);
  }
  json statistics = json::object();
  for (const auto& name : statistic_names()) statistics[name] = json_number(row.statistics.at(name));
  json out = {{"point", row.point}, {"replicate", row.replicate}, {"seed", row.seed},
              {"parameters", parameters}, {"statistics", statistics}};
  if (row.fitted) {
    json fit = {{"converged", row.fit_converged}};
    for (const auto& [name, value] : row.fit) {
      fit[name] = {{"value", json_number(value.value)},
                   {"ci95", {json_number(value.ci95_low), json_number(value.ci95_high)}},
                   {"calibrated", value.calibrated}};
    }
    out["fit"] = fit;
  }
  out["seconds"] = row.seconds;
  return out;
}

RunRow row_from_json(const json& o) {
  RunRow row;
  try {
    row.point = o.at("point").get<std::size_t>();
    row.replicate = o.at("replicate").get<int>();
    row.seed = o.at("seed").get<std::uint64_t>();
    for (const auto& name : statistic_names()) row.statistics[name] = number_or_nan(o.at("statistics").at(name));
    if (o.contains("fit")) {
      row.fitted = true;
      row.fit_converged = o["fit"].at("converged").get<bool>();
      for (const char* name : {"hs", "tp", "gamma"}) {
        const auto& f = o["fit"].at(name);
        row.fit[name] = {number_or_nan(f.at("value")), number_or_nan(f.at("ci95")[0]),
                         number_or_nan(f.at("ci95")[1]), f.at("calibrated").get<bool>()};
      }
    }
    row.seconds = o.at("seconds").get<double>();
  } catch (const json::exception& e) {
    throw InvalidInput(std::string("not a sweep row: ") + e.what());
  }
  return row;
}

namespace {

// Mean, standard deviation and the t interval of the mean (95 %) of the finite values.
struct Summary {
  int n = 0;
  double mean = kNaN, sd = kNaN, low = kNaN, high = kNaN;
};

Summary summarize(const std::vector<double>& values) {
  Summary s;
  double sum = 0;
  for (double x : values) {
    if (std::isfinite(x)) {
      sum += x;
      ++s.n;
    }
  }
  if (s.n == 0) return s;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double squares = 0;
  for (double x : values) {
    if (std::isfinite(x)) squares += (x - s.mean) * (x - s.mean);
  }
  s.sd = std::sqrt(squares / (s.n - 1));
  const double t = boost::math::quantile(boost::math::students_t(s.n - 1), 0.975);
  s.low = s.mean - t * s.sd / std::sqrt(double(s.n));
  s.high = s.mean + t * s.sd / std::sqrt(double(s.n));
  return s;
}

struct PointSummary {
  std::size_t point = 0;
  int runs = 0;
  std::map<std::string, Summary> statistics;  // statistic_names() and fit_hs, fit_tp, fit_gamma
  // The fit against the point's truth (its case's JONSWAP parameters).
  std::map<std::string, double> truth, bias, coverage;
  std::map<std::string, int> calibrated;
  int converged = 0;
  // What the point's spectrum gives on its grid (band-limited: Σ μ(k) over the grid's k ≠ 0,
  // each at ω(|k|)): hs = 4 √m0, tm01 = 2π m0/m1, tm02 = 2π √(m0/m2). The measured means
  // scatter about these; the spectrum's untruncated moments (swell spectrum) differ from them
  // by the tail beyond the grid's Nyquist wave number.
  double expected_hs = kNaN, expected_tm01 = kNaN, expected_tm02 = kNaN;
};

void expected_moments(const reference::OceanCase& ocean, PointSummary& p) {
  const FrequencyMoments moments =
      frequency_moments(ocean, expected_periodogram(*ocean.directional_spectrum(), ocean.grid));
  p.expected_hs = 4 * std::sqrt(moments.m[0]);
  p.expected_tm01 = moments.tm01();
  p.expected_tm02 = moments.tm02();
}

}  // namespace

std::vector<std::string> write_outputs(const SweepSpec& spec, std::vector<RunRow> rows,
                                       const fs::path& dir, const std::string& gnuplot) {
  std::sort(rows.begin(), rows.end(), [](const RunRow& a, const RunRow& b) {
    return std::tie(a.point, a.replicate) < std::tie(b.point, b.replicate);
  });
  fs::create_directories(dir);
  const std::vector<std::string> fit_names = {"hs", "tp", "gamma"};

  // The value labels of each row's point.
  auto labels_of = [&](std::size_t point) {
    std::vector<std::string> labels(spec.variations.size());
    for (std::size_t v = spec.variations.size(); v-- > 0;) {
      labels[v] = spec.variations[v].labels[point % spec.variations[v].labels.size()];
      point /= spec.variations[v].labels.size();
    }
    return labels;
  };
  auto csv_cell = [](const std::string& s) {
    return s.find_first_of(",\"\n") == std::string::npos ? s : "\"" + s + "\"";
  };

  // runs.csv and runs.json
  {
    std::ofstream csv(dir / "runs.csv");
    csv << "point,replicate,seed";
    for (const auto& v : spec.variations) csv << "," << csv_cell(v.name);
    for (const auto& name : statistic_names()) csv << "," << name;
    if (spec.fit) {
      for (const auto& name : fit_names) {
        csv << ",fit_" << name << ",fit_" << name << "_ci95_low,fit_" << name << "_ci95_high,fit_"
            << name << "_calibrated";
      }
      csv << ",fit_converged";
    }
    csv << ",seconds\n";
    json runs = json::array();
    for (const auto& row : rows) {
      csv << row.point << "," << row.replicate << "," << row.seed;
      for (const auto& label : labels_of(row.point)) csv << "," << csv_cell(label);
      for (const auto& name : statistic_names()) csv << "," << text(row.statistics.at(name));
      if (spec.fit) {
        for (const auto& name : fit_names) {
          const auto& f = row.fit.at(name);
          csv << "," << text(f.value) << "," << text(f.ci95_low) << "," << text(f.ci95_high) << ","
              << (f.calibrated ? 1 : 0);
        }
        csv << "," << (row.fit_converged ? 1 : 0);
      }
      csv << "," << fmt::format("{:.6f}", row.seconds) << "\n";
      runs.push_back(row_json(spec, row));
    }
    std::ofstream(dir / "runs.json") << json{{"sweep", spec.to_json()}, {"runs", runs}}.dump(1) << "\n";
  }

  // points.csv and points.json: per point, over its seeds.
  std::vector<PointSummary> points;
  {
    std::map<std::size_t, std::vector<const RunRow*>> by_point;
    for (const auto& row : rows) by_point[row.point].push_back(&row);
    for (const auto& [index, point_rows] : by_point) {
      PointSummary p;
      p.point = index;
      p.runs = int(point_rows.size());
      for (const auto& name : statistic_names()) {
        std::vector<double> values;
        for (const auto* r : point_rows) values.push_back(r->statistics.at(name));
        p.statistics[name] = summarize(values);
      }
      const Point point = make_point(spec, index);
      expected_moments(point.case_file.ocean, p);
      if (spec.fit) {
        const auto truth = case_jonswap_parameters(point.case_file.ocean);
        p.truth = {{"hs", truth.hs}, {"tp", truth.tp}, {"gamma", truth.gamma}};
        for (const auto* r : point_rows) p.converged += r->fit_converged;
        for (const auto& name : fit_names) {
          std::vector<double> values;
          int covered = 0, calibrated = 0;
          for (const auto* r : point_rows) {
            const auto& f = r->fit.at(name);
            values.push_back(r->fit_converged ? f.value : kNaN);
            if (r->fit_converged && f.calibrated) {
              ++calibrated;
              covered += f.ci95_low <= p.truth[name] && p.truth[name] <= f.ci95_high;
            }
          }
          p.statistics["fit_" + name] = summarize(values);
          p.bias[name] = p.statistics["fit_" + name].mean - p.truth[name];
          p.calibrated[name] = calibrated;
          p.coverage[name] = calibrated > 0 ? double(covered) / calibrated : kNaN;
        }
      }
      points.push_back(std::move(p));
    }
    std::vector<std::string> summarized = statistic_names();
    if (spec.fit) {
      for (const auto& name : fit_names) summarized.push_back("fit_" + name);
    }
    std::ofstream csv(dir / "points.csv");
    csv << "point";
    for (const auto& v : spec.variations) csv << "," << csv_cell(v.name);
    csv << ",runs,expected_hs,expected_tm01,expected_tm02";
    for (const auto& name : summarized) {
      csv << "," << name << "_mean," << name << "_sd," << name << "_ci95_low," << name << "_ci95_high";
    }
    if (spec.fit) {
      for (const auto& name : fit_names) {
        csv << ",true_" << name << ",bias_" << name << ",coverage_" << name << ",calibrated_" << name;
      }
      csv << ",converged";
    }
    csv << "\n";
    json points_json = json::array();
    for (const auto& p : points) {
      csv << p.point;
      const auto labels = labels_of(p.point);
      for (const auto& label : labels) csv << "," << csv_cell(label);
      csv << "," << p.runs << "," << text(p.expected_hs) << "," << text(p.expected_tm01) << ","
          << text(p.expected_tm02);
      json entry = {{"point", p.point}, {"runs", p.runs},
                    {"expected", {{"hs", json_number(p.expected_hs)}, {"tm01", json_number(p.expected_tm01)},
                                  {"tm02", json_number(p.expected_tm02)}}}};
      for (std::size_t v = 0; v < spec.variations.size(); ++v) entry["parameters"][spec.variations[v].name] = labels[v];
      for (const auto& name : summarized) {
        const Summary& s = p.statistics.at(name);
        csv << "," << text(s.mean) << "," << text(s.sd) << "," << text(s.low) << "," << text(s.high);
        entry["statistics"][name] = {{"mean", json_number(s.mean)}, {"sd", json_number(s.sd)},
                                     {"ci95_of_mean", {json_number(s.low), json_number(s.high)}}, {"n", s.n}};
      }
      if (spec.fit) {
        for (const auto& name : fit_names) {
          csv << "," << text(p.truth.at(name)) << "," << text(p.bias.at(name)) << ","
              << text(p.coverage.at(name)) << "," << p.calibrated.at(name);
          entry["fit"][name] = {{"truth", json_number(p.truth.at(name))}, {"bias", json_number(p.bias.at(name))},
                                {"coverage", json_number(p.coverage.at(name))},
                                {"calibrated_intervals", p.calibrated.at(name)}};
        }
        csv << "," << p.converged;
        entry["fit"]["converged"] = p.converged;
      }
      csv << "\n";
      points_json.push_back(entry);
    }
    std::ofstream(dir / "points.json") << json{{"sweep", spec.to_json()}, {"points", points_json}}.dump(1) << "\n";
  }

  // Plots: each statistic against each numeric varied key, one series per combination of the
  // other keys' values, with the 95 % interval of the mean as a band.
  std::vector<std::string> notes;
  const bool render = reports::program_found(gnuplot);
  if (!render) {
    notes.push_back(gnuplot.empty()
                        ? std::string("no gnuplot given: the plots' .dat and .gp are written to plots/, their PNGs are not")
                        : fmt::format("gnuplot ('{}') was not found: the plots' .dat and .gp are written "
                                      "to plots/, their PNGs are not (install gnuplot-nox)", gnuplot));
  }
  const fs::path plots = dir / "plots";
  fs::create_directories(plots);
  std::vector<std::string> plotted = statistic_names();
  if (spec.fit) {
    for (const auto& name : fit_names) plotted.push_back("fit_" + name);
  }
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    const Variation& variation = spec.variations[v];
    if (!variation.numeric()) continue;
    for (const auto& name : plotted) {
      std::map<std::string, reports::Series> series;
      reports::Series truth{name.rfind("fit_", 0) == 0 ? "truth (the point's case)"
                                                       : "the spectrum on the grid (band-limited)",
                            {}, true, {}};
      for (const auto& p : points) {
        const auto labels = labels_of(p.point);
        std::string others;
        for (std::size_t w = 0; w < labels.size(); ++w) {
          if (w != v) others += (others.empty() ? "" : ", ") + spec.variations[w].name + " = " + labels[w];
        }
        const auto x_index = [&] {
          std::size_t rest = p.point, index = 0;
          for (std::size_t w = spec.variations.size(); w-- > 0;) {
            if (w == v) index = rest % spec.variations[w].labels.size();
            rest /= spec.variations[w].labels.size();
          }
          return index;
        }();
        const double x = variation.numbers[x_index];
        const Summary& s = p.statistics.at(name);
        if (!std::isfinite(s.mean)) continue;
        auto& line = series[others];
        line.title = others.empty() ? "mean over seeds (band: 95 % interval of the mean)" : others;
        line.points.emplace_back(x, s.mean);
        line.band.push_back({std::isfinite(s.low) ? s.low : s.mean, std::isfinite(s.high) ? s.high : s.mean});
        if (others.empty()) {
          // The value the statistic should scatter about: the fit's truth, or the spectrum's
          // band-limited value on the grid.
          if (name.rfind("fit_", 0) == 0) truth.points.emplace_back(x, p.truth.at(name.substr(4)));
          if (name == "hs") truth.points.emplace_back(x, p.expected_hs);
          if (name == "tm01") truth.points.emplace_back(x, p.expected_tm01);
          if (name == "tm02") truth.points.emplace_back(x, p.expected_tm02);
        }
      }
      reports::Figure figure;
      figure.stem = name + "_vs_" + variation.key;
      figure.title = fmt::format("{} against {} ({} seeds per point)", name, variation.name, spec.seeds);
      figure.xlabel = variation.name;
      figure.ylabel = name;
      figure.log_x = figure.log_y = false;
      figure.written_by = "swell sweep";
      figure.key = "inside top left box opaque";
      for (auto& entry : series) {
        // A named reference, not a structured binding: lambdas may not capture bindings before C++20
        // (clang refuses it in the sanitizer build).
        const auto& line = entry.second;
        // Sorted by x, bands kept beside their points.
        std::vector<std::size_t> order(line.points.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](auto a, auto b) { return line.points[a].first < line.points[b].first; });
        reports::Series sorted{line.title, {}, false, {}};
        for (auto i : order) {
          sorted.points.push_back(line.points[i]);
          sorted.band.push_back(line.band[i]);
        }
        figure.series.push_back(std::move(sorted));
      }
      if (!truth.points.empty()) {
        std::sort(truth.points.begin(), truth.points.end());
        figure.series.push_back(truth);
      }
      reports::write_figure(figure, plots, gnuplot, render, notes);
    }
  }
  return notes;
}

}  // namespace swell::validation::sweep
