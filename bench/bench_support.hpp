#pragma once
// What the benchmark suites share: the backends to run and the sea they synthesize.
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "swell/reference/ocean_case.hpp"

namespace swell::bench {

// SWELL_BENCH_IMPLS (comma separated, backend options allowed: "fftw:threads=2") when set,
// else `fallback`.
inline std::vector<std::string> backends_from_environment(std::vector<std::string> fallback) {
  const char* chosen = std::getenv("SWELL_BENCH_IMPLS");
  if (!chosen || !*chosen) return fallback;
  std::vector<std::string> names;
  std::stringstream list(chosen);
  for (std::string name; std::getline(list, name, ',');) names.push_back(name);
  return names;
}

// JONSWAP (Hs 3 m, Tp 8 s, γ 3.3) with cos-2s s = 10 toward 30°, n² over 1000 m, λ = 0.8.
inline reference::OceanCase jonswap_bench_case(int n, int frames, double dt) {
  reference::OceanCase c;
  c.grid = reference::Grid::create(n, n, 1000.0, 1000.0);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
  c.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.wind_dir_deg = 30;
  c.choppiness = 0.8;
  c.dt = dt;
  c.frames = frames;
  c.seed = 2024;
  return c;
}

}  // namespace swell::bench
