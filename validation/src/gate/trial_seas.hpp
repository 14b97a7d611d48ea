#pragma once
// Ψ' of trial seas at a fixed list of wave vectors: the power table (power.cpp) asks the same
// waves again for every γ', s' or turn its bisections try.
//
// Where the case's Ψ and a trial's are both S(ω) D(ω, θ) c_g / k (reference::SpreadSpectrum)
// under the same dispersion relation and mean direction, the case's factors at each wave vector
// are made once, and a trial evaluates only what it changes: its S or D wherever that model's
// name or parameters differ from the case's, or the one it varies (`Varied`). What it shares is
// read back, so its Ψ' has the bits of its own psi (SpreadSpectrum::psi_of). Any other sea
// (Phillips, a scaled, faded, banded or summed one) is evaluated whole.
#include <array>
#include <vector>

#include "swell/reference/directional.hpp"

namespace swell::validation::detail {

class TrialSeas {
 public:
  using WaveVector = std::array<double, 2>;  // (kx, ky), rad/m
  // The factor of Ψ a trial varies: the frequency spectrum S (γ), the spreading D (s), or
  // neither but the direction (a turned sea).
  enum class Varied { spectrum, spreading, direction };

  TrialSeas(reference::DirectionalSpectrumPtr sea, std::vector<WaveVector> wave_vectors);

  std::size_t size() const { return wave_vectors_.size(); }
  const std::vector<WaveVector>& wave_vectors() const { return wave_vectors_; }
  // The case's own Ψ at the wave vectors.
  const std::vector<double>& own() const { return own_; }
  // Ψ' at the wave vectors into `out`: of `trial` (varying `varied`), turned by `turn` radians
  // counter-clockwise — Ψ'(R(−turn) k). A turn is S D(ω, θ − turn) c_g / k at the wave's own |k|
  // where the factors are kept: the value of Ψ' at the rotated vector but for the rounding of the
  // rotation (which the whole evaluation of other seas carries).
  void evaluate(const reference::DirectionalSpectrum& trial, Varied varied, double turn,
                std::vector<double>& out) const;

 private:
  reference::DirectionalSpectrumPtr sea_;
  const reference::SpreadSpectrum* spread_ = nullptr;  // sea_ as S D c_g / k, where it is one
  std::vector<WaveVector> wave_vectors_;
  std::vector<reference::SpreadSpectrum::Factors> factors_;  // where spread_ is set
  std::vector<double> own_;
};

}  // namespace swell::validation::detail
