#include "gate/trial_seas.hpp"

#include <cmath>

namespace swell::validation::detail {
namespace {

using reference::Parameter;

bool same_parameters(const std::vector<Parameter>& a, const std::vector<Parameter>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // Bit for bit: −0 and +0 or two NaNs are not taken for the same model.
    if (a[i].name != b[i].name || std::signbit(a[i].value) != std::signbit(b[i].value) ||
        !(a[i].value == b[i].value)) {
      return false;
    }
  }
  return true;
}

template <class Model>
bool same_model(const Model& a, const Model& b) {
  return &a == &b || (a.name() == b.name() && same_parameters(a.parameters(), b.parameters()));
}

}  // namespace

TrialSeas::TrialSeas(reference::DirectionalSpectrumPtr sea, std::vector<WaveVector> wave_vectors)
    : sea_(std::move(sea)), wave_vectors_(std::move(wave_vectors)) {
  spread_ = dynamic_cast<const reference::SpreadSpectrum*>(sea_.get());
  own_.reserve(wave_vectors_.size());
  if (spread_) {
    factors_.reserve(wave_vectors_.size());
    for (const auto& [kx, ky] : wave_vectors_) {
      factors_.push_back(spread_->factors(kx, ky));
      own_.push_back(reference::SpreadSpectrum::psi_of(factors_.back()));
    }
  } else {
    for (const auto& [kx, ky] : wave_vectors_) own_.push_back(sea_->psi(kx, ky));
  }
}

void TrialSeas::evaluate(const reference::DirectionalSpectrum& trial, Varied varied, double turn,
                         std::vector<double>& out) const {
  out.resize(wave_vectors_.size());
  const auto* other = dynamic_cast<const reference::SpreadSpectrum*>(&trial);
  const bool factored =
      spread_ && other && other->mean_direction() == spread_->mean_direction() &&
      other->dispersion().gravity() == spread_->dispersion().gravity() &&
      other->dispersion().depth() == spread_->dispersion().depth() &&
      other->dispersion().tension_over_density() == spread_->dispersion().tension_over_density();
  if (!factored) {
    const double c = std::cos(turn), s = std::sin(turn);
    for (std::size_t i = 0; i < wave_vectors_.size(); ++i) {
      const auto [kx, ky] = wave_vectors_[i];
      out[i] = turn == 0 ? trial.psi(kx, ky) : trial.psi(c * kx + s * ky, -s * kx + c * ky);
    }
    return;
  }
  const bool new_spectrum = varied == Varied::spectrum ||
                            !same_model(spread_->omnidirectional(), other->omnidirectional());
  const bool new_spreading = varied == Varied::spreading || turn != 0 ||
                             !same_model(spread_->spreading(), other->spreading());
  for (std::size_t i = 0; i < wave_vectors_.size(); ++i) {
    reference::SpreadSpectrum::Factors f = factors_[i];
    if (f.k != 0) {
      if (new_spectrum) f.spectrum = other->omnidirectional()(f.omega);
      if (new_spreading) f.spreading = other->spreading()(f.omega, f.theta - turn);
    }
    out[i] = reference::SpreadSpectrum::psi_of(f);
  }
}

}  // namespace swell::validation::detail
