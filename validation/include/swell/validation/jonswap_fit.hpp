#pragma once
// Estimates JONSWAP parameters from sampled surfaces by maximum Whittle likelihood (Whittle
// 1953; for a periodogram of a Gaussian field, I(k) ~ μ(k; θ)·Exp(1) independently over a half
// plane, so −log L = Σ log μ + I/μ is exact, not an approximation), minimized with Ceres, and
// reports each estimate with a 95 % interval from the expected Fisher information
// F_ij = Σ (∂μ/∂θi)(∂μ/∂θj)/μ².
//
// Model: μ(k; θ) = ½ (Ψ(k) + Ψ(−k)) Δk² with Ψ from JONSWAP S(ω; Hs, Tp, γ[, σa, σb]) (exact
// normalization, m0 = Hs²/16) and the case's spreading, dispersion and depth (TMA: the
// Kitaigorodskii factor of the case's depth), which are held fixed.
#include <optional>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"

namespace swell::validation {

struct Estimate {
  double value = 0;
  double standard_error = 0;
  double ci95_low = 0, ci95_high = 0;
};

struct JonswapFitOptions {
  bool fit_sigma = false;  // also estimate σa and σb
  int frame = 0;           // which frame of each realization to use
};

struct JonswapFit {
  Estimate hs, tp, gamma;              // m, s, 1
  std::optional<Estimate> sigma_a, sigma_b;
  int wave_vectors = 0;                // independent periodogram ordinates used
  int realizations = 0;
  double negative_log_likelihood = 0;
  int iterations = 0;
  bool converged = false;
  std::string report;                  // Ceres' brief report
};

// `realizations`: independent surfaces of the same case (different seeds); each contributes one
// frame. Throws InvalidInput when the case's spectrum is not jonswap/tma-compatible or the
// frames lack a height field.
JonswapFit fit_jonswap(const reference::OceanCase& ocean_case,
                       const std::vector<reference::FrameSequence>& realizations,
                       const JonswapFitOptions& options = {});

}  // namespace swell::validation
