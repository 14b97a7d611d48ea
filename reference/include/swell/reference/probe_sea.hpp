#pragma once
// Seas as time series at points (docs/conventions.md §2.4, docs/probes.md): the elevation at
// probes x_p, sampled at t_n = t0 + n dt, synthesized as offshore engines do — a sum of wave
// lines
//
//     η(x, t) = Σ_l a_l cos(k_l ê(θ_l)·x − ω_l t + φ_l),   k_l = k(ω_l) of the case's dispersion,
//
// each travelling toward θ_l (radians counter-clockwise from +x, as every direction in swell).
// The declared scheme fixes the lines:
//   frequencies  uniform: ω_i = i Δω, Δω = 2π/repeat_period, inside the cut-off band (the series
//                then repeats after repeat_period); equal_energy: n_frequencies lines at the
//                energy quantiles (i + ½)/n of S over the band, each carrying m0_band/n;
//                random: n_frequencies bins of equal width, one line uniform within each;
//   amplitudes   deterministic: a = √(2 S Δω) (per line's share), φ uniform; rayleigh: the
//                complex amplitude a e^(iφ) = √(S Δω)(ξ1 + i ξ2), so a² ~ 2 S Δω Exp(1);
//   directions   long_crested: every line toward the sea's mean direction; single_per_frequency:
//                one line per frequency, θ drawn from D(ω, ·); double_summation: n_directions
//                lines per frequency at the medians of equal-probability sectors of D(ω, ·), each
//                with 1/n_directions of the frequency's energy and its own phase.
// D(ω, θ) = E(ω, θ)/S(ω) with E(ω, θ) = Ψ(k ê(θ)) k dk/dω, so composite and tabulated seas take
// part as any other.
//
// Random numbers are wave_noise's (Philox keyed by the seed): line i's direction j uses counter
// (i, j) of stream kProbeAmplitudeStream for ξ1, ξ2 and of stream kProbeUniformStream for the
// uniform phase (u1) and direction draw (u2); counter (i, −1) of kProbeUniformStream places a
// random frequency within its bin (u1).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "swell/reference/ocean_case.hpp"

namespace swell::reference {

enum class ProbeAmplitudes { deterministic, rayleigh };
enum class ProbeFrequencies { uniform, equal_energy, random };
enum class ProbeDirections { double_summation, single_per_frequency, long_crested };

const char* to_string(ProbeAmplitudes a);   // "deterministic", "rayleigh"
const char* to_string(ProbeFrequencies f);  // "uniform", "equal_energy", "random"
const char* to_string(ProbeDirections d);   // "double_summation", "single_per_frequency", "long_crested"
// The value of that name; InvalidInput listing the valid ones for any other.
ProbeAmplitudes probe_amplitudes_from_string(const std::string& name);
ProbeFrequencies probe_frequencies_from_string(const std::string& name);
ProbeDirections probe_directions_from_string(const std::string& name);

inline constexpr std::uint32_t kProbeAmplitudeStream = 2;
inline constexpr std::uint32_t kProbeUniformStream = 3;

// Where and when the elevation is sampled.
struct ProbeLayout {
  std::vector<std::array<double, 2>> positions;  // m, (x, y) of each probe
  double t0 = 0;                                 // s
  double dt = 0;                                 // s, > 0
  std::size_t samples = 0;                       // per probe, ≥ 2
  double time(std::size_t n) const { return t0 + double(n) * dt; }
  double duration() const { return double(samples) * dt; }  // the record length T = N dt
};

// How the engine makes its lines ([synthesis] of a probes case).
struct ProbeSynthesis {
  ProbeAmplitudes amplitudes = ProbeAmplitudes::rayleigh;
  ProbeFrequencies frequencies = ProbeFrequencies::uniform;
  double repeat_period = 0;  // s; uniform frequencies need it (Δω = 2π/repeat_period); 0 = none
  double omega_low = 0;      // rad/s: the band the engine synthesizes, [low, high]
  double omega_high = 0;
  ProbeDirections directions = ProbeDirections::long_crested;
  int n_directions = 1;      // double_summation: lines per frequency
  int n_frequencies = 0;     // equal_energy and random: lines (bins) over the band
};

// A probes case: the sea (its grid unused) with where and how it is sampled.
struct ProbeCase {
  OceanCase sea;
  ProbeLayout layout;
  ProbeSynthesis synthesis;
  // Throws InvalidInput naming the first thing wrong: the sea's own rules (OceanCase::validate
  // without its grid), probe positions finite, dt > 0, samples ≥ 2, a cut-off band inside
  // (0, π/dt] (the sampling's Nyquist frequency: a line above it would alias), uniform
  // frequencies with a repeat period of at least one line in the band, n_frequencies ≥ 1 for the
  // other schemes, n_directions ≥ 1.
  void validate() const;
  std::string describe() const;
  // Ψ of the sea as the lines see it. A long-crested sea needs no spreading model (its lines all
  // travel toward the sea's mean direction): a component without one is given cos-2s s = 1 here,
  // which leaves its S(ω) and mean direction — all a long-crested sea uses — unchanged.
  DirectionalSpectrumPtr spectrum() const;
  // The sea as spectrum() sees it: `sea`, with cos-2s s = 1 for a long-crested sea's components
  // that give no spreading model.
  OceanCase synthesized_sea() const;  // "jonswap hs=3 tp=10 gamma=3.3 …, 9 probes, 43200 samples at 0.25 s"
};

// One wave line: η += amplitude · cos(k (cos θ x + sin θ y) − ω t + phase).
struct WaveLine {
  double omega = 0;       // rad/s
  double band_width = 0;  // rad/s: the share of ω this line stands for
  double k = 0;           // rad/m, k(ω)
  double theta = 0;       // rad, direction of travel
  double amplitude = 0;   // m
  double phase = 0;       // rad
  int frequency = 0;      // the index i of its frequency (lines of one frequency share it)
};

// The lines of `probe_case` for `seed`, frequency by frequency (directions within one frequency
// consecutive). Deterministic: the same case and seed give the same lines bit for bit.
std::vector<WaveLine> probe_wave_lines(const ProbeCase& probe_case, std::uint64_t seed);

// The frequencies of the declared scheme over the cut-off band, with their band widths, before
// any random placement: uniform's i Δω, equal_energy's quantiles, random's bin centres.
struct FrequencyLine {
  double omega = 0, band_width = 0;
  double variance = 0;  // m², E a²/2 of the frequency's lines together: S(ω) band_width, or equal_energy's
                        // m0 over the band / n_frequencies (random: at the bin's centre)
};
std::vector<FrequencyLine> probe_frequency_lines(const ProbeCase& probe_case);

// D(ω, θ) of the sea on `count` equal cells of the circle starting at `from` (rad), normalized
// to Σ D Δθ = 1: each cell's value at its centre.
std::vector<double> direction_distribution(const DirectionalSpectrum& sea, double omega, double from,
                                           int count);

// The directions of double summation's `count` lines at ω (rad): the medians of D(ω, ·)'s
// equal-probability sectors, as probe_wave_lines places them (the same numbers bit for bit).
std::vector<double> sector_directions(const DirectionalSpectrum& sea, double omega, int count);

// η at (x, y) at the layout's times, summed line by line with exactly reduced phases: the
// oracle of faster evaluations (impls/probe_synthesis.hpp).
std::vector<double> probe_series_direct(const std::vector<WaveLine>& lines, double x, double y,
                                        const ProbeLayout& layout);

}  // namespace swell::reference
