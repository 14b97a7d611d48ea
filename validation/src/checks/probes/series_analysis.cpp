#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "swell/impls/transform.hpp"

namespace swell::validation::probe_analysis {

using reference::ProbeAmplitudes;
using reference::ProbeCase;
using reference::ProbeDirections;
using reference::ProbeFrequencies;
constexpr double kPi = std::numbers::pi;

namespace {

// X_q = (1/N) Σ η_n e^(−2πi q n/N), q = 0 … N/2, by FFTW.
std::vector<Complex> half_spectrum(const std::vector<double>& series) {
  const std::size_t n = series.size();
  impls::TransformSpec spec;
  spec.nx = int(n);
  spec.kind = impls::Kind::c2c;
  spec.direction = impls::Direction::forward;
  const auto plan = impls::make_backend("fftw")->plan(spec);
  std::vector<Complex> in(series.begin(), series.end()), out(n);
  plan->execute(std::span<const Complex>(in), std::span<Complex>(out));
  out.resize(n / 2 + 1);
  for (auto& x : out) x /= double(n);
  return out;
}

// give it unbiased). 1 where the amplitudes are ∝ S Δω instead of √(2 S Δω): a missing √.
double ratio_slope(const std::vector<double>& expected, const std::vector<double>& measured) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, largest = 0;
  int n = 0;
  for (double e : expected) largest = std::max(largest, e);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    // The bins holding 10⁻⁶ of the largest line's power and more: in the far tails the measured
    // power is the stored values' rounding, which no slope of the engine's law describes.
    if (!(expected[i] >= 1e-6 * largest && measured[i] > 0)) continue;
    const double x = std::log(expected[i]), y = std::log(measured[i] / expected[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
  }
  if (n < 8) return NAN;
  const double spread = sxx - sx * sx / n;
  return spread > 0 ? (sxy - sx * sy / n) / spread : NAN;
}

// Whether the measured power sits on every r-th line only (r = 2 … 8), the others empty: the
// engine's lines are r Δω apart — its series repeats after repeat_period/r. Returns r, or 0.
int shorter_repeat(const std::vector<double>& measured) {
  double total = 0;
  for (double m : measured) total += m;
  if (!(total > 0)) return 0;
  for (int r = 2; r <= 8; ++r) {
    for (int offset = 0; offset < r; ++offset) {
      double on = 0;
      for (std::size_t i = std::size_t(offset); i < measured.size(); i += std::size_t(r)) on += measured[i];
      if (on >= (1 - 1e-6) * total) return r;
    }
  }
  return 0;
}


}  // namespace

LineBins line_bins(const ProbeCase& c) {
  LineBins out;
  const auto& s = c.synthesis;
  if (s.frequencies != ProbeFrequencies::uniform || !(s.repeat_period > 0)) return out;
  const double periods = c.layout.duration() / s.repeat_period;
  const double whole = std::round(periods);
  if (!(whole >= 1) || std::abs(periods - whole) > 1e-9 * whole) return out;
  out.periodic = true;
  out.whole_periods = std::size_t(whole);
  out.step = 2 * kPi / s.repeat_period;
  const auto sea = c.spectrum();
  const auto& spectrum = sea->omnidirectional();
  const std::size_t n = c.layout.samples;
  for (const auto& line : reference::probe_frequency_lines(c)) {
    const auto q = std::size_t(std::llround(line.omega / out.step)) * out.whole_periods;
    if (q == 0 || 2 * q >= n) continue;  // the Nyquist bin holds a line's real part only
    out.bins.push_back(q);
    out.omega.push_back(line.omega);
    out.expected.push_back(spectrum(line.omega) * out.step);
  }
  return out;
}

ProbeSpectrum probe_spectrum(const std::vector<double>& series, double stored_rounding) {
  ProbeSpectrum out;
  out.x = half_spectrum(series);
  double largest = 0;
  for (double v : series) largest = std::max(largest, std::abs(v));
  out.rounding = stored_rounding + 8 * 0x1p-53 * std::log2(double(series.size())) * largest;
  return out;
}

double periodogram_error_bound(const Complex& x, double r) {
  return 4 * (std::abs(x) + r) * r + 2 * r * r;
}

int directions_per_frequency(const ProbeCase& c) {
  return c.synthesis.directions == ProbeDirections::double_summation ? c.synthesis.n_directions : 1;
}

double engine_arithmetic_allowance(const ProbeCase& c, std::size_t p) {
  const auto lines = reference::probe_frequency_lines(c);
  const int directions = c.synthesis.directions == ProbeDirections::double_summation ? c.synthesis.n_directions : 1;
  const double amplitude_factor = c.synthesis.amplitudes == ProbeAmplitudes::rayleigh ? 3.0 : 1.0;
  const double latest = std::max(std::abs(c.layout.t0), std::abs(c.layout.time(c.layout.samples - 1)));
  const double distance = std::hypot(c.layout.positions[p][0], c.layout.positions[p][1]);
  const double terms = double(lines.size()) * directions;
  const auto dispersion = c.sea.dispersion();
  double sum = 0;
  for (const auto& line : lines) {
    const double amplitudes = amplitude_factor * std::sqrt(2 * line.variance * directions);
    const double argument = line.omega * latest + dispersion.wavenumber(line.omega) * distance + 2 * kPi;
    sum += amplitudes * (argument + terms);
  }
  return 0x1p-53 * sum;
}

std::string probe_name(std::size_t p, const ProbeCase& c) {
  return fmt::format("probe {} at ({:g}, {:g}) m", p, c.layout.positions[p][0], c.layout.positions[p][1]);
}

// The factor an engine's series carry when it slips on a convention, named where the
// measured energy ratio's range [low, high] holds it (the nearest in log). With n directions per
// frequency in equal-probability sectors (weights 1/n), variance weights √(1/n) instead of 1/n
// give × √n, amplitude weights 1/n instead of √(1/n) give × 1/n.
std::string energy_factor_meaning(double ratio, double low, double high, int directions) {
  const double two_pi = 2 * kPi;
  std::vector<std::pair<double, std::string>> factors = {
      {two_pi * two_pi, "× 4π²: amplitudes × 2π"},
      {1 / (two_pi * two_pi), "× 1/(4π²): amplitudes ÷ 2π"},
      {two_pi, "× 2π: a density in m²/Hz used as m²·s/rad"},
      {1 / two_pi, "× 1/(2π): a density in m²·s/rad used as m²/Hz"},
      {0.5, "× ½: a two-sided density used as one-sided, or a = √(S Δω) without its 2"},
      {2.0, "× 2: a one-sided density counted twice, or a = √(4 S Δω)"},
      {16.0, "× 16: Hs² where m0 = Hs²/16 belongs"},
  };
  if (directions > 1) {
    factors.push_back({std::sqrt(double(directions)),
                       fmt::format("× √{} = √n_directions: spreading weights √D per direction instead of D (the "
                                   "directional energy is not conserved)",
                                   directions)});
    factors.push_back({1.0 / directions, fmt::format("× 1/{} = 1/n_directions: amplitudes weighted by D instead of "
                                                     "√D per direction (the directional energy is not conserved)",
                                                     directions)});
  }
  const std::string* best = nullptr;
  double nearest = INFINITY;
  for (const auto& [factor, meaning] : factors) {
    if (factor < low || factor > high) continue;
    const double distance = std::abs(std::log(ratio / factor));
    if (distance < nearest) nearest = distance, best = &meaning;
  }
  return best ? " — " + *best : "";
}

// How the measured-to-expected ratio of the line bins scales with the expected power: the

// A failed spectrum check's explanation in the engine's terms.
std::string spectrum_diagnosis(const std::vector<double>& expected, const std::vector<double>& measured,
                               const std::string& otherwise) {
  if (const int r = shorter_repeat(measured); r > 0) {
    return fmt::format("only one line in {} of Δω = 2π/repeat_period carries energy: the series repeats "
                       "after repeat_period/{}, sooner than declared",
                       r, r);
  }
  const double slope = ratio_slope(expected, measured);
  if (std::abs(slope - 1) < 0.1) {
    return fmt::format("the periodogram over S Δω grows as S Δω itself (slope {:.3f} in log–log): amplitudes ∝ S Δω "
                       "instead of √(2 S Δω) — a missing √",
                       slope);
  }
  return otherwise;
}

bool exact_scheme(const ProbeCase& c) {
  return c.synthesis.amplitudes == ProbeAmplitudes::deterministic &&
         (c.synthesis.directions != ProbeDirections::double_summation || c.synthesis.n_directions == 1);
}

bool equal_phasor_scheme(const ProbeCase& c) {
  return c.synthesis.amplitudes == ProbeAmplitudes::deterministic && !exact_scheme(c);
}
}  // namespace swell::validation::probe_analysis
