#pragma once
// The per-wave-vector fit every time-resolved check shares (dispersion, direction, randomness,
// the cascade checks): a frame's spectrum at one k over the frame times is, on a right surface,
// ĥ(k, t) = a e^(−iωt) + b e^(+iωt) with a = h̃0(k) and b = conj h̃0(−k) (conventions
// §Amplitudes).
#include <complex>
#include <span>
#include <vector>

namespace swell::validation {

// Least squares of a e^(−iωt) + b e^(+iωt) to samples y_f at times t_f (phases reduced exactly,
// reference/phase.hpp). Returns false when the two columns are nearly parallel (2ω Δt ≈ 0 mod
// 2π: the normal matrix's smaller eigenvalue F − |S| below 5 % of F), so a and b are not
// identifiable; `residual` is Σ_f |y_f − fit_f|².
bool fit_two_waves(double omega, const std::vector<double>& times,
                   std::span<const std::complex<double>> y, std::complex<double>& a,
                   std::complex<double>& b, double& residual);

// The same from the phases e^(−iωt_f) of two_wave_phases, for wave vectors that share ω (the
// result is the one above, bit for bit).
void two_wave_phases(double omega, const std::vector<double>& times,
                     std::vector<std::complex<double>>& phases);
bool fit_two_waves(std::span<const std::complex<double>> phases,
                   std::span<const std::complex<double>> y, std::complex<double>& a,
                   std::complex<double>& b, double& residual);

// The solution from the sums the fit makes over the frames (S = Σ conj(e)², r1 = Σ conj(e) y,
// r2 = Σ e y over `frames` frames, each summed in frame order): what fit_two_waves computes,
// bit for bit, for a caller that sums frame by frame (the gate's streaming pass). False when
// a and b are not identifiable.
bool solve_two_waves(double frames, std::complex<double> s, std::complex<double> r1,
                     std::complex<double> r2, std::complex<double>& a, std::complex<double>& b);

}  // namespace swell::validation
