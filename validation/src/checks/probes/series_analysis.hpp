#pragma once
// What the series checks of a probes case share (docs/probes.md): each probe's one-sided
// spectrum, the bins the declared lines fall on, and the diagnoses in the engine's terms. One
// check per file beside this one; checks/probe_checks.cpp runs them.
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "swell/reference/probe_sea.hpp"
#include "swell/validation/checks/probe_checks.hpp"

namespace swell::validation::probe_analysis {

using Complex = std::complex<double>;

// What the scheme and the record make of the bins: line i of Δω = 2π/repeat_period on bin
// q = m i when the record holds m whole repeat periods.
struct LineBins {
  bool periodic = false;
  std::size_t whole_periods = 0;  // m
  double step = 0;                // Δω, rad/s
  std::vector<std::size_t> bins;  // q of every line in the band below the Nyquist bin
  std::vector<double> expected;   // S(ω_q) Δω, m², per line bin
  std::vector<double> omega;      // ω_q, rad/s
};
LineBins line_bins(const reference::ProbeCase& c);

// One probe's spectrum X_q = (1/N) Σ η_n e^(−2πi q n/N), q = 0 … N/2, and the rounding it
// carries: r bounds each X's error (its stored rounding plus the transform's, 8 u log2 N of its
// largest value).
struct ProbeSpectrum {
  std::vector<Complex> x;
  double rounding = 0;
  // I_q = 2|X_q|² (|X_q|² at q = 0 and the Nyquist bin), E I_q = S(ω_q) Δω.
  double periodogram(std::size_t q, std::size_t n) const {
    const double two_sided = std::norm(x[q]);
    return q == 0 || 2 * q == n ? two_sided : 2 * two_sided;
  }
};
ProbeSpectrum probe_spectrum(const std::vector<double>& series, double stored_rounding);

// |I − I_true| for a bin whose X carries an error of at most r.
double periodogram_error_bound(const Complex& x, double r);

// The error a double-precision engine's own arithmetic may put on each value at probe `p`, m: each
// line's cosine carries its argument's rounding, u (|ω| t + k |x_p| + 2π), and the sum of all n
// lines n u of their amplitudes (a worst-case bound: Σ over frequencies of Σ_j |a_ij| ≤
// √(2 v n_dir), three times that for Rayleigh amplitudes). An independent engine summing its lines
// in double stays within it; the exact checks allow it beside the stored values' rounding.
double engine_arithmetic_allowance(const reference::ProbeCase& c, std::size_t p);

std::string probe_name(std::size_t p, const reference::ProbeCase& c);  // "probe 2 at (10, 0) m"

// " — × 4π²: amplitudes × 2π" for the convention factor nearest `ratio` in log within the
// range [low, high] the sampling allows, "" when none lies there; `directions` per frequency
// (double summation's n) adds the spreading weights' factors √n and 1/n.
std::string energy_factor_meaning(double ratio, double low, double high, int directions);
// The lines per frequency of the case's scheme: n_directions for double summation, else 1.
int directions_per_frequency(const reference::ProbeCase& c);

// A failed spectrum check's explanation in the engine's terms: a series repeating sooner than
// declared, a missing √, or `otherwise`.
std::string spectrum_diagnosis(const std::vector<double>& expected, const std::vector<double>& measured,
                               const std::string& otherwise);

// "Tm01 × c and Tm02 × c with the energy × r: … frequencies rescaled …" when the measured
// powers hold the expected energy at frequencies scaled alike; "" otherwise.
std::string frequency_rescale_diagnosis(const std::vector<double>& expected_omega, const std::vector<double>& expected,
                                        const std::vector<double>& measured_omega,
                                        const std::vector<double>& measured);

// Deterministic amplitudes with one line per frequency: the periodogram is S Δω exactly.
bool exact_scheme(const reference::ProbeCase& c);
// Deterministic amplitudes with several directions per frequency: equal phasors per line.
bool equal_phasor_scheme(const reference::ProbeCase& c);

// The checks, one per file.
void line_spectrum_and_energy(const reference::ProbeCase& c, const LineBins& lines,
                              const std::vector<ProbeSpectrum>& spectra, double alpha, ProbeCheckReport& report);
// series.moments: Hs, Tm01 and Tm02 of each probe's line powers against the lines' own.
void spectral_moments(const reference::ProbeCase& c, const LineBins& lines,
                             const std::vector<ProbeSpectrum>& spectra, double alpha, ProbeCheckReport& report);
// series.spectrum and series.energy of records that are not whole repeat periods of uniform
// lines (equal-energy or random frequencies, or another record length): Welch estimates and the
// mean square against their exact moments over the declared lines.
void welch_spectrum_and_energy(const reference::ProbeCase& c, const std::vector<std::vector<double>>& elevation,
                               const std::vector<double>& rounding, double alpha, ProbeCheckReport& report);
// repeat_period/dt when it is a whole number of samples M ≥ 2 of uniform lines, else 0.
std::size_t repeat_period_samples(const reference::ProbeCase& c);
// series.repeat_period: a record longer than M samples repeats after M, exactly.
void repeat_period(const reference::ProbeCase& c, const std::vector<std::vector<double>>& elevation,
                   const std::vector<double>& rounding, ProbeCheckReport& report);
// One direction per frequency: series.phase — each line's phases between probes are one plane
// wave's at the case's k(ω), exactly — and, with three probes or more off one line,
// series.direction — the lines' directions read from their plane waves against D(ω, θ).
void plane_waves(const reference::ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                 double alpha, ProbeCheckReport& report);
// Several directions per frequency: series.coherence — each line's vector of probe amplitudes
// whitened by the covariance R its declared directions give, against its exact law.
void coherence(const reference::ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
               double alpha, ProbeCheckReport& report);
void stray_energy(const reference::ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                  ProbeCheckReport& report);
void same_amplitude(const reference::ProbeCase& c, const LineBins& lines,
                    const std::vector<ProbeSpectrum>& spectra, ProbeCheckReport& report);
void phase(const reference::ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
           ProbeCheckReport& report);

}  // namespace swell::validation::probe_analysis
