// The gate's power (gate/power.hpp, docs/gate.md §11): the smallest error of each kind the gate
// detects with 90 % power on a case's sampling, from the checks' own laws. Everything is
// deterministic: the simulations draw from a fixed seed with common random numbers, so every
// bisection step sees the same draws and the table is the same on every run.
#include "swell/validation/gate/power.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <numeric>
#include <random>
#include <span>

#include "common/parallel_tasks.hpp"
#include "common/sorted_by_key.hpp"
#include "gate/trial_seas.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/phase.hpp"
#include "swell/validation/checks/ocean_check_table.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/half.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/validation/stats/rounding.hpp"
#include "swell/validation/stats/statistics.hpp"
#include "swell/validation/stats/wave_fit.hpp"

namespace swell::validation {
namespace {

using Complex = std::complex<double>;
using detail::TrialSeas;
constexpr double kPower = 0.9;
constexpr double kFp64 = 0x1p-53;
constexpr double kDegree = 180.0 / std::numbers::pi;
// Draws of the simulated statistics: the power's sampling sd at 90 % is √(0.09/M), 0.01 at
// M = 1000 (ring shapes) and 0.005 at 4000 (the direction's four-dimensional score).
constexpr int kShapeDraws = 1000, kDirectionDraws = 4000;
// The direction and spreading sums run over at most this many entries (an even stride through
// them, scaled back up): their mean and covariance are sums of many small terms.
constexpr std::size_t kMostEntries = 20000;

// One resolved wave vector of the half plane, as the gate's analysis keeps it.
using Wave = HalfPlaneWave;

struct Setup {
  reference::DirectionalSpectrumPtr psi;
  // The resolved waves sorted by |k|: pointers into the analysis' half plane, or into own_waves
  // where the table evaluates them itself. Pointers (8 bytes) rather than copies (80): at 4096²
  // the copies were half a gigabyte beside the gate's passes.
  std::vector<const Wave*> waves;
  std::vector<Wave> own_waves;
  std::vector<double> times;
  double mean_square = 0, floor = 0, u = kFp64, storage = 0, log2n = 1, alpha_per_check = 0;
  std::size_t count = 0;
  std::vector<double> half_plane_weights;  // 2μ over the half plane: the energy check's law
  std::span<const double> mu;              // μ(k) over the samples: the analysis' or own_mu
  std::vector<double> own_mu;
};

// The case on its samples as the table reads it, into `s` (which `s.mu` may point into): μ
// and the resolved waves by |k|, taken from what the gate's analysis holds (`samples`) or
// evaluated from τ — the same numbers, as the analysis evaluates them the same way.
void make_setup(Setup& s, const CaseFile& case_file, double alpha, double unit_roundoff, double storage_roundoff,
                const std::vector<double>& tau, const CaseSamples* samples) {
  const auto& c = case_file.ocean;
  const reference::Sampling sampling = c.sampling();
  if (samples) {
    s.mu = samples->expected_periodogram;
  } else {
    s.own_mu = expected_periodogram(tau, sampling);
    s.mu = s.own_mu;
  }
  const auto& mu = s.mu;
  s.psi = c.directional_spectrum();
  s.count = sampling.size();
  s.log2n = std::max(1.0, std::log2(double(s.count)));
  s.u = std::max(unit_roundoff, kFp64);
  s.storage = storage_roundoff;
  s.mean_square = std::accumulate(mu.begin(), mu.end(), 0.0);
  // The analysis' resolution floor (checks/ocean/analysis.hpp), on the expected mean h².
  s.floor = std::max(1e6 * s.u * s.u, 1e4 * s.storage * s.storage) * s.mean_square / double(s.count);
  const std::size_t frames = std::size_t(std::max(1, c.frames));
  s.alpha_per_check = alpha / double(statistical_ocean_checks(case_file.scale == SpectrumScale::free, frames).size());
  for (int f = 0; f < c.frames; ++f) s.times.push_back(c.time(f));
  s.half_plane_weights.reserve(s.count / 2 + 1);
  auto resolved = [&](double wave_mu) { return wave_mu >= s.floor && wave_mu > 0; };
  std::span<const Wave> candidates;
  if (samples) {
    for (const Wave& w : samples->half_plane) s.half_plane_weights.push_back(2 * w.mu);
    candidates = samples->half_plane;
  } else {
    for (std::size_t e = 0; e < s.count; ++e) {
      if (!sampling.carries_energy(e)) continue;
      const auto [n, m] = sampling.wave_index(e);
      if (!in_half_plane(n, m)) continue;
      s.half_plane_weights.push_back(2 * mu[e]);
      if (!resolved(mu[e])) continue;
      Wave w;
      w.index = e;
      w.minus_index = sampling.conjugate(e);
      w.kx = n * sampling.dkx(), w.ky = m * sampling.dky(), w.k = std::hypot(w.kx, w.ky);
      w.omega = c.omega(w.k);
      w.theta = std::atan2(w.ky, w.kx);
      w.mu = mu[e];
      w.tau_plus = tau[e], w.tau_minus = tau[w.minus_index];
      s.own_waves.push_back(w);
    }
    candidates = s.own_waves;
  }
  // By |k|, equal |k| in the samples' order (a stable sort's order), through a sort of (|k|,
  // position) keys of the resolved candidates.
  std::vector<std::size_t> kept;
  kept.reserve(std::size_t(std::count_if(candidates.begin(), candidates.end(),
                                         [&](const Wave& w) { return resolved(w.mu); })));
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (resolved(candidates[i].mu)) kept.push_back(i);
  }
  const auto order = detail::sorted_by_key(kept.size(), [&](std::size_t i) { return candidates[kept[i]].k; });
  s.waves.resize(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) s.waves[i] = &candidates[kept[order[i].second]];
}

// visit(wave, rank) for the resolved waves in |k| order. They lie in the half plane's order,
// so each is a cache miss: the next ones are fetched while this one is visited (at 4096² a plain
// loop over the 8 × 10⁶ pointers took about a second).
template <class Visit>
void for_each_by_k(const Setup& s, Visit&& visit) {
  constexpr std::size_t kAhead = 16;
  const std::size_t n = s.waves.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kAhead < n) {
      const char* next = reinterpret_cast<const char*>(s.waves[i + kAhead]);
      __builtin_prefetch(next);
      __builtin_prefetch(next + sizeof(Wave) - 1);
    }
    visit(*s.waves[i], i);
  }
}

// The smallest x in [low, high] where `detects(x)` holds (to 0.3 %): the first of 17 sizes spaced evenly in
// log x that is detected, then bisection in log x below it (detection grows with the error up to
// there; past it a symmetric sea can look right again — Phillips' cos² turned by 180°). NaN when
// none is detected.
double smallest_detected(double low, double high, const std::function<bool(double)>& detects) {
  constexpr int kSteps = 16;
  double previous = low;
  bool found = false;
  for (int i = 0; i <= kSteps; ++i) {
    const double x = low * std::pow(high / low, double(i) / kSteps);
    if (detects(x)) {
      if (i == 0) return low;
      low = previous, high = x, found = true;
      break;
    }
    previous = x;
  }
  if (!found) return std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 40 && high / low > 1.003; ++i) {
    const double middle = std::sqrt(low * high);
    (detects(middle) ? high : low) = middle;
  }
  return high;
}

// ------------------------------------------------------------------ spectrum.shape

// spectrum.shape's rings (checks/ocean/analysis.cpp ring_shape): the resolved waves by |k| in
// R = clamp(n/64, 1, 24) rings of equal count. Under an engine whose μ' = w μ, a ring's Σ u is
// Σ w_i E_i, drawn here as the Gamma of its mean Σw and variance Σw²; its two-sided Gamma(n, 1)
// p, Fisher's method, α/2. Gamma draws and p-values by Wilson and Hilferty's cube root (Gamma(k)
// ≈ k (1 − 1/(9k) + z/(3√k))³; rings hold ≥ 64 waves, where it is accurate to a few per cent
// of p in the tails that matter here): the incomplete gamma function itself was 90 % of the
// gate's time on a 128² case. Common random numbers: every bisection step sees the same z.
class ShapePower {
 public:
  ShapePower(const Setup& s, double alpha) : s_(s) {
    const int n = int(s.waves.size());
    rings_ = std::clamp(n / 64, 1, 24);
    std::mt19937_64 random(20261206);
    std::normal_distribution<double> normal(0, 1);
    normals_.resize(std::size_t(kShapeDraws) * rings_);
    for (double& x : normals_) x = normal(random);
    critical_ = boost::math::quantile(boost::math::complement(boost::math::chi_squared(2.0 * rings_), alpha / 2));
    for (int r = 0; r < rings_; ++r) {
      counts_.push_back((r + 1) * n / rings_ - r * n / rings_);
      const int begin = r * n / rings_, end = (r + 1) * n / rings_;
      const int stride = std::max(1, (end - begin) / 512);
      for (int i = begin; i < end; i += stride) sampled_.push_back(s.waves[std::size_t(i)]);
    }
  }
  int rings() const { return rings_; }
  // The power against an engine whose energy is f × the case's on every wave.
  double power_of_factor(double f) const {
    std::vector<double> shape(counts_.begin(), counts_.end()), scale(rings_, f);
    return power(shape, scale);
  }
  // The waves whose μ'/μ the ring moments below read, in the order they read them: at most
  // 512 per ring, evenly spread.
  const std::vector<const Wave*>& sampled() const { return sampled_; }
  // The power against an engine whose μ'/μ at each sampled() wave is `ratios`.
  double power(const std::vector<double>& ratios) const {
    const int n = int(s_.waves.size());
    std::vector<double> shape(rings_), scale(rings_);
    std::size_t next = 0;
    for (int r = 0; r < rings_; ++r) {
      const int begin = r * n / rings_, end = (r + 1) * n / rings_;
      const int stride = std::max(1, (end - begin) / 512);
      double sum = 0, squares = 0;
      int used = 0;
      for (int i = begin; i < end; i += stride, ++used) {
        const double w = ratios[next++];
        sum += w;
        squares += w * w;
      }
      const double factor = double(end - begin) / used;
      sum *= factor, squares *= factor;
      shape[r] = sum * sum / squares;
      scale[r] = squares / sum;
    }
    return power(shape, scale);
  }

 private:
  // Σ u of ring r drawn as scale[r] × Gamma(shape[r]).
  double power(const std::vector<double>& shape, const std::vector<double>& scale) const {
    int detected = 0;
    for (int d = 0; d < kShapeDraws; ++d) {
      double fisher = 0;
      for (int r = 0; r < rings_; ++r) {
        const double k = shape[r], z = normals_[std::size_t(d) * rings_ + r];
        const double cube = 1 - 1 / (9 * k) + z / (3 * std::sqrt(k));
        const double x = scale[r] * k * std::max(cube, 0.0) * cube * cube;
        // The null's Gamma(n, 1) two-sided p of x, by the same cube root.
        const double n = counts_[std::size_t(r)];
        const double z_observed = (std::cbrt(x / n) - (1 - 1 / (9 * n))) * 3 * std::sqrt(n);
        const double p = std::erfc(std::abs(z_observed) / std::numbers::sqrt2);
        fisher += p > 0 ? -2 * std::log(p) : std::numeric_limits<double>::infinity();
      }
      detected += fisher > critical_;
    }
    return double(detected) / kShapeDraws;
  }
  const Setup& s_;
  int rings_ = 1;
  std::vector<int> counts_;
  std::vector<const Wave*> sampled_;
  std::vector<double> normals_;
  double critical_ = 0;
};

// ------------------------------------------------------------------ direction.distribution

// A 4×4 symmetric positive definite matrix's Cholesky factor (lower); false where it is not.
bool cholesky(const std::array<std::array<double, 4>, 4>& a, std::array<std::array<double, 4>, 4>& l) {
  l = {};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j <= i; ++j) {
      double sum = a[i][j];
      for (int k = 0; k < j; ++k) sum -= l[i][k] * l[j][k];
      if (i == j) {
        if (!(sum > 1e-12 * std::max(1.0, a[i][i]))) return false;
        l[i][i] = std::sqrt(sum);
      } else {
        l[i][j] = sum / l[j][j];
      }
    }
  }
  return true;
}

// direction.distribution's score D = Σ (u − 1)(g − ḡ), g = (cos θ, sin θ, cos 2θ, sin 2θ), over
// both travelling waves of each resolved wave vector: under an engine whose τ' = r τ, D is
// normal (a sum of many small independent terms) with mean Σ (r − 1)(g − ḡ) and covariance
// Σ r² (g − ḡ)(g − ḡ)ᵀ; T = Dᵀ C⁻¹ D with the null's C against χ²(4) at α/2.
class DirectionPower {
 public:
  DirectionPower(const Setup& s, double alpha) {
    // Both travelling waves of each resolved wave vector above the floor, every stride-th of
    // them kept (counted first: at 4096² the whole list was 400 MB for the 20000 kept).
    std::size_t count = 0;
    for_each_by_k(s, [&](const Wave& w, std::size_t) {
      count += std::size_t(w.tau_plus >= s.floor) + std::size_t(w.tau_minus >= s.floor);
    });
    stride_ = std::max<std::size_t>(1, count / kMostEntries);
    std::vector<Entry> entries;
    std::size_t position = 0;
    auto keep = [&](const Entry& entry) {
      if (position++ % stride_ == 0) entries.push_back(entry);
    };
    for_each_by_k(s, [&](const Wave& w, std::size_t) {
      if (w.tau_plus >= s.floor) keep({w.kx, w.ky, w.theta});
      if (w.tau_minus >= s.floor) keep({-w.kx, -w.ky, w.theta + std::numbers::pi});
    });
    std::array<double, 4> mean{};
    for (const Entry& e : entries) {
      const auto g = harmonics(e.theta);
      for (int j = 0; j < 4; ++j) mean[j] += g[j];
    }
    for (double& v : mean) v /= double(std::max<std::size_t>(entries.size(), 1));
    std::vector<TrialSeas::WaveVector> wave_vectors;
    for (const Entry& e : entries) {
      auto g = harmonics(e.theta);
      for (int j = 0; j < 4; ++j) g[j] -= mean[j];
      centred_.push_back(g);
      wave_vectors.push_back({e.kx, e.ky});
    }
    seas_.emplace(s.psi, std::move(wave_vectors));
    critical_ = boost::math::quantile(boost::math::complement(boost::math::chi_squared(4), alpha / 2));
    std::mt19937_64 random(20261207);
    std::normal_distribution<double> normal(0, 1);
    normals_.resize(std::size_t(kDirectionDraws));
    for (auto& z : normals_) {
      for (double& x : z) x = normal(random);
    }
  }
  bool usable() const { return centred_.size() >= 8; }
  // The wave vectors the score reads, and the case's Ψ there.
  const TrialSeas& seas() const { return *seas_; }
  // The power against an engine whose Ψ' at seas()' wave vectors is `psi` (a rotated or
  // otherwise spread sea).
  double power(const std::vector<double>& psi) const {
    const std::vector<double>& psi0 = seas_->own();
    std::array<double, 4> m{};
    std::array<std::array<double, 4>, 4> c0{}, c1{};
    for (std::size_t j = 0; j < centred_.size(); ++j) {
      const double r = psi0[j] > 0 ? psi[j] / psi0[j] : 1.0;
      const auto& g = centred_[j];
      for (int a = 0; a < 4; ++a) {
        m[a] += (r - 1) * g[a];
        for (int b = 0; b < 4; ++b) {
          c0[a][b] += g[a] * g[b];
          c1[a][b] += r * r * g[a] * g[b];
        }
      }
    }
    const double scale = double(stride_);
    for (int a = 0; a < 4; ++a) {
      m[a] *= scale;
      for (int b = 0; b < 4; ++b) c0[a][b] *= scale, c1[a][b] *= scale;
    }
    std::array<std::array<double, 4>, 4> l0, l1;
    // A few waves with a huge ratio (a back lobe turned forward) make C1 nearly rank one: a
    // relative ridge keeps its factor finite without moving the draws it describes.
    double largest = 0;
    for (int a = 0; a < 4; ++a) largest = std::max(largest, c1[a][a]);
    for (int a = 0; a < 4; ++a) c1[a][a] += 1e-9 * largest;
    if (!cholesky(c0, l0) || !cholesky(c1, l1)) return 0;
    int detected = 0;
    for (const auto& z : normals_) {
      std::array<double, 4> d = m;
      for (int a = 0; a < 4; ++a) {
        for (int b = 0; b <= a; ++b) d[a] += l1[a][b] * z[b];
      }
      // T = dᵀ C0⁻¹ d = |L0⁻¹ d|².
      std::array<double, 4> y{};
      double t = 0;
      for (int a = 0; a < 4; ++a) {
        double sum = d[a];
        for (int b = 0; b < a; ++b) sum -= l0[a][b] * y[b];
        y[a] = sum / l0[a][a];
        t += y[a] * y[a];
      }
      detected += t > critical_;
    }
    return double(detected) / kDirectionDraws;
  }

 private:
  struct Entry {
    double kx, ky, theta;
  };
  static std::array<double, 4> harmonics(double theta) {
    return {std::cos(theta), std::sin(theta), std::cos(2 * theta), std::sin(2 * theta)};
  }
  std::size_t stride_ = 1;
  std::vector<std::array<double, 4>> centred_;
  std::optional<TrialSeas> seas_;
  double critical_ = 0;
  std::vector<std::array<double, 4>> normals_;
};

// ------------------------------------------------------------------ dispersion

// dispersion.residual's fraction when every wave runs at ω(1 + ε) and the fit is made at ω:
// each travelling wave's share of its energy left outside the span of e^(∓iωt) over the frames
// (the same least squares, wave_fit.hpp), weighted by its power — over `waves`, the most
// energetic (an energy-weighted mean: the rest move it little).
double dispersion_fraction(const Setup& s, const std::vector<const Wave*>& waves, double epsilon) {
  std::vector<Complex> phases, y(s.times.size());
  double left = 0, energy = 0, phases_omega = -1;
  const double frames = double(s.times.size());
  for (const Wave* wave : waves) {
    const Wave& w = *wave;
    if (w.omega != phases_omega) {
      phases_omega = w.omega;
      two_wave_phases(w.omega, s.times, phases);
    }
    Complex a, b;
    double minus = 0, plus = 0;
    const double shifted = w.omega * (1 + epsilon);
    for (std::size_t f = 0; f < y.size(); ++f) y[f] = std::polar(1.0, -reference::reduced_phase(shifted, s.times[f]));
    if (!fit_two_waves(phases, y, a, b, minus)) continue;
    for (auto& v : y) v = std::conj(v);
    fit_two_waves(phases, y, a, b, plus);
    left += w.tau_plus * minus + w.tau_minus * plus;
    energy += frames * (w.tau_plus + w.tau_minus);
  }
  return energy > 0 ? left / energy : 0;
}

// The frames' energy over what dispersion.residual's fits see: Σ (τ+ + τ−) over every wave
// over that of the waves whose two waves the frame times tell apart (fit_two_waves accepts
// them) — 2 when those carry the sea (the half plane's half), far more when a loop period
// leaves only weak waves identifiable. The check's bound scales its rounding by it.
double fits_energy_share(const Setup& s) {
  std::vector<Complex> phases, y(s.times.size());
  double all = 0, fitted = 0, phases_omega = -1;
  bool identifiable = false;
  for_each_by_k(s, [&](const Wave& w, std::size_t) {
    const double power = w.tau_plus + w.tau_minus;
    all += power;
    if (w.omega != phases_omega) {
      phases_omega = w.omega;
      two_wave_phases(w.omega, s.times, phases);
      Complex a, b;
      double residual = 0;
      identifiable = fit_two_waves(phases, y, a, b, residual);
    }
    if (identifiable) fitted += power;
  });
  return 2 * all / std::max(2 * fitted, all * 1e-300);
}

// JONSWAP γ: spectrum.shape against the case's spectrum with γ' (its μ'/μ at each wave).
PowerLine gamma_power_line(const Setup& s, const reference::OceanCase& c, const ShapePower& shape) {
  PowerLine gamma;
  gamma.error = "JONSWAP γ";
  const auto found = c.spectrum.numbers.find("gamma");
  const bool jonswap = c.spectrum.model == "jonswap" || c.spectrum.model == "tma";
  if (!jonswap || c.components().size() > 1) {
    gamma.smallest = "n/a (the case's spectrum has no γ)";
    gamma.below = gamma.above = std::numeric_limits<double>::quiet_NaN();
  } else {
    const double gamma0 = found != c.spectrum.numbers.end() ? found->second : 3.3;
    // Ψ(k) and Ψ(−k) at the waves the rings read, in turn; the case's sums once for every γ'.
    std::vector<TrialSeas::WaveVector> wave_vectors;
    for (const Wave* w : shape.sampled()) {
      wave_vectors.push_back({w->kx, w->ky});
      wave_vectors.push_back({-w->kx, -w->ky});
    }
    const TrialSeas seas(s.psi, std::move(wave_vectors));
    std::vector<double> own(shape.sampled().size());
    for (std::size_t j = 0; j < own.size(); ++j) own[j] = seas.own()[2 * j] + seas.own()[2 * j + 1];
    std::vector<double> trial;
    auto power_at = [&](double g) {
      reference::OceanCase other = c;
      other.spectrum.numbers["gamma"] = std::max(1.0, g);  // γ ≥ 1; γ0/(γ0) may round below it
      seas.evaluate(*other.directional_spectrum(), TrialSeas::Varied::spectrum, 0, trial);
      std::vector<double> ratios(own.size());
      for (std::size_t j = 0; j < own.size(); ++j) {
        ratios[j] = own[j] > 0 ? (trial[2 * j] + trial[2 * j + 1]) / own[j] : 1.0;
      }
      return shape.power(ratios);
    };
    const double up = smallest_detected(1.001, 20, [&](double q) { return power_at(gamma0 * q) >= kPower; });
    const double lowest = 1 / gamma0;  // γ ≥ 1
    const double down = lowest < 0.999
                            ? smallest_detected(1.001, 1 / lowest, [&](double q) { return power_at(gamma0 / q) >= kPower; })
                            : std::numeric_limits<double>::quiet_NaN();
    gamma.above = gamma0 * up;
    gamma.below = gamma0 / down;
    gamma.smallest = fmt::format("γ ≥ {:.4g} or ≤ {:.4g} (the case's {:g})", gamma.above, gamma.below, gamma0);
    gamma.check = "spectrum.shape";
    gamma.method = fmt::format("simulation ({} draws of {} rings)", kShapeDraws, shape.rings());
  }
  return gamma;
}

// ω × (1 ± ε) on every wave: the smallest ε that dispersion.residual (the fit's residual,
// closed form) or dispersion.omega (its bound on the measured ω of the most energetic waves)
// detects, and which of them in `omega_check`; NaN with fewer than 3 frames.
double omega_epsilon(const Setup& s, std::string& omega_check) {
  double epsilon = std::numeric_limits<double>::quiet_NaN();
  if (s.times.size() >= 3) {
    // As dispersion.residual judges: the rounding against the frames' energy where the fitted
    // waves carry less than the half plane's half of it.
    const double share = fits_energy_share(s);
    const double bound = std::pow(rounding_budget(kCompoundRounding, s.u, s.log2n), 2) * std::max(1.0, share / 2) +
                         4 * s.storage * s.storage * share;
    // The most energetic waves, ties in τ+ + τ− and in ω taken in |k| order (their ranks in
    // s.waves): the kMostWaves best in one pass through a heap whose top is the worst kept (a
    // total order, so the same waves as a sort of all of them would keep).
    struct Candidate {
      double power = 0;
      std::size_t rank = 0;
    };
    const auto better = [](const Candidate& x, const Candidate& y) {
      return x.power > y.power || (x.power == y.power && x.rank < y.rank);
    };
    constexpr std::size_t kMostWaves = 4000;
    std::vector<Candidate> kept;
    kept.reserve(std::min(kMostWaves, s.waves.size()));
    for_each_by_k(s, [&](const Wave& w, std::size_t rank) {
      const Candidate c{w.tau_plus + w.tau_minus, rank};
      if (kept.size() < kMostWaves) {
        kept.push_back(c);
        std::push_heap(kept.begin(), kept.end(), better);
      } else if (better(c, kept.front())) {
        std::pop_heap(kept.begin(), kept.end(), better);
        kept.back() = c;
        std::push_heap(kept.begin(), kept.end(), better);
      }
    });
    std::sort(kept.begin(), kept.end(), [&](const Candidate& x, const Candidate& y) {
      const double ox = s.waves[x.rank]->omega, oy = s.waves[y.rank]->omega;
      return ox < oy || (ox == oy && x.rank < y.rank);
    });
    std::vector<const Wave*> strongest(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) strongest[i] = s.waves[kept[i].rank];
    // The fraction grows as ε² while εωT ≪ 1 (T the frames' span): from ε = 10⁻⁶, a few steps of
    // ε ← ε √(bound/fraction) reach the ε where it meets the bound (to 0.1 %).
    double e = 1e-6;
    for (int i = 0; i < 12; ++i) {
      const double fraction = dispersion_fraction(s, strongest, e);
      if (!(fraction > 0)) break;
      const double step = std::sqrt(bound / fraction);
      e = std::min(0.5, e * step);
      if (std::abs(step - 1) < 1e-3) {
        epsilon = e;
        break;
      }
    }
    omega_check = "dispersion.residual";
    double dt = 0;
    for (std::size_t f = 1; f < s.times.size(); ++f) dt = std::max(dt, s.times[f] - s.times[f - 1]);
    bool below_nyquist = false;
    for_each_by_k(s, [&](const Wave& w, std::size_t) {
      below_nyquist = below_nyquist || (w.omega > 0 && 1.5 * w.omega < 0.95 * std::numbers::pi / dt);
    });
    const double omega_bound = std::max(1e-6, rounding_budget(kCompoundRounding, s.u, s.log2n));
    if (below_nyquist && !(epsilon <= omega_bound)) epsilon = omega_bound, omega_check = "dispersion.omega";
  }
  return epsilon;
}

PowerLine omega_power_line(const Setup& s, const reference::OceanCase& c, double epsilon,
                           const std::string& omega_check) {
  PowerLine line;
  line.error = "ω, relative, on every wave";
  line.above = epsilon, line.below = -epsilon;
  if (std::isnan(epsilon)) {
    line.smallest = "none (dispersion needs ≥ 3 frames)";
  } else {
    line.smallest = fmt::format("± {:.2g}", epsilon);
    line.check = omega_check;
    line.method = "closed form";
    // At the peak k_p (the most energetic wave): ω ∝ √g, and ω² = g k tanh(k h).
    // The first of the largest μ in |k| order (max_element's).
    const Wave* peak = s.waves.front();
    for_each_by_k(s, [&](const Wave& w, std::size_t) {
      if (peak->mu < w.mu) peak = &w;
    });
    const double kp = peak->k;
    const double tanh0 = std::isinf(c.depth) ? 1.0 : std::tanh(kp * c.depth);
    const double shallower = std::pow(1 - epsilon, 2) * tanh0;
    line.note = fmt::format("g × {:.6g} or × {:.6g}; a depth of {:.4g} m instead of {} at the peak (k = {:.3g} rad/m)",
                            std::pow(1 + epsilon, 2), std::pow(1 - epsilon, 2), std::atanh(shallower) / kp,
                            std::isinf(c.depth) ? std::string("deep water") : fmt::format("{:g} m", c.depth), kp);
  }
  return line;
}

// Direction offset and spreading: direction.distribution's score, simulated.
void direction_power_lines(const Setup& s, const reference::OceanCase& c, PowerLine& offset_line,
                           PowerLine& spreading_line) {
  const DirectionPower direction(s, s.alpha_per_check);
  std::vector<double> trial;
  {
    PowerLine line;
    line.error = "mean direction offset";
    if (!direction.usable() || s.times.size() < 2) {
      line.smallest = "none (direction needs ≥ 2 frames at identifiable times)";
      line.above = line.below = std::numeric_limits<double>::quiet_NaN();
    } else {
      const double offset = smallest_detected(0.01, 180, [&](double degrees) {
        direction.seas().evaluate(*s.psi, TrialSeas::Varied::direction, degrees / kDegree, trial);  // Ψ(R(−Δθ) k)
        return direction.power(trial) >= kPower;
      });
      line.above = offset, line.below = -offset;
      line.smallest = std::isnan(offset) ? "none up to 180°" : fmt::format("{:.3g}°", offset);
      line.check = "direction.distribution";
      line.method = fmt::format("simulation ({} draws of the score)", kDirectionDraws);
    }
    offset_line = line;
  }
  {
    PowerLine line;
    line.error = "spreading s";
    const auto found = c.spreading.numbers.find("s");
    if (c.spreading.model != "cos2s" || found == c.spreading.numbers.end() || c.components().size() > 1) {
      line.smallest = "n/a (the case's spreading has no s)";
      line.above = line.below = std::numeric_limits<double>::quiet_NaN();
    } else if (!direction.usable() || s.times.size() < 2) {
      line.smallest = "none (direction needs ≥ 2 frames at identifiable times)";
      line.above = line.below = std::numeric_limits<double>::quiet_NaN();
    } else {
      const double s0 = found->second;
      auto detects = [&](double value) {
        reference::OceanCase other = c;
        other.spreading.numbers["s"] = std::max(value, 1e-6 * s0);
        direction.seas().evaluate(*other.directional_spectrum(), TrialSeas::Varied::spreading, 0, trial);
        return direction.power(trial) >= kPower;
      };
      const double up = smallest_detected(1.001, 100, [&](double q) { return detects(s0 * q); });
      const double down = smallest_detected(1.001, 100, [&](double q) { return detects(s0 / q); });
      line.above = s0 * up, line.below = s0 / down;
      line.smallest = fmt::format("s ≥ {:.4g} or ≤ {:.4g} (the case's {:g})", line.above, line.below, s0);
      line.check = "direction.distribution";
      line.method = fmt::format("simulation ({} draws of the score)", kDirectionDraws);
    }
    spreading_line = line;
  }
}

// λ: derived.disp_x is exact; its bound (checks/ocean/derived.cpp) on the expected fields is
// the smallest relative error of λ it sees, with certainty.
PowerLine lambda_power_line(const Setup& s, const reference::OceanCase& c) {
  const reference::Sampling sampling = c.sampling();
  const double lambda = c.choppiness == 0 ? 1.0 : c.choppiness;
  double mean_m2 = 0, own = 0;
  const auto& mu = s.mu;
  for (std::size_t e = 0; e < s.count; ++e) {
    if (!sampling.carries_energy(e)) continue;
    const auto [n, m] = sampling.wave_index(e);
    const double kx = n * sampling.dkx(), ky = m * sampling.dky(), k = std::hypot(kx, ky);
    const double m2 = c.choppiness * c.choppiness * kx * kx / (k * k);
    mean_m2 += m2;
    own += lambda * lambda * kx * kx / (k * k) * mu[e];
  }
  mean_m2 /= double(s.count);
  const double own_case = c.choppiness == 0 ? 0.0 : own;
  const double transform = s.log2n * s.log2n * own_case;
  const double rounding = std::sqrt(s.u * s.u * (s.mean_square * mean_m2 + own_case + transform) / own);
  const double storage = std::sqrt(s.storage * s.storage * (s.mean_square * mean_m2 + own_case) / own);
  const double bound = 10 * rounding + 3 * storage + rounding_budget(kCompoundRounding, kFp64, s.log2n);
  PowerLine line;
  line.error = "choppiness λ";
  line.above = bound, line.below = -bound;
  line.smallest = c.choppiness == 0 ? fmt::format("any λ ≥ {:.2g} (the case's λ = 0)", bound)
                                    : fmt::format("± {:.2g} relative (λ = {:g})", bound, c.choppiness);
  line.check = "derived.disp_x";
  line.method = "closed form";
  line.note = "when the frames carry displacements";
  return line;

}

}  // namespace

namespace {

PowerTable make_power_table(const CaseFile& case_file, double alpha, double unit_roundoff, double storage_roundoff,
                            const std::vector<double>& travelling_power, const CaseSamples* samples, int threads) {
  if (case_file.is_probe_case() || case_file.is_cascade_set()) {
    throw InvalidInput("the power table is made for one surface's case (not a probes case or a cascade set)");
  }
  require(alpha > 0 && alpha < 1, "alpha", "in (0, 1)", alpha);
  Setup setup;
  make_setup(setup, case_file, alpha, unit_roundoff, storage_roundoff, travelling_power, samples);
  const Setup& s = setup;
  PowerTable table;
  table.power = kPower;
  table.alpha = alpha;
  table.alpha_per_check = s.alpha_per_check;
  table.precision = storage_roundoff > 0 ? "half" : s.u > 2 * kFp64 ? "float" : "double";
  if (s.waves.size() < 2) return table;
  const auto& c = case_file.ocean;
  const bool absolute = case_file.scale == SpectrumScale::absolute;

  // The lines are independent but for their last assembly: their pieces run side by side on
  // `threads` threads (the energy law's four quantiles each a piece), numbered in the order the
  // table used to make them, so an error is the one a sequential run meets first.
  const ShapePower shape(s, s.alpha_per_check);
  double shape_up = 0, shape_down = 0;
  std::array<double, 4> energy_quantiles{};  // α/2, 1 − α/2, 1 − power, power
  std::optional<stats::WeightedExponentialSum> law;
  if (absolute) law.emplace(s.half_plane_weights);
  PowerLine gamma_line, omega_line, offset_line, spreading_line, lambda_line;
  double epsilon = std::numeric_limits<double>::quiet_NaN();
  std::string omega_check;
  const std::array<std::function<void()>, 9> pieces = {
      [&] {
        shape_up = smallest_detected(1.0001, 1e4, [&](double f) { return shape.power_of_factor(f) >= kPower; });
        shape_down = 1 / smallest_detected(1.0001, 1e4, [&](double f) {
          return shape.power_of_factor(1 / f) >= kPower;
        });
      },
      [&] { if (law) energy_quantiles[0] = law->quantile(1 - s.alpha_per_check / 2); },
      [&] { if (law) energy_quantiles[1] = law->quantile(1 - kPower); },
      [&] { if (law) energy_quantiles[2] = law->quantile(s.alpha_per_check / 2); },
      [&] { if (law) energy_quantiles[3] = law->quantile(kPower); },
      [&] { gamma_line = gamma_power_line(s, c, shape); },
      [&] { epsilon = omega_epsilon(s, omega_check); omega_line = omega_power_line(s, c, epsilon, omega_check); },
      [&] { direction_power_lines(s, c, offset_line, spreading_line); },
      [&] { lambda_line = lambda_power_line(s, c); },
  };
  detail::run_tasks(pieces.size(), threads, [&](std::size_t i) { pieces[i](); });

  // Energy × f: energy's law in closed form (the f whose 10 % quantile of f X reaches the
  // check's upper bound), and spectrum.shape's rings simulated; the smaller error of the two.
  {
    PowerLine line;
    line.error = "energy factor";
    double up = absolute ? shape_up : std::numeric_limits<double>::quiet_NaN();
    double down = absolute ? shape_down : std::numeric_limits<double>::quiet_NaN();
    std::string up_check = "spectrum.shape", down_check = "spectrum.shape";
    if (absolute) {
      const double energy_up = energy_quantiles[0] / energy_quantiles[1];
      const double energy_down = energy_quantiles[2] / energy_quantiles[3];
      if (!(energy_up >= up)) up = energy_up, up_check = "energy";
      if (!(energy_down <= down)) down = energy_down, down_check = "energy";
    }
    line.above = up, line.below = down;
    line.smallest = absolute ? fmt::format("× {:.4g} or × {:.4g}", up, down)
                             : "n/a (scale = \"free\": the gate fits the scale)";
    if (!absolute) up_check = down_check = "";
    line.check = up_check == down_check ? up_check : up_check + " (above), " + down_check + " (below)";
    line.method = up_check == "energy" && down_check == "energy"
                      ? "closed form"
                      : fmt::format("{}simulation ({} draws of {} rings)",
                                    up_check == "energy" || down_check == "energy" ? "closed form and " : "",
                                    kShapeDraws, shape.rings());
    if (!absolute) line.method.clear();
    table.lines.push_back(line);
  }
  table.lines.push_back(gamma_line);
  table.lines.push_back(omega_line);
  table.lines.push_back(offset_line);
  table.lines.push_back(spreading_line);
  table.lines.push_back(lambda_line);

  // The time step dt(1 + ε) moves every phase ωt as ω(1 + ε) does.
  {
    PowerLine line;
    line.error = "time step";
    line.above = epsilon, line.below = -epsilon;
    line.smallest = std::isnan(epsilon) ? "none (dispersion needs ≥ 3 frames)"
                                        : fmt::format("dt × (1 ± {:.2g})", epsilon);
    line.check = omega_check;
    line.method = std::isnan(epsilon) ? "" : "closed form";
    line.note = std::isnan(epsilon) ? "" : "the phase ωt moves as under ω × (1 ± ε)";
    table.lines.push_back(line);
  }
  // In the order docs/gate.md §11 lists them.
  const std::vector<std::string> order = {"energy factor", "ω, relative, on every wave", "mean direction offset",
                                          "spreading s", "JONSWAP γ", "choppiness λ", "time step"};
  std::stable_sort(table.lines.begin(), table.lines.end(), [&](const PowerLine& x, const PowerLine& y) {
    return std::find(order.begin(), order.end(), x.error) < std::find(order.begin(), order.end(), y.error);
  });
  return table;
}

}  // namespace

PowerTable gate_power(const CaseFile& case_file, double alpha, double unit_roundoff,
                      double storage_roundoff, const std::vector<double>& travelling_power, int threads) {
  return make_power_table(case_file, alpha, unit_roundoff, storage_roundoff, travelling_power, nullptr, threads);
}

PowerTable gate_power(const CaseFile& case_file, double alpha, double unit_roundoff,
                      double storage_roundoff, const CaseSamples& samples, int threads) {
  return make_power_table(case_file, alpha, unit_roundoff, storage_roundoff, samples.travelling_power, &samples,
                          threads);
}

PowerTable gate_power(const CaseFile& case_file, double alpha, int threads) {
  const std::string& precision = case_file.input.precision;
  const auto tau = expected_travelling_power(case_file.ocean, threads);
  if (precision == "half") return gate_power(case_file, alpha, 0x1p-24, kHalfUlp, tau, threads);
  if (precision == "double") return gate_power(case_file, alpha, kFp64, 0, tau, threads);
  return gate_power(case_file, alpha, 0x1p-24, 0, tau, threads);
}

nlohmann::json power_json(const PowerTable& table) {
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& line : table.lines) {
    lines.push_back({{"error", line.error}, {"smallest", line.smallest}, {"below", number(line.below)},
                     {"above", number(line.above)}, {"check", line.check}, {"method", line.method},
                     {"note", line.note}});
  }
  return {{"power", table.power}, {"alpha", table.alpha}, {"alpha_per_check", table.alpha_per_check},
          {"precision", table.precision}, {"lines", lines}};
}

std::string render_power(const PowerTable& table) {
  std::string out = fmt::format(
      "Power: the smallest error the gate detects with {:.0f} % power (α = {:g}, {:.2g} per "
      "statistical check; {} precision)\n",
      100 * table.power, table.alpha, table.alpha_per_check, table.precision);
  for (const auto& line : table.lines) {
    out += fmt::format("  {:<28} {:<44} {:<24} {}{}\n", line.error, line.smallest, line.check, line.method,
                       line.note.empty() ? "" : " — " + line.note);
  }
  return out;
}

}  // namespace swell::validation
