#include "swell/reference/table_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "swell/reference/errors.hpp"

namespace swell::reference {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// Where ω falls in the table: the pair of rows to interpolate between and the weight of the
// upper one; none outside the table. A band-averaged table gives its band's row with weight 0.
struct Bracket {
  std::size_t lower = 0;
  double upper_weight = 0;
  bool inside = false;
};

Bracket bracket(const SpectrumTable& t, double omega) {
  Bracket b;
  if (!(omega > 0)) return b;
  if (!t.band_width.empty()) {
    // The band whose [ω_i − w_i/2, ω_i + w_i/2) holds ω: the nearest centre below or above.
    const auto above = std::upper_bound(t.omega.begin(), t.omega.end(), omega);
    for (auto it : {above, above == t.omega.begin() ? above : above - 1}) {
      if (it == t.omega.end()) continue;
      const std::size_t i = std::size_t(it - t.omega.begin());
      const double half = 0.5 * t.band_width[i];
      if (omega >= t.omega[i] - half && omega < t.omega[i] + half) {
        b.lower = i;
        b.inside = true;
        return b;
      }
    }
    return b;
  }
  if (omega < t.omega.front() || omega > t.omega.back()) return b;
  const auto above = std::upper_bound(t.omega.begin(), t.omega.end(), omega);
  if (above == t.omega.end()) {  // ω = the last point
    b.lower = t.omega.size() - 1;
    b.inside = true;
    return b;
  }
  b.lower = std::size_t(above - t.omega.begin()) - 1;
  b.upper_weight = (omega - t.omega[b.lower]) / (t.omega[b.lower + 1] - t.omega[b.lower]);
  b.inside = true;
  return b;
}

// The θ-integration weights of the periodic trapezoid rule: ∫ f dθ = Σ_j f_j w_j for the
// periodic piecewise-linear interpolant of f_j at θ_j.
std::vector<double> angular_weights(const std::vector<double>& theta) {
  const std::size_t n = theta.size();
  std::vector<double> w(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double before = j == 0 ? theta[0] - (theta[n - 1] - kTwoPi) : theta[j] - theta[j - 1];
    const double after = j + 1 == n ? theta[0] + kTwoPi - theta[j] : theta[j + 1] - theta[j];
    w[j] = 0.5 * (before + after);
  }
  return w;
}

class TableFrequencySpectrum final : public FrequencySpectrum {
 public:
  // values: S at each table row (1-D: the table's own; 2-D: ∫ E dθ of each row).
  TableFrequencySpectrum(std::shared_ptr<const SpectrumTable> table, std::vector<double> values)
      : table_(std::move(table)), values_(std::move(values)) {
    const auto top = std::max_element(values_.begin(), values_.end());
    peak_ = table_->omega[std::size_t(top - values_.begin())];
  }
  double operator()(double omega) const override {
    const Bracket b = bracket(*table_, omega);
    if (!b.inside) return 0;
    if (b.upper_weight == 0) return values_[b.lower];
    return (1 - b.upper_weight) * values_[b.lower] + b.upper_weight * values_[b.lower + 1];
  }
  double peak_omega() const override { return peak_; }
  double tail_exponent() const override { return std::numeric_limits<double>::infinity(); }
  // Every node (and band edge): the interpolant is smooth only between them.
  std::vector<double> breakpoints() const override {
    std::vector<double> out;
    const auto& t = *table_;
    for (std::size_t i = 0; i < t.omega.size(); ++i) {
      if (t.band_width.empty()) {
        out.push_back(t.omega[i]);
      } else {
        out.push_back(t.omega[i] - 0.5 * t.band_width[i]);
        out.push_back(t.omega[i] + 0.5 * t.band_width[i]);
      }
    }
    return out;
  }
  std::string name() const override { return "table"; }
  std::vector<Parameter> parameters() const override {
    return {{"rows", double(table_->omega.size()), ""},
            {"directions", double(table_->theta.size()), ""}};
  }

 private:
  std::shared_ptr<const SpectrumTable> table_;
  std::vector<double> values_;
  double peak_ = 0;
};

class TableDirectionalSpectrum final : public DirectionalSpectrum {
 public:
  TableDirectionalSpectrum(std::shared_ptr<const SpectrumTable> table, Dispersion dispersion)
      : table_(std::move(table)), dispersion_(dispersion),
        omni_(std::dynamic_pointer_cast<const TableFrequencySpectrum>(
            table_frequency_spectrum(table_))) {
    // ∫∫ E (cos θ, sin θ) dω dθ of the interpolant: the periodic trapezoid rule in θ, and in
    // ω the trapezoid rule (point tables) or each band's width (band tables).
    const auto w = angular_weights(table_->theta);
    const std::size_t n = table_->theta.size();
    const auto& omega = table_->omega;
    double x = 0, y = 0;
    for (std::size_t i = 0; i < omega.size(); ++i) {
      const double dw = !table_->band_width.empty() ? table_->band_width[i]
                        : omega.size() == 1         ? 1.0
                        : 0.5 * (omega[std::min(i + 1, omega.size() - 1)] - omega[i == 0 ? 0 : i - 1]);
      for (std::size_t j = 0; j < n; ++j) {
        const double e = table_->density[i * n + j] * w[j] * dw;
        x += e * std::cos(table_->theta[j]);
        y += e * std::sin(table_->theta[j]);
      }
    }
    mean_direction_ = std::atan2(y, x);
  }
  double psi(double kx, double ky) const override {
    const double k = std::hypot(kx, ky);
    if (!(k > 0)) return 0;
    const double omega = dispersion_.omega(k);
    const Bracket b = bracket(*table_, omega);
    if (!b.inside) return 0;
    const double e = b.upper_weight == 0
                         ? along_theta(b.lower, std::atan2(ky, kx))
                         : (1 - b.upper_weight) * along_theta(b.lower, std::atan2(ky, kx)) +
                               b.upper_weight * along_theta(b.lower + 1, std::atan2(ky, kx));
    return e == 0 ? 0.0 : e * dispersion_.group_velocity(k) / k;
  }
  const Dispersion& dispersion() const override { return dispersion_; }
  const FrequencySpectrum& omnidirectional() const override { return *omni_; }
  double mean_direction() const override { return mean_direction_; }

 private:
  // E of row i at θ, linear between the table's directions, across 2π from the last to the
  // first.
  double along_theta(std::size_t i, double theta) const {
    const auto& t = table_->theta;
    const double* row = table_->density.data() + i * t.size();
    if (t.size() == 1) return row[0];
    double x = std::fmod(theta - t.front(), kTwoPi);
    if (x < 0) x += kTwoPi;
    x += t.front();  // now in [θ_0, θ_0 + 2π)
    const auto above = std::upper_bound(t.begin(), t.end(), x);
    const std::size_t j = std::size_t(above - t.begin()) - 1;
    const double next_theta = j + 1 < t.size() ? t[j + 1] : t.front() + kTwoPi;
    const double next_value = j + 1 < t.size() ? row[j + 1] : row[0];
    const double u = (x - t[j]) / (next_theta - t[j]);
    return (1 - u) * row[j] + u * next_value;
  }

  std::shared_ptr<const SpectrumTable> table_;
  Dispersion dispersion_;
  std::shared_ptr<const TableFrequencySpectrum> omni_;
  double mean_direction_ = 0;
};

}  // namespace

void validate_table(const SpectrumTable& t) {
  const std::string where = t.source.empty() ? std::string("spectrum table") : t.source;
  if (t.omega.empty()) throw InvalidInput(where + ": the table has no frequencies");
  for (std::size_t i = 0; i < t.omega.size(); ++i) {
    if (!(std::isfinite(t.omega[i]) && t.omega[i] > 0)) {
      throw InvalidInput(fmt::format("{}: frequency row {} is {} (must be finite and > 0)", where,
                                     i, t.omega[i]));
    }
    if (i > 0 && !(t.omega[i] > t.omega[i - 1])) {
      throw InvalidInput(fmt::format("{}: the frequencies are not strictly increasing at row {} "
                                     "({} after {} rad/s)", where, i, t.omega[i], t.omega[i - 1]));
    }
  }
  for (std::size_t j = 0; j < t.theta.size(); ++j) {
    if (!(t.theta[j] >= 0 && t.theta[j] < kTwoPi)) {
      throw InvalidInput(fmt::format("{}: direction column {} is {} rad (must be in [0, 2π))",
                                     where, j, t.theta[j]));
    }
    if (j > 0 && !(t.theta[j] > t.theta[j - 1])) {
      throw InvalidInput(fmt::format("{}: the directions are not strictly increasing at column {}",
                                     where, j));
    }
  }
  const std::size_t columns = std::max<std::size_t>(1, t.theta.size());
  if (t.density.size() != t.omega.size() * columns) {
    throw InvalidInput(fmt::format("{}: {} density values for {} frequencies × {} directions",
                                   where, t.density.size(), t.omega.size(), t.theta.size()));
  }
  for (std::size_t i = 0; i < t.omega.size(); ++i) {
    for (std::size_t j = 0; j < columns; ++j) {
      const double v = t.density[i * columns + j];
      if (!(std::isfinite(v) && v >= 0)) {
        throw InvalidInput(t.theta.empty()
                               ? fmt::format("{}: the density at row {} is {} (must be finite and "
                                             "≥ 0)", where, i, v)
                               : fmt::format("{}: the density at row {}, column {} is {} (must be "
                                             "finite and ≥ 0)", where, i, j, v));
      }
    }
  }
  if (!t.band_width.empty()) {
    if (t.band_width.size() != t.omega.size()) {
      throw InvalidInput(fmt::format("{}: {} band widths for {} bands", where, t.band_width.size(),
                                     t.omega.size()));
    }
    for (std::size_t i = 0; i < t.omega.size(); ++i) {
      if (!(std::isfinite(t.band_width[i]) && t.band_width[i] > 0 &&
            t.omega[i] - 0.5 * t.band_width[i] >= 0)) {
        throw InvalidInput(fmt::format("{}: band {} has width {} rad/s about {} rad/s", where, i,
                                       t.band_width[i], t.omega[i]));
      }
      if (i > 0 && t.omega[i] - 0.5 * t.band_width[i] <
                       t.omega[i - 1] + 0.5 * t.band_width[i - 1] - 1e-12 * t.omega[i]) {
        throw InvalidInput(fmt::format("{}: bands {} and {} overlap", where, i - 1, i));
      }
    }
  }
}

FrequencySpectrumPtr table_frequency_spectrum(std::shared_ptr<const SpectrumTable> table) {
  validate_table(*table);
  std::vector<double> values;
  if (!table->is_directional()) {
    values = table->density;
  } else {
    const auto w = angular_weights(table->theta);
    const std::size_t n = table->theta.size();
    for (std::size_t i = 0; i < table->omega.size(); ++i) {
      double s = 0;
      for (std::size_t j = 0; j < n; ++j) s += table->density[i * n + j] * w[j];
      values.push_back(s);
    }
  }
  if (std::all_of(values.begin(), values.end(), [](double v) { return v == 0; })) {
    throw InvalidInput((table->source.empty() ? std::string("spectrum table") : table->source) +
                       ": every density is zero");
  }
  return std::make_shared<TableFrequencySpectrum>(std::move(table), std::move(values));
}

DirectionalSpectrumPtr table_directional_spectrum(std::shared_ptr<const SpectrumTable> table,
                                                  Dispersion dispersion) {
  validate_table(*table);
  if (!table->is_directional()) {
    throw InternalError("table_directional_spectrum: a 1-D table needs a spreading model");
  }
  return std::make_shared<TableDirectionalSpectrum>(std::move(table), dispersion);
}

}  // namespace swell::reference
