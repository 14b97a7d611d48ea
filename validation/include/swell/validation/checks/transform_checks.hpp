#pragma once
// Transform accuracy against a long-double oracle (docs/transforms.md): a backend's
// output for random input, compared with the same transform computed in long double.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "swell/impls/transform.hpp"

namespace swell::validation {

struct TransformAccuracy {
  std::string impl;
  impls::TransformSpec spec;
  std::string oracle;     // "naive fp80" or "fftw fp80"
  double rel_l2 = 0;      // ‖y − y_ref‖₂ / ‖y_ref‖₂
  double rel_linf = 0;    // max|y − y_ref| / max|y_ref|
  double bound = 0;       // transform_error_bound(spec)
  bool pass = false;
};

// c · ε · max(1, log2(nx·ny)) with c = 4. Higham (2002), "Accuracy and Stability of Numerical
// Algorithms", Thm 24.2: radix-2 Cooley–Tukey in floating point with unit roundoff u = ε/2 and
// twiddles accurate to μ satisfies ‖ŷ − y‖₂/‖y‖₂ ≤ log2 N · η / (1 − log2 N · η),
// η = μ + γ4 (√2 + μ) ≈ u + 4√2 u ≈ 3.3 ε; c = 4 rounds that up. The same bound is applied to
// the relative L∞ error, which for random input is of the same size as the L2 one (the output
// is then statistically flat: max|y| is a few times its rms, as is max|error|).
double transform_error_bound(const impls::TransformSpec& spec);

// The oracle: naive in long double while O(N²) is cheap, FFTW's long double build beyond.
// `input` holds spec.input_elements()·howmany values (complex as re, im pairs).
std::vector<long double> oracle_transform(impls::TransformSpec spec,
                                          const std::vector<long double>& input,
                                          std::string* oracle_name = nullptr);

// Runs `backend` on seeded random input (uniform in [−1, 1); for c2r the half spectrum of a
// random real field) and compares with the oracle.
TransformAccuracy measure_transform_accuracy(const impls::Backend& backend,
                                             impls::TransformSpec spec, std::uint64_t seed = 1);

// The matrix `swell check transforms` runs for one backend: every precision it offers but
// fp80, c2c forward and inverse, r2c, c2r, over square sizes 16…1024 (naive: to 256, the
// oracle beyond) and an odd size where allowed, plus c2c inverse at 2048² (not naive).
std::vector<TransformAccuracy> run_transform_checks(const std::string& backend_name);

std::string render_transform_table(const std::vector<TransformAccuracy>& results);
// {"transforms": [{"impl", "precision", "kind", "n": [nx, ny], "rel_l2", "rel_linf", "bound",
//  "pass"}]}
nlohmann::json transforms_to_json(const std::vector<TransformAccuracy>& results);

}  // namespace swell::validation
