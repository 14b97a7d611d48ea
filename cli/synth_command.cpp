// swell synth (--case FILE | --model M [params]) [--spreading S [params]] --impl NAME --n N
//             [--ny N] --length L [--length-y L] [--seed S] [--frames F --dt DT] [--t0 T]
//             [--depth H] [--gravity G] [--wind-dir DEG] [--choppiness C] [--loop-period T]
//             [--precision fp32|fp64] [--format exr|npy|tiff|png [--value-range LO,HI]]
//             --out DIR [--json FILE|-]
//
// Synthesizes the frames of an ocean case (docs/conventions.md §Amplitudes) with one transform
// backend and writes them to DIR (frame_0000.exr, …, docs/case_files.md) with DIR/case.toml, a
// complete case file whose [input] section reads those frames back.
//
// With --case the case file gives everything and flags override it: --model replaces the
// spectrum (model and parameters), --spreading the spreading model, a parameter flag sets that
// one parameter of whichever model takes it, and --n/--length set both axes unless --ny/--length-y
// are given. A non-phillips spectrum without a spreading model gets cos2s with s = 10.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>

#include "commands.hpp"
#include "synth_options.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/validation/io/npy.hpp"
#include "swell/validation/io/mesh_io.hpp"
#include "swell/reference/lattice_mesh.hpp"
#include "swell/reference/lattice.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/checks/ocean_checks.hpp"

namespace swell::cli {
namespace {

namespace fs = std::filesystem;
using reference::Field;
using reference::ModelSpec;

// The spreading a directional spectrum gets when none is named (documented in --help and
// docs/case_files.md): a moderately broad cos-2s.
constexpr const char* kDefaultSpreading = "cos2s";
constexpr double kDefaultSpreadingS = 10;

std::string flag_of(const std::string& parameter) {
  std::string flag = "--" + parameter;
  for (auto& c : flag) c = c == '_' ? '-' : c;
  return flag;
}

bool takes(const std::string& model, const std::string& parameter) {
  if (model.empty()) return false;
  for (const auto& info : reference::model_parameters(model)) {
    if (info.name == parameter) return true;
  }
  return false;
}

std::string parameter_list(const std::string& model) {
  std::string out;
  for (const auto& info : reference::model_parameters(model)) {
    if (info.name == "gravity" || info.name == "depth" || info.name == "wind_dir") continue;
    out += (out.empty() ? "" : ", ") + flag_of(info.name);
  }
  return out.empty() ? "none" : out;
}

// --impl lattice[:fft=NAME]: rank-1 lattice synthesis (docs/conventions.md §2.1) through the
// 1-D transforms of backend NAME (default fftw; NAME may carry its own options, as
// "fftw:threads=2"). Anything else is a grid backend.
struct ImplChoice {
  bool lattice = false;
  std::string backend;  // the transform backend
};

ImplChoice parse_impl(const std::string& impl) {
  const std::string prefix = "lattice";
  if (impl.compare(0, prefix.size(), prefix) != 0 ||
      (impl.size() > prefix.size() && impl[prefix.size()] != ':')) {
    return {false, impl};
  }
  if (impl == prefix) return {true, "fftw"};
  const std::string option = impl.substr(prefix.size() + 1);
  if (option.compare(0, 4, "fft=") != 0 || option.size() == 4) {
    throw InvalidInput(fmt::format("--impl {}: a lattice takes one option, fft=NAME (the 1-D "
                                   "transform backend: {}), as lattice:fft=radix2",
                                   impl, fmt::join(impls::backend_names(), ", ")));
  }
  return {true, option.substr(4)};
}

// The case the flags (and the case file, if any) describe.
validation::CaseFile build_case(const SynthOptions& o) {
  validation::CaseFile c;
  auto& ocean = c.ocean;
  const bool from_file = !o.case_file.empty();
  const bool lattice = parse_impl(o.impl).lattice;
  if (!lattice && (o.has("--points") || o.has("--kind"))) {
    throw InvalidInput(fmt::format("{} chooses a lattice's points: it needs --impl "
                                   "lattice[:fft=NAME] (got --impl {})",
                                   o.has("--points") ? "--points" : "--kind", o.impl));
  }
  if (lattice && (o.has("--n") || o.has("--ny"))) {
    throw InvalidInput("--n and --ny set a grid; a lattice (--impl lattice) takes --points N");
  }
  if (from_file) {
    c = validation::read_case_file(o.case_file);
    if (c.is_cascade_set()) {
      for (const char* flag : {"--n", "--ny", "--length", "--length-y", "--points"}) {
        if (o.has(flag)) {
          throw InvalidInput(fmt::format("{}: {} is a cascade set; each cascade's grid is its "
                                         "[[cascade]] n and length",
                                         flag, o.case_file));
        }
      }
      if (lattice) {
        throw InvalidInput(fmt::format("--impl {}: {} is a cascade set of grids; give a grid "
                                       "backend",
                                       o.impl, o.case_file));
      }
    }
    if (c.ocean.is_lattice() && !lattice) {
      throw InvalidInput(fmt::format("{} samples a lattice ([sampling] kind = \"lattice\"): "
                                     "synthesize it with --impl lattice[:fft=NAME]",
                                     o.case_file));
    }
    if (lattice && !c.ocean.is_lattice() && !o.has("--points")) {
      throw InvalidInput(fmt::format("--impl lattice on the grid case {}: give --points N (the "
                                     "lattice replaces the grid over the same patch)",
                                     o.case_file));
    }
  } else {
    for (const auto& [flag, what] : {std::pair{"--model", "a spectrum model"},
                                     std::pair{lattice ? "--points" : "--n",
                                               lattice ? "the lattice points" : "the grid size"},
                                     std::pair{"--length", "the patch size in m"}}) {
      if (!o.has(flag)) {
        throw InvalidInput(fmt::format("{} ({}) is required without --case", flag, what));
      }
    }
  }

  apply_sea_flags(o, ocean);

  // Grid, time, physics, synthesis.
  if (o.has("--n")) ocean.grid.nx = ocean.grid.ny = o.n;
  if (lattice && !ocean.is_lattice()) ocean.grid.nx = ocean.grid.ny = 0;  // lengths only
  if (o.has("--ny")) ocean.grid.ny = o.ny;
  if (o.has("--length")) ocean.grid.lx = ocean.grid.ly = o.length;
  if (o.has("--length-y")) ocean.grid.ly = o.length_y;
  if (o.has("--frames")) ocean.frames = o.frames;
  if (o.has("--dt")) ocean.dt = o.dt;
  if (o.has("--t0")) ocean.t0 = o.t0;
  if (o.has("--choppiness")) ocean.choppiness = o.choppiness;
  if (o.has("--loop-period")) ocean.loop_period = o.loop_period;
  if (lattice) {
    // The lattice over the case's patch: --points (and --kind) make a new one; a lattice case
    // keeps its points and generator, over the patch --length may have changed.
    const std::vector<double> lengths = {ocean.grid.lx, ocean.grid.ly};
    for (const double l : lengths) {
      if (!(std::isfinite(l) && l > 0)) {
        throw InvalidInput(fmt::format("--length: the patch must be finite and > 0 m (got {:g})", l));
      }
    }
    std::shared_ptr<const reference::RankOneLattice> chosen;
    if (o.has("--points")) {
      if (o.kind == "fibonacci") {
        const int j = reference::fibonacci_index(o.points);
        chosen = std::make_shared<const reference::RankOneLattice>(
            reference::fibonacci_lattice(j, lengths[0], lengths[1]));
      } else {
        chosen = std::make_shared<const reference::RankOneLattice>(
            reference::korobov_lattice(o.points, lengths));
      }
    } else {
      chosen = std::make_shared<const reference::RankOneLattice>(reference::RankOneLattice::create(
          ocean.lattice->points(), ocean.lattice->generator(), lengths));
    }
    ocean.set_lattice(std::move(chosen));
  }
  ocean.validate();
  // Flags may have changed what the cascades share (the spectrum, and so each band's share of
  // m0): the set's rules again.
  for (std::size_t k = 0; k < c.cascades.size(); ++k) c.cascade_case(k).validate();
  // A reference set is made as declared only when it is one: an additive set whose bands
  // overlap or leave a gap has no right frames to make (swell gate judges such a set and names
  // every range; independent seas that sum are relation = "independent").
  if (c.is_cascade_set() && c.relation == reference::CascadeRelation::additive) {
    try {
      reference::require_bands_share_out(ocean, c.members());
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}; swell synth makes right sets only (swell gate judges "
                                     "this one)",
                                     e.what()));
    }
  }
  return c;
}

double rms(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v * v;
  return values.empty() ? 0 : std::sqrt(sum / static_cast<double>(values.size()));
}

// The values a PNG over `range` with `levels` steps gives back for `values`: each rounded to
// its pixel, as the writer stores it (values outside the range are refused there).
std::vector<double> as_stored(const std::vector<double>& values, const validation::IntegerRange& range,
                              double levels) {
  const double width = range.high - range.low;
  std::vector<double> stored(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double pixel = std::clamp(std::nearbyint((values[k] - range.low) / width * levels), 0.0, levels);
    stored[k] = range.low + width * (pixel / levels);
  }
  return stored;
}

// How one surface's frames are made and stored: the choices run_synth takes from the flags.
struct SurfaceWriting {
  ImplChoice impl;
  impls::Precision precision = impls::Precision::f32;
  validation::FrameWriteOptions write_options;
  std::vector<Field> fields;  // the fields stored
  bool png = false;
  bool quiet = false;  // standard output carries the JSON only
  std::string label;   // "" or "cascade 1: ", before each frame's line
};

// Synthesizes `ocean`'s frames into `dir` (created if missing), appending the files written to
// `files`; a lattice's frame 0 goes to `first_surface` for its mesh. The validity rule runs
// first, in the narrower of the synthesis precision and what the files store (EXR, TIFF and PNG
// hold float32 or less), with the memory a synthesizer and the writer need.
void write_surface(const reference::OceanCase& ocean, const fs::path& dir,
                   const SurfaceWriting& w, std::vector<fs::path>& files,
                   validation::MeshSurface* first_surface = nullptr) {
  const bool stores_fp64 = w.write_options.float64;
  const auto& numbers = w.precision == impls::Precision::f64 && stores_fp64 ? reference::kFloat64
                                                                           : reference::kFloat32;
  const double samples = double(ocean.sampling().size());
  // A lattice: the synthesizer's row of N classes, and the mesh (about 100 bytes a point).
  const reference::Grid transform_shape =
      w.impl.lattice ? reference::Grid{static_cast<int>(std::min<double>(samples, 2147483647.0)), 1,
                                       ocean.grid.lx, ocean.grid.ly}
                     : ocean.grid;
  const double writer_bytes =
      samples * 6 * (stores_fp64 ? 8 : 4) + (w.impl.lattice ? samples * 100 : 0);
  reference::require_valid_sampling(
      ocean, numbers,
      impls::Synthesizer::bytes_needed(transform_shape, w.precision) +
          std::uint64_t(std::min(writer_bytes, 1e18)),
      "swell synth");

  impls::SynthesizerOptions options;
  options.backend = w.impl.backend;
  options.precision = w.precision;
  const impls::Synthesizer synthesizer(ocean, options);  // unknown backends name the valid ones
  double png_roundoff = 0, png_mean_square0 = 0;
  for (int f = 0; f < ocean.frames; ++f) {
    reference::FieldFrame frame = synthesizer.frame(ocean.time(f));
    if (first_surface && f == 0) {
      first_surface->h = frame.fields.at(Field::height);
      first_surface->dx = frame.fields.at(Field::disp_x);
      first_surface->dy = frame.fields.at(Field::disp_y);
    }
    if (w.png) {
      // The gate judges PNG frames by their quantization (frame_io.hpp) as it reads them back:
      // the largest unit roundoff of any field in any frame, against frame 0's mean square
      // height. Refuse, before writing this frame, a PNG whose step would hide every wave vector
      // from it.
      const validation::IntegerRange range = w.write_options.png_range;
      const double levels = w.write_options.png_bits == 8 ? 255.0 : 65535.0;
      for (Field field : w.fields) {
        const auto stored = as_stored(frame.fields.at(field), range, levels);
        png_roundoff = std::max(png_roundoff, validation::quantization_roundoff(range, levels, stored));
        if (f == 0 && field == Field::height) png_mean_square0 = std::pow(rms(stored), 2);
      }
      validation::require_judgeable_rounding(ocean, png_roundoff, png_mean_square0);
    }
    const auto& j = frame.fields.at(Field::jacobian);
    const double min_j = *std::min_element(j.begin(), j.end());
    for (Field field : reference::kAllFields) {
      if (std::find(w.fields.begin(), w.fields.end(), field) == w.fields.end()) {
        frame.fields.erase(field);
      }
    }
    fs::create_directories(dir);
    const auto written = validation::write_frame(dir, ocean.grid, frame, f, w.write_options);
    files.insert(files.end(), written.begin(), written.end());
    if (!w.quiet) {
      const auto& h = frame.fields.at(Field::height);
      fmt::print("{}frame {:4d}  t = {:g} s  rms h = {:.4g} m (4σ = {:.4g} m)  min J = {:.4g}  "
                 "→ {}{}\n",
                 w.label, f, ocean.time(f), rms(h), 4 * rms(h), min_j, written.front().string(),
                 written.size() > 1 ? fmt::format(" (+{} files)", written.size() - 1) : "");
    }
  }
}

// The input section that reads frames written into the subfolder `folder` back.
validation::InputSpec input_in(const std::string& folder, const SurfaceWriting& w) {
  auto input = validation::frame_input_spec(w.fields, w.write_options);
  input.files = folder + "/" + input.files;
  return input;
}

int run_synth(const SynthOptions& o) {
  if (wants_probes(o)) return run_probe_synth(o);
  if (!o.has("--impl")) {
    throw InvalidInput("--impl is required: the transform backend (" +
                       fmt::format("{}", fmt::join(impls::backend_names(), ", ")) +
                       "), or lattice[:fft=NAME]; a probes case needs none");
  }
  validation::CaseFile c = build_case(o);
  const auto& ocean = c.ocean;
  SurfaceWriting w;
  w.impl = parse_impl(o.impl);
  w.precision = impls::precision_from_string(o.precision);
  auto& write_options = w.write_options;
  // A lattice's frames are arrays of its N points: .npy unless asked otherwise (and then
  // refused by name: an image needs a grid).
  write_options.format = validation::frame_format_from_string(
      w.impl.lattice && !o.has("--format") ? std::string("npy") : o.format);
  if (w.impl.lattice && write_options.format != validation::FrameFormat::npy) {
    throw InvalidInput(fmt::format("--format {}: lattice frames are written as npy (one array of "
                                   "the N points per field, with points.npy and mesh.ply); "
                                   "images need a grid",
                                   o.format));
  }
  write_options.float64 =
      w.precision == impls::Precision::f64 && write_options.format == validation::FrameFormat::npy;
  // PNG: 16 bits through a value range, and room for three fields (R, G, B): the height and
  // the horizontal displacements, what a game engine's heightmap textures hold.
  w.png = write_options.format == validation::FrameFormat::png;
  if (w.png != !o.value_range.empty()) {
    throw InvalidInput(w.png ? "--format png needs --value-range LO,HI: the values (m) that pixel 0 "
                               "and pixel 65535 stand for, such as -4,4"
                             : "--value-range applies to --format png only");
  }
  if (w.png) {
    if (o.value_range.size() != 2) {
      throw InvalidInput(fmt::format("--value-range takes two numbers LO,HI (got {})",
                                     o.value_range.size()));
    }
    write_options.png_range = {o.value_range[0], o.value_range[1]};
  }
  w.fields.assign(reference::kAllFields.begin(), reference::kAllFields.end());
  if (w.png) w.fields = {Field::height, Field::disp_x, Field::disp_y};
  if (!o.fields.empty()) {
    // In swell's field order, whatever order they are named in; every gate needs the height.
    std::vector<Field> named;
    for (const auto& name : o.fields) {
      const Field field = reference::field_from_name(name);  // names the valid ones
      if (std::find(named.begin(), named.end(), field) != named.end()) {
        throw InvalidInput(fmt::format("--fields names {} twice", reference::field_name(field)));
      }
      named.push_back(field);
    }
    if (std::find(named.begin(), named.end(), Field::height) == named.end()) {
      throw InvalidInput("--fields must include height (h): every ocean check reads it");
    }
    if (w.png && named.size() > 4) {
      throw InvalidInput(fmt::format("--fields names {} fields; a PNG holds at most 4 (R, G, B, A)",
                                     named.size()));
    }
    w.fields.clear();
    for (Field field : reference::kAllFields) {
      if (std::find(named.begin(), named.end(), field) != named.end()) w.fields.push_back(field);
    }
  }
  w.quiet = o.json == "-";

  const auto start = std::chrono::steady_clock::now();
  const fs::path out(o.out);
  if (!w.quiet) {
    fmt::print("swell synth: {}; {} frame{}; {} {}; {} files in {}\n",
               c.is_cascade_set()
                   ? fmt::format("{} set of {} cascades, {}", to_string(c.relation),
                                 c.cascades.size(), ocean.describe())
                   : ocean.describe(),
               ocean.frames, ocean.frames == 1 ? "" : "s", o.impl, o.precision, o.format,
               out.string());
    if (w.precision == impls::Precision::f64 && !write_options.float64) {
      fmt::print("note: {} frames store float32; use --format npy to keep fp64\n", o.format);
    }
  }
  std::vector<fs::path> files;
  // A refusal part-way (a PNG value outside --value-range in a later frame) removes the frames
  // already written: a refused command leaves no output behind.
  struct RemoveUnlessKept {
    std::vector<fs::path>& files;
    bool keep = false;
    ~RemoveUnlessKept() {
      if (keep) return;
      std::error_code ignored;
      for (const auto& file : files) fs::remove(file, ignored);
    }
  } cleanup{files};
  std::string sum_note;
  if (c.is_cascade_set()) {
    // Each cascade under its own folder, and the summed surface (an additive set whose patch
    // lengths allow it) under sum/; the case's [[cascade]] and [sum] tables read them back.
    for (std::size_t k = 0; k < c.cascades.size(); ++k) {
      const std::string folder = fmt::format("cascade{}", k);
      w.label = c.cascades.size() > 1 ? fmt::format("cascade {}: ", k) : "";
      write_surface(c.cascade_case(k), out / folder, w, files);
      c.cascades[k].input = input_in(folder, w);
    }
    std::string why;
    auto summed = c.summed_case(&why);
    // auto: the sum when its grid is at most 2048² (16 frames of six fp32 fields of 2048² are
    // 1.6 GB already).
    constexpr double kLargestAutomaticSum = 2048.0 * 2048.0;
    if (summed && o.sum == "no") {
      summed.reset();
      why = "--sum no";
    } else if (summed && o.sum == "auto" &&
               double(summed->grid.nx) * summed->grid.ny > kLargestAutomaticSum) {
      why = fmt::format("it would be {}×{} (more than 2048²); --sum yes writes it",
                        summed->grid.nx, summed->grid.ny);
      summed.reset();
    } else if (!summed && o.sum == "yes") {
      throw InvalidInput("--sum yes: the cascades cannot be summed on one grid: " + why);
    }
    if (summed) {
      w.label = "sum: ";
      write_surface(*summed, out / "sum", w, files);
      c.sum = input_in("sum", w);
      sum_note = fmt::format("; the sum on {}×{} over {:g}×{:g} m in sum/", summed->grid.nx,
                             summed->grid.ny, summed->grid.lx, summed->grid.ly);
    } else {
      c.sum = {};
      sum_note = fmt::format("; no summed surface: {}", why);
    }
  } else {
    validation::MeshSurface first_surface;  // a lattice's frame 0, for mesh.ply
    write_surface(ocean, out, w, files, w.impl.lattice ? &first_surface : nullptr);
    if (w.impl.lattice) {
      // The points (N × 2, metres, float64) and the first frame as a tileable mesh (the
      // periodic Delaunay triangulation of the lattice, two triangles a point; docs/lattice.md).
      const auto& lat = *ocean.lattice;
      std::vector<double> xy(2 * static_cast<std::size_t>(lat.points()));
      for (std::int64_t n = 0; n < lat.points(); ++n) {
        const auto x = lat.point(n);
        xy[2 * static_cast<std::size_t>(n)] = x[0];
        xy[2 * static_cast<std::size_t>(n) + 1] = x[1];
      }
      const fs::path points_path = out / "points.npy";
      validation::write_npy(points_path, validation::NpyArray::from_values(
                                             {static_cast<std::size_t>(lat.points()), 2},
                                             std::span<const double>(xy)));
      files.push_back(points_path);
      const auto& g = lat.generator();
      first_surface.mesh = reference::periodic_delaunay(lat.points(), g[0], g[1],
                                                        lat.lengths()[0], lat.lengths()[1]);
      const fs::path mesh_path = out / "mesh.ply";
      validation::write_ply(mesh_path, first_surface);
      files.push_back(mesh_path);
      if (!w.quiet) {
        fmt::print("points → {}; frame 0 as a tileable mesh ({} triangles) → {}\n",
                   points_path.string(), 2 * lat.points(), mesh_path.string());
      }
    }
    c.input = validation::frame_input_spec(w.fields, write_options);
  }
  c.directory = out;
  const fs::path case_path = out / "case.toml";
  validation::write_case_file(case_path, c);
  cleanup.keep = true;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (!o.json.empty()) {
    std::vector<std::string> names;
    for (const auto& file : files) names.push_back(file.string());
    nlohmann::json document = {{"case", case_path.string()},
                               {"description", ocean.describe()},
                               {"impl", o.impl},
                               {"precision", o.precision},
                               {"format", o.format},
                               {"n", ocean.is_lattice()
                                         ? nlohmann::json{ocean.lattice->points()}
                                         : nlohmann::json{ocean.grid.nx, ocean.grid.ny}},
                               {"sampling", ocean.sampling().describe()},
                               {"frames", ocean.frames},
                               {"files", names},
                               {"seconds", seconds}};
    if (c.is_cascade_set()) {
      nlohmann::json list = nlohmann::json::array();
      for (std::size_t k = 0; k < c.cascades.size(); ++k) {
        const auto& cascade = c.cascades[k];
        list.push_back({{"n", {cascade.grid.nx, cascade.grid.ny}},
                        {"length", {cascade.grid.lx, cascade.grid.ly}},
                        {"band", {cascade.band.lo, std::isinf(cascade.band.hi)
                                                       ? nlohmann::json(nullptr)
                                                       : nlohmann::json(cascade.band.hi)}},
                        {"files", cascade.input.files}});
      }
      document["relation"] = to_string(c.relation);
      document["cascades"] = list;
      document["sum"] = c.sum.files.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.sum.files);
    }
    write_json(o.json, document);
    if (w.quiet) return 0;
  }
  fmt::print("wrote {} frame file{} and {} in {:.3g} s{}\n", files.size(),
             files.size() == 1 ? "" : "s", case_path.string(), seconds, sum_note);
  return 0;
}

}  // namespace

// CLI11 reads "-1" into a uint64 as 2⁶⁴ − 1; a seed is parsed here, digits only.
std::uint64_t parse_seed(const std::string& text) {
  std::uint64_t value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size()) {
    throw InvalidInput("--seed: '" + text + "' is not an integer in 0…18446744073709551615");
  }
  return value;
}

double parse_depth(const std::string& text) {
  if (text == "inf") return reference::kInfiniteDepth;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    throw InvalidInput("--depth: '" + text + "' is not a depth in metres or inf");
  }
  return value;
}

void apply_sea_flags(const SynthOptions& o, reference::OceanCase& ocean, bool default_spreading_allowed) {
  // A composite or tabulated sea is the case file's to say: the model flags set the one
  // component of a parametric sea.
  if (ocean.is_composite() || ocean.table) {
    std::vector<std::string> given;
    for (const char* flag : {"--model", "--spreading", "--wind-dir"}) {
      if (o.has(flag)) given.push_back(flag);
    }
    for (const auto& [name, option] : o.number_options) {
      if (option->count()) given.push_back(flag_of(name));
    }
    for (const auto& [name, option] : o.choice_options) {
      if (option->count()) given.push_back(flag_of(name));
    }
    if (!given.empty()) {
      throw InvalidInput(fmt::format(
          "{} with --case {}: the case's sea is {}; its models and parameters are the case file's "
          "to change ([[spectrum]] tables)", given.front(), o.case_file,
          ocean.is_composite() ? fmt::format("composite ({} components)", ocean.more_components.size() + 1)
                               : "a table (model = \"" + ocean.spectrum.model + "\")"));
    }
  }
  // Models: --model replaces the spectrum; phillips carries its own directionality.
  if (o.has("--model")) {
    ocean.spectrum = ModelSpec{o.model, {}, {}};
    if (o.model == "phillips" && !o.has("--spreading")) ocean.spreading = ModelSpec{};
  }
  if (o.has("--spreading")) ocean.spreading = ModelSpec{o.spreading, {}, {}};
  // A 2-D table carries its own directions, as phillips does.
  const bool default_spreading = default_spreading_allowed && ocean.spectrum.model != "phillips" &&
                                 ocean.spreading.model.empty() &&
                                 !(ocean.table && ocean.table->is_directional());
  if (default_spreading) ocean.spreading.model = kDefaultSpreading;

  // Parameters go to whichever model takes them.
  auto route = [&](const std::string& name) -> ModelSpec& {
    if (takes(ocean.spectrum.model, name)) return ocean.spectrum;
    if (takes(ocean.spreading.model, name)) return ocean.spreading;
    if (ocean.spectrum.model == "phillips" && (name == "hs" || name == "tp")) {
      throw InvalidInput(fmt::format(
          "{} is not a parameter of spectrum 'phillips': Phillips is scaled by its amplitude A "
          "(--amplitude) and shaped by its wind speed (--wind-speed), not by a sea state; for a "
          "given Hs and Tp use --model jonswap or bretschneider",
          flag_of(name)));
    }
    throw InvalidInput(fmt::format(
        "{} is not a parameter of spectrum '{}' (takes {}){}", flag_of(name), ocean.spectrum.model,
        parameter_list(ocean.spectrum.model),
        ocean.spreading.model.empty()
            ? std::string(" and there is no spreading model")
            : fmt::format(" nor of spreading '{}' (takes {})", ocean.spreading.model,
                          parameter_list(ocean.spreading.model))));
  };
  for (const auto& [name, option] : o.number_options) {
    if (option->count()) route(name).numbers[name] = o.numbers.at(name);
  }
  for (const auto& [name, option] : o.choice_options) {
    if (option->count()) route(name).choices[name] = o.choices.at(name);
  }
  if (default_spreading && !ocean.spreading.numbers.count("s")) {
    ocean.spreading.numbers["s"] = kDefaultSpreadingS;
  }

  if (o.has("--depth")) ocean.depth = parse_depth(o.depth);
  if (o.has("--gravity")) ocean.gravity = o.gravity;
  if (o.has("--wind-dir")) ocean.wind_dir_deg = o.wind_dir;
  if (o.has("--seed")) ocean.seed = parse_seed(o.seed);
}


Action add_synth_command(CLI::App& app) {
  auto o = std::make_shared<SynthOptions>();
  const auto models = reference::frequency_model_names();
  const auto spreadings = reference::spreading_model_names();
  o->given["--case"] = app.add_option("--case", o->case_file,
                                      "case file (docs/case_files.md); flags override it");
  o->given["--model"] = app.add_option("--model", o->model, "spectrum model")
                            ->check(model_name_check(reference::ModelKind::spectrum));
  o->given["--spreading"] =
      app.add_option("--spreading", o->spreading,
                     "spreading model (default for non-phillips spectra: cos2s with s = 10)")
          ->check(model_name_check(reference::ModelKind::spreading));
  // One flag per parameter any spectrum or spreading model takes; each goes to the model that
  // takes it. gravity, depth and wind_dir are case-wide flags below.
  std::set<std::string> seen = {"gravity", "depth", "wind_dir"};
  std::vector<std::string> all = models;
  all.insert(all.end(), spreadings.begin(), spreadings.end());
  for (const auto& model : all) {
    for (const auto& info : reference::model_parameters(model)) {
      if (!seen.insert(info.name).second) continue;
      const bool is_choice = info.unit.find('|') != std::string::npos;
      const auto help = info.meaning + (info.unit.empty() ? "" : " [" + info.unit + "]");
      if (is_choice) {
        o->choice_options[info.name] = app.add_option(flag_of(info.name), o->choices[info.name], help);
      } else {
        o->number_options[info.name] = app.add_option(flag_of(info.name), o->numbers[info.name], help);
      }
    }
  }
  std::string names;
  for (const auto& name : impls::backend_names()) names += (names.empty() ? "" : ", ") + name;
  o->given["--impl"] = app.add_option("--impl", o->impl,
                                      "transform backend (" + names + "), or lattice[:fft=NAME] for "
                                      "rank-1 lattice synthesis through NAME's 1-D transforms "
                                      "(required, but for probes)");
  o->given["--points"] = app.add_option("--points", o->points,
                                        "--impl lattice: the number of lattice points N");
  o->given["--kind"] = app.add_option("--kind", o->kind,
                                      "--impl lattice: korobov (generator by the spectral test, "
                                      "any N; default) or fibonacci (N a Fibonacci number)")
                           ->check(CLI::IsMember({"korobov", "fibonacci"}));
  o->given["--n"] = app.add_option("--n", o->n, "samples along x (and y unless --ny)");
  o->given["--ny"] = app.add_option("--ny", o->ny, "samples along y");
  o->given["--length"] = app.add_option("--length", o->length, "patch size along x (and y unless --length-y) [m]");
  o->given["--length-y"] = app.add_option("--length-y", o->length_y, "patch size along y [m]");
  o->given["--seed"] = app.add_option("--seed", o->seed, "random seed, 0…2⁶⁴−1 (default 0)");
  o->given["--frames"] = app.add_option("--frames", o->frames, "number of frames (default 1)");
  o->given["--dt"] = app.add_option("--dt", o->dt, "time between frames [s]");
  o->given["--t0"] = app.add_option("--t0", o->t0, "time of frame 0 [s] (default 0)");
  o->given["--depth"] = app.add_option("--depth", o->depth, "water depth [m] or inf (default inf)");
  o->given["--gravity"] = app.add_option("--gravity", o->gravity, "gravity [m/s²] (default 9.81)");
  o->given["--wind-dir"] = app.add_option("--wind-dir", o->wind_dir,
                                          "direction the waves travel toward, counter-clockwise "
                                          "from +x [deg] (default 0)");
  o->given["--choppiness"] = app.add_option("--choppiness", o->choppiness,
                                            "λ: stored displacement is λD (default 1)");
  o->given["--loop-period"] = app.add_option("--loop-period", o->loop_period,
                                             "loop period [s]; 0 = none (default)");
  app.add_option("--precision", o->precision, "synthesis precision (default fp32)")
      ->check(CLI::IsMember({"fp32", "fp64"}));
  o->given["--format"] = app.add_option("--format", o->format, "frame files (default exr; npy for a lattice)")
      ->check(CLI::IsMember({"exr", "npy", "tiff", "png"}));
  app.add_option("--value-range", o->value_range,
                 "png: the values pixel 0 and pixel 65535 stand for, LO,HI [m]; a value outside "
                 "is an error, never clipped")
      ->delimiter(',');
  app.add_option("--fields", o->fields,
                 "the fields stored, e.g. h,dx,dy (field or channel names: height h, slope_x sx, "
                 "slope_y sy, disp_x dx, disp_y dy, jacobian J; default all six, or h,dx,dy for "
                 "png); height is required")
      ->delimiter(',');
  app.add_option("--sum", o->sum,
                 "cascade sets: write the summed surface under DIR/sum (auto: when the patch "
                 "lengths allow and its grid is at most 2048²; yes; no)")
      ->check(CLI::IsMember({"auto", "yes", "no"}));
  o->given["--sampling"] = app.add_option("--sampling", o->sampling,
                                          "probes: time series at points (docs/probes.md), with "
                                          "--positions, --dt, --samples and the scheme below")
                               ->check(CLI::IsMember({"grid", "probes"}));
  o->given["--positions"] = app.add_option("--positions", o->positions,
                                           "probes: x0,y0,x1,y1,… [m]")->delimiter(',');
  o->given["--samples"] = app.add_option("--samples", o->samples, "probes: samples per probe");
  o->given["--amplitudes"] = app.add_option("--amplitudes", o->amplitudes,
                                            "probes: rayleigh (default) or deterministic")
                                 ->check(CLI::IsMember({"rayleigh", "deterministic"}));
  o->given["--frequencies"] = app.add_option("--frequencies", o->frequencies,
                                             "probes: uniform (default; Δω = 2π/repeat period), "
                                             "equal_energy or random (--n-frequencies lines)")
                                  ->check(CLI::IsMember({"uniform", "equal_energy", "random"}));
  o->given["--repeat-period"] = app.add_option("--repeat-period", o->repeat_period,
                                               "probes: the repeat period of uniform lines [s]");
  o->given["--omega-cutoff"] = app.add_option("--omega-cutoff", o->omega_cutoff,
                                              "probes: LOW,HIGH, the band synthesized [rad/s]")
                                   ->delimiter(',');
  o->given["--directions"] = app.add_option("--directions", o->directions,
                                            "probes: long_crested (default), single_per_frequency "
                                            "or double_summation (--n-directions per frequency)")
                                 ->check(CLI::IsMember({"long_crested", "single_per_frequency",
                                                        "double_summation"}));
  o->given["--n-directions"] = app.add_option("--n-directions", o->n_directions,
                                              "probes: lines per frequency (double_summation)");
  o->given["--n-frequencies"] = app.add_option("--n-frequencies", o->n_frequencies,
                                               "probes: lines over the band (equal_energy, random)");
  app.add_option("--out", o->out, "output directory (created if missing)")->required();
  app.add_option("--json", o->json, "write JSON to FILE, or - for standard output");
  app.footer(
      "Without --case, --model, --n and --length are required. With --case, the case file gives "
      "everything and flags override it (--model replaces the spectrum and its parameters, "
      "--spreading the spreading model, a parameter flag sets one parameter). A spectrum other "
      "than phillips with no spreading model gets cos2s with s = 10. Writes DIR/frame_0000.exr "
      "(channels h sx sy dx dy J), or frame_0000_h.npy … (fp64 → float64 with --format npy), or "
      ".tif, or 16-bit .png with height, disp_x, disp_y as R, G, B (--value-range), and DIR/case.toml, whose [input] reads them back. "
      "With --impl lattice[:fft=NAME] --points N [--kind korobov|fibonacci]: N-vectors "
      "frame_0000_h.npy …, points.npy (N × 2, m), mesh.ply (frame 0, tileable) and a case.toml "
      "with [sampling] kind = \"lattice\". A cascade set ([cascades], docs/case_files.md) writes each "
      "cascade's frames under DIR/cascade0, DIR/cascade1, … and, where the patch lengths are integer "
      "ratios (--sum), the summed surface on the finest spacing over the largest patch under DIR/sum. "
      "JSON: {case, description, impl, precision, format, n, sampling, frames, files, seconds} "
      "(+ relation, cascades, sum for a set). Probes (--sampling probes, or a probes case file; "
      "no --impl): DIR/elevation.csv (time, then one column per probe, m) and DIR/case.toml, the "
      "sum of wave lines of the declared scheme (docs/probes.md).");
  return [o] { return run_synth(*o); };
}

}  // namespace swell::cli
