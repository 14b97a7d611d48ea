#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::ocean_analysis {

// u(k) = I(k)/μ(k) are independent Exp(1) over the resolved half plane. In rings of |k| with
// n wave vectors each, Σ u ~ Gamma(n, 1) exactly; the rings' two-sided p-values combine by
// Fisher's method. Energy where the case puts none (k = 0, Nyquist, μ below resolution) must
// stay within the sampling law of what μ puts there plus rounding.
Results check_spectrum(const Analysis& a, OceanCheckReport&) {
  const double alpha = a.options().alpha / 2;
  std::vector<const Wave*> order;
  std::vector<NormalizedOrdinate> ordinates;
  for (const Wave& w : a.waves()) {
    order.push_back(&w);
    ordinates.push_back({w.k, a.periodogram0(w.index) / w.mu});
  }
  std::sort(order.begin(), order.end(), [](const Wave* x, const Wave* y) { return x->k < y->k; });
  const int n = int(order.size());
  const RingShape shape = ring_shape(std::move(ordinates));
  const int rings = shape.rings;
  const double p = shape.p;
  // In the engine's terms: a band of |k| carrying twice its energy (two cascades overlapping).
  std::string shape_hint;
  if (p < alpha) {
    int doubled = 0;
    double lowest = 1e300;
    for (int r = 0; r < rings; ++r) {
      const int begin = r * n / rings, end = (r + 1) * n / rings;
      double energy = 0, observed = 0;
      for (int i = begin; i < end; ++i) {
        energy += order[i]->mu;
        observed += a.periodogram0(order[i]->index);
      }
      const double ratio = observed / energy;  // energy-weighted: what the ring carries
      doubled += std::abs(ratio - 2) < 0.3;
      lowest = std::min(lowest, ratio);
    }
    if (doubled >= 2 && lowest < 1.3) {
      shape_hint = fmt::format(" — {} rings of |k| carry twice their energy: a band counted twice "
                               "(overlapping cascades?)", doubled);
    }
  }
  Results out;
  out.push_back(statistical_check(
      "spectrum.shape", a.subject(), shape.worst_ratio, 1.0, p, alpha,
      fmt::format("p ≥ α = {:.0e} (Gamma law per ring, Fisher's method over {} rings)", alpha, rings),
      fmt::format("periodogram/model {:.3f}…{:.3f} over {} rings of |k| ({} wave vectors); "
                  "worst ring at k = {:.4g} rad/m: {:.3f} (p = {:.2g}){}",
                  shape.low_ratio, shape.high_ratio, rings, n, shape.worst_k, shape.worst_ratio, shape.worst_p,
                  p < alpha ? " — " + or_table(a, "the spectrum's shape differs from the case's" + shape_hint) : "")));

  // Energy where the case puts (almost) none.
  const Sampling& sampling = a.sampling();
  const bool grid = !sampling.is_lattice();
  const Grid& g = sampling.grid();
  double stray = 0, largest_stray = 0, stray_corner = 0;
  std::size_t largest_at = 0;
  std::vector<double> weights;
  for (std::size_t e = 0; e < a.count(); ++e) {
    const bool carries = sampling.carries_energy(e);
    const bool unresolved = !carries || a.mu()[e] < a.floor();
    if (!unresolved) continue;
    const auto [nn, m] = sampling.wave_index(e);
    const double power = a.periodogram0(e);
    stray += power;
    if (grid && std::abs(nn) >= g.nx / 4 && std::abs(m) >= g.ny / 4) stray_corner += power;
    if (power > largest_stray) {
      largest_stray = power;
      largest_at = e;
    }
    if (carries && in_half_plane(nn, m) && a.mu()[e] > 0) weights.push_back(2 * a.mu()[e]);
  }
  double bound = 0;
  if (!weights.empty()) bound = stats::WeightedExponentialSum(weights).quantile(1 - alpha);
  // The field's own rounding (u per value, amplified by log2 N through a transform) may all
  // land there.
  const double rounding = std::pow(rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n()), 2) * a.mean_square0();
  bound += rounding;
  const auto [stray_n, stray_m] = sampling.wave_index(largest_at);
  std::string where = fmt::format("largest at (n, m) = ({}, {})", stray_n, stray_m);
  if (grid && (Grid::is_nyquist(stray_n, g.nx) || Grid::is_nyquist(stray_m, g.ny))) {
    where += ", the Nyquist row/column";
  }
  if (!grid && largest_at != 0 && sampling.conjugate(largest_at) == largest_at) {
    where += ", the lattice's self-conjugate class N/2";
  }
  // A (−1)^(i+j) factor shifts the spectrum by (nx/2, ny/2): the waves pile up around the
  // Nyquist corner.
  if (stray_corner > 0.5 * stray) {
    where += fmt::format("; {:.0f} % of it near the Nyquist corner — a checkerboard (−1)^(i+j)",
                         100 * stray_corner / stray);
  }
  // Heave: k = 0 is the mean level. An artist sees the whole patch rise and fall (or sit
  // offset), not "energy at (0, 0)".
  if (largest_at == 0 && stray > bound) {
    const double share = a.periodogram0(0) / a.mean_square0();
    double level_sum = 0, level_square = 0, level_min = 1e300, level_max = -1e300;
    const auto frames = a.frames().frames.size();
    for (std::size_t f = 0; f < frames; ++f) {
      const auto& h = a.frames().field(int(f), Field::height);
      const double level = std::accumulate(h.begin(), h.end(), 0.0) / double(h.size());
      level_sum += level;
      level_square += level * level;
      level_min = std::min(level_min, level);
      level_max = std::max(level_max, level);
    }
    const double rms = std::sqrt(level_square / double(frames));
    const double rounding_level = rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n()) * std::sqrt(a.mean_square0());
    if (frames > 1 && level_max - level_min > rounding_level) {
      where = fmt::format("k = 0 carries {:.0f} % of the height variance: the mean level moves (heave) — "
                          "the whole patch rises and falls, rms {:.3g} m, from {:.3g} to {:.3g} m over the "
                          "frames",
                          100 * share, rms, level_min, level_max);
    } else {
      where = fmt::format("k = 0 carries {:.0f} % of the height variance: the mean level sits at {:.3g} m "
                          "instead of 0",
                          100 * share, level_sum / double(frames));
    }
  }
  const bool ok = stray <= bound;
  out.push_back(bounded_check(
      "spectrum.unexpected_energy", a.subject(), stray / a.mean_square0(), bound / a.mean_square0(),
      fmt::format("fraction of mean h² where the case puts none ≤ {:.1e} (1 − α quantile + rounding)",
                  bound / a.mean_square0()),
      ok ? fmt::format("{:.1e} of the energy where the case puts none", stray / a.mean_square0())
         : fmt::format("{:.3g} of the energy sits where the case puts none ({})",
                       stray / a.mean_square0(), where)));
  return out;
}

}  // namespace swell::validation::ocean_analysis
