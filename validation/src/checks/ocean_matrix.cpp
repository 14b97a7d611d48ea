#include "swell/validation/checks/ocean_matrix.hpp"

#include <memory>

#include "swell/reference/lattice.hpp"

#include <fmt/format.h>

#include <chrono>
#include <map>

#include "swell/impls/synthesizer.hpp"
#include "swell/validation/results/report.hpp"

namespace swell::validation {
namespace {

reference::OceanCase base_case(int n, double length) {
  reference::OceanCase c;
  c.grid = reference::Grid::create(n, n, length, length);
  c.wind_dir_deg = 30;
  c.choppiness = 0.8;
  c.dt = 0.5;
  c.frames = 8;
  c.seed = 2026;
  return c;
}

std::string category(const std::string& check) { return check.substr(0, check.find('.')); }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::vector<BuiltinOceanCase> builtin_ocean_cases(int n) {
  std::vector<BuiltinOceanCase> cases;
  {
    auto c = base_case(n, 400);  // λp ≈ 100 m: 4 peak wavelengths across, ω up to ≈ 3 ωp at 64²
    c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
    c.spreading = {"cos2s", {{"s", 10.0}}, {}};
    cases.push_back({"jonswap_deep", c});
  }
  {
    auto c = base_case(n, 300);
    c.spectrum = {"tma", {{"hs", 1.5}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
    c.spreading = {"cos2s", {{"s", 10.0}}, {}};
    c.depth = 10;
    cases.push_back({"tma_10m", c});
  }
  {
    auto c = base_case(n, 200);
    c.spectrum = {"phillips",
                  {{"amplitude", 3e-4}, {"wind_speed", 12.0}, {"small_wave_cutoff", 0.5}},
                  {}};
    cases.push_back({"phillips", c});
  }
  {
    auto c = base_case(n, 400);
    c.spectrum = {"pierson-moskowitz", {{"u19_5", 15.0}}, {}};
    c.spreading = {"cos2s", {{"s", 4.0}}, {}};
    cases.push_back({"pierson_moskowitz_cos2s", c});
  }
  return cases;
}

bool OceanMatrixRow::passed() const { return all_passed(report.results); }

std::vector<OceanMatrixRow> run_ocean_matrix(const std::string& backend,
                                             const OceanCheckOptions& options, int n) {
  std::vector<OceanMatrixRow> rows;
  for (const auto& builtin : builtin_ocean_cases(n)) {
    for (auto precision : {impls::Precision::f32, impls::Precision::f64}) {
      OceanMatrixRow row;
      row.case_name = builtin.name;
      row.backend = backend;
      row.precision = precision;
      auto start = std::chrono::steady_clock::now();
      const auto frames = impls::Synthesizer(builtin.ocean_case, {backend, precision}).frames();
      row.synthesis_seconds = seconds_since(start);
      start = std::chrono::steady_clock::now();
      OceanCheckOptions own = options;
      own.analysis_backend = backend;
      row.report = run_ocean_checks(builtin.ocean_case, frames, own);
      row.check_seconds = seconds_since(start);
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

std::vector<OceanMatrixRow> run_lattice_ocean_matrix(const std::string& fft_backend,
                                                     const OceanCheckOptions& options, int n) {
  const std::int64_t points = std::int64_t(n) * n;
  // The Fibonacci number nearest n².
  int j = 3;
  while (reference::fibonacci_number(j + 1) <= points) ++j;
  if (points - reference::fibonacci_number(j) > reference::fibonacci_number(j + 1) - points) ++j;
  const bool any_size = impls::make_backend(fft_backend)->capabilities().any_size;
  std::vector<OceanMatrixRow> rows;
  for (const auto& builtin : builtin_ocean_cases(n)) {
    const std::vector<double> lengths = {builtin.ocean_case.grid.lx, builtin.ocean_case.grid.ly};
    std::vector<std::shared_ptr<const reference::RankOneLattice>> lattices = {
        std::make_shared<const reference::RankOneLattice>(reference::korobov_lattice(points, lengths))};
    // A Fibonacci N is no power of two: only for backends of any size (radix2 and vulkan
    // run the Korobov rows alone).
    if (any_size) {
      lattices.push_back(std::make_shared<const reference::RankOneLattice>(
          reference::fibonacci_lattice(j, lengths[0], lengths[1])));
    }
    for (const auto& lattice : lattices) {
      reference::OceanCase ocean_case = builtin.ocean_case;
      ocean_case.set_lattice(lattice);
      for (auto precision : {impls::Precision::f32, impls::Precision::f64}) {
        OceanMatrixRow row;
        row.case_name = builtin.name + " @ " + lattice->describe();
        row.backend = "lattice:fft=" + fft_backend;
        row.precision = precision;
        auto start = std::chrono::steady_clock::now();
        const auto frames = impls::Synthesizer(ocean_case, {fft_backend, precision}).frames();
        row.synthesis_seconds = seconds_since(start);
        start = std::chrono::steady_clock::now();
        OceanCheckOptions own = options;
        own.analysis_backend = fft_backend;
        row.report = run_ocean_checks(ocean_case, frames, own);
        row.check_seconds = seconds_since(start);
        rows.push_back(std::move(row));
      }
    }
  }
  return rows;
}

std::string render_ocean_matrix(const std::vector<OceanMatrixRow>& rows) {
  const auto checks = ocean_check_names();
  std::size_t case_width = 26, backend_width = 8;
  for (const auto& row : rows) {
    case_width = std::max(case_width, row.case_name.size());
    backend_width = std::max(backend_width, row.backend.size());
  }
  std::string out = fmt::format("{:<{}} {:<{}} {:<5}", "case", case_width, "backend", backend_width, "prec");
  for (const auto& check : checks) out += fmt::format(" {:>10}", check);
  out += "\n";
  std::string failures;
  for (const auto& row : rows) {
    std::map<std::string, std::string> status;
    for (const auto& r : row.report.results) {
      auto& s = status[category(r.check)];
      if (!r.passed) s = "FAIL"; else if (s.empty()) s = "pass";
      if (!r.passed) {
        failures += fmt::format("  {} {} {}: {}: {}\n", row.case_name, row.backend,
                                impls::to_string(row.precision), r.check, r.reason);
      }
    }
    out += fmt::format("{:<{}} {:<{}} {:<5}", row.case_name, case_width, row.backend, backend_width,
                       impls::to_string(row.precision));
    for (const auto& check : checks) {
      out += fmt::format(" {:>10}", status.count(check) ? status[check] : "–");
    }
    out += "\n";
  }
  if (!failures.empty()) out += "failed:\n" + failures;
  return out;
}

nlohmann::json ocean_matrix_to_json(const std::vector<OceanMatrixRow>& rows) {
  auto array = nlohmann::json::array();
  for (const auto& row : rows) {
    auto entry = to_json(row.report.results);
    entry["case"] = row.case_name;
    entry["backend"] = row.backend;
    entry["precision"] = impls::to_string(row.precision);
    auto skipped = nlohmann::json::array();
    for (const auto& s : row.report.skipped) skipped.push_back(s.text());
    entry["skipped"] = skipped;
    entry["synthesis_seconds"] = row.synthesis_seconds;
    entry["check_seconds"] = row.check_seconds;
    entry["pass"] = row.passed();
    array.push_back(entry);
  }
  return array;
}

}  // namespace swell::validation
