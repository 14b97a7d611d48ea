#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::probe_analysis {

using reference::ProbeCase;
constexpr double kPi = std::numbers::pi;

namespace {

// One line's phases between probes: φ_p = arg(conj X_p X_0), each within bound_p of exact.
struct LinePhases {
  double omega = 0;
  std::vector<double> phase, bound;
};

// The direction θ whose plane wave at wavenumber k best explains the phases (least squares of
// the wrapped residuals, weighted by 1/bound²), and the largest |residual|/bound there, each
// bound widened by `k_tolerance` k |Δx_p| (an engine's own g moves k by 10⁻³ and less). A grid
// of the circle fine enough for k |Δx| (16 points per radian of the widest phase), then
// Gauss–Newton.
struct PlaneWaveFit {
  double theta = 0, worst = INFINITY;
};

PlaneWaveFit fit_plane_wave(const LinePhases& line, double k, const std::vector<std::array<double, 2>>& offsets,
                            double k_tolerance = 0) {
  double reach = 0;
  for (const auto& d : offsets) reach = std::max(reach, k * std::hypot(d[0], d[1]));
  const int points = std::max(72, int(std::ceil(16 * reach)));
  const auto residual = [&](std::size_t p, double theta) {
    return std::remainder(line.phase[p] - k * (std::cos(theta) * offsets[p][0] + std::sin(theta) * offsets[p][1]),
                          2 * kPi);
  };
  const auto cost = [&](double theta) {
    double sum = 0;
    for (std::size_t p = 0; p < offsets.size(); ++p) sum += 1 - std::cos(residual(p, theta));
    return sum;
  };
  std::vector<double> costs(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i) costs[std::size_t(i)] = cost(2 * kPi * i / points);
  // Starting directions: with two baselines not parallel, every wave vector K of length near k
  // whose phases K·Δx_a = φ_a + 2π n_a, K·Δx_b = φ_b + 2π n_b (all wrappings n with
  // |φ + 2π n| ≤ k |Δx|) — exhaustive, so the true direction is among them; else the grid's
  // eight lowest minima (a grid point beside the true θ can cost more than an alias's).
  std::vector<double> starts;
  std::size_t a = offsets.size(), b = offsets.size();
  double widest = 0;
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    for (std::size_t j = i + 1; j < offsets.size(); ++j) {
      const double cross = offsets[i][0] * offsets[j][1] - offsets[i][1] * offsets[j][0];
      const double size = std::hypot(offsets[i][0], offsets[i][1]) * std::hypot(offsets[j][0], offsets[j][1]);
      // The pair closest to perpendicular, of the shortest baselines (fewest wrappings).
      const double score = std::abs(cross) / size / (size + 1e-300);
      if (std::abs(cross) > 1e-6 * size && score > widest) widest = score, a = i, b = j;
    }
  }
  if (a < offsets.size()) {
    const double cross = offsets[a][0] * offsets[b][1] - offsets[a][1] * offsets[b][0];
    const double reach_a = k * std::hypot(offsets[a][0], offsets[a][1]);
    const double reach_b = k * std::hypot(offsets[b][0], offsets[b][1]);
    for (long na = long(std::floor((-reach_a - line.phase[a]) / (2 * kPi)));
         na <= long(std::ceil((reach_a - line.phase[a]) / (2 * kPi))); ++na) {
      for (long nb = long(std::floor((-reach_b - line.phase[b]) / (2 * kPi)));
           nb <= long(std::ceil((reach_b - line.phase[b]) / (2 * kPi))); ++nb) {
        const double pa = line.phase[a] + 2 * kPi * double(na), pb = line.phase[b] + 2 * kPi * double(nb);
        // K from K·Δx_a = pa, K·Δx_b = pb.
        const double kx = (pa * offsets[b][1] - pb * offsets[a][1]) / cross;
        const double ky = (offsets[a][0] * pb - offsets[b][0] * pa) / cross;
        if (std::abs(std::hypot(kx, ky) - k) <= 0.05 * k) starts.push_back(std::atan2(ky, kx));
      }
    }
  }
  std::vector<int> minima;
  for (int i = 0; i < points; ++i) {
    const double here = costs[std::size_t(i)];
    if (here <= costs[std::size_t((i + points - 1) % points)] && here <= costs[std::size_t((i + 1) % points)]) {
      minima.push_back(i);
    }
  }
  std::sort(minima.begin(), minima.end(), [&](int x, int y) { return costs[std::size_t(x)] < costs[std::size_t(y)]; });
  if (minima.size() > 8) minima.resize(8);
  for (int i : minima) starts.push_back(2 * kPi * i / points);
  PlaneWaveFit fit;
  for (double start : starts) {
    double theta = start;
    for (int iteration = 0; iteration < 30; ++iteration) {
      double numerator = 0, denominator = 0;
      for (std::size_t p = 0; p < offsets.size(); ++p) {
        const double slope = k * (std::sin(theta) * offsets[p][0] - std::cos(theta) * offsets[p][1]);  // ∂r/∂θ
        const double weight = 1 / (line.bound[p] * line.bound[p]);
        numerator += weight * residual(p, theta) * slope, denominator += weight * slope * slope;
      }
      if (!(denominator > 0)) break;
      const double step = numerator / denominator;
      theta -= step;
      if (std::abs(step) < 1e-15) break;
    }
    double worst = 0;
    for (std::size_t p = 0; p < offsets.size(); ++p) {
      const double bound = line.bound[p] + k_tolerance * k * std::hypot(offsets[p][0], offsets[p][1]);
      worst = std::max(worst, std::abs(residual(p, theta)) / bound);
    }
    if (worst < fit.worst) fit.theta = theta, fit.worst = worst;
  }
  return fit;
}

// Whether the offsets shorter than `longest` span the plane (two not parallel to 10⁻⁶): three or
// more probes off one line fix a direction; where those baselines' phases k ê·Δx stay within
// (−π, π) they fix it for every θ, with no alias.
bool spans_plane(const std::vector<std::array<double, 2>>& offsets, double longest = INFINITY) {
  for (std::size_t a = 0; a < offsets.size(); ++a) {
    if (!(std::hypot(offsets[a][0], offsets[a][1]) < longest)) continue;
    for (std::size_t b = a + 1; b < offsets.size(); ++b) {
      if (!(std::hypot(offsets[b][0], offsets[b][1]) < longest)) continue;
      const double cross = offsets[a][0] * offsets[b][1] - offsets[a][1] * offsets[b][0];
      const double size = std::hypot(offsets[a][0], offsets[a][1]) * std::hypot(offsets[b][0], offsets[b][1]);
      if (std::abs(cross) > 1e-6 * size) return true;
    }
  }
  return false;
}

// E e^(i m α) of the case's D(ω, ·) about its mean direction, m = 1 … 4.
std::array<Complex, 5> circular_moments(const reference::DirectionalSpectrum& sea, double omega, double mean) {
  constexpr int kCells = 720;
  const auto density = reference::direction_distribution(sea, omega, mean - kPi, kCells);
  std::array<Complex, 5> out{};
  const double width = 2 * kPi / kCells;
  for (int j = 0; j < kCells; ++j) {
    const double alpha = -kPi + (j + 0.5) * width;
    for (int m = 0; m <= 4; ++m) out[std::size_t(m)] += density[std::size_t(j)] * width * std::polar(1.0, m * alpha);
  }
  return out;
}

// Solves the 4 × 4 symmetric positive definite system C x = y by Cholesky; false if C is not.
bool solve_spd(std::array<std::array<double, 4>, 4> c, std::array<double, 4>& x) {
  for (int j = 0; j < 4; ++j) {
    for (int k = 0; k < j; ++k) c[j][j] -= c[j][k] * c[j][k];
    if (!(c[j][j] > 0)) return false;
    c[j][j] = std::sqrt(c[j][j]);
    for (int i = j + 1; i < 4; ++i) {
      for (int k = 0; k < j; ++k) c[i][j] -= c[i][k] * c[j][k];
      c[i][j] /= c[j][j];
    }
  }
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < i; ++k) x[i] -= c[i][k] * x[k];
    x[i] /= c[i][i];
  }
  for (int i = 3; i >= 0; --i) {
    for (int k = i + 1; k < 4; ++k) x[i] -= c[k][i] * x[k];
    x[i] /= c[i][i];
  }
  return true;
}

// The probes whose series are one (X equal at every judged line to their rounding).
std::string identical_probes(const LineBins& lines, const std::vector<ProbeSpectrum>& spectra) {
  for (std::size_t a = 0; a < spectra.size(); ++a) {
    for (std::size_t b = a + 1; b < spectra.size(); ++b) {
      bool same = true;
      for (std::size_t q : lines.bins) {
        if (std::abs(spectra[a].x[q] - spectra[b].x[q]) > spectra[a].rounding + spectra[b].rounding) {
          same = false;
          break;
        }
      }
      if (same) return fmt::format("probes {} and {} carry one series", a, b);
    }
  }
  return "";
}

}  // namespace

void plane_waves(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                 double alpha, ProbeCheckReport& report) {
  std::vector<std::array<double, 2>> offsets;
  for (std::size_t p = 1; p < spectra.size(); ++p) {
    offsets.push_back({c.layout.positions[p][0] - c.layout.positions[0][0],
                       c.layout.positions[p][1] - c.layout.positions[0][1]});
  }
  const auto dispersion = c.sea.dispersion();
  const double g = c.sea.gravity;
  // The lines that stand 10³ above the rounding at every probe.
  std::vector<LinePhases> judged;
  for (std::size_t i = 0; i < lines.bins.size(); ++i) {
    const std::size_t q = lines.bins[i];
    LinePhases line;
    line.omega = lines.omega[i];
    bool clear = true;
    const Complex reference = spectra[0].x[q];
    for (std::size_t p = 1; p < spectra.size() && clear; ++p) {
      const Complex x = spectra[p].x[q];
      const double r0 = spectra[0].rounding, rp = spectra[p].rounding;
      clear = std::abs(reference) > 1e3 * r0 && std::abs(x) > 1e3 * rp;
      if (!clear) break;
      const double k = dispersion.wavenumber(line.omega);
      line.phase.push_back(std::arg(std::conj(x) * reference));
      line.bound.push_back(std::asin(r0 / std::abs(reference)) + std::asin(rp / std::abs(x)) +
                           1e-12 * (1 + k * std::hypot(offsets[p - 1][0], offsets[p - 1][1])));
    }
    if (clear) judged.push_back(std::move(line));
  }
  if (judged.empty()) {
    report.skipped.push_back({"series.phase", SkipReason::too_few_wave_vectors,
                              "no line stands 10³ above the rounding at every probe"});
    return;
  }
  // series.phase: each line one plane wave at the case's k(ω).
  double worst = 0, worst_omega = 0;
  std::vector<PlaneWaveFit> fits;
  for (const auto& line : judged) {
    fits.push_back(fit_plane_wave(line, dispersion.wavenumber(line.omega), offsets));
    if (fits.back().worst > worst) worst = fits.back().worst, worst_omega = line.omega;
  }
  const bool ok = worst <= 1;
  std::string reason;
  if (ok) {
    reason = fmt::format("every line's phases between the {} probes are one plane wave's at the case's k(ω) ({} "
                         "lines)",
                         spectra.size(), judged.size());
  } else {
    reason = fmt::format("at ω = {:.4g} rad/s no direction of travel explains the phases between probes at the "
                         "case's k(ω) ({:.3g}× the rounding's phase bound)",
                         worst_omega, worst);
    double deep_worst = 0;
    for (const auto& line : judged) {
      deep_worst = std::max(deep_worst, fit_plane_wave(line, line.omega * line.omega / g, offsets, 1e-3).worst);
    }
    const std::string same = identical_probes(lines, spectra);
    if (!same.empty()) {
      reason += " — " + same + ", as if both stood at one point: a probe clamped to the domain's edge, or two "
                               "probes read from one grid node";
    } else if (deep_worst <= 1 && std::isfinite(c.sea.depth)) {
      reason += fmt::format(" — the phases follow deep-water k = ω²/g where the case's depth is {:g} m (a "
                            "deep-water dispersion in finite depth)",
                            c.sea.depth);
    } else {
      reason += " — a line holds more than one direction (double summation declared as single), or the probes "
                "stand elsewhere than declared";
    }
  }
  report.results.push_back(exact_check("series.phase", c.describe(), worst, 1, ok,
                                       "each line's phases between probes: one plane wave at k(ω) of the case, to "
                                       "the rounding's phase bound",
                                       reason));
  // series.direction: the lines' directions against D(ω, ·), by their first two circular
  // moments about the declared mean direction.
  if (!spans_plane(offsets)) {
    report.skipped.push_back({"series.direction", SkipReason::scheme_not_judged,
                              "the probes stand on one line: their phases cannot tell a direction from its mirror"});
    return;
  }
  if (!ok) {
    report.skipped.push_back({"series.direction", SkipReason::scheme_not_judged,
                              "series.phase failed: the lines are not plane waves whose direction could be read"});
    return;
  }
  const auto sea = c.spectrum();
  const double mean = sea->mean_direction();
  // D's moments on a grid of frequencies over the judged band, interpolated between.
  double low = INFINITY, high = 0;
  for (const auto& line : judged) low = std::min(low, line.omega), high = std::max(high, line.omega);
  constexpr int kGrid = 48;
  std::vector<std::array<Complex, 5>> moments;
  for (int j = 0; j <= kGrid; ++j) moments.push_back(circular_moments(*sea, low + (high - low) * j / kGrid, mean));
  std::array<double, 4> sum{};
  std::array<std::array<double, 4>, 4> covariance{};
  Complex resultant = 0, expected_resultant = 0;
  int count = 0;
  for (std::size_t i = 0; i < judged.size(); ++i) {
    // Judged where the baselines shorter than π/k span the plane: chosen by k alone, never by
    // the direction read, so the lines judged are not a selection of directions.
    if (!spans_plane(offsets, kPi * (1 - 1e-6) / dispersion.wavenumber(judged[i].omega))) continue;
    const double position = high > low ? (judged[i].omega - low) / (high - low) * kGrid : 0;
    const int j = std::min(kGrid - 1, int(position));
    const double f = position - j;
    std::array<Complex, 5> mu;
    for (std::size_t m = 0; m < 5; ++m) mu[m] = (1 - f) * moments[std::size_t(j)][m] + f * moments[std::size_t(j + 1)][m];
    const double a = fits[i].theta - mean;
    const std::array<double, 4> y = {std::cos(a) - mu[1].real(), std::sin(a) - mu[1].imag(),
                                     std::cos(2 * a) - mu[2].real(), std::sin(2 * a) - mu[2].imag()};
    // E[f_m f_l] of f = (cos α, sin α, cos 2α, sin 2α) from μ_0 … μ_4 (product-to-sum).
    const auto cc = [&](int m, int l) { return 0.5 * (mu[std::size_t(std::abs(m - l))].real() + mu[std::size_t(m + l)].real()); };
    const auto ss = [&](int m, int l) { return 0.5 * (mu[std::size_t(std::abs(m - l))].real() - mu[std::size_t(m + l)].real()); };
    const auto cs = [&](int m, int l) {  // E cos mα sin lα
      const double difference = l >= m ? mu[std::size_t(l - m)].imag() : -mu[std::size_t(m - l)].imag();
      return 0.5 * (mu[std::size_t(m + l)].imag() + difference);
    };
    const std::array<double, 4> e = {mu[1].real(), mu[1].imag(), mu[2].real(), mu[2].imag()};
    const std::array<std::array<double, 4>, 4> second = {{{cc(1, 1), cs(1, 1), cc(1, 2), cs(1, 2)},
                                                          {cs(1, 1), ss(1, 1), cs(2, 1), ss(1, 2)},
                                                          {cc(1, 2), cs(2, 1), cc(2, 2), cs(2, 2)},
                                                          {cs(1, 2), ss(1, 2), cs(2, 2), ss(2, 2)}}};
    for (int r = 0; r < 4; ++r) {
      sum[std::size_t(r)] += y[std::size_t(r)];
      for (int s = 0; s < 4; ++s) {
        covariance[std::size_t(r)][std::size_t(s)] += second[std::size_t(r)][std::size_t(s)] - e[std::size_t(r)] * e[std::size_t(s)];
      }
    }
    resultant += std::polar(1.0, a), expected_resultant += mu[1];
    ++count;
  }
  if (count < 20) {
    report.skipped.push_back({"series.direction", SkipReason::too_few_wave_vectors,
                              fmt::format("{} lines are long enough for this array to read their direction without "
                                          "alias (two baselines shorter than half their wavelength; 20 needed)",
                                          count)});
    return;
  }
  std::array<double, 4> solved = sum;
  const bool solvable = solve_spd(covariance, solved);
  double t2 = 0;
  for (int r = 0; r < 4; ++r) t2 += sum[std::size_t(r)] * solved[std::size_t(r)];
  const double p_value = solvable ? stats::chi_squared_upper_p(t2, 4) : NAN;
  const double measured_direction = std::arg(resultant) + mean;
  const double spread = std::abs(resultant) / count, expected_spread = std::abs(expected_resultant) / count;
  const auto degrees = [](double radians) { return std::remainder(radians * 180 / kPi, 360.0); };
  std::string direction_reason =
      fmt::format("{} lines' directions from {} probes: mean {:.1f}° (declared {:.1f}°), mean resultant length {:.3f} "
                  "(declared {:.3f})",
                  count, spectra.size(), degrees(measured_direction), degrees(mean), spread, expected_spread);
  if (p_value < alpha) {
    const double off = std::abs(degrees(measured_direction - mean));
    if (off > 135) {
      direction_reason += " — the waves travel against the declared direction (θ + 180°): a direction taken as "
                          "where the waves come from, or a reversed phase sign";
    } else if (off > 10) {
      direction_reason += fmt::format(" — the waves travel {:.1f}° off the declared direction", off);
    } else if (spread < expected_spread) {
      direction_reason += " — directions spread wider than D(ω, θ): a wider spreading model than declared";
    } else {
      direction_reason += " — directions gathered closer than D(ω, θ): a narrower spreading than declared";
    }
  }
  report.results.push_back(statistical_check(
      "series.direction", c.describe(), spread, expected_spread, p_value, alpha,
      fmt::format("p ≥ α = {:.0e} (each line's direction read from its plane wave; Σ (cos α, sin α, cos 2α, sin 2α) "
                  "against D(ω, θ)'s moments, Hotelling's T² ~ χ²(4))",
                  alpha),
      direction_reason));
}

}  // namespace swell::validation::probe_analysis
