// The per-wave-vector fit of two counter-rotating waves (stats/wave_fit.hpp).
#include "swell/validation/stats/wave_fit.hpp"

#include <complex>
#include <span>
#include <vector>

#include "swell/reference/phase.hpp"

namespace swell::validation {

using Complex = std::complex<double>;

void two_wave_phases(double omega, const std::vector<double>& times, std::vector<Complex>& phases) {
  phases.resize(times.size());
  for (std::size_t f = 0; f < times.size(); ++f) {
    phases[f] = reference::unit_phasor(-reference::reduced_phase(omega, times[f]));
  }
}

bool fit_two_waves(double omega, const std::vector<double>& times, std::span<const Complex> y,
                   Complex& a, Complex& b, double& residual) {
  // Per thread: the gate runs checks concurrently.
  thread_local std::vector<Complex> phases;
  two_wave_phases(omega, times, phases);
  return fit_two_waves(phases, y, a, b, residual);
}

bool fit_two_waves(std::span<const Complex> phases, std::span<const Complex> y, Complex& a,
                   Complex& b, double& residual) {
  const double frames = double(phases.size());
  Complex s = 0, r1 = 0, r2 = 0;
  for (std::size_t f = 0; f < phases.size(); ++f) {
    const Complex e = phases[f];
    s += std::conj(e) * std::conj(e);
    r1 += std::conj(e) * y[f];
    r2 += e * y[f];
  }
  if (!solve_two_waves(frames, s, r1, r2, a, b)) return false;
  residual = 0;
  for (std::size_t f = 0; f < phases.size(); ++f) {
    const Complex e = phases[f];
    residual += std::norm(y[f] - a * e - b * std::conj(e));
  }
  return true;
}

bool solve_two_waves(double frames, Complex s, Complex r1, Complex r2, Complex& a, Complex& b) {
  // Normal equations [[F, S], [S*, F]] (a, b) = (r1, r2); eigenvalues F ± |S|.
  if (frames - std::abs(s) < 0.05 * frames) return false;
  const double det = frames * frames - std::norm(s);
  a = (frames * r1 - s * r2) / det;
  b = (frames * r2 - std::conj(s) * r1) / det;
  return true;
}

}  // namespace swell::validation
