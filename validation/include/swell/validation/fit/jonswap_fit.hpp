#pragma once
// Estimates JONSWAP parameters from sampled surfaces by maximum Whittle likelihood (Whittle
// 1953; for a periodogram of a Gaussian field, I(k) ~ μ(k; θ)·Exp(1) independently over a half
// plane, so −log L = Σ log μ + I/μ is exact, not an approximation), minimized with Ceres, and
// reports each estimate with a standard error from the expected Fisher information
// F_ij = Σ (∂μ/∂θi)(∂μ/∂θj)/μ² and a 95 % profile-likelihood interval (or, on request, the Wald
// interval), each marked calibrated or not by the resolution rule of docs/fit.md §4.
//
// Model: μ(k; θ) = ½ (Ψ(k) + Ψ(−k)) Δk² with Ψ from JONSWAP S(ω; Hs, Tp, γ[, σa, σb]) (exact
// normalization, m0 = Hs²/16) and the case's spreading, dispersion and depth (TMA: the
// Kitaigorodskii factor of the case's depth), which are held fixed.
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"

namespace swell::validation {

struct Estimate {
  double value = 0;
  double standard_error = 0;       // √(F⁻¹)_ii, expected Fisher information at the estimate
  double ci95_low = 0, ci95_high = 0;
  std::string method;              // "profile-likelihood" or "wald": how ci95 was computed
  // false: the interval is not one swell can vouch for at 95 % (reason says why: the peak is
  // resolved by too few wave vectors, or the profile does not close inside the model's valid
  // region). ci95 then still holds what the method gave, for diagnosis only.
  bool calibrated = true;
  std::string reason;
  // The effective number of independent ordinates behind this parameter: (Σ g²)²/Σ g⁴ over
  // ordinates × realizations, g the efficient score direction ∂ log μ/∂θi with the other
  // parameters projected out (docs/fit.md §4). A diagnostic: measured, it does not tell the
  // grids where intervals fail from those where they hold, so the rule does not use it.
  double effective_ordinates = 0;
};

enum class IntervalMethod { profile_likelihood, wald };

struct JonswapFitOptions {
  bool fit_sigma = false;  // also estimate σa and σb
  int frame = 0;           // which frame of each realization to use
  IntervalMethod interval = IntervalMethod::profile_likelihood;
};

// "profile-likelihood" / "wald".
const char* interval_method_name(IntervalMethod method);

struct JonswapFit {
  Estimate hs, tp, gamma;              // m, s, 1
  std::optional<Estimate> sigma_a, sigma_b;
  int wave_vectors = 0;                // independent periodogram ordinates used
  std::vector<std::size_t> wave_vector_index;  // which: indices into the nx·ny grid, FFT order
  // How well the grid resolves the spectral peak. peak_wavelengths: the patch's longer side
  // over the case's peak wavelength λp = 2π/k(2π/Tp); below 2 no interval is called calibrated
  // (the resolution rule, measured: docs/fit.md §4). peak_wave_vectors: independent ordinates
  // (wave vectors of the half plane × realizations) whose fitted mean μ(k; θ̂) is at least half
  // the largest, the peak's half-power band in k (diagnostic).
  double peak_wavelengths = 0;
  int peak_wave_vectors = 0;
  int realizations = 0;
  double negative_log_likelihood = 0;
  int iterations = 0;
  bool converged = false;
  std::string report;                  // Ceres' brief report
};

// `realizations`: independent surfaces of the same case (different seeds); each contributes one
// frame. The optimizer stays inside the model's valid region (Hs, Tp, σ > 0, γ ≥ 1; docs/fit.md
// §3). Throws InvalidInput when the case's spectrum is not jonswap/tma-compatible or the
// frames lack a height field. docs/fit.md has the model, the likelihood and the intervals.
JonswapFit fit_jonswap(const reference::OceanCase& ocean_case,
                       const std::vector<reference::FrameSequence>& realizations,
                       const JonswapFitOptions& options = {});

// The same fit from periodograms I(k) = |ĥ(k)|², one per realization, each nx·ny values in FFT
// order (only the half plane of energy-carrying k is read). `unit_roundoff` of the numbers the
// periodograms were computed from sets the rounding-noise floor below which ordinates are not
// used (0: no floor). fit_jonswap computes I from the frames and calls this.
JonswapFit fit_jonswap_periodograms(const reference::OceanCase& ocean_case,
                                    const std::vector<std::vector<double>>& periodograms,
                                    const JonswapFitOptions& options = {},
                                    double unit_roundoff = 0);

// A point of the fitted family: JONSWAP with exact normalization (m0 = Hs²/16).
struct JonswapParameters {
  double hs = 0, tp = 0;  // m, s
  double gamma = 3.3, sigma_a = 0.07, sigma_b = 0.09;
};

// The family's parameters of a case's spectrum (jonswap in any form, tma's JONSWAP part,
// bretschneider and pierson-moskowitz as γ = 1): hs = 4√m0 of that JONSWAP spectrum (for a
// DNV-normalized case, its actual m0), tp = 2π/ωp. Throws InvalidInput for other spectra.
JonswapParameters case_jonswap_parameters(const reference::OceanCase& ocean_case);

// The fit's model μ(k; θ) = ½ (Ψ(k) + Ψ(−k)) Δkx Δky over the case's grid in FFT order (0 where
// no energy): the case's spreading, dispersion and TMA depth factor with the JONSWAP part at θ.
std::vector<double> jonswap_model_periodogram(const reference::OceanCase& ocean_case,
                                              const JonswapParameters& parameters);

// {"value", "ci95", "se", "method", "calibrated", "effective_ordinates"}: an uncalibrated
// interval is not given as "ci95" (null there), so that no reader takes it for a 95 % interval;
// what the method gave is under "ci95_uncalibrated", with the reason.
nlohmann::json estimate_json(const Estimate& estimate);

// The fit as `swell fit --json` writes it (and swell.fit returns it): {"fit": {name: estimate_json},
// "converged", "wave_vectors", "realizations", "interval", "peak_wavelengths", "peak_wave_vectors",
// "truth": {name: the case's value}, "negative_log_likelihood", "iterations"}. The truth is left
// out where it does not mean the same as the estimate: Hs of a free-scale case (`free_scale`).
nlohmann::json jonswap_fit_json(const JonswapFit& fit, const JonswapParameters& truth, bool free_scale,
                                IntervalMethod interval);

}  // namespace swell::validation
