#include "swell/reference/moments.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>

#include "swell/reference/errors.hpp"

namespace swell::reference {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double power(double omega, int n) {
  switch (n) {
    case -1: return 1.0 / omega;
    case 0: return 1.0;
    case 1: return omega;
    case 2: return omega * omega;
    default: return std::pow(omega, n);
  }
}

double peak_in_band(const FrequencySpectrum& spectrum, Band band) {
  return std::clamp(spectrum.peak_omega(), band.omega_min, band.omega_max);
}

}  // namespace

double spectral_moment(const FrequencySpectrum& spectrum, int n, Band band) {
  require(band.omega_min >= 0, "band lower edge ω_min", "≥ 0 rad/s", band.omega_min);
  require(!std::isnan(band.omega_max) && band.omega_max > band.omega_min,
          "band upper edge ω_max", "> ω_min", band.omega_max);
  if (std::isinf(band.omega_max) && n >= spectrum.tail_exponent() - 1) return kInfinity;
  // S ~ ω^q near 0 makes ∫₀ ωⁿ S dω diverge for n ≤ −q − 1 (a Gaussian swell's m−1).
  if (band.omega_min == 0 && n <= -spectrum.low_frequency_exponent() - 1) return kInfinity;

  // Split the band at the spectrum's breakpoints so each piece is smooth for Gauss–Kronrod.
  std::vector<double> edges{band.omega_min};
  for (double b : spectrum.breakpoints()) {
    if (b > band.omega_min && b < band.omega_max) edges.push_back(b);
  }
  // Sorted, and breakpoints closer than a relative 1e-6 merged: a TMA's peak (found
  // numerically) and its JONSWAP's σ switch lie 1.7e-8 rad/s apart, and on that sliver the
  // error estimate (rounding of S relative to a piece that holds 1e-7 of m0) never met the
  // 1e-11 tolerance: Boost bisected it to max_depth, 4·10⁶ evaluations and 0.4 s a moment
  // (20× that under the sanitizers). A kink within 1e-6 of a piece's end costs its neighbour
  // a few bisections.
  std::sort(edges.begin() + 1, edges.end());
  std::vector<double> merged{edges.front()};
  for (std::size_t i = 1; i < edges.size(); ++i) {
    if (edges[i] > merged.back() * (1 + 1e-6) && edges[i] > merged.back()) merged.push_back(edges[i]);
  }
  edges = std::move(merged);
  edges.push_back(band.omega_max);

  auto integrand = [&](double omega) { return omega > 0 ? power(omega, n) * spectrum(omega) : 0.0; };
  using Rule = boost::math::quadrature::gauss_kronrod<double, 61>;
  double total = 0, total_error = 0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    double error = 0;
    const double a = edges[i], b = edges[i + 1];
    // Boost maps [a, ∞) by ω = a + x/(1 − x), which turns an integrand decaying as ω^−q into
    // (1 − x)^(q − 2) at x → 1: singular for q < 2, and with a singular derivative for
    // fractional q < 3, where the rule bisects to its depth limit without meeting 1e-11 (an
    // Ochi–Hubble component with λ = 0.3 has q = 2.2 in m0, 1.2 in m1). For such a slow tail
    // the piece is taken in t = ln(ω/a) instead, where ω^−q becomes the smooth e^−(q−1)t. The
    // ω⁻⁵ spectra (q ≥ 3 up to m2) keep the direct mapping.
    if (std::isinf(b) && a > 0 && spectrum.tail_exponent() - n < 3) {
      auto in_log = [&](double t) {
        const double omega = a * std::exp(t);
        // Beyond ω ~ 1e308 the tail holds < (1e308/a)^−(q−1) of the piece: nothing at q > 1.
        if (!std::isfinite(omega)) return 0.0;
        // ω^(n+1) S(ω) factor by factor: far out ω^(n+1) alone overflows while S has
        // underflowed, and each partial product lies between S and the (small) result.
        double value = spectrum(omega);
        for (int k = 0; k < n + 1; ++k) value *= omega;
        for (int k = 0; k > n + 1; --k) value /= omega;
        return value;
      };
      total += Rule::integrate(in_log, 0.0, kInfinity, 15, 1e-11, &error);
      total_error += error;
      continue;
    }
    // 61-point Kronrod rule, bisected adaptively (Boost maps [a, ∞) onto a finite interval).
    // 1e-11 per piece keeps the sum well inside kMomentRelativeTolerance; a tighter request is
    // a trap: the error estimate bottoms out at rounding (~1e-13 of the piece), so the rule
    // would bisect to max_depth, and the summed estimates of 2^depth pieces grow past 1e-9.
    total += Rule::integrate(integrand, a, b, 15, 1e-11, &error);
    total_error += error;
  }
  if (!(total_error <= kMomentRelativeTolerance * std::abs(total))) {
    throw NumericalError("spectral moment m" + std::to_string(n) + " of " + spectrum.name() +
                         " did not reach relative accuracy 1e-9 (estimated error " +
                         std::to_string(total_error) + " of " + std::to_string(total) + ")");
  }
  return total;
}

SeaState sea_state_from_moments(const Moments& m, double omega_p) {
  SeaState s;
  s.moments = m;
  s.omega_p = omega_p;
  s.hs = 4.0 * std::sqrt(m.m0);
  s.tp = kTwoPi / omega_p;
  s.tm01 = kTwoPi * m.m0 / m.m1;
  s.tm02 = kTwoPi * std::sqrt(m.m0 / m.m2);
  s.te = kTwoPi * m.m_minus1 / m.m0;
  // → 1 when m4 = ∞, also when m2 diverges too (an ω^−p tail, p ≤ 3): over a band up to Ω,
  // m2²/m4 ~ Ω^(1−p) → 0, while the formula would take ∞/∞.
  s.epsilon4 = std::isinf(m.m4) ? 1.0 : std::sqrt(1.0 - m.m2 * m.m2 / (m.m0 * m.m4));
  s.nu = std::sqrt(m.m0 * m.m2 / (m.m1 * m.m1) - 1.0);
  return s;
}

SeaState sea_state(const FrequencySpectrum& spectrum, Band band) {
  Moments m;
  m.m_minus1 = spectral_moment(spectrum, -1, band);
  m.m0 = spectral_moment(spectrum, 0, band);
  m.m1 = spectral_moment(spectrum, 1, band);
  m.m2 = spectral_moment(spectrum, 2, band);
  m.m4 = spectral_moment(spectrum, 4, band);
  return sea_state_from_moments(m, peak_in_band(spectrum, band));
}

namespace {
// The largest |n| along an axis of `samples` points that carries energy (Nyquist excluded).
int largest_energetic_index(int samples) { return samples % 2 == 0 ? samples / 2 - 1 : (samples - 1) / 2; }
}  // namespace

Band grid_band(const Grid& grid, const Dispersion& dispersion) {
  const int nx_max = largest_energetic_index(grid.nx), ny_max = largest_energetic_index(grid.ny);
  require(nx_max >= 1 || ny_max >= 1, "grid size", "large enough to hold a wave (n ≥ 3 on an axis)",
          std::max(grid.nx, grid.ny));
  const double k_min = std::min(nx_max >= 1 ? grid.dkx() : kInfinity,
                                ny_max >= 1 ? grid.dky() : kInfinity);
  const double k_max = std::hypot(nx_max * grid.dkx(), ny_max * grid.dky());
  return {dispersion.omega(k_min), dispersion.omega(k_max)};
}

SeaState grid_sea_state(const DirectionalSpectrum& spectrum, const Grid& grid) {
  const Dispersion& dispersion = spectrum.dispersion();
  const double cell = grid.dkx() * grid.dky();
  // Long-double sums: up to millions of terms of one sign, summed in any order.
  long double m_minus1 = 0, m0 = 0, m1 = 0, m2 = 0, m4 = 0;
  for (int j = 0; j < grid.ny; ++j) {
    const int m = Grid::signed_index(j, grid.ny);
    for (int i = 0; i < grid.nx; ++i) {
      const int n = Grid::signed_index(i, grid.nx);
      if (!grid.carries_energy(n, m)) continue;
      const double kx = n * grid.dkx(), ky = m * grid.dky();
      const double energy = spectrum.psi(kx, ky) * cell;
      const double omega = dispersion.omega(std::hypot(kx, ky));
      m_minus1 += energy / omega;
      m0 += energy;
      m1 += energy * omega;
      m2 += energy * omega * omega;
      m4 += energy * omega * omega * omega * omega;
    }
  }
  const Moments moments{static_cast<double>(m_minus1), static_cast<double>(m0),
                        static_cast<double>(m1), static_cast<double>(m2), static_cast<double>(m4)};
  return sea_state_from_moments(
      moments, peak_in_band(spectrum.omnidirectional(), grid_band(grid, dispersion)));
}

HzSeaState measured_sea_state_hz(const std::vector<double>& f, const std::vector<double>& s,
                                 const std::vector<double>& df) {
  if (f.empty()) throw InvalidInput("measured spectrum: no frequency bins");
  if (s.size() != f.size() || df.size() != f.size()) {
    throw InvalidInput("measured spectrum: " + std::to_string(f.size()) + " frequencies but " +
                       std::to_string(s.size()) + " densities and " + std::to_string(df.size()) +
                       " bin widths; they must match");
  }
  long double m_minus1 = 0, m0 = 0, m1 = 0, m2 = 0, m4 = 0;
  std::size_t peak = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    require(std::isfinite(f[i]) && f[i] > 0, "measured spectrum: frequency [" + std::to_string(i) + "]",
            "finite and > 0 Hz", f[i]);
    require(std::isfinite(s[i]) && s[i] >= 0, "measured spectrum: density [" + std::to_string(i) + "]",
            "finite and ≥ 0 m²/Hz", s[i]);
    require(std::isfinite(df[i]) && df[i] > 0, "measured spectrum: bin width [" + std::to_string(i) + "]",
            "finite and > 0 Hz", df[i]);
    const long double e = static_cast<long double>(s[i]) * df[i];
    m_minus1 += e / f[i];
    m0 += e;
    m1 += e * f[i];
    m2 += e * f[i] * f[i];
    m4 += e * f[i] * f[i] * f[i] * f[i];
    if (s[i] > s[peak]) peak = i;
  }
  HzSeaState r;
  r.moments_hz = {static_cast<double>(m_minus1), static_cast<double>(m0), static_cast<double>(m1),
                  static_cast<double>(m2), static_cast<double>(m4)};
  const Moments& m = r.moments_hz;
  r.hs = 4.0 * std::sqrt(m.m0);
  r.tp = 1.0 / f[peak];
  r.tm01 = m.m0 / m.m1;
  r.tm02 = std::sqrt(m.m0 / m.m2);
  r.te = m.m_minus1 / m.m0;
  r.epsilon4 = std::sqrt(1.0 - m.m2 * m.m2 / (m.m0 * m.m4));
  r.nu = std::sqrt(m.m0 * m.m2 / (m.m1 * m.m1) - 1.0);
  return r;
}

// ---------------------------------------------------------------- Grid

Grid Grid::create(int nx, int ny, double lx, double ly) {
  require(nx >= 1, "grid nx", "≥ 1", nx);
  require(ny >= 1, "grid ny", "≥ 1", ny);
  require(std::isfinite(lx) && lx > 0, "patch length lx", "finite and > 0 m", lx);
  require(std::isfinite(ly) && ly > 0, "patch length ly", "finite and > 0 m", ly);
  return Grid{nx, ny, lx, ly};
}

double Grid::dkx() const { return kTwoPi / lx; }
double Grid::dky() const { return kTwoPi / ly; }

}  // namespace swell::reference
