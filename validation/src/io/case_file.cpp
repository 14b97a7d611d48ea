// Case files (docs/case_files.md): TOML through toml++, checked key by key so that every
// problem is reported with the file, the line, the section and the key.
#include "swell/validation/io/case_file.hpp"

#include "swell/reference/lattice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <toml++/toml.h>
#include <vector>

#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/io/ndbc_directional.hpp"
#include "swell/validation/io/spectrum_table_file.hpp"

namespace swell::validation {
namespace {

namespace fs = std::filesystem;
using reference::Field;
using reference::ModelSpec;

const std::vector<std::string> kSections = {"grid",      "time",      "physics", "spectrum",
                                            "spreading", "synthesis", "input",   "sampling",
                                            "cascades",  "cascade",   "sum"};
// The parameters every frequency model takes, which a case holds once ([physics],
// wind_dir_deg) instead of in [spectrum].
const std::set<std::string> kCaseLevel = {"gravity", "depth", "wind_dir"};

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

// Everything that reads one file shares its name for the messages.
class Reporter {
 public:
  explicit Reporter(std::string origin) : origin_(std::move(origin)) {}

  // "<origin>:<line>: <what>" (the line when toml++ knows it); a case with no file (an empty
  // origin: a TOML string or a dict handed to the Python module) says <what> alone.
  [[noreturn]] void fail(const toml::source_region& where, const std::string& what) const {
    if (where.begin.line > 0 && !origin_.empty()) {
      throw InvalidInput(fmt::format("{}:{}: {}", origin_, where.begin.line, what));
    }
    fail(what);
  }
  [[noreturn]] void fail(const std::string& what) const {
    if (origin_.empty()) throw InvalidInput(what);
    throw InvalidInput(fmt::format("{}: {}", origin_, what));
  }
  const std::string& origin() const { return origin_; }

 private:
  std::string origin_;
};

// One [section]: typed accessors that name the section and key in every error, and a list of
// the keys it accepts.
class Section {
 public:
  Section(const Reporter& report, std::string name, const toml::table* table)
      : report_(report), name_(std::move(name)), table_(table) {}

  bool present() const { return table_ != nullptr; }
  const toml::node* find(const std::string& key) const {
    return table_ ? table_->get(key) : nullptr;
  }
  bool has(const std::string& key) const { return find(key) != nullptr; }

  // Rejects every key not in `valid`.
  void allow_only(const std::vector<std::string>& valid, const std::string& note = "") const {
    if (!table_) return;
    for (auto&& [key, node] : *table_) {
      if (std::find(valid.begin(), valid.end(), std::string(key.str())) != valid.end()) continue;
      report_.fail(key.source(), fmt::format("unknown key '{}' in [{}]{}; valid keys: {}",
                                             key.str(), name_, note, join(valid)));
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const toml::node* node = find(key);
    report_.fail(node ? node->source() : (table_ ? table_->source() : toml::source_region{}),
                 fmt::format("[{}] {}: {}", name_, key, what));
  }
  [[noreturn]] void wrong_type(const std::string& key, const std::string& expected) const {
    fail(key, fmt::format("must be {} (got {})", expected, describe(*find(key))));
  }

  std::optional<double> number(const std::string& key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (auto v = node->as_floating_point()) return v->get();
    if (auto v = node->as_integer()) return static_cast<double>(v->get());
    wrong_type(key, "a number");
  }
  double number_or(const std::string& key, double fallback) const {
    return number(key).value_or(fallback);
  }
  std::optional<std::int64_t> integer(const std::string& key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (auto v = node->as_integer()) return v->get();
    wrong_type(key, "an integer");
  }
  std::optional<std::string> string(const std::string& key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (auto v = node->as_string()) return v->get();
    wrong_type(key, "a string");
  }
  std::string required_string(const std::string& key, const std::string& meaning) const {
    if (!has(key)) missing(key, meaning);
    return *string(key);
  }
  [[noreturn]] void missing(const std::string& key, const std::string& meaning) const {
    report_.fail(table_ ? table_->source() : toml::source_region{},
                 fmt::format("[{}] needs '{}' ({})", name_, key, meaning));
  }

  // A pair [x, y] of numbers, or one number for both.
  std::optional<std::array<double, 2>> number_pair(const std::string& key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (node->is_number()) {
      const double v = *number(key);
      return std::array<double, 2>{v, v};
    }
    const auto* array = node->as_array();
    if (!array || array->size() != 2) wrong_type(key, "an array of 2 numbers [x, y]");
    std::array<double, 2> out{};
    for (std::size_t i = 0; i < 2; ++i) {
      const toml::node& item = *array->get(i);
      if (auto v = item.as_floating_point()) {
        out[i] = v->get();
      } else if (auto w = item.as_integer()) {
        out[i] = static_cast<double>(w->get());
      } else {
        wrong_type(key, "an array of 2 numbers [x, y]");
      }
    }
    return out;
  }
  std::optional<std::array<std::int64_t, 2>> integer_pair(const std::string& key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (auto v = node->as_integer()) return std::array<std::int64_t, 2>{v->get(), v->get()};
    const auto* array = node->as_array();
    if (!array || array->size() != 2) wrong_type(key, "an array of 2 integers [nx, ny]");
    std::array<std::int64_t, 2> out{};
    for (std::size_t i = 0; i < 2; ++i) {
      const auto* v = array->get(i)->as_integer();
      if (!v) wrong_type(key, "an array of 2 integers [nx, ny]");
      out[i] = v->get();
    }
    return out;
  }

  const std::string& name() const { return name_; }

 private:
  static std::string describe(const toml::node& node) {
    if (auto v = node.as_string()) return fmt::format("the string \"{}\"", v->get());
    if (auto v = node.as_integer()) return fmt::format("the integer {}", v->get());
    if (auto v = node.as_floating_point()) return fmt::format("the float {}", v->get());
    if (auto v = node.as_boolean()) return v->get() ? "true" : "false";
    return type_name(node);
  }

  const Reporter& report_;
  std::string name_;
  const toml::table* table_;
};

int checked_int(const Section& section, const std::string& key, std::int64_t value,
                std::int64_t lowest) {
  if (value < lowest || value > std::numeric_limits<int>::max()) {
    section.fail(key, fmt::format("must be an integer in {}…{} (got {})", lowest,
                                  std::numeric_limits<int>::max(), value));
  }
  return static_cast<int>(value);
}

// The model's own parameters (without gravity, depth and wind_dir, which the case holds once)
// go to numbers or choices by their kind.
void read_model_parameters(const Section& section, const std::string& model,
                           const std::vector<std::string>& other_keys, ModelSpec& spec) {
  const auto infos = reference::model_parameters(model);
  std::vector<std::string> valid = other_keys;
  for (const auto& info : infos) {
    if (!kCaseLevel.count(info.name)) valid.push_back(info.name);
  }
  for (const auto& key : {"depth", "gravity"}) {
    if (section.has(key)) {
      section.fail(key, "belongs in [physics] (the case holds depth and gravity once for all "
                        "models)");
    }
  }
  if (section.has("wind_dir")) {
    section.fail("wind_dir", "give the mean direction as wind_dir_deg (degrees, in [spreading], "
                             "or in [spectrum] for phillips)");
  }
  section.allow_only(valid, " for model '" + model + "'");
  for (const auto& info : infos) {
    if (kCaseLevel.count(info.name) || !section.has(info.name)) continue;
    const bool is_choice = info.unit.find('|') != std::string::npos;
    if (is_choice) {
      spec.choices[info.name] = *section.string(info.name);
    } else {
      spec.numbers[info.name] = *section.number(info.name);
    }
  }
}

// [input] value_range: [low, high] for every field given, or an inline table of them by field
// ({ height = [-4.0, 4.0], disp_x = [-2.0, 2.0] }).
std::map<Field, IntegerRange> read_value_ranges(const Section& input,
                                                const std::map<Field, std::string>& channels) {
  const std::string key = "value_range";
  const toml::node* node = input.find(key);
  if (!node) return {};
  const std::string shape = "[low, high] (the values of pixel 0 and of the largest pixel), or a "
                            "table of them by field such as { height = [-4.0, 4.0] }";
  auto pair_of = [&](const toml::node& item, const std::string& where) {
    const auto* array = item.as_array();
    double values[2] = {0, 0};
    bool numbers = array && array->size() == 2;
    for (std::size_t i = 0; numbers && i < 2; ++i) {
      if (auto v = array->get(i)->as_floating_point()) {
        values[i] = v->get();
      } else if (auto w = array->get(i)->as_integer()) {
        values[i] = static_cast<double>(w->get());
      } else {
        numbers = false;
      }
    }
    if (!numbers) input.fail(key, where + "must be " + shape);
    if (!(std::isfinite(values[0]) && std::isfinite(values[1]) && values[0] < values[1])) {
      input.fail(key, fmt::format("{}[{:g}, {:g}] must be finite with low < high", where,
                                  values[0], values[1]));
    }
    return IntegerRange{values[0], values[1]};
  };
  std::map<Field, IntegerRange> out;
  if (const auto* table = node->as_table()) {
    for (auto&& [name, item] : *table) {
      const std::string field_name(name.str());
      Field field{};
      try {
        field = reference::field_from_name(field_name);
      } catch (const std::exception&) {
        std::vector<std::string> names;
        for (Field f : reference::kAllFields) names.push_back(reference::field_name(f));
        input.fail(key, fmt::format("unknown field '{}'; fields: {}", field_name, join(names)));
      }
      if (!channels.count(field)) {
        input.fail(key, fmt::format("gives a range for {}, which [input] does not provide",
                                    field_name));
      }
      out[field] = pair_of(item, field_name + ": ");
    }
    if (out.empty()) input.fail(key, "is an empty table; give a range per field, or [low, high]");
    return out;
  }
  const IntegerRange range = pair_of(*node, "");
  for (const auto& [field, channel] : channels) out[field] = range;
  return out;
}

std::string model_name(const Section& section, const std::vector<std::string>& valid,
                       const std::string& kind) {
  const std::string model = *section.string("model");
  if (std::find(valid.begin(), valid.end(), model) == valid.end()) {
    section.fail("model", reference::unknown_model_message(kind == "spreading"
                                                               ? reference::ModelKind::spreading
                                                               : reference::ModelKind::spectrum,
                                                           model));
  }
  return model;
}

// ------------------------------------------------------------------ writing

// Shortest text that reads back to the same double, always a TOML float.
std::string toml_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string toml_string(const std::string& value) {
  std::string out = "\"";
  for (const char c : value) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          out += fmt::format("\\u{:04X}", static_cast<unsigned>(static_cast<unsigned char>(c)));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string toml_key(const std::string& key) {
  const bool bare = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '_' || c == '-';
  });
  return bare ? key : toml_string(key);
}

void write_parameters(std::string& out, const ModelSpec& spec) {
  // A table's netCDF selection is kept as numbers "select.<dimension>" and written back as the
  // inline table it was read from.
  std::string select;
  for (const auto& [name, value] : spec.numbers) {
    if (name.rfind("select.", 0) == 0) {
      select += fmt::format("{}{} = {}", select.empty() ? "" : ", ", toml_key(name.substr(7)),
                            static_cast<long long>(value));
      continue;
    }
    // ndbc's number of directions is a TOML integer.
    out += name == "directions"
               ? fmt::format("{} = {}\n", toml_key(name), static_cast<long long>(value))
               : fmt::format("{} = {}\n", toml_key(name), toml_number(value));
  }
  if (!select.empty()) out += "select = {" + select + "}\n";
  for (const auto& [name, value] : spec.choices) {
    out += fmt::format("{} = {}\n", toml_key(name), toml_string(value));
  }
}

// The keys of an input section (`valid`: files, raw_type, value_range, the field names, and
// whatever else the section's reader takes itself).
void read_input_keys(const Reporter& report, const Section& input,
                     const std::vector<std::string>& valid, InputSpec& out,
                     bool frames_optional = false) {
  {
    input.allow_only(valid);
    if (auto files = input.string("files")) {
      if (files->empty()) input.fail("files", "must not be empty");
      try {
        (void)frame_file_name(*files, 0);
      } catch (const InvalidInput& e) {
        input.fail("files", e.what());
      }
      std::string ext = fs::path(*files).extension().string();
      for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      if (ext != ".exr" && ext != ".tif" && ext != ".tiff" && ext != ".png" && ext != ".npy" &&
          ext != ".raw") {
        input.fail("files", fmt::format("extension '{}' is not one swell reads (.exr, .tif, .tiff, "
                                        ".png, .npy, .raw)",
                                        ext));
      }
      out.files = *files;
    }
    std::map<std::string, Field> used;
    for (Field field : reference::kAllFields) {
      const std::string key = reference::field_name(field);
      auto channel = input.string(key);
      if (!channel) continue;
      if (channel->empty()) input.fail(key, "must name a channel (or file suffix), not \"\"");
      if (auto [it, fresh] = used.emplace(*channel, field); !fresh) {
        input.fail(key, fmt::format("channel \"{}\" is already given to {}", *channel,
                                    reference::field_name(it->second)));
      }
      out.channels[field] = *channel;
    }
    if (auto raw_type = input.string("raw_type")) {
      if (*raw_type != "float32" && *raw_type != "float64") {
        input.fail("raw_type", "must be \"float32\" or \"float64\" (got \"" + *raw_type + "\")");
      }
      out.raw_type = *raw_type;
    }
    if (auto precision = input.string("precision")) {
      if (*precision != "half" && *precision != "float" && *precision != "double") {
        input.fail("precision", "must be \"half\", \"float\" or \"double\" (got \"" + *precision + "\")");
      }
      out.precision = *precision;
    }
    if (input.present() && out.channels.empty() && !(frames_optional && out.files.empty())) {
      std::vector<std::string> fields;
      for (Field field : reference::kAllFields) fields.push_back(reference::field_name(field));
      report.fail(fmt::format("[{}] names no field; give at least one of {} with its channel "
                              "(EXR/TIFF/PNG) or file suffix (.npy/.raw)",
                              input.name(), join(fields)));
    }
    out.value_ranges = read_value_ranges(input, out.channels);
  }
}

std::vector<std::string> input_keys() {
  std::vector<std::string> valid = {"files", "raw_type", "value_range", "precision"};
  for (Field field : reference::kAllFields) valid.push_back(reference::field_name(field));
  return valid;
}

// [input] or [sum]: the frames' pattern, one channel (or file suffix) per field provided.
InputSpec read_input(const Reporter& report, const Section& input) {
  InputSpec out;
  read_input_keys(report, input, input_keys(), out);
  return out;
}

std::vector<reference::SeaComponent> read_components(const Reporter& report, const toml::table& holder,
                                                     const std::string& name,
                                                     const std::string& header, CaseFile* scale,
                                                     const fs::path& directory);

// [cascades] relation, crossover and the [[cascade]] tables (docs/conventions.md §2.2): each its grid
// (n, length), its band [lo, hi) in rad/m, its frames as in [input] and, for independent seas,
// its own sea ([cascade.spectrum], [cascade.spreading]); [sum] the summed surface's frames.
// `ocean` holds what the cascades share; it takes cascade 0's grid.
void read_cascades(const Reporter& report, const toml::table& document, CaseFile& out) {
  const auto* settings = document.get_as<toml::table>("cascades");
  const auto* list = document.get_as<toml::array>("cascade");
  const Section sum(report, "sum", document.get_as<toml::table>("sum"));
  if (!settings && !list) {
    if (sum.present()) {
      report.fail("[sum] holds the summed surface of a cascade set; this case has no "
                  "[cascades] and [[cascade]] tables");
    }
    return;
  }
  const Section cascades(report, "cascades", settings);
  if (!settings) {
    report.fail("[[cascade]] tables need a [cascades] section (relation = \"additive\" | "
                "\"independent\" | \"nested\")");
  }
  if (!list || list->empty()) {
    report.fail("[cascades] needs at least one [[cascade]] table (n, length, band, files and "
                "channels)");
  }
  cascades.allow_only({"relation", "crossover"});
  const std::string relation = cascades.string("relation").value_or("additive");
  if (relation == "additive") {
    out.relation = reference::CascadeRelation::additive;
  } else if (relation == "nested") {
    out.relation = reference::CascadeRelation::nested;
  } else if (relation == "independent") {
    out.relation = reference::CascadeRelation::independent;
  } else {
    cascades.fail("relation", fmt::format("must be \"additive\" (bands that share one sea out), "
                                          "\"independent\" (whole seas that sum) or \"nested\" "
                                          "(two samplings of one sea) (got \"{}\")",
                                          relation));
  }
  const bool additive = out.relation == reference::CascadeRelation::additive;
  const bool independent = out.relation == reference::CascadeRelation::independent;
  const bool nested = out.relation == reference::CascadeRelation::nested;
  const double crossover = cascades.number_or("crossover", 1);
  if (!(std::isfinite(crossover) && crossover >= 1)) {
    cascades.fail("crossover", fmt::format("must be a ratio ≥ 1 (1: hard cuts; got {:g})",
                                           crossover));
  }
  if (nested && cascades.has("crossover")) {
    cascades.fail("crossover", "weights the bands of an additive set; nested bands are not added");
  }
  auto keys = input_keys();
  for (const char* key : {"n", "length", "band"}) keys.push_back(key);
  if (independent) {
    keys.push_back("spectrum");
    keys.push_back("spreading");
  }
  for (std::size_t c = 0; c < list->size(); ++c) {
    const toml::table* cascade_table = list->get(c)->as_table();
    const Section table(report, fmt::format("cascade {}", c), cascade_table);
    CascadeInput cascade;
    cascade.index = int(c);
    // Only an independent sea carries a sea of its own: an additive set's bands share the set's
    // sea out, and nested bands sample it.
    if (!independent) {
      for (const char* key : {"spectrum", "spreading"}) {
        if (table.has(key)) {
          table.fail(key, fmt::format("a cascade declares its own sea only in a set of "
                                      "independent seas ([cascades] relation = \"independent\"); "
                                      "{} cascades carry the set's [spectrum]",
                                      to_string(out.relation)));
        }
      }
    } else if (table.has("spectrum")) {
      cascade.components = read_components(report, *cascade_table, fmt::format("cascade {}.", c),
                                           "cascade.", nullptr, out.directory);
    } else if (table.has("spreading")) {
      table.fail("spreading", "a cascade's own spreading goes with its own sea: give "
                              "[cascade.spectrum] too, or leave both out for the set's sea");
    }
    // A cascade's frames are optional: the gate may judge the summed surface alone.
    read_input_keys(report, table, keys, cascade.input, true);
    const auto n = table.integer_pair("n");
    if (!n) table.missing("n", "samples [nx, ny]");
    const auto length = table.number_pair("length");
    if (!length) table.missing("length", "patch size [lx, ly] in m");
    auto& grid = cascade.grid;
    grid.nx = checked_int(table, "n", (*n)[0], 1);
    grid.ny = checked_int(table, "n", (*n)[1], 1);
    grid.lx = (*length)[0];
    grid.ly = (*length)[1];
    try {
      (void)reference::Grid::create(grid.nx, grid.ny, grid.lx, grid.ly);
    } catch (const InvalidInput& e) {
      table.fail("n", e.what());
    }
    if (const auto band = table.number_pair("band")) {
      if (!table.find("band")->is_array()) table.wrong_type("band", "an array [lo, hi] of |k| in rad/m");
      cascade.band = reference::BandWeight{(*band)[0], (*band)[1], crossover};
      try {
        cascade.band.validate(fmt::format("cascade {}", c));
      } catch (const InvalidInput& e) {
        table.fail("band", e.what());
      }
    } else if (additive && list->size() > 1) {
      table.missing("band", "[lo, hi): the |k| in rad/m this cascade carries");
    }
    if (!cascade.input.channels.empty() && cascade.input.files.empty()) {
      table.missing("files", "the pattern of this cascade's frames");
    }
    out.cascades.push_back(std::move(cascade));
  }
  if (nested) {
    for (const auto& c : out.cascades) {
      const auto& first = out.cascades.front().grid;
      if (c.grid.lx != first.lx || c.grid.ly != first.ly) {
        report.fail(fmt::format(
            "[cascade {}] length: nested bands are two samplings of one patch (the low band's "
            "waves are the broad band's at the same k); its {:g}×{:g} m differs from cascade "
            "0's {:g}×{:g} m",
            c.index, c.grid.lx, c.grid.ly, first.lx, first.ly));
      }
    }
  }
  // A set of independent seas that each declare their own: the set's sea is cascade 0's (the
  // case's [spectrum] may be left out).
  if (independent && !document.contains("spectrum")) {
    out.ocean.set_components(out.cascades.front().components);
  }
  out.sum = read_input(report, sum);
  if (sum.present()) {
    if (nested) sum.fail("files", "nested bands are not added: a nested set has no summed surface");
    if (out.sum.files.empty()) sum.missing("files", "the pattern of the summed surface's frames");
    reference::Grid fine;
    std::string why;
    std::vector<reference::CascadeMember> grids;  // their grids are all summed_grid asks
    for (const auto& c : out.cascades) grids.push_back({c.index, c.grid, c.band, nullptr});
    if (!reference::summed_grid(grids, fine, &why)) {
      sum.fail("files", "the cascades cannot be summed on one grid: " + why);
    }
  }
}

// Every top-level key is a known section: a table, or [[cascade]] an array of tables.
void check_sections(const Reporter& report, const toml::table& document) {
  for (auto&& [key, node] : document) {
    const std::string name(key.str());
    if (std::find(kSections.begin(), kSections.end(), name) == kSections.end()) {
      report.fail(key.source(), fmt::format("unknown section [{}]; valid sections: {}", name,
                                            join(kSections)));
    }
    if (name == "spectrum" && node.is_array()) {
      if (!node.is_array_of_tables()) {
        report.fail(key.source(), fmt::format("'spectrum' must be a section [spectrum] or an array "
                                              "of tables [[spectrum]] (one per component of a "
                                              "composite sea), not {}",
                                              type_name(node)));
      }
      continue;
    }
    if (name == "cascade") {
      if (!node.is_array_of_tables()) {
        report.fail(key.source(), fmt::format("'cascade' must be an array of tables [[cascade]], "
                                              "one per cascade, not {}",
                                              type_name(node)));
      }
      continue;
    }
    if (!node.is_table()) {
      report.fail(key.source(), fmt::format("'{}' must be a section [{}] (a table), not {}", name,
                                            name, type_name(node)));
    }
  }
}

Section section_of(const Reporter& report, const toml::table& document, const std::string& name) {
  return Section(report, name, document.get_as<toml::table>(name));
}

// [sampling] kind = "probes": positions = [[x, y], …] in m; no [grid] and no cascades.
void read_probe_positions(const Reporter& report, const toml::table& document, const Section& sampling,
                          CaseFile& out) {
  if (sampling.has("points") || sampling.has("generator")) {
    sampling.fail(sampling.has("points") ? "points" : "generator", "belongs to kind = \"lattice\"");
  }
  if (document.contains("grid")) {
    report.fail("[grid]: a probes case samples points ([sampling] positions), not a grid; remove [grid]");
  }
  if (document.contains("cascades") || document.contains("cascade")) {
    report.fail("[cascades]: cascades are grids; a probes case samples points");
  }
  ProbeSetup setup;
  const toml::node* node = sampling.find("positions");
  if (!node) sampling.missing("positions", "[[x, y], …] in m, one pair per probe");
  const auto* list = node->as_array();
  const std::string expected = "an array of [x, y] pairs of numbers in m, one per probe";
  if (!list || list->empty()) sampling.wrong_type("positions", expected);
  for (std::size_t p = 0; p < list->size(); ++p) {
    const auto* pair = list->get(p)->as_array();
    if (!pair || pair->size() != 2) {
      sampling.fail("positions", fmt::format("probe {} is not an [x, y] pair of numbers ({})", p, expected));
    }
    std::array<double, 2> xy{};
    for (std::size_t i = 0; i < 2; ++i) {
      const toml::node& item = *pair->get(i);
      if (auto v = item.as_floating_point()) {
        xy[i] = v->get();
      } else if (auto w = item.as_integer()) {
        xy[i] = double(w->get());
      } else {
        sampling.fail("positions", fmt::format("probe {}'s {} is not a number", p, i == 0 ? "x" : "y"));
      }
      if (!std::isfinite(xy[i])) {
        sampling.fail("positions", fmt::format("probe {}'s {} is not finite", p, i == 0 ? "x" : "y"));
      }
    }
    setup.layout.positions.push_back(xy);
  }
  out.probes = std::move(setup);
}

// [time] of a probes case: t0, dt (> 0) and samples (per probe, ≥ 2).
void read_probe_time(const Section& time, CaseFile& out) {
  time.allow_only({"t0", "dt", "samples"}, " (a probes case counts samples, not frames)");
  auto& layout = out.probes->layout;
  layout.t0 = time.number_or("t0", 0);
  const auto dt = time.number("dt");
  if (!dt) time.missing("dt", "the sampling interval in s");
  if (!(std::isfinite(*dt) && *dt > 0)) time.fail("dt", fmt::format("must be finite and > 0 s (got {:g})", *dt));
  layout.dt = *dt;
  const auto samples = time.integer("samples");
  if (!samples) time.missing("samples", "the number of samples per probe");
  if (*samples < 2 || *samples > (std::int64_t(1) << 31)) {
    time.fail("samples", fmt::format("must be in 2…2³¹ (got {})", *samples));
  }
  layout.samples = std::size_t(*samples);
  out.ocean.t0 = layout.t0;
  out.ocean.dt = layout.dt;
}

// [synthesis] seed: an integer in 0…2⁶⁴−1 (a TOML integer, or a decimal string beyond 2⁶³ − 1).
void read_seed(const Section& synthesis, std::uint64_t& into) {
  if (const toml::node* seed = synthesis.find("seed")) {
    // TOML integers stop at 2⁶³ − 1; a larger uint64 seed is written as a decimal string.
    if (auto v = seed->as_integer()) {
      if (v->get() < 0) synthesis.fail("seed", fmt::format("must be ≥ 0 (got {})", v->get()));
      into = static_cast<std::uint64_t>(v->get());
    } else if (auto s = seed->as_string()) {
      const std::string& digits = s->get();
      const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), into);
      if (digits.empty() || result.ec != std::errc() || result.ptr != digits.data() + digits.size()) {
        synthesis.fail("seed", "must be an integer in 0…2⁶⁴−1 (got \"" + digits + "\")");
      }
    } else {
      synthesis.wrong_type("seed", "an integer ≥ 0");
    }
  }
}

// [synthesis] of a probes case: the seed and how the engine makes its lines
// (reference/probe_sea.hpp).
void read_probe_synthesis(const Section& synthesis, CaseFile& out) {
  synthesis.allow_only({"seed", "amplitudes", "frequencies", "repeat_period", "omega_cutoff", "directions",
                        "n_directions", "n_frequencies"},
                       " (a probes case)");
  read_seed(synthesis, out.ocean.seed);
  auto& s = out.probes->synthesis;
  auto choice = [&](const char* key, auto parse, auto& into) {
    if (const auto value = synthesis.string(key)) {
      try {
        into = parse(*value);
      } catch (const InvalidInput& e) {
        synthesis.fail(key, e.what());
      }
    }
  };
  choice("amplitudes", reference::probe_amplitudes_from_string, s.amplitudes);
  choice("frequencies", reference::probe_frequencies_from_string, s.frequencies);
  choice("directions", reference::probe_directions_from_string, s.directions);
  s.repeat_period = synthesis.number_or("repeat_period", 0);
  if (const auto band = synthesis.number_pair("omega_cutoff")) {
    if (!synthesis.find("omega_cutoff")->is_array()) {
      synthesis.wrong_type("omega_cutoff", "an array [low, high] in rad/s");
    }
    s.omega_low = (*band)[0];
    s.omega_high = (*band)[1];
  } else {
    synthesis.missing("omega_cutoff", "[low, high] in rad/s: the band the engine synthesizes");
  }
  if (const auto n = synthesis.integer("n_directions")) s.n_directions = checked_int(synthesis, "n_directions", *n, 1);
  if (const auto n = synthesis.integer("n_frequencies")) {
    s.n_frequencies = checked_int(synthesis, "n_frequencies", *n, 1);
  }
}

// [input] of a probes case: files (.csv, .out, .npy), time_column and probes (CSV and .out).
ProbeInput read_probe_input(const Section& input, std::size_t probes) {
  input.allow_only({"files", "time_column", "probes"}, " (a probes case)");
  ProbeInput out;
  if (!input.present()) return out;
  if (const auto files = input.string("files")) {
    std::string ext = fs::path(*files).extension().string();
    for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".csv" && ext != ".out" && ext != ".npy") {
      input.fail("files", fmt::format("extension '{}' is not one a probes case reads (.csv, .out "
                                      "from OpenFAST, .npy of samples × probes)",
                                      ext));
    }
    out.files = *files;
  }
  out.time_column = input.string("time_column").value_or("");
  if (const toml::node* names = input.find("probes")) {
    const auto* list = names->as_array();
    if (!list) input.wrong_type("probes", "an array of column names, one per probe");
    for (std::size_t i = 0; i < list->size(); ++i) {
      const auto* name = list->get(i)->as_string();
      if (!name || name->get().empty()) {
        input.fail("probes", fmt::format("entry {} is not a column name (a non-empty string)", i));
      }
      out.probes.push_back(name->get());
    }
    if (out.probes.size() != probes) {
      input.fail("probes", fmt::format("names {} columns for {} probes in [sampling] positions",
                                       out.probes.size(), probes));
    }
  }
  return out;
}

// [sampling] kind = "grid" (the default: [grid] n and length) or "lattice" (points and
// generator here, [grid] length only; docs/conventions.md §2.1). [grid] n, length: required
// (length only for a lattice); a cascade set gives a grid per [[cascade]] instead.
void read_sampling(const Reporter& report, const toml::table& document, CaseFile& out) {
  auto& ocean = out.ocean;
  auto section = [&](const std::string& name) { return section_of(report, document, name); };
  const Section sampling = section("sampling");
  sampling.allow_only({"kind", "points", "generator", "positions"});
  const std::string kind = sampling.string("kind").value_or("grid");
  if (kind != "grid" && kind != "lattice" && kind != "probes") {
    sampling.fail("kind", fmt::format("must be \"grid\", \"lattice\" or \"probes\" (got \"{}\")", kind));
  }
  if (kind != "probes" && sampling.has("positions")) {
    sampling.fail("positions", "belongs to kind = \"probes\" (the points where the elevation is sampled)");
  }
  if (kind == "probes") {
    read_probe_positions(report, document, sampling, out);
    return;
  }
  const bool lattice = kind == "lattice";
  if (!lattice && (sampling.has("points") || sampling.has("generator"))) {
    sampling.fail(sampling.has("points") ? "points" : "generator",
                  "belongs to kind = \"lattice\" (a grid's samples are [grid] n)");
  }

  const Section grid = section("grid");
  const bool cascade_set = document.contains("cascades") || document.contains("cascade");
  if (cascade_set) {
    if (grid.present()) {
      report.fail("[grid]: a cascade set gives each cascade's grid (n, length) in its "
                  "[[cascade]] table; remove [grid]");
    }
    if (document.contains("input")) {
      report.fail("[input]: a cascade set gives each cascade's frames (files, channels) in its "
                  "[[cascade]] table, and the summed surface's in [sum]; remove [input]");
    }
    if (lattice) sampling.fail("kind", "cascades are grids; a lattice samples one patch");
  } else if (!grid.present()) {
    report.fail(lattice ? "missing section [grid] (length = [lx, ly] in m: the lattice's patch)"
                        : "missing section [grid] (n = [nx, ny], length = [lx, ly] in m)");
  }
  grid.allow_only({"n", "length"});
  const auto length = cascade_set ? std::optional<std::array<double, 2>>{{1.0, 1.0}}
                                  : grid.number_pair("length");
  if (!length) grid.missing("length", "patch size [lx, ly] in m");
  if (cascade_set) {
    // cascade 0's grid, once [[cascade]] is read
  } else if (lattice) {
    if (grid.has("n")) {
      grid.fail("n", "a lattice case has no grid samples: its points are [sampling] points");
    }
    const auto points = sampling.integer("points");
    if (!points) sampling.missing("points", "N, the number of lattice points");
    const auto generator = sampling.integer_pair("generator");
    if (!generator || !sampling.find("generator")->is_array()) {
      if (!sampling.has("generator")) sampling.missing("generator", "[g0, g1], the lattice's generator");
      sampling.wrong_type("generator", "an array of 2 integers [g0, g1]");
    }
    try {
      ocean.set_lattice(std::make_shared<const reference::RankOneLattice>(
          reference::RankOneLattice::create(*points, {(*generator)[0], (*generator)[1]},
                                            {(*length)[0], (*length)[1]})));
    } catch (const InvalidInput& e) {
      sampling.fail("points", fmt::format("points = {}, generator = [{}, {}], length = [{:g}, "
                                          "{:g}]: {}",
                                          *points, (*generator)[0], (*generator)[1], (*length)[0],
                                          (*length)[1], e.what()));
    }
  } else {
    const auto n = grid.integer_pair("n");
    if (!n) grid.missing("n", "samples [nx, ny]");
    ocean.grid.nx = checked_int(grid, "n", (*n)[0], 1);
    ocean.grid.ny = checked_int(grid, "n", (*n)[1], 1);
    ocean.grid.lx = (*length)[0];
    ocean.grid.ly = (*length)[1];
  }
}

void read_time(const Section& time, reference::OceanCase& ocean) {
  time.allow_only({"t0", "dt", "frames"});
  ocean.t0 = time.number_or("t0", 0);
  ocean.dt = time.number_or("dt", 0);
  if (auto frames = time.integer("frames")) ocean.frames = checked_int(time, "frames", *frames, 1);
}

// [physics]: depth is metres, or "inf" (a TOML inf works too).
void read_physics(const Section& physics, reference::OceanCase& ocean) {
  physics.allow_only({"gravity", "depth"});
  ocean.gravity = physics.number_or("gravity", reference::kStandardGravity);
  if (const toml::node* depth = physics.find("depth")) {
    if (auto s = depth->as_string()) {
      if (s->get() != "inf") physics.fail("depth", "must be a number of metres or \"inf\" (got \"" + s->get() + "\")");
      ocean.depth = reference::kInfiniteDepth;
    } else if (depth->is_number()) {
      ocean.depth = *physics.number("depth");
    } else {
      physics.wrong_type("depth", "a number of metres or \"inf\"");
    }
  }
}

// One component of the sea from its spectrum table (model, the model's parameters,
// energy_factor, short_wave_fade; scale where `scale_allowed`; wind_dir_deg for phillips, which
// has no spreading model) and its spreading table (model, its parameters, wind_dir_deg).
// The keys of model = "table" (docs/case_files.md §Spectra from files): the file, relative to
// the case file, its declared units and direction convention, and for netCDF the variables
// and the index of every other dimension. The table is read here, once.
void read_table(const Section& spectrum, const fs::path& directory, reference::SeaComponent& c) {
  const std::vector<std::string> choices = {"frequency_unit",     "density_unit",
                                            "direction_convention", "direction_unit",
                                            "variable",           "frequency_variable",
                                            "direction_variable"};
  SpectrumTableDeclaration d;
  const std::string file = spectrum.required_string("file", "the table's path, relative to the case file");
  d.file = fs::path(file).is_absolute() ? fs::path(file) : directory / file;
  // A regular file only: a device or a pipe could be read without end.
  std::error_code error;
  if (!fs::is_regular_file(d.file, error)) {
    spectrum.fail("file", fmt::format("{}: no such file (or not a regular file)", d.file.string()));
  }
  c.spectrum.choices["file"] = fs::absolute(d.file).lexically_normal().string();
  for (const auto& key : choices) {
    if (const auto value = spectrum.string(key)) c.spectrum.choices[key] = *value;
  }
  auto choice = [&](const std::string& key, std::string& into) {
    if (auto it = c.spectrum.choices.find(key); it != c.spectrum.choices.end()) into = it->second;
  };
  choice("frequency_unit", d.frequency_unit);
  choice("density_unit", d.density_unit);
  choice("direction_convention", d.direction_convention);
  choice("direction_unit", d.direction_unit);
  choice("variable", d.variable);
  choice("frequency_variable", d.frequency_variable);
  choice("direction_variable", d.direction_variable);
  if (const toml::node* select = spectrum.find("select")) {
    const auto* table = select->as_table();
    if (!table) spectrum.wrong_type("select", "an inline table of indices by dimension name, e.g. {time = 0, site = 0}");
    for (auto&& [dim, index] : *table) {
      const auto value = index.as_integer();
      if (!value) spectrum.wrong_type("select", "integer indices, e.g. {time = 0, site = 0}");
      d.select[std::string(dim.str())] = long(value->get());
      c.spectrum.numbers["select." + std::string(dim.str())] = double(value->get());
    }
  }
  try {
    c.table = std::make_shared<const reference::SpectrumTable>(read_spectrum_table(d));
  } catch (const InvalidInput& e) {
    spectrum.fail("file", e.what());
  }
}

// The keys of model = "ndbc" (docs/case_files.md §A buoy's measured sea): the five files of an
// NDBC station's directional product (relative to the case file), the hour, the method and the
// number of directions sampled.
void read_ndbc(const Section& spectrum, const fs::path& directory, reference::SeaComponent& c) {
  NdbcDirectionalFiles files;
  const std::pair<const char*, std::string*> paths[] = {{"data_spec", &files.data_spec},
                                                        {"swdir", &files.swdir},
                                                        {"swdir2", &files.swdir2},
                                                        {"swr1", &files.swr1},
                                                        {"swr2", &files.swr2}};
  for (const auto& [key, into] : paths) {
    const std::string given = spectrum.required_string(key, "the path of the station's ." +
                                                                std::string(key) + " file");
    const fs::path path = fs::path(given).is_absolute() ? fs::path(given) : directory / given;
    // A regular file only: a device or a pipe could be read without end.
    std::error_code error;
    if (!fs::is_regular_file(path, error)) {
      spectrum.fail(key, fmt::format("{}: no such file (or not a regular file)", path.string()));
    }
    *into = fs::absolute(path).lexically_normal().string();
    c.spectrum.choices[key] = *into;
  }
  const std::string time = spectrum.required_string(
      "time", "the hour, as the files stamp it: \"YYYY-MM-DD hh:mm\", e.g. \"2020-06-02 02:50\"");
  c.spectrum.choices["time"] = time;
  const std::string method_name = spectrum.string("method").value_or("mem");
  c.spectrum.choices["method"] = method_name;
  DirectionalMethod method = DirectionalMethod::mem;
  try {
    method = parse_directional_method(method_name);
  } catch (const InvalidInput& e) {
    spectrum.fail("method", e.what());
  }
  // 360 directions (1°): the maximum entropy estimate's narrowest peaks in a week of station
  // 41010 need more than 72 samples to reproduce their own coefficients (docs/ndbc_directional.md).
  const auto directions = spectrum.integer("directions").value_or(360);
  if (directions < 5 || directions > 36000) {
    spectrum.fail("directions", fmt::format("must be an integer in 5…36000 (got {})", directions));
  }
  c.spectrum.numbers["directions"] = double(directions);
  try {
    c.table = std::make_shared<const reference::SpectrumTable>(
        read_ndbc_directional(files, time, method, int(directions)));
  } catch (const InvalidInput& e) {
    spectrum.fail("time", e.what());
  }
}

reference::SeaComponent read_component(const Section& spectrum, const Section& spreading,
                                       std::vector<std::string> other_keys,
                                       const fs::path& directory) {
  reference::SeaComponent c;
  if (spectrum.string("model") == std::optional<std::string>("table")) {
    c.spectrum.model = "table";
    std::vector<std::string> valid = other_keys;
    for (const char* key : {"model", "file", "frequency_unit", "density_unit", "direction_convention",
                            "direction_unit", "variable", "frequency_variable",
                            "direction_variable", "select", "energy_factor", "short_wave_fade"}) {
      valid.push_back(key);
    }
    spectrum.allow_only(valid, " for model 'table'");
    read_table(spectrum, directory, c);
    other_keys.clear();
  } else if (spectrum.string("model") == std::optional<std::string>("ndbc")) {
    c.spectrum.model = "ndbc";
    std::vector<std::string> valid = other_keys;
    for (const char* key : {"model", "data_spec", "swdir", "swdir2", "swr1", "swr2", "time",
                            "method", "directions", "energy_factor", "short_wave_fade"}) {
      valid.push_back(key);
    }
    spectrum.allow_only(valid, " for model 'ndbc'");
    read_ndbc(spectrum, directory, c);
    other_keys.clear();
  } else if (!spectrum.has("model")) {
    spectrum.missing("model", "one of " + join(reference::frequency_model_names()));
  }
  if (!c.table) {
    c.spectrum.model = model_name(spectrum, reference::frequency_model_names(), "spectrum");
    for (const char* key : {"model", "wind_dir_deg", "energy_factor", "short_wave_fade"}) {
      other_keys.push_back(key);
    }
    read_model_parameters(spectrum, c.spectrum.model, other_keys, c.spectrum);
  }
  c.energy_factor = spectrum.number_or("energy_factor", 1);
  if (!(std::isfinite(c.energy_factor) && c.energy_factor > 0)) {
    spectrum.fail("energy_factor", fmt::format("must be finite and > 0: the factor F by which the "
                                               "engine's energy exceeds the declared spectrum's "
                                               "(got {:g})", c.energy_factor));
  }
  c.short_wave_fade = spectrum.number_or("short_wave_fade", 0);
  if (!(std::isfinite(c.short_wave_fade) && c.short_wave_fade >= 0)) {
    spectrum.fail("short_wave_fade", fmt::format("must be a length ≥ 0 in m, Ψ·e^(−k²l²) (got {:g})",
                                                 c.short_wave_fade));
  }
  if (spreading.has("model")) {
    c.spreading.model = model_name(spreading, reference::spreading_model_names(), "spreading");
    read_model_parameters(spreading, c.spreading.model, {"model", "wind_dir_deg"}, c.spreading);
  } else {
    spreading.allow_only({"model", "wind_dir_deg"},
                         " (spreading parameters need a model = \"cos2s\" | …)");
  }
  if (spectrum.has("wind_dir_deg") && spreading.has("wind_dir_deg")) {
    spreading.fail("wind_dir_deg", fmt::format("given in both [{}] and [{}]; give it once",
                                               spectrum.name(), spreading.name()));
  }
  c.wind_dir_deg = spectrum.has("wind_dir_deg") ? *spectrum.number("wind_dir_deg")
                                                : spreading.number_or("wind_dir_deg", 0);
  return c;
}

void read_scale(const Section& spectrum, CaseFile& out) {
  if (auto scale = spectrum.string("scale")) {
    if (*scale == "absolute") {
      out.scale = SpectrumScale::absolute;
    } else if (*scale == "free") {
      out.scale = SpectrumScale::free;
    } else {
      spectrum.fail("scale", "must be \"absolute\" or \"free\" (got \"" + *scale + "\")");
    }
  }
}

// A sea's components from `holder` (the document, or a [[cascade]] table of independent seas):
// [spectrum] and [spreading] for one component, or [[spectrum]] tables, each with its own
// [spectrum.spreading], for a composite sea whose components' Ψ add. `name` prefixes the
// sections' names in messages ("" or "cascade 1."), `header` the tables' ("" or "cascade.").
// scale applies to the whole case and is given once, in the first component of the case's own
// sea (`scale` non-null); a cascade's sea has none.
std::vector<reference::SeaComponent> read_components(const Reporter& report, const toml::table& holder,
                                                     const std::string& name,
                                                     const std::string& header, CaseFile* scale,
                                                     const fs::path& directory) {
  const toml::node* node = holder.get("spectrum");
  if (!node) {
    report.fail(fmt::format("missing section [{}spectrum] (model = \"jonswap\" | …, with its "
                            "parameters)",
                            header));
  }
  auto refuse_scale = [&](const Section& spectrum) {
    if (!scale && spectrum.has("scale")) {
      spectrum.fail("scale", "applies to the whole case: give it in the set's [spectrum]");
    }
  };
  if (!node->is_array()) {
    if (!node->is_table()) {
      report.fail(node->source(), fmt::format("'{}spectrum' must be a table [{}spectrum] or an "
                                              "array of tables [[{}spectrum]], not {}",
                                              header, header, header, type_name(*node)));
    }
    const Section spectrum(report, name + "spectrum", node->as_table());
    const toml::node* spreading_node = holder.get("spreading");
    if (spreading_node && !spreading_node->is_table()) {
      report.fail(spreading_node->source(),
                  fmt::format("'{}spreading' must be a table [{}spreading], not {}", header,
                              header, type_name(*spreading_node)));
    }
    const Section spreading(report, name + "spreading",
                            spreading_node ? spreading_node->as_table() : nullptr);
    refuse_scale(spectrum);
    if (scale) read_scale(spectrum, *scale);
    return {read_component(spectrum, spreading,
                           scale ? std::vector<std::string>{"scale"} : std::vector<std::string>{},
                           directory)};
  }
  if (holder.contains("spreading")) {
    report.fail(fmt::format("[{0}spreading]: a composite sea ([[{0}spectrum]] tables) gives each "
                            "component's spreading in its own [{0}spectrum.spreading] table, "
                            "after that component's [[{0}spectrum]]; remove [{0}spreading]",
                            header));
  }
  const toml::array& tables = *node->as_array();
  if (tables.empty()) report.fail(fmt::format("[[{}spectrum]]: no components", header));
  std::vector<reference::SeaComponent> components;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const toml::table* table = tables[i].as_table();
    if (!table) {
      report.fail(node->source(), fmt::format("[[{}spectrum]] must be tables, one per component",
                                              header));
    }
    const std::string component = fmt::format("{}spectrum {}", name, i);
    const Section spectrum(report, component, table);
    const toml::node* spreading_node = table->get("spreading");
    if (spreading_node && !spreading_node->is_table()) {
      spectrum.wrong_type("spreading", fmt::format("a table [{}spectrum.spreading] (model, its "
                                                   "parameters, wind_dir_deg)",
                                                   header));
    }
    const Section spreading(report, component + ".spreading",
                            spreading_node ? spreading_node->as_table() : nullptr);
    refuse_scale(spectrum);
    if (scale && i == 0) {
      read_scale(spectrum, *scale);
    } else if (spectrum.has("scale")) {
      spectrum.fail("scale", "applies to the whole sea: give it once, in the first [[spectrum]]");
    }
    components.push_back(
        read_component(spectrum, spreading,
                       scale && i == 0 ? std::vector<std::string>{"scale", "spreading"}
                                       : std::vector<std::string>{"spreading"},
                       directory));
  }
  return components;
}

// True when the document is a set of independent seas whose every [[cascade]] declares its own
// spectrum: the set's [spectrum] may then be left out.
bool every_cascade_has_its_sea(const toml::table& document) {
  const auto* settings = document.get_as<toml::table>("cascades");
  const auto* list = document.get_as<toml::array>("cascade");
  if (!settings || !list || list->empty()) return false;
  const auto* relation = settings->get_as<std::string>("relation");
  if (!relation || relation->get() != "independent") return false;
  for (const auto& node : *list) {
    const auto* table = node.as_table();
    if (!table || !table->contains("spectrum")) return false;
  }
  return true;
}

// The case's sea ([spectrum], [spreading] or [[spectrum]] tables; read_components).
void read_sea(const Reporter& report, const toml::table& document, CaseFile& out) {
  if (!document.contains("spectrum") && every_cascade_has_its_sea(document)) {
    if (document.contains("spreading")) {
      report.fail("[spreading] without [spectrum]: each cascade declares its own sea; give its "
                  "spreading in [cascade.spreading]");
    }
    return;  // read_cascades gives the set cascade 0's sea
  }
  out.ocean.set_components(read_components(report, document, "", "", &out, out.directory));
}

void read_synthesis(const Section& synthesis, reference::OceanCase& ocean) {
  synthesis.allow_only({"choppiness", "loop_period", "seed"});
  ocean.choppiness = synthesis.number_or("choppiness", 1);
  ocean.loop_period = synthesis.number_or("loop_period", 0);
  read_seed(synthesis, ocean.seed);
}

// The rules of the case as a whole (OceanCase::validate and each cascade's), reported against
// the file. An additive set whose bands do not share the spectrum out is still read: the gate
// judges it (cascades.bands, docs/gate.md §10).
void validate_case(const Reporter& report, CaseFile& out) {
  auto& ocean = out.ocean;
  try {
    ocean.validate();
    for (std::size_t c = 0; c < out.cascades.size(); ++c) {
      try {
        out.cascade_case(c).validate();
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("[cascade {}]: {}", c, e.what()));
      }
    }
  } catch (const InvalidInput& e) {
    report.fail(e.what());
  } catch (const NumericalError& e) {
    // validate() builds the spectrum and the spreading. The model factory already turns a
    // spectrum outside any sea (tp = 1e60 s, found by validation/fuzz/case_file_fuzzer) into
    // InvalidInput; any other quadrature that fails on the case's values is bad input too.
    report.fail(fmt::format("the case's spectrum cannot be evaluated with these parameters: {}",
                            e.what()));
  }
}

}  // namespace

CaseFile parse_case_toml(const std::string& text, const fs::path& origin) {
  const Reporter report(origin.string());
  toml::table document;
  try {
    document = toml::parse(text, origin.string());
  } catch (const toml::parse_error& e) {
    report.fail(e.source(), fmt::format("not valid TOML: {}", e.description()));
  }
  check_sections(report, document);
  auto section = [&](const std::string& name) { return section_of(report, document, name); };

  CaseFile out;
  out.origin = origin;
  out.directory = origin.parent_path();
  read_sampling(report, document, out);
  if (out.is_probe_case()) {
    read_probe_time(section("time"), out);
  } else {
    read_time(section("time"), out.ocean);
  }
  read_physics(section("physics"), out.ocean);
  read_sea(report, document, out);
  if (out.is_probe_case()) {
    read_probe_synthesis(section("synthesis"), out);
    out.probes->input = read_probe_input(section("input"), out.probes->layout.positions.size());
    try {
      out.probe_case().validate();
    } catch (const InvalidInput& e) {
      report.fail(e.what());
    } catch (const NumericalError& e) {
      report.fail(fmt::format("the case's spectrum cannot be evaluated with these parameters: {}", e.what()));
    }
    return out;
  }
  read_synthesis(section("synthesis"), out.ocean);
  // [input]: the frames' pattern, one channel (or file suffix) per field provided.
  out.input = read_input(report, section("input"));
  read_cascades(report, document, out);
  if (out.is_cascade_set()) out.ocean.grid = out.cascades.front().grid;
  validate_case(report, out);
  return out;
}

reference::ProbeCase CaseFile::probe_case() const {
  if (!probes) throw InternalError("probe_case() of a case that is not a probes case");
  reference::ProbeCase out;
  out.sea = ocean;
  out.layout = probes->layout;
  out.synthesis = probes->synthesis;
  return out;
}

reference::OceanCase CaseFile::cascade_case(std::size_t c) const {
  const auto& cascade = cascades.at(c);
  reference::OceanCase out = ocean;
  out.members.clear();
  out.grid = cascade.grid;
  out.band = cascade.band;
  if (!cascade.components.empty()) out.set_components(cascade.components);
  out.cascade = reference::is_summed(relation) ? cascade.index : 0;
  return out;
}

std::vector<reference::CascadeMember> CaseFile::members() const {
  std::vector<reference::CascadeMember> out;
  for (std::size_t c = 0; c < cascades.size(); ++c) {
    const auto sea = cascade_case(c);
    reference::CascadeMember member{sea.cascade, sea.grid, sea.band, nullptr};
    // Independent seas each carry their own Ψ; the sum's sea is theirs added.
    if (relation == reference::CascadeRelation::independent) member.spectrum = sea.sea_spectrum();
    out.push_back(std::move(member));
  }
  return out;
}

std::optional<reference::OceanCase> CaseFile::summed_case(std::string* why) const {
  if (!is_cascade_set() || !reference::is_summed(relation)) {
    if (why) *why = is_cascade_set() ? "nested bands are not added" : "not a cascade set";
    return std::nullopt;
  }
  reference::Grid fine;
  const auto list = members();
  if (!reference::summed_grid(list, fine, why)) return std::nullopt;
  reference::OceanCase out = ocean;
  out.grid = fine;
  out.band = {};
  out.cascade = 0;
  out.members = list;
  if (relation == reference::CascadeRelation::independent) {
    // The sum of independent seas: every cascade's components, its sea added once per cascade.
    std::vector<reference::SeaComponent> all;
    for (std::size_t c = 0; c < cascades.size(); ++c) {
      const auto parts = cascade_case(c).components();
      all.insert(all.end(), parts.begin(), parts.end());
    }
    out.set_components(all);
  }
  return out;
}

void require_single_grid(const CaseFile& case_file, const std::string& command) {
  if (case_file.is_probe_case()) {
    throw InvalidInput(fmt::format("{} takes a single-grid case; this one samples {} probes (swell synth "
                                   "makes their series and swell gate judges them)",
                                   command, case_file.probes->layout.positions.size()));
  }
  if (!case_file.is_cascade_set()) return;
  throw InvalidInput(fmt::format("{} takes a single-grid case; this one is a set of {} cascades "
                                 "(swell synth makes them and swell gate judges them)",
                                 command, case_file.cascades.size()));
}

CaseFile read_case_file(const fs::path& path) {
  std::error_code error;
  if (!fs::exists(path, error)) throw InvalidInput(path.string() + ": no such case file");
  if (fs::is_directory(path, error)) {
    throw InvalidInput(path.string() + ": is a directory, not a case file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InvalidInput(path.string() + ": cannot open the case file for reading");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw InvalidInput(path.string() + ": read error");
  return parse_case_toml(text.str(), path);
}

// The keys of an input section under `header` ("[input]", "[sum]"; "" inside a [[cascade]]
// table already open), nothing when it names no frames.
void write_input(std::string& out, const std::string& header, const InputSpec& input) {
  if (input.files.empty() && input.channels.empty()) return;
  if (!header.empty()) out += "\n" + header + "\n";

    if (!input.files.empty()) out += fmt::format("files = {}\n", toml_string(input.files));
    for (const auto& [field, channel] : input.channels) {
      out += fmt::format("{} = {}\n", reference::field_name(field), toml_string(channel));
    }
    if (input.raw_type != "float32") out += fmt::format("raw_type = {}\n", toml_string(input.raw_type));
    if (!input.precision.empty()) out += fmt::format("precision = {}\n", toml_string(input.precision));
    if (!input.value_ranges.empty()) {
      const IntegerRange first = input.value_ranges.begin()->second;
      bool one_for_all = input.value_ranges.size() == input.channels.size();
      for (const auto& [field, range] : input.value_ranges) one_for_all = one_for_all && range == first;
      auto pair = [](const IntegerRange& r) {
        return fmt::format("[{}, {}]", toml_number(r.low), toml_number(r.high));
      };
      if (one_for_all) {
        out += fmt::format("value_range = {}\n", pair(first));
      } else {
        std::string table;
        for (const auto& [field, range] : input.value_ranges) {
          table += fmt::format("{}{} = {}", table.empty() ? "" : ", ", reference::field_name(field),
                               pair(range));
        }
        out += fmt::format("value_range = {{ {} }}\n", table);
      }
    }
}

// A sea's components: one as [spectrum] + [spreading], a composite sea as [[spectrum]] tables,
// each followed by its [spectrum.spreading]; `header` prefixes the tables ("cascade." for a
// [[cascade]]'s own sea), `scale` (the case's, in its first component) is left out when empty.
void write_sea(std::string& out, const std::vector<reference::SeaComponent>& components,
               const std::string& header, bool probes, const std::string& scale) {
  const bool composite = components.size() > 1;
  const std::string spectrum_table =
      composite ? "[[" + header + "spectrum]]" : "[" + header + "spectrum]";
  const std::string spreading_table =
      composite ? "[" + header + "spectrum.spreading]" : "[" + header + "spreading]";
  for (std::size_t i = 0; i < components.size(); ++i) {
    const auto& part = components[i];
    // The direction of a sea without a spreading model: phillips's own; a 2-D table has none.
    const bool direction_in_spectrum = part.spreading.model.empty() && !part.table;
    out += fmt::format("{}\nmodel = {}\n", spectrum_table, toml_string(part.spectrum.model));
    if (i == 0 && !scale.empty()) out += fmt::format("scale = \"{}\"\n", scale);
    write_parameters(out, part.spectrum);
    if (part.energy_factor != 1) {
      out += fmt::format("energy_factor = {}\n", toml_number(part.energy_factor));
    }
    if (part.short_wave_fade != 0) {
      out += fmt::format("short_wave_fade = {}\n", toml_number(part.short_wave_fade));
    }
    // A long-crested probes sea without a spreading model keeps its direction in [spreading].
    const bool direction_alone = direction_in_spectrum && probes && part.spectrum.model != "phillips";
    if (direction_in_spectrum && !direction_alone) {
      out += fmt::format("wind_dir_deg = {}\n", toml_number(part.wind_dir_deg));
    }
    out += "\n";
    if (direction_alone) {
      out += fmt::format("{}\nwind_dir_deg = {}\n\n", spreading_table,
                         toml_number(part.wind_dir_deg));
    }
    if (!part.spreading.model.empty()) {
      out += fmt::format("{}\nmodel = {}\n", spreading_table, toml_string(part.spreading.model));
      write_parameters(out, part.spreading);
      out += fmt::format("wind_dir_deg = {}\n\n", toml_number(part.wind_dir_deg));
    }
  }
}

std::string case_toml(const CaseFile& case_file) {
  const auto& c = case_file.ocean;
  std::string out = "# swell case file (docs/case_files.md)\n";
  std::string summary = case_file.is_probe_case() ? case_file.probe_case().describe() : c.describe();
  std::replace(summary.begin(), summary.end(), '\n', ' ');  // stays one comment line
  out += fmt::format("# {}\n\n", summary);
  if (case_file.is_probe_case()) {
    const auto& layout = case_file.probes->layout;
    std::string positions;
    for (const auto& [x, y] : layout.positions) {
      positions += fmt::format("{}[{}, {}]", positions.empty() ? "" : ", ", toml_number(x), toml_number(y));
    }
    out += fmt::format("[sampling]\nkind = \"probes\"\npositions = [{}]\n\n", positions);
    out += fmt::format("[time]\nt0 = {}\ndt = {}\nsamples = {}\n\n", toml_number(layout.t0),
                       toml_number(layout.dt), layout.samples);
  } else if (case_file.is_cascade_set()) {
    // [[cascade]] tables below
  } else if (c.is_lattice()) {
    const auto& g = c.lattice->generator();
    out += fmt::format("[grid]\nlength = [{}, {}]\n\n", toml_number(c.grid.lx),
                       toml_number(c.grid.ly));
    out += fmt::format("[sampling]\nkind = \"lattice\"\npoints = {}\ngenerator = [{}, {}]\n\n",
                       c.lattice->points(), g[0], g[1]);
  } else {
    out += fmt::format("[grid]\nn = [{}, {}]\nlength = [{}, {}]\n\n", c.grid.nx, c.grid.ny,
                       toml_number(c.grid.lx), toml_number(c.grid.ly));
  }
  if (!case_file.is_probe_case()) {
    out += fmt::format("[time]\nt0 = {}\ndt = {}\nframes = {}\n\n", toml_number(c.t0),
                       toml_number(c.dt), c.frames);
  }
  out += fmt::format("[physics]\ngravity = {}\ndepth = {}\n\n", toml_number(c.gravity),
                     std::isinf(c.depth) && c.depth > 0 ? "\"inf\"" : toml_number(c.depth));

  // An independent set whose cascades all carry their own sea needs no [spectrum] of its own,
  // but writing cascade 0's there reads back to the same set.
  write_sea(out, c.components(), "", case_file.is_probe_case(),
            case_file.scale == SpectrumScale::free ? "free" : "absolute");

  const std::string seed =
      c.seed > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())
          ? fmt::format("\"{}\"", c.seed)
          : fmt::format("{}", c.seed);
  if (case_file.is_probe_case()) {
    const auto& p = *case_file.probes;
    const auto& s = p.synthesis;
    out += fmt::format("[synthesis]\nseed = {}\namplitudes = \"{}\"\nfrequencies = \"{}\"\n"
                       "repeat_period = {}\nomega_cutoff = [{}, {}]\ndirections = \"{}\"\n",
                       seed, to_string(s.amplitudes), to_string(s.frequencies), toml_number(s.repeat_period),
                       toml_number(s.omega_low), toml_number(s.omega_high), to_string(s.directions));
    if (s.directions == reference::ProbeDirections::double_summation) {
      out += fmt::format("n_directions = {}\n", s.n_directions);
    }
    if (s.frequencies != reference::ProbeFrequencies::uniform) {
      out += fmt::format("n_frequencies = {}\n", s.n_frequencies);
    }
    if (!p.input.files.empty()) {
      out += fmt::format("\n[input]\nfiles = {}\n", toml_string(p.input.files));
      if (!p.input.time_column.empty()) out += fmt::format("time_column = {}\n", toml_string(p.input.time_column));
      if (!p.input.probes.empty()) {
        std::string names;
        for (const auto& name : p.input.probes) names += (names.empty() ? "" : ", ") + toml_string(name);
        out += fmt::format("probes = [{}]\n", names);
      }
    }
    return out;
  }
  out += fmt::format("[synthesis]\nchoppiness = {}\nloop_period = {}\nseed = {}\n",
                     toml_number(c.choppiness), toml_number(c.loop_period), seed);

  write_input(out, "[input]", case_file.input);
  if (case_file.is_cascade_set()) {
    out += fmt::format("\n[cascades]\nrelation = \"{}\"\n", to_string(case_file.relation));
    const double crossover = case_file.cascades.front().band.crossover;
    if (crossover != 1) out += fmt::format("crossover = {}\n", toml_number(crossover));
    for (const auto& cascade : case_file.cascades) {
      out += fmt::format("\n[[cascade]]\nn = [{}, {}]\nlength = [{}, {}]\n", cascade.grid.nx,
                         cascade.grid.ny, toml_number(cascade.grid.lx),
                         toml_number(cascade.grid.ly));
      if (!cascade.band.everywhere()) {
        out += fmt::format("band = [{}, {}]\n", toml_number(cascade.band.lo),
                           std::isinf(cascade.band.hi) ? std::string("inf")
                                                       : toml_number(cascade.band.hi));
      }
      write_input(out, "", cascade.input);
      if (!cascade.components.empty()) {
        out += "\n";
        write_sea(out, cascade.components, "cascade.", false, "");
        out.pop_back();  // write_sea ends each table with a blank line; the next header adds one
      }
    }
    write_input(out, "[sum]", case_file.sum);
  }
  return out;
}

void write_case_file(const fs::path& path, const CaseFile& case_file) {
  const std::string text = case_toml(case_file);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw InvalidInput(path.string() + ": cannot open for writing");
  file << text;
  file.close();
  if (!file) throw InvalidInput(path.string() + ": write failed");
}

}  // namespace swell::validation
