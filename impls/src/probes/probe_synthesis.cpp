#include "swell/impls/probe_synthesis.hpp"

#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/phase.hpp"

namespace swell::impls {
namespace {

using Complex = std::complex<double>;
using reference::WaveLine;
constexpr double kPi = std::numbers::pi;

// One frequency's lines combined at a probe.
struct FrequencyAmplitude {
  double omega = 0;
  Complex amplitude;  // B_i(x)
};

std::vector<FrequencyAmplitude> combine(const std::vector<WaveLine>& lines, double x, double y) {
  std::vector<FrequencyAmplitude> out;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const WaveLine& line = lines[l];
    const double space = line.k * (std::cos(line.theta) * x + std::sin(line.theta) * y) + line.phase;
    const Complex term = line.amplitude * reference::unit_phasor(std::remainder(space, 2 * kPi));
    if (l == 0 || line.frequency != lines[l - 1].frequency) {
      out.push_back({line.omega, term});
    } else {
      out.back().amplitude += term;
    }
  }
  return out;
}

// Re Σ B e^(−iω t_n), frequency by frequency with a re-anchored rotation.
void sum_directly(const std::vector<FrequencyAmplitude>& parts, const reference::ProbeLayout& layout,
                  std::vector<double>& series) {
  constexpr std::size_t kAnchor = 64;
  series.assign(layout.samples, 0.0);
  for (const auto& part : parts) {
    const Complex step = reference::unit_phasor(-reference::reduced_phase(part.omega, layout.dt));
    for (std::size_t begin = 0; begin < layout.samples; begin += kAnchor) {
      Complex z = part.amplitude * reference::unit_phasor(-reference::reduced_phase(part.omega, layout.time(begin)));
      const std::size_t end = std::min(layout.samples, begin + kAnchor);
      for (std::size_t n = begin; n < end; ++n) {
        series[n] += z.real();
        z *= step;
      }
    }
  }
}

}  // namespace

bool probe_series_is_periodic(const reference::ProbeCase& c, std::size_t* period_samples) {
  const auto& s = c.synthesis;
  if (s.frequencies != reference::ProbeFrequencies::uniform || !(s.repeat_period > 0)) return false;
  const double ratio = s.repeat_period / c.layout.dt;
  const double whole = std::round(ratio);
  if (!(whole >= 2) || std::abs(ratio - whole) > 1e-9 * whole || whole > 1e9) return false;
  if (period_samples) *period_samples = std::size_t(whole);
  return true;
}

std::vector<std::vector<double>> synthesize_probe_series(const reference::ProbeCase& c,
                                                         const std::vector<WaveLine>& lines, int threads) {
  const std::size_t probes = c.layout.positions.size();
  std::vector<std::vector<double>> out(probes);
  std::size_t period = 0;
  const bool periodic = probe_series_is_periodic(c, &period);
  std::unique_ptr<Plan> plan;
  if (periodic) {
    TransformSpec spec;
    spec.nx = int(period);
    spec.kind = Kind::c2c;
    spec.direction = Direction::forward;
    spec.precision = Precision::f64;
    plan = make_backend("fftw")->plan(spec);
  }
  const double step = periodic ? 2 * kPi / c.synthesis.repeat_period : 0;
#pragma omp parallel for schedule(dynamic) num_threads(std::max(1, threads))
  for (std::size_t p = 0; p < probes; ++p) {
    const auto parts = combine(lines, c.layout.positions[p][0], c.layout.positions[p][1]);
    auto& series = out[p];
    if (!periodic) {
      sum_directly(parts, c.layout, series);
      continue;
    }
    // ω_i = q_i Δω: C[q_i] = B_i e^(−iω_i t0), and η_n = Re Σ_q C[q] e^(−2πi q n/M).
    std::vector<Complex> coefficients(period, Complex(0)), transform(period);
    for (const auto& part : parts) {
      const auto q = std::size_t(std::llround(part.omega / step)) % period;
      coefficients[q] += part.amplitude * reference::unit_phasor(-reference::reduced_phase(part.omega, c.layout.t0));
    }
    plan->execute(std::span<const Complex>(coefficients), std::span<Complex>(transform));
    series.resize(c.layout.samples);
    for (std::size_t n = 0; n < c.layout.samples; ++n) series[n] = transform[n % period].real();
  }
  return out;
}

}  // namespace swell::impls
