#pragma once
// series.skewness and series.kurtosis of a probes case (docs/probes.md §3): each probe's sample
// skewness g1 = m3/m2^(3/2) and excess kurtosis g2 = m4/m2² − 3 against their law under the
// declared linear model, simulated.
//
// A linear sea's elevation at a point is a sum of lines, so both are near 0, but how near
// depends on the spectrum and the scheme: a narrow band has few effective degrees of freedom
// (for a Gaussian process Var g1 ≈ (6/N) Σ_τ ρ(τ)³ and Var g2 ≈ (24/N) Σ_τ ρ(τ)⁴, Lomnicki
// 1961, with ρ the autocorrelation — far above the white-noise 6/N and 24/N), and deterministic
// amplitudes (a random-phase sum, not a Gaussian process) put the mean of g2 below 0. The law
// is therefore simulated: R replicas of the case's model at one point (a linear homogeneous sea
// has one one-point law everywhere), with the case's samples, dt, band and scheme.
//
// Each frequency's lines meet at a point as one complex amplitude B_i = Σ_j a_ij e^(iφ_ij):
// Rayleigh amplitudes make it √(S Δω)(ξ1 + i ξ2) whatever the directions; deterministic ones
// √(2 S Δω/n) Σ_j e^(iψ_j) over the frequency's n directions (n = 1 unless double_summation).
// The replicas draw B_i directly from fixed keys (Philox normals for Rayleigh; phases on a
// 2¹²-point lattice of the circle, SplitMix64, for deterministic amplitudes), so the same series
// get the same verdict on every run, and sum the lines by one FFT of length M = repeat_period/dt,
// two replicas per complex transform (as η1 + iη2). Only uniform frequencies whose repeat period
// is a whole number of samples are simulated; other schemes are skipped, saying so.
//
//   series.skewness  g1's law is symmetric (η → −η leaves the model's law as it was): each
//                    replica counts with its mirror, g1/sd ~ Student t on R dof;
//   series.kurtosis  g2's law is skewed to the right (1.1–1.4 at 1024 samples of a Tp = 10 s
//                    sea at dt 0.5 s, 0.2–0.5 at 43 200 at dt 0.25 s) with a tail heavier than
//                    its moments' Pearson III: g2 is judged through y = −1/(3 + g2), by a
//                    Pearson type III of y's replicas' mean, sd (× √(1 + 1/R), a prediction) and
//                    skewness (on its short side, past the Pearson III's end, the normal law).
// Each per probe, Bonferroni over the probes (they see one sea and are correlated: × P is
// conservative). R = 400: 0.34 s (Rayleigh) and 0.12 s (deterministic, 15 directions) for
// three hours at 4 Hz on nine probes, on one core.
#include <cstddef>
#include <vector>

#include "swell/reference/probe_sea.hpp"
#include "swell/validation/checks/probe_checks.hpp"

namespace swell::validation {

// The simulated law of one point's sample skewness and excess kurtosis.
struct MomentNull {
  std::vector<double> skewness;  // g1 of each replica
  std::vector<double> kurtosis;  // g2 of each replica
};

// The replicas skewness_and_kurtosis judges by.
inline constexpr int kMomentNullReplicas = 400;

// `replicas` (even, ≥ 2) replicas of the declared model at one point. InvalidInput when the
// scheme is not one it simulates (uniform frequencies, repeat_period a whole number of dt).
MomentNull simulate_moment_null(const reference::ProbeCase& probe_case, int replicas);

// Whether simulate_moment_null takes the case's scheme.
bool moment_null_simulated(const reference::ProbeCase& probe_case);

// Appends series.skewness and series.kurtosis (two statistical checks, each at `alpha`) to
// `report`, or two Skipped when the scheme is not simulated. `elevation[p][n]`: probe p's series.
void skewness_and_kurtosis(const reference::ProbeCase& probe_case,
                           const std::vector<std::vector<double>>& elevation,  // [probe][sample]
                           double alpha, ProbeCheckReport& report);

}  // namespace swell::validation
