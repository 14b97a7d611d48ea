#pragma once
// The seas of the gate's tests: the catalogue's (gate_catalogue_test.cpp), shared with the golden
// reports (gate_golden_test.cpp), which judge the same engines, and the small sea of the gate's
// own tests (gate_test.cpp, streamed_gate_test.cpp).
#include "swell/reference/ocean_case.hpp"
#include "swell/validation/io/case_file.hpp"

namespace swell::test {

// The gate tests' small sea: JONSWAP (Hs 3 m, Tp 8 s, γ 3.3), cos2s s = 10 from 30°, λ 0.8,
// 64² over 400 m, dt 0.5 s, seed 2026.
inline reference::OceanCase small_gate_case(int frames = 8) {
  reference::OceanCase c;
  c.grid = reference::Grid::create(64, 64, 400, 400);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
  c.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.wind_dir_deg = 30;
  c.choppiness = 0.8;
  c.dt = 0.5;
  c.frames = frames;
  c.seed = 2026;
  return c;
}

// The catalogue's sea: JONSWAP (Hs 3 m, Tp 8 s, γ 3.3) with cos-2s s = 4 toward 30°, deep
// water, 128² over 800 m (the peak at 8 Δk), 8 frames 0.5 s apart, λ = 0.8. s = 4 rather
// than 10 because an unnormalized cos-2s multiplies the energy by 1/G(s): 1.72 at s = 4, which
// one realization resolves, but only 1.11 at s = 10, which it cannot at α = 10⁻³.
inline reference::OceanCase catalogue_case() {
  reference::OceanCase c;
  c.grid = reference::Grid::create(128, 128, 800, 800);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
  c.spreading = {"cos2s", {{"s", 4.0}}, {}};
  c.wind_dir_deg = 30;
  c.choppiness = 0.8;
  c.dt = 0.5;
  c.frames = 8;
  c.seed = 7;
  return c;
}

// The same sea over 10 m of water (TMA), for the bug that ignores depth.
inline reference::OceanCase shallow_case() {
  reference::OceanCase c = catalogue_case();
  c.spectrum.model = "tma";
  c.spectrum.numbers["hs"] = 1.5;
  c.depth = 10;
  return c;
}

inline validation::CaseFile as_case_file(const reference::OceanCase& c) {
  validation::CaseFile file;
  file.ocean = c;
  return file;
}

}  // namespace swell::test
