#include "swell/reference/composite_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"

namespace swell::reference {
namespace {

// The ω of the largest S among `candidates`, refined by golden-section search over the
// neighbouring candidates' interval on a log scale: a sum's or a faded spectrum's peak lies
// near one of its parts' peaks but not exactly on it.
double refined_peak(const FrequencySpectrum& s, std::vector<double> candidates) {
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                  [](double w) { return !(w > 0) || !std::isfinite(w); }),
                   candidates.end());
  if (candidates.empty()) return 0;
  std::size_t best = 0;
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    if (s(candidates[i]) > s(candidates[best])) best = i;
  }
  const double w = candidates[best];
  double lo = std::log(w / 2), hi = std::log(w * 2);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = s(std::exp(x1)), f2 = s(std::exp(x2));
  for (int i = 0; i < 100 && hi - lo > 1e-12; ++i) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = s(std::exp(x1));
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = s(std::exp(x2));
    }
  }
  const double refined = std::exp(0.5 * (lo + hi));
  return s(refined) >= s(w) ? refined : w;
}

// F · S(ω) · e^(−k(ω)² l²).
class AdjustedFrequencySpectrum final : public FrequencySpectrum {
 public:
  AdjustedFrequencySpectrum(const FrequencySpectrum& base, Dispersion dispersion, double factor,
                            double fade)
      : base_(base), dispersion_(dispersion), factor_(factor), fade_(fade) {
    peak_ = fade_ == 0 ? base_.peak_omega() : refined_peak(*this, base_.breakpoints());
  }
  double operator()(double omega) const override {
    if (!(omega > 0)) return 0;
    const double s = base_(omega);
    if (s == 0) return 0;
    if (fade_ == 0) return factor_ * s;
    const double kl = dispersion_.wavenumber(omega) * fade_;
    return factor_ * s * std::exp(-kl * kl);
  }
  double peak_omega() const override { return peak_; }
  // The fade decays as e^(−k² l²), faster than any power of ω.
  double tail_exponent() const override {
    return fade_ > 0 ? std::numeric_limits<double>::infinity() : base_.tail_exponent();
  }
  std::vector<double> breakpoints() const override {
    auto out = base_.breakpoints();
    out.push_back(peak_);
    return out;
  }
  std::string name() const override { return base_.name(); }
  std::vector<Parameter> parameters() const override {
    auto out = base_.parameters();
    if (factor_ != 1) out.push_back({"energy_factor", factor_, ""});
    if (fade_ != 0) out.push_back({"short_wave_fade", fade_, "m"});
    return out;
  }

 private:
  const FrequencySpectrum& base_;
  Dispersion dispersion_;
  double factor_, fade_;
  double peak_ = 0;
};

class AdjustedSpectrum final : public DirectionalSpectrum {
 public:
  AdjustedSpectrum(DirectionalSpectrumPtr base, double factor, double fade)
      : base_(std::move(base)), factor_(factor), fade_(fade),
        omni_(base_->omnidirectional(), base_->dispersion(), factor, fade) {}
  double psi(double kx, double ky) const override {
    const double psi = base_->psi(kx, ky);
    if (psi == 0) return 0;
    if (fade_ == 0) return factor_ * psi;
    const double k2l2 = (kx * kx + ky * ky) * fade_ * fade_;
    return factor_ * psi * std::exp(-k2l2);
  }
  const Dispersion& dispersion() const override { return base_->dispersion(); }
  const FrequencySpectrum& omnidirectional() const override { return omni_; }
  double mean_direction() const override { return base_->mean_direction(); }

 private:
  DirectionalSpectrumPtr base_;
  double factor_, fade_;
  AdjustedFrequencySpectrum omni_;
};

class SummedFrequencySpectrum final : public FrequencySpectrum {
 public:
  explicit SummedFrequencySpectrum(std::vector<const FrequencySpectrum*> parts)
      : parts_(std::move(parts)) {
    std::vector<double> candidates;
    for (const auto* p : parts_) candidates.push_back(p->peak_omega());
    peak_ = refined_peak(*this, candidates);
  }
  double operator()(double omega) const override {
    double total = 0;
    for (const auto* p : parts_) total += (*p)(omega);
    return total;
  }
  double peak_omega() const override { return peak_; }
  double tail_exponent() const override {
    double slowest = std::numeric_limits<double>::infinity();
    for (const auto* p : parts_) slowest = std::min(slowest, p->tail_exponent());
    return slowest;
  }
  std::vector<double> breakpoints() const override {
    std::vector<double> out{peak_};
    for (const auto* p : parts_) {
      for (double w : p->breakpoints()) out.push_back(w);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  std::string name() const override { return "composite"; }
  // Each part's parameters, named "<component>.<name>".
  std::vector<Parameter> parameters() const override {
    std::vector<Parameter> out;
    for (std::size_t i = 0; i < parts_.size(); ++i) {
      for (auto p : parts_[i]->parameters()) {
        p.name = std::to_string(i) + "." + p.name;
        out.push_back(std::move(p));
      }
    }
    return out;
  }

 private:
  std::vector<const FrequencySpectrum*> parts_;
  double peak_ = 0;
};

class SummedSpectrum final : public DirectionalSpectrum {
 public:
  explicit SummedSpectrum(std::vector<DirectionalSpectrumPtr> parts)
      : parts_(std::move(parts)), omni_(omnidirectional_parts(parts_)) {
    double x = 0, y = 0;
    for (const auto& p : parts_) {
      const double m0 = spectral_moment(p->omnidirectional(), 0);
      x += m0 * std::cos(p->mean_direction());
      y += m0 * std::sin(p->mean_direction());
    }
    mean_direction_ = std::atan2(y, x);
  }
  double psi(double kx, double ky) const override {
    double total = 0;
    for (const auto& p : parts_) total += p->psi(kx, ky);
    return total;
  }
  const Dispersion& dispersion() const override { return parts_.front()->dispersion(); }
  const FrequencySpectrum& omnidirectional() const override { return omni_; }
  double mean_direction() const override { return mean_direction_; }

 private:
  static std::vector<const FrequencySpectrum*> omnidirectional_parts(
      const std::vector<DirectionalSpectrumPtr>& parts) {
    std::vector<const FrequencySpectrum*> out;
    for (const auto& p : parts) out.push_back(&p->omnidirectional());
    return out;
  }
  std::vector<DirectionalSpectrumPtr> parts_;
  SummedFrequencySpectrum omni_;
  double mean_direction_ = 0;
};

}  // namespace

DirectionalSpectrumPtr adjusted_spectrum(DirectionalSpectrumPtr psi, double energy_factor,
                                         double fade_length) {
  require(std::isfinite(energy_factor) && energy_factor > 0, "energy_factor", "finite and > 0",
          energy_factor);
  require(std::isfinite(fade_length) && fade_length >= 0, "short_wave_fade", "finite and ≥ 0 (m)",
          fade_length);
  if (energy_factor == 1 && fade_length == 0) return psi;
  return std::make_shared<AdjustedSpectrum>(std::move(psi), energy_factor, fade_length);
}

DirectionalSpectrumPtr summed_spectrum(std::vector<DirectionalSpectrumPtr> parts) {
  if (parts.empty()) throw InternalError("summed_spectrum: no parts");
  if (parts.size() == 1) return parts.front();
  const Dispersion& first = parts.front()->dispersion();
  for (const auto& p : parts) {
    if (!(p->dispersion().depth() == first.depth()) || p->dispersion().gravity() != first.gravity()) {
      throw InternalError("summed_spectrum: the parts' dispersion relations differ");
    }
  }
  return std::make_shared<SummedSpectrum>(std::move(parts));
}

}  // namespace swell::reference
