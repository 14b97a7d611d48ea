#pragma once
// JONSWAP fitted to a measured 1-D buoy spectrum (docs/buoy_fit.md): (Hs, Tp, γ) with σa, σb
// held, by maximum likelihood under the band estimates' own sampling law, with 95 %
// profile-likelihood intervals (as docs/fit.md §4) and a misfit measure that says when one
// JONSWAP cannot describe the hour.
//
// Model. The band value Ŝ_j (m²/Hz) is S̄_j · χ²_νj/νj (a band average of a periodogram whose raw
// ordinates are χ²₂ each; Bendat & Piersol, Random Data, §8.5.4), with S̄_j the band average of
// JONSWAP in Hz (exact normalization, m0 = Hs²/16) and νj proportional to the band's width
// (νj = dof · Δf_j / 0.01 Hz). So
//     −log L = Σ_j (νj/2)(log S̄_j + Ŝ_j/S̄_j)                 (values of 10 quanta and more)
//            − Σ_j log P(lo_j ≤ Ŝ_j < hi_j | S̄_j)             (smaller values, interval-censored)
// where a value printed as v stands for [v − q/2, v + q/2) with the printed quantum q
// (0.001 m²/Hz), and "0.000" for [0, q/2).
#include <string>
#include <vector>

#include "swell/validation/fit/buoy_spectrum.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"

namespace swell::validation {

struct BuoyFitOptions {
  // ν of a 0.01 Hz band; νj = dof · Δf_j / 0.01 Hz. 24: NDBC's WPM record is 2048 samples at
  // 1.7066 Hz (1200 s; NDBC Technical Document 96-01, Earle 1996, §3.3.7), so a band of Δf
  // merges Δf·1200 s raw FFT ordinates of 2 degrees of freedom each — 12, 24, 48 for the
  // 0.005, 0.01, 0.02 Hz bands (docs/buoy_fit.md §3 says what is confirmed and what not).
  double dof = 24;
  double quantum = 0.001;  // m²/Hz: the printed resolution of Ŝ
  double sigma_a = 0.07, sigma_b = 0.09;
  bool intervals = true;   // profile-likelihood intervals (false: Wald only, faster)
  // Quasi-likelihood intervals (McCullagh & Nelder 1989, §9.2; Wedderburn 1974): where the
  // deviance shows overdispersion (φ̂ = D/dof > 1), the profile's threshold 1.92 = χ²₁(0.95)/2
  // is multiplied by φ̂ and the standard errors by √φ̂; where φ̂ ≤ 1, nothing is scaled.
  // false: the plain likelihood's intervals (for the tests' comparison).
  bool quasi_likelihood = true;
};

// Why one JONSWAP may not describe the hour (docs/buoy_fit.md §5).
struct BuoyMisfit {
  // Deviance D = 2(ℓ_saturated − ℓ(θ̂)), each band's term divided by its expectation
  // 2a(log a − ψ(a)) under the model (a = ν/2; the Bartlett-type factor 1 + 1/(3ν) to first
  // order), against χ² with `deviance_dof` = (informative bands − 3) degrees of freedom. Graded
  // information, not the flag: on real spectra the χ² test rejects exact JONSWAP in every hour
  // (real seas carry shape detail beyond JONSWAP at ν = 24).
  double deviance = 0;
  int deviance_dof = 0;
  double deviance_p = 1;  // P(χ²_dof ≥ D)
  // The overdispersion φ̂ = D / deviance_dof: how many times the residuals' variance exceeds
  // the sampling law's (1 for data that follow it). The intervals are scaled by max(1, φ̂)
  // (quasi-likelihood; BuoyFit::dispersion).
  double dispersion = 1;
  // A second significant peak, by either of two rules (docs/buoy_fit.md §5):
  //  - against the fit: a run of bands outside the fitted peak's neighbourhood (f/f̂p outside
  //    [0.8, 1.25]) where the data exceed the model, holding ≥ 5 % of the measured m0, at ≥ 4
  //    standard deviations of the model's own scatter, with a local maximum of the measured
  //    spectrum (3-band running mean) inside it;
  //  - in the data alone: a second local maximum of the 3-band running mean, outside [0.8, 1.25]
  //    of the highest one's frequency, with a valley toward it at most half its height and 4
  //    standard deviations below it, holding ≥ 5 % of m0 beyond the valley.
  bool second_peak = false;
  double second_peak_frequency = 0;        // Hz, that local maximum (0 if none)
  double second_peak_energy_fraction = 0;  // its excess over the model / measured m0
  double second_peak_z = 0;                // excess / its standard deviation under the model
  // The energy test (a shape misfit gross enough to matter): the fitted spectrum's energy in
  // the likelihood's bands, m0_model = Σ S̄_j Δf_j, against the measured Σ Ŝ_j Δf_j there, in
  // standard deviations of the measured sum under the model with the overdispersion allowed,
  //     t = (m0_model − m0_measured) / √(max(1, φ̂) Σ (2 S̄_j²/νj + q²/12) Δf_j²),
  // referred to Student's t with deviance_dof degrees of freedom (φ̂ is estimated from them);
  // |t| beyond its two-sided 1 − kShapeAlpha quantile flags the hour: the fitted JONSWAP does
  // not hold the energy the buoy measured, whatever the spectrum's fine shape.
  double energy_model = 0, energy_measured = 0;  // m², over the likelihood's bands
  double energy_t = 0;
  double energy_t_limit = 0;                    // the two-sided quantile |t| is held to
  bool energy_misfit = false;
  bool flagged = false;                          // second_peak or energy_misfit
  std::string reason;                            // empty when not flagged
};

// The deviance's reference level, reported (deviance_p < it: the χ² test rejects exact
// JONSWAP), not the flag (docs/buoy_fit.md §5).
inline constexpr double kDevianceAlpha = 1e-3;
// The energy test's two-sided false-alarm level per hour.
inline constexpr double kShapeAlpha = 1e-3;

struct BuoyFit {
  Estimate hs, tp, gamma;  // m, s, 1; standard errors from the observed information
  // The scale applied to the intervals: max(1, φ̂) with quasi_likelihood, else 1 (the profile's
  // threshold is 1.92·dispersion, the standard errors √dispersion times the likelihood's).
  double dispersion = 1;
  BuoyMisfit misfit;
  int bands_used = 0;      // bands with a value (not "MM")
  // The likelihood reads the bands from window_low = half the measured peak frequency up (below
  // it JONSWAP has no energy to speak of: docs/buoy_fit.md §2); the second-peak check reads all.
  double window_low = 0;   // Hz
  int bands_below_window = 0;
  int censored_bands = 0;  // in the window, values under 10 quanta (interval-censored)
  double negative_log_likelihood = 0;
  int iterations = 0;
  bool converged = false;
  std::string report;
};

// νj for each band.
std::vector<double> band_degrees_of_freedom(const SpectralBands& bands, double dof);

// The band averages S̄_j (m²/Hz) of JONSWAP in Hz (S(f) = 2π S(ω = 2πf), exact normalization)
// over each band [f_j − Δf_j/2, f_j + Δf_j/2], by 8-point Gauss–Legendre quadrature per band.
std::vector<double> jonswap_band_averages(const JonswapParameters& parameters,
                                          const SpectralBands& bands);

// Fits one spectrum (density: m²/Hz per band, NaN for missing bands, as read). Throws
// InvalidInput for a spectrum with no energy, negative values, or fewer than 6 valid bands.
BuoyFit fit_buoy_spectrum(const std::vector<double>& density, const SpectralBands& bands,
                          const BuoyFitOptions& options = {});

// The band with the largest value: the spectrum's own peak; Tp = 1/f of its centre.
double peak_band_period(const std::vector<double>& density, const SpectralBands& bands);

}  // namespace swell::validation
