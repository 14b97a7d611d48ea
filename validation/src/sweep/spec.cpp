// A sweep's description: the varied case keys and their values, its points (the base case with
// one value of each), the rules a sweep refuses before any run, and the runs' seeds.
#include "swell/validation/sweep/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "sweep/sweep_internal.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"

namespace swell::validation::sweep {

using namespace detail;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

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
// The component index of a composite sea's "spectrum.N…" path, if `name` is one.
std::optional<std::size_t> component_index(const std::string& name) {
  if (name.rfind("spectrum.", 0) != 0) return std::nullopt;
  const auto end = name.find('.', 9);
  const std::string digits = name.substr(9, end == std::string::npos ? std::string::npos : end - 9);
  if (digits.empty() || !std::all_of(digits.begin(), digits.end(), ::isdigit)) return std::nullopt;
  return std::stoul(digits);
}

std::pair<std::string, std::string> resolve_key(const std::string& name, const toml::table& document,
                                                const std::string& spec) {
  // A composite sea's component: spectrum.N.KEY, or spectrum.N.spreading.KEY.
  if (const auto index = component_index(name)) {
    const auto* components = document["spectrum"].as_array();
    if (!components) {
      throw InvalidInput(fmt::format("--vary {}: the case's sea has one component ([spectrum]); "
                                     "spectrum.N.KEY names a component of a composite sea "
                                     "([[spectrum]] tables)", spec));
    }
    if (*index >= components->size()) {
      throw InvalidInput(fmt::format("--vary {}: the case's sea has {} components (spectrum.0 … "
                                     "spectrum.{})", spec, components->size(),
                                     components->size() - 1));
    }
    const auto last = name.rfind('.');
    const std::string section = name.substr(0, last), key = name.substr(last + 1);
    const auto depth = std::count(name.begin(), name.end(), '.');
    if (key.empty() || depth > 3 || (depth == 3 && section.substr(section.rfind('.') + 1) != "spreading") ||
        depth < 2) {
      throw InvalidInput(fmt::format("--vary {}: '{}' is not a component key (write spectrum.N.KEY "
                                     "or spectrum.N.spreading.KEY, such as spectrum.1.hs)", spec, name));
    }
    return {section, key};
  }
  if (const auto* components = document["spectrum"].as_array(); components && name.find('.') == std::string::npos) {
    for (const auto& component : *components) {
      const auto* table = component.as_table();
      const auto* spreading = table ? table->get_as<toml::table>("spreading") : nullptr;
      if ((table && table->contains(name)) || (spreading && spreading->contains(name))) {
        throw InvalidInput(fmt::format("--vary {}: '{}' is a key of the components of a composite "
                                       "sea; name one: spectrum.N.{} or spectrum.N.spreading.{} "
                                       "(N = 0 … {})", spec, name, name, name,
                                       components->size() - 1));
      }
    }
  }
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

}  // namespace

namespace detail {

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

std::vector<std::size_t> value_indices(const SweepSpec& spec, std::size_t point) {
  std::vector<std::size_t> index(spec.variations.size());
  for (std::size_t v = spec.variations.size(); v-- > 0;) {
    const std::size_t n = spec.variations[v].labels.size();
    index[v] = point % n;
    point /= n;
  }
  return index;
}

}  // namespace detail

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
  point.value_index = value_indices(spec, index);
  toml::table document = parse_toml(spec.case_text, spec.case_path);
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    const Variation& variation = spec.variations[v];
    const std::string& literal = variation.toml_values[point.value_index[v]];
    // The value parsed by toml++ itself, so that its type is TOML's reading of the literal.
    toml::table value = toml::parse("value = " + literal);
    toml::table* section = nullptr;
    if (const auto component = component_index(variation.section)) {
      // spectrum.N or spectrum.N.spreading of a composite sea (resolve_key checked N).
      section = document["spectrum"][*component].as_table();
      if (section && variation.section.ends_with(".spreading")) {
        if (!section->contains("spreading")) section->insert("spreading", toml::table{});
        section = (*section)["spreading"].as_table();
      }
    } else {
      if (!document.contains(variation.section)) document.insert(variation.section, toml::table{});
      section = document[variation.section].as_table();
    }
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

}  // namespace swell::validation::sweep
