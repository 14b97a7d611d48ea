#include <array>

#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::ocean_analysis {
namespace {

// dᵀ C⁺ d for a symmetric positive semi-definite C and d in C's column space, with the rank
// of C: Gaussian elimination with diagonal pivoting (LDLᵀ), pivots at or below 1e-10 of the
// largest diagonal are C's null space and are dropped. A few waves all along one line (a
// narrow Phillips spectrum on a small grid) make the harmonics' covariance singular; the
// statistic then has that many fewer degrees of freedom, not a NaN (the command line's property test).
template <std::size_t D>
double quadratic_form(std::array<std::array<double, D>, D> c, std::array<double, D> d, int& rank) {
  double largest = 0;
  for (std::size_t i = 0; i < D; ++i) largest = std::max(largest, c[i][i]);
  double form = 0;
  rank = 0;
  for (std::size_t k = 0; k < D; ++k) {
    std::size_t pivot = k;
    for (std::size_t r = k + 1; r < D; ++r) {
      if (c[r][r] > c[pivot][pivot]) pivot = r;
    }
    std::swap(c[k], c[pivot]);
    for (auto& row : c) std::swap(row[k], row[pivot]);
    std::swap(d[k], d[pivot]);
    if (!(c[k][k] > 1e-10 * largest)) break;  // the rest is null space
    ++rank;
    for (std::size_t r = k + 1; r < D; ++r) {
      const double factor = c[r][k] / c[k][k];
      for (std::size_t j = k; j < D; ++j) c[r][j] -= factor * c[k][j];
      d[r] -= factor * d[k];
    }
    form += d[k] * d[k] / c[k][k];
  }
  return form;
}

}  // namespace

// From the fitted travelling waves: |a|² is the power moving along +k (E = τ(k)), |b|² along
// −k (E = τ(−k)), all independent exponentials. T = Dᵀ C⁻¹ D of the score below ~ χ²(4)
// (central limit over the wave vectors). And a, b are independent: Re(a b) / √(τ+ τ− / 2)
// has mean 0 and variance 1.
Results check_direction(const Analysis& a, OceanCheckReport& report) {
  if (a.times().size() < 2) {
    report.skipped.push_back({"direction", SkipReason::too_few_frames, "needs ≥ 2 frames (one frame cannot tell k from −k)"});
    return {};
  }
  const auto& fits = a.wave_fits();
  if (fits.empty()) {
    report.skipped.push_back({"direction", SkipReason::unidentifiable_times, "no wave vector's two waves are identifiable from these frame times"});
    return {};
  }
  const double alpha = a.options().alpha / 2;
  // Each fitted wave vector's two travelling waves, along +k then −k: made as they are visited
  // (two per wave vector of the half plane, too many to hold at film scale).
  struct Entry { double theta, power, tau; };
  auto for_each_entry = [&](const auto& visit) {
    for (const WaveFit& f : fits) {
      visit(Entry{f.wave->theta, std::norm(f.a), f.wave->tau_plus});
      visit(Entry{f.wave->theta + kPi, std::norm(f.b), f.wave->tau_minus});
    }
  };
  auto harmonics = [](double theta) {
    return std::array<double, 4>{std::cos(theta), std::sin(theta), std::cos(2 * theta), std::sin(2 * theta)};
  };
  // Score test of a directional modulation τ (1 + β·g(θ)): with u = P/τ ~ Exp(1) independent,
  // D = Σ (u − 1)(g − ḡ) has mean 0 and covariance Σ (g − ḡ)(g − ḡ)ᵀ; equal weights per wave
  // make the central limit accurate even where a few waves carry most of the energy. Only
  // waves above the rounding floor take part.
  std::array<double, 4> mean_g{};
  int used = 0;
  for_each_entry([&](const Entry& e) {
    if (!(e.tau >= a.floor())) return;
    const auto g = harmonics(e.theta);
    for (int i = 0; i < 4; ++i) mean_g[i] += g[i];
    ++used;
  });
  for (double& v : mean_g) v /= std::max(used, 1);
  // u at the frames' measured level L (MeasuredLevel): a scale error alone makes u ~ L Exp(1),
  // whose (u − 1) would score a direction where there is none.
  const MeasuredLevel& level = a.measured_level();
  const double scale = level.rings >= 4 && level.level > 0 ? level.level : 1.0;
  std::array<double, 4> d{};
  std::array<std::array<double, 4>, 4> cov{};
  Complex measured_resultant = 0, expected_resultant = 0;
  double power_total = 0, tau_total = 0;
  for_each_entry([&](const Entry& e) {
    measured_resultant += e.power * std::polar(1.0, e.theta);
    expected_resultant += e.tau * std::polar(1.0, e.theta);
    power_total += e.power;
    tau_total += e.tau;
    if (!(e.tau >= a.floor())) return;
    auto g = harmonics(e.theta);
    for (int i = 0; i < 4; ++i) g[i] -= mean_g[i];
    for (int i = 0; i < 4; ++i) {
      d[i] += (e.power / (scale * e.tau) - 1) * g[i];
      for (int j = 0; j < 4; ++j) cov[i][j] += g[i] * g[j];
    }
  });
  int rank = 0;
  const double t = quadratic_form<4>(cov, d, rank);
  const double p = rank > 0 ? stats::chi_squared_upper_p(t, rank) : 1.0;
  const double theta_measured = std::arg(measured_resultant) * kDegree;
  const double theta_expected = std::arg(expected_resultant) * kDegree;
  const double spread_measured = std::sqrt(2 * (1 - std::abs(measured_resultant) / power_total)) * kDegree;
  const double spread_expected = std::sqrt(2 * (1 - std::abs(expected_resultant) / tau_total)) * kDegree;
  double turn = std::remainder(theta_measured - theta_expected, 360.0);
  std::string diagnosis;
  if (p < alpha) {
    if (std::abs(turn) > 135) {
      diagnosis = " — waves travel against the wind (time reversed or e^(+iωt) on h̃0(k))";
    } else if (const double mirrored = std::remainder(theta_measured - (270.0 - theta_expected), 360.0);
               std::abs(mirrored) < 15 && std::abs(turn) > 15) {
      // θ ↦ 270° − θ maps nautical "coming from" directions to swell's "toward, counter-clockwise
      // from +x" and back: one applied too few or too many times mirrors the sea this way.
      diagnosis = fmt::format(" — the mean direction is the case's mirrored, 270° − {:.1f}°: "
                              "directions where the waves come from (clockwise from north) read "
                              "as where they travel (counter-clockwise from +x), or the reverse "
                              "(a table's direction_convention)", theta_expected);
    } else if (std::abs(measured_resultant) < 0.25 * std::abs(expected_resultant)) {
      diagnosis = " — as much energy travels along −k as along +k: standing waves";
    } else {
      diagnosis = " — " + or_table(a, "the directional distribution differs from the case's spreading");
    }
  }
  Results out;
  out.push_back(statistical_check(
      "direction.distribution", a.subject(), theta_measured, theta_expected, p, alpha,
      fmt::format("p ≥ α = {:.1e} (χ²({}) of the first two circular harmonics)", alpha, rank),
      fmt::format("mean direction {:.1f}° (spread {:.1f}°) against {:.1f}° ({:.1f}°), "
                  "T = {:.1f}{}",
                  theta_measured, spread_measured, theta_expected, spread_expected, t, diagnosis)));

  double sum = 0;
  int count = 0;
  for (const WaveFit& f : fits) {
    // Both waves must stand above the rounding floor: a wave the model makes 10⁻³⁰ of the
    // peak is pure rounding noise in the data, not a sample of its law.
    if (!(f.wave->tau_plus >= a.floor() && f.wave->tau_minus >= a.floor())) continue;
    const double product = f.wave->tau_plus * f.wave->tau_minus;
    sum += (f.a * f.b).real() / std::sqrt(0.5 * product);
    ++count;
  }
  if (count < 8) {
    report.skipped.push_back({"direction.travelling", SkipReason::too_few_wave_vectors, "fewer than 8 wave vectors carry energy both "
                             "ways (one-sided spreading)"});
    return out;
  }
  // Normalized by the frames' measured level L, as above: Re(a b) scales with the spectrum, so a
  // scale error alone would make z ~ N(0, L²); this check judges the pairing.
  const double z = sum / (scale * std::sqrt(double(count)));
  const double p_travel = stats::normal_two_sided_p(z);
  out.push_back(statistical_check(
      "direction.travelling", a.subject(), z, 0.0, p_travel, alpha,
      fmt::format("p ≥ α = {:.1e} (normal, {} wave vectors, at the frames' measured level)", alpha, count),
      fmt::format("waves at k and −k independent: z = {:.2f}{}", z,
                  p_travel < alpha ? " — h̃0(k) and h̃0(−k) are correlated (the same random pair "
                                     "reused, or standing waves)"
                                   : "")));
  return out;
}

}  // namespace swell::validation::ocean_analysis
