// swell synth for probes (docs/probes.md): the elevation series at points, as offshore engines
// synthesize them — a sum of wave lines of the declared frequency, amplitude and direction
// scheme (reference/probe_sea.hpp) — written to DIR/elevation.csv (a time column, then one
// column per probe, m, in shortest round-trip form) with DIR/case.toml reading them back.
//
//   swell synth --case PROBES.toml --out DIR
//   swell synth --sampling probes --model M [params] --positions X0,Y0,… --dt DT --samples N
//               [--t0 T] [--amplitudes rayleigh|deterministic] [--frequencies uniform|
//               equal_energy|random] [--repeat-period T] [--omega-cutoff LO,HI]
//               [--directions long_crested|single_per_frequency|double_summation]
//               [--n-directions N] [--n-frequencies N] --out DIR
//
// Without a case file: uniform frequencies repeat after the record (repeat_period = samples ×
// dt) and the band is [0, π/dt] unless given. A grid case with --sampling probes lends its sea.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <thread>

#include "commands.hpp"
#include "swell/impls/probe_synthesis.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/probe_series.hpp"
#include "synth_options.hpp"

namespace swell::cli {
namespace {

namespace fs = std::filesystem;

// The probes case the options describe.
validation::CaseFile build_probe_case(const SynthOptions& o) {
  for (const char* flag : {"--impl", "--n", "--ny", "--length", "--length-y", "--frames", "--points", "--kind",
                           "--choppiness", "--loop-period", "--format"}) {
    if (o.has(flag)) {
      throw InvalidInput(fmt::format("{} belongs to frames on a grid or lattice; a probes case writes "
                                     "series at points (--positions, --dt, --samples)",
                                     flag));
    }
  }
  validation::CaseFile c;
  if (!o.case_file.empty()) c = validation::read_case_file(o.case_file);
  if (c.is_cascade_set()) {
    throw InvalidInput(fmt::format("{} is a cascade set; probes sample one sea at points", o.case_file));
  }
  const bool from_probe_file = c.is_probe_case();
  if (!from_probe_file) {
    c.probes.emplace();
    c.ocean.frames = 1;
    c.ocean.lattice = nullptr;
    for (const auto& [flag, what] : {std::pair{"--positions", "x0,y0,x1,y1,… in m"},
                                     std::pair{"--dt", "the sampling interval in s"},
                                     std::pair{"--samples", "the samples per probe"}}) {
      if (!o.has(flag)) {
        throw InvalidInput(fmt::format("{} ({}) is required for --sampling probes without a probes case", flag,
                                       what));
      }
    }
    if (o.case_file.empty() && !o.has("--model")) {
      throw InvalidInput("--model (a spectrum model) is required without --case");
    }
  }
  auto& layout = c.probes->layout;
  auto& scheme = c.probes->synthesis;
  if (o.has("--directions")) scheme.directions = reference::probe_directions_from_string(o.directions);
  // A long-crested sea needs no spreading model; any other draws its directions from one.
  apply_sea_flags(o, c.ocean, scheme.directions != reference::ProbeDirections::long_crested);
  if (o.has("--positions")) {
    if (o.positions.empty() || o.positions.size() % 2 != 0) {
      throw InvalidInput(fmt::format("--positions takes pairs x,y in m (got {} numbers)", o.positions.size()));
    }
    layout.positions.clear();
    for (std::size_t i = 0; i < o.positions.size(); i += 2) {
      layout.positions.push_back({o.positions[i], o.positions[i + 1]});
    }
  }
  if (o.has("--dt")) layout.dt = o.dt;
  if (o.has("--t0")) layout.t0 = o.t0;
  if (o.has("--samples")) {
    if (o.samples < 2) throw InvalidInput(fmt::format("--samples must be ≥ 2 (got {})", o.samples));
    layout.samples = std::size_t(o.samples);
  }
  c.ocean.t0 = layout.t0;
  c.ocean.dt = layout.dt;
  if (o.has("--amplitudes")) scheme.amplitudes = reference::probe_amplitudes_from_string(o.amplitudes);
  if (o.has("--frequencies")) scheme.frequencies = reference::probe_frequencies_from_string(o.frequencies);
  if (o.has("--repeat-period")) scheme.repeat_period = o.repeat_period;
  if (o.has("--n-directions")) scheme.n_directions = o.n_directions;
  if (o.has("--n-frequencies")) scheme.n_frequencies = o.n_frequencies;
  if (o.has("--omega-cutoff")) {
    if (o.omega_cutoff.size() != 2) {
      throw InvalidInput(fmt::format("--omega-cutoff takes LOW,HIGH in rad/s (got {} numbers)", o.omega_cutoff.size()));
    }
    scheme.omega_low = o.omega_cutoff[0];
    scheme.omega_high = o.omega_cutoff[1];
  }
  if (!from_probe_file) {
    if (!o.has("--omega-cutoff") && layout.dt > 0) scheme.omega_high = std::numbers::pi / layout.dt;
    if (!o.has("--repeat-period") && scheme.frequencies == reference::ProbeFrequencies::uniform) {
      scheme.repeat_period = layout.duration();
    }
  }
  c.probe_case().validate();
  return c;
}

double rms(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / double(values.size()));
}

}  // namespace

bool wants_probes(const SynthOptions& o) {
  if (o.has("--sampling")) return o.sampling == "probes";
  if (o.case_file.empty()) return false;
  return validation::read_case_file(o.case_file).is_probe_case();
}

int run_probe_synth(const SynthOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  validation::CaseFile c = build_probe_case(o);
  const auto probe_case = c.probe_case();
  const bool quiet = o.json == "-";
  const fs::path out(o.out);
  if (!quiet) fmt::print("swell synth: {}; {} in {}\n", probe_case.describe(), to_string(probe_case.synthesis.frequencies), out.string());
  const auto lines = reference::probe_wave_lines(probe_case, c.ocean.seed);
  const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  const auto series = impls::synthesize_probe_series(probe_case, lines, threads);

  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw InvalidInput(fmt::format("--out {}: cannot create the directory ({})", out.string(), error.message()));
  std::vector<std::string> names;
  for (std::size_t p = 0; p < series.size(); ++p) names.push_back(fmt::format("probe{}", p));
  validation::write_probe_series_csv(out / "elevation.csv", probe_case.layout, series, names);
  c.probes->input = {"elevation.csv", "time", names};
  validation::write_case_file(out / "case.toml", c);

  const double band_m0 = reference::spectral_moment(probe_case.spectrum()->omnidirectional(), 0,
                                                    reference::Band{probe_case.synthesis.omega_low,
                                                                    probe_case.synthesis.omega_high});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json probes = nlohmann::json::array();
  for (std::size_t p = 0; p < series.size(); ++p) {
    const double r = rms(series[p]);
    probes.push_back({{"name", names[p]}, {"x", probe_case.layout.positions[p][0]},
                      {"y", probe_case.layout.positions[p][1]}, {"rms", r}, {"hs_4sigma", 4 * r}});
    if (!quiet) {
      fmt::print("{}  at ({:g}, {:g}) m  rms η = {:.4g} m (4σ = {:.4g} m)\n", names[p],
                 probe_case.layout.positions[p][0], probe_case.layout.positions[p][1], r, 4 * r);
    }
  }
  if (!quiet) {
    fmt::print("{} lines ({}, {} amplitudes); the band's Hs = 4√m0 = {:.4g} m; wrote {} and {} in {:.3g} s\n",
               lines.size(), to_string(probe_case.synthesis.directions), to_string(probe_case.synthesis.amplitudes),
               4 * std::sqrt(band_m0), (out / "elevation.csv").string(), (out / "case.toml").string(), seconds);
  }
  if (!o.json.empty()) {
    write_json(o.json, {{"case", (out / "case.toml").string()},
                        {"description", probe_case.describe()},
                        {"sampling", "probes"},
                        {"samples", probe_case.layout.samples},
                        {"dt", probe_case.layout.dt},
                        {"lines", lines.size()},
                        {"band_hs", 4 * std::sqrt(band_m0)},
                        {"probes", probes},
                        {"files", {(out / "elevation.csv").string()}},
                        {"seconds", seconds}});
  }
  return 0;
}

}  // namespace swell::cli
