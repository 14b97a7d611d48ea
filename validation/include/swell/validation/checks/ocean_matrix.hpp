#pragma once
// The self-validation matrix of `swell check ocean`: every exact transform backend, in fp32 and
// fp64, synthesizes each built-in case and every ocean check judges the frames, the Parseval
// check through the same backend.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "swell/impls/transform.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/validation/checks/ocean_checks.hpp"

namespace swell::validation {

struct BuiltinOceanCase {
  std::string name;
  reference::OceanCase ocean_case;
};

// JONSWAP γ = 3.3 in deep water with cos-2s (s = 10); TMA at 10 m depth; Phillips
// (Tessendorf); Pierson–Moskowitz (U19.5 = 15 m/s) with cos-2s (s = 4). n × n samples,
// 8 frames 0.5 s apart, wind toward 30°, λ = 0.8, seed 2026.
std::vector<BuiltinOceanCase> builtin_ocean_cases(int n = 128);

struct OceanMatrixRow {
  std::string case_name, backend;
  impls::Precision precision = impls::Precision::f32;
  OceanCheckReport report;
  double synthesis_seconds = 0, check_seconds = 0;
  bool passed() const;
};

// Every built-in case × {fp32, fp64} through `backend`; `progress` is told each row's name.
std::vector<OceanMatrixRow> run_ocean_matrix(const std::string& backend,
                                             const OceanCheckOptions& options = {},
                                             int n = 128);

// The lattice rows (docs/conventions.md §2.1): every built-in case on a Korobov
// lattice of n² points (generator by the spectral test) and on the Fibonacci lattice F_j nearest
// n² points (only for backends of any size: radix2 and vulkan take powers of two), over the
// case's patch, × {fp32, fp64}, synthesized by rank-1 lattice synthesis
// through `fft_backend`'s 1-D transforms; the rows' backend reads "lattice:fft=NAME" and their
// case names the lattice ("jonswap_deep @ korobov N=16384 g=(1,…)").
std::vector<OceanMatrixRow> run_lattice_ocean_matrix(const std::string& fft_backend,
                                                     const OceanCheckOptions& options = {},
                                                     int n = 128);
// Rows (case, backend, precision) × columns (the checks): "pass", "FAIL" or "–" (skipped);
// then one line per failed result with its reason.
std::string render_ocean_matrix(const std::vector<OceanMatrixRow>& rows);
nlohmann::json ocean_matrix_to_json(const std::vector<OceanMatrixRow>& rows);

}  // namespace swell::validation
