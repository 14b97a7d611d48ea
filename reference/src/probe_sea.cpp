#include "swell/reference/probe_sea.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/phase.hpp"
#include "swell/reference/wave_noise.hpp"

namespace swell::reference {
namespace {

constexpr double kPi = std::numbers::pi;

template <typename Enum, std::size_t N>
Enum from_name(const std::string& name, const std::pair<const char*, Enum> (&names)[N], const char* key) {
  std::string valid;
  for (const auto& [text, value] : names) {
    if (name == text) return value;
    valid += (valid.empty() ? "\"" : ", \"") + std::string(text) + "\"";
  }
  throw InvalidInput(fmt::format("{} \"{}\" is not one of {}", key, name, valid));
}

const std::pair<const char*, ProbeAmplitudes> kAmplitudeNames[] = {
    {"deterministic", ProbeAmplitudes::deterministic}, {"rayleigh", ProbeAmplitudes::rayleigh}};
const std::pair<const char*, ProbeFrequencies> kFrequencyNames[] = {
    {"uniform", ProbeFrequencies::uniform},
    {"equal_energy", ProbeFrequencies::equal_energy},
    {"random", ProbeFrequencies::random}};
const std::pair<const char*, ProbeDirections> kDirectionNames[] = {
    {"double_summation", ProbeDirections::double_summation},
    {"single_per_frequency", ProbeDirections::single_per_frequency},
    {"long_crested", ProbeDirections::long_crested}};

template <typename Enum, std::size_t N>
const char* name_of(Enum value, const std::pair<const char*, Enum> (&names)[N]) {
  for (const auto& [text, v] : names) {
    if (v == value) return text;
  }
  return "?";
}

// S(ω) integrated from the band's low end on a fine grid: `omega` and `cumulative` of equal
// length, by the trapezoid rule on 2¹⁴ panels (the quantiles it gives move the lines by
// < 1e-6 of the band for the smooth spectra swell offers; the series' laws use each line's own
// S(ω) Δω, not the quantiles' exactness).
struct Cumulative {
  std::vector<double> omega, cumulative;
  double total() const { return cumulative.back(); }
  // ω at which the cumulative integral reaches `share` × total, linearly between grid points.
  double quantile(double share) const {
    const double target = share * total();
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    if (it == cumulative.begin()) return omega.front();
    if (it == cumulative.end()) return omega.back();
    const std::size_t i = std::size_t(it - cumulative.begin());
    const double span = cumulative[i] - cumulative[i - 1];
    const double f = span > 0 ? (target - cumulative[i - 1]) / span : 0;
    return omega[i - 1] + f * (omega[i] - omega[i - 1]);
  }
};

Cumulative cumulative_spectrum(const FrequencySpectrum& s, double low, double high) {
  constexpr int kPanels = 1 << 14;
  Cumulative out;
  out.omega.resize(kPanels + 1);
  out.cumulative.resize(kPanels + 1);
  const double h = (high - low) / kPanels;
  double previous = s(low), sum = 0;
  out.omega[0] = low;
  for (int i = 1; i <= kPanels; ++i) {
    const double w = i == kPanels ? high : low + i * h;
    const double value = s(w);
    sum += 0.5 * h * (previous + value);
    previous = value;
    out.omega[i] = w;
    out.cumulative[i] = sum;
  }
  return out;
}

// The inverse of the distribution function of D(ω, ·) tabulated on cells: θ where the
// cumulative probability reaches `p`, linear within a cell.
double inverse_direction_cdf(const std::vector<double>& density, double from, double p) {
  const int count = int(density.size());
  const double width = 2 * kPi / count;
  double cumulative = 0;
  for (int j = 0; j < count; ++j) {
    const double mass = density[j] * width;
    if (cumulative + mass >= p && mass > 0) return from + (j + (p - cumulative) / mass) * width;
    cumulative += mass;
  }
  return from + 2 * kPi;
}

constexpr int kDirectionCells = 720;  // 0.5°: D's tails and narrow swells resolved

}  // namespace

const char* to_string(ProbeAmplitudes a) { return name_of(a, kAmplitudeNames); }
const char* to_string(ProbeFrequencies f) { return name_of(f, kFrequencyNames); }
const char* to_string(ProbeDirections d) { return name_of(d, kDirectionNames); }
ProbeAmplitudes probe_amplitudes_from_string(const std::string& name) {
  return from_name(name, kAmplitudeNames, "amplitudes");
}
ProbeFrequencies probe_frequencies_from_string(const std::string& name) {
  return from_name(name, kFrequencyNames, "frequencies");
}
ProbeDirections probe_directions_from_string(const std::string& name) {
  return from_name(name, kDirectionNames, "directions");
}

namespace {

// The sea with cos-2s s = 1 for a long-crested sea's components that give no spreading model
// (ProbeCase::spectrum).
OceanCase long_crested_sea(const ProbeCase& c) {
  auto parts = c.sea.components();
  for (auto& part : parts) {
    if (part.spreading.model.empty() && part.spectrum.model != "phillips" &&
        !(part.table && part.table->is_directional())) {
      if (c.synthesis.directions != ProbeDirections::long_crested) {
        throw InvalidInput(fmt::format("directions = \"{}\" draws directions from D(ω, θ): give a "
                                       "spreading model (only a long_crested sea needs none)",
                                       to_string(c.synthesis.directions)));
      }
      part.spreading = {"cos2s", {{"s", 1.0}}, {}};
    }
  }
  OceanCase copy = c.sea;
  copy.set_components(parts);
  return copy;
}

}  // namespace

DirectionalSpectrumPtr ProbeCase::spectrum() const { return long_crested_sea(*this).sea_spectrum(); }
OceanCase ProbeCase::synthesized_sea() const { return long_crested_sea(*this); }

void ProbeCase::validate() const {
  long_crested_sea(*this).validate_sea();
  if (layout.positions.empty()) throw InvalidInput("positions: no probes (give at least one [x, y] in m)");
  for (std::size_t p = 0; p < layout.positions.size(); ++p) {
    const auto& [x, y] = layout.positions[p];
    if (!std::isfinite(x) || !std::isfinite(y)) {
      throw InvalidInput(fmt::format("positions: probe {} at ({:g}, {:g}) m is not finite", p, x, y));
    }
  }
  require(std::isfinite(layout.dt) && layout.dt > 0, "dt", "finite and > 0 (s)", layout.dt);
  if (layout.samples < 2) {
    throw InvalidInput(fmt::format("samples must be ≥ 2 per probe (got {})", layout.samples));
  }
  const double last = layout.time(layout.samples - 1);
  require(std::isfinite(last) && std::abs(last) < 1e12, "t0 + (samples − 1) dt", "finite and < 1e12 s", last);
  const double nyquist = kPi / layout.dt;
  const auto& s = synthesis;
  require(std::isfinite(s.omega_low) && s.omega_low >= 0, "omega_cutoff[0]", "finite and ≥ 0 (rad/s)",
          s.omega_low);
  if (!(std::isfinite(s.omega_high) && s.omega_high > s.omega_low)) {
    throw InvalidInput(fmt::format("omega_cutoff = [{:g}, {:g}] rad/s: the upper end must be finite "
                                   "and above the lower",
                                   s.omega_low, s.omega_high));
  }
  if (s.omega_high > nyquist * (1 + 1e-12)) {
    throw InvalidInput(fmt::format(
        "omega_cutoff upper end {:g} rad/s is above the sampling's Nyquist frequency π/dt = {:g} "
        "rad/s (dt = {:g} s): lines above it alias onto lower frequencies; lower the cut-off or dt",
        s.omega_high, nyquist, layout.dt));
  }
  require(std::isfinite(s.repeat_period) && s.repeat_period >= 0, "repeat_period", "finite and ≥ 0 (s)",
          s.repeat_period);
  if (s.frequencies == ProbeFrequencies::uniform) {
    if (!(s.repeat_period > 0)) {
      throw InvalidInput("frequencies = \"uniform\" needs repeat_period > 0 (s): its lines are "
                         "Δω = 2π/repeat_period apart");
    }
    const double step = 2 * kPi / s.repeat_period;
    const double first = std::max(1.0, std::ceil(s.omega_low / step));
    const double lines = std::floor(s.omega_high / step) - first + 1;
    if (lines < 1) {
      throw InvalidInput(fmt::format("no line of Δω = 2π/repeat_period = {:g} rad/s falls in "
                                     "omega_cutoff [{:g}, {:g}] rad/s",
                                     step, s.omega_low, s.omega_high));
    }
    if (lines > 1e7) {
      throw InvalidInput(fmt::format("{:g} lines of Δω = {:g} rad/s in the cut-off band: more than "
                                     "10⁷; shorten repeat_period or narrow omega_cutoff",
                                     lines, step));
    }
  } else if (s.n_frequencies < 1 || s.n_frequencies > 10000000) {
    throw InvalidInput(fmt::format("n_frequencies must be in 1…10⁷ for frequencies = \"{}\" (got {})",
                                   to_string(s.frequencies), s.n_frequencies));
  }
  if (s.n_directions < 1 || s.n_directions > 100000) {
    throw InvalidInput(fmt::format("n_directions must be in 1…10⁵ (got {})", s.n_directions));
  }
  if (s.directions != ProbeDirections::double_summation && s.n_directions != 1) {
    throw InvalidInput(fmt::format("n_directions = {} belongs to directions = \"double_summation\" "
                                   "(\"{}\" has one direction per frequency)",
                                   s.n_directions, to_string(s.directions)));
  }
  if (s.frequencies != ProbeFrequencies::uniform && s.frequencies != ProbeFrequencies::equal_energy &&
      s.repeat_period > 0) {
    throw InvalidInput("repeat_period belongs to frequencies = \"uniform\" (random frequencies do "
                       "not repeat); set it to 0");
  }
  const auto psi = spectrum();
  if (!(cumulative_spectrum(psi->omnidirectional(), s.omega_low, s.omega_high).total() > 0)) {
    throw InvalidInput(fmt::format("the sea's spectrum puts no energy in omega_cutoff [{:g}, {:g}] rad/s",
                                   s.omega_low, s.omega_high));
  }
}

std::string ProbeCase::describe() const {
  std::string out = sea.describe_sea();
  out += fmt::format(", {} probe{}, {} samples at {:g} s", layout.positions.size(),
                     layout.positions.size() == 1 ? "" : "s", layout.samples, layout.dt);
  if (std::isfinite(sea.depth)) out += fmt::format(", depth {:g} m", sea.depth);
  return out;
}

std::vector<FrequencyLine> probe_frequency_lines(const ProbeCase& c) {
  const auto& s = c.synthesis;
  const auto sea = c.spectrum();
  const FrequencySpectrum& spectrum = sea->omnidirectional();
  std::vector<FrequencyLine> out;
  if (s.frequencies == ProbeFrequencies::uniform) {
    const double step = 2 * kPi / s.repeat_period;
    const long first = std::max(1L, long(std::ceil(s.omega_low / step)));
    const long last = long(std::floor(s.omega_high / step));
    for (long i = first; i <= last; ++i) out.push_back({double(i) * step, step, spectrum(double(i) * step) * step});
  } else if (s.frequencies == ProbeFrequencies::equal_energy) {
    const auto cumulative = cumulative_spectrum(spectrum, s.omega_low, s.omega_high);
    const int n = s.n_frequencies;
    for (int i = 0; i < n; ++i) {
      const double lo = cumulative.quantile(double(i) / n), hi = cumulative.quantile(double(i + 1) / n);
      out.push_back({cumulative.quantile((i + 0.5) / n), hi - lo, cumulative.total() / n});
    }
  } else {
    const double width = (s.omega_high - s.omega_low) / s.n_frequencies;
    for (int i = 0; i < s.n_frequencies; ++i) {
      const double omega = s.omega_low + (i + 0.5) * width;
      out.push_back({omega, width, spectrum(omega) * width});
    }
  }
  return out;
}

std::vector<double> direction_distribution(const DirectionalSpectrum& sea, double omega, double from,
                                           int count) {
  const Dispersion& dispersion = sea.dispersion();
  const double k = dispersion.wavenumber(omega);
  std::vector<double> density(std::size_t(count), 0.0);
  if (!(k > 0) || !std::isfinite(k)) return density;
  const double width = 2 * kPi / count;
  double sum = 0;
  for (int j = 0; j < count; ++j) {
    const double theta = from + (j + 0.5) * width;
    // E(ω, θ) ∝ Ψ(k ê(θ)) at fixed ω: k dk/dω is the same for every θ and cancels.
    density[std::size_t(j)] = sea.psi(k * std::cos(theta), k * std::sin(theta));
    sum += density[std::size_t(j)] * width;
  }
  if (sum > 0) {
    for (double& d : density) d /= sum;
  }
  return density;
}

std::vector<WaveLine> probe_wave_lines(const ProbeCase& c, std::uint64_t seed) {
  const auto& s = c.synthesis;
  const auto sea = c.spectrum();
  const FrequencySpectrum& spectrum = sea->omnidirectional();
  const Dispersion dispersion = c.sea.dispersion();
  const double mean = sea->mean_direction();
  const double from = mean - kPi;  // D's cells centred on the mean direction's circle
  std::vector<WaveLine> out;
  const auto frequencies = probe_frequency_lines(c);
  const int directions = s.directions == ProbeDirections::double_summation ? s.n_directions : 1;
  out.reserve(frequencies.size() * std::size_t(directions));
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    const int index = int(i);
    double omega = frequencies[i].omega;
    const double width = frequencies[i].band_width;
    if (s.frequencies == ProbeFrequencies::random) {
      omega += (wave_uniforms(seed, index, -1, kProbeUniformStream).u1 - 0.5) * width;
    }
    // Each line's energy S Δω (equal_energy: the band's m0 shared out), split equally over the
    // frequency's directions.
    const double energy =
        s.frequencies == ProbeFrequencies::random ? spectrum(omega) * width : frequencies[i].variance;
    const double k = dispersion.wavenumber(omega);
    std::vector<double> density;
    if (s.directions != ProbeDirections::long_crested) {
      density = direction_distribution(*sea, omega, from, kDirectionCells);
    }
    for (int j = 0; j < directions; ++j) {
      WaveLine line;
      line.omega = omega;
      line.band_width = width;
      line.k = k;
      line.frequency = index;
      const UniformPair uniforms = wave_uniforms(seed, index, j, kProbeUniformStream);
      switch (s.directions) {
        case ProbeDirections::long_crested: line.theta = mean; break;
        case ProbeDirections::single_per_frequency:
          line.theta = inverse_direction_cdf(density, from, uniforms.u2);
          break;
        case ProbeDirections::double_summation:
          line.theta = inverse_direction_cdf(density, from, (j + 0.5) / directions);
          break;
      }
      const double share = energy / directions;  // a² = 2 × share (E a² for Rayleigh)
      if (s.amplitudes == ProbeAmplitudes::deterministic) {
        line.amplitude = std::sqrt(2 * share);
        line.phase = 2 * kPi * uniforms.u1;
      } else {
        const NormalPair xi = wave_noise(seed, index, j, kProbeAmplitudeStream);
        line.amplitude = std::sqrt(share) * std::hypot(xi.xi1, xi.xi2);
        line.phase = std::atan2(xi.xi2, xi.xi1);
      }
      out.push_back(line);
    }
  }
  return out;
}

std::vector<double> sector_directions(const DirectionalSpectrum& sea, double omega, int count) {
  const double from = sea.mean_direction() - kPi;
  const auto density = direction_distribution(sea, omega, from, kDirectionCells);
  std::vector<double> out;
  for (int j = 0; j < count; ++j) out.push_back(inverse_direction_cdf(density, from, (j + 0.5) / count));
  return out;
}

std::vector<double> probe_series_direct(const std::vector<WaveLine>& lines, double x, double y,
                                        const ProbeLayout& layout) {
  std::vector<double> out(layout.samples, 0.0);
  for (const WaveLine& line : lines) {
    // k·x + φ reduced once; ω t reduced exactly per sample (phase.hpp).
    const double space = std::remainder(line.k * (std::cos(line.theta) * x + std::sin(line.theta) * y) + line.phase,
                                        2 * kPi);
    for (std::size_t n = 0; n < layout.samples; ++n) {
      out[n] += line.amplitude * std::cos(space - reduced_phase(line.omega, layout.time(n)));
    }
  }
  return out;
}

}  // namespace swell::reference
