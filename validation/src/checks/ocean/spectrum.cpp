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
  const int n = int(a.waves().size());
  const RingShape& shape = a.frame0_rings();
  const int rings = shape.rings;
  const double p = shape.p;
  // In the engine's terms: a band of |k| carrying twice its energy (two cascades overlapping).
  std::string shape_hint;
  if (p < alpha) {
    std::vector<const Wave*> order;
    order.reserve(a.waves().size());
    for (const Wave& w : a.waves()) order.push_back(&w);
    std::sort(order.begin(), order.end(), [](const Wave* x, const Wave* y) { return x->k < y->k; });
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
  // Every ring off by one factor is a scale error, whose whole factor is named here as energy
  // names it (energy's own total can miss it where a handful of waves carry the sea); the shape
  // is then judged again at the measured level, to say whether anything beyond the scale fails.
  std::string scale_explanation;
  const MeasuredLevel& level = a.measured_level();
  if (p < alpha && level.uniform && level.off()) {
    std::vector<NormalizedOrdinate> ordinates = a.frame0_ordinates();
    for (auto& o : ordinates) o.u /= level.level;
    const RingShape normalized = ring_shape(std::move(ordinates));
    const std::string cause = name_scale_cause(a, level.level, level.low, level.high, true);
    scale_explanation = fmt::format(
        "every ring carries {:.3g}–{:.3g}× the case's energy: one factor on every wave, {:.3g}× (the "
        "rings' median; Hs × {:.3g}){}; at that level the shape {} (p = {:.2g})",
        level.lowest_ring, level.highest_ring, level.level, std::sqrt(level.level),
        cause.empty() ? "" : " — " + cause,
        normalized.p < alpha ? "differs too" : "is the case's, so this failure is the scale's",
        normalized.p);
  }
  Results out;
  out.push_back(statistical_check(
      "spectrum.shape", a.subject(), shape.worst_ratio, 1.0, p, alpha,
      fmt::format("p ≥ α = {:.0e} (Gamma law per ring, Fisher's method over {} rings)", alpha, rings),
      fmt::format("periodogram/model {:.3f}…{:.3f} over {} rings of |k| ({} wave vectors); "
                  "worst ring at k = {:.4g} rad/m: {:.3f} (p = {:.2g}){}",
                  shape.low_ratio, shape.high_ratio, rings, n, shape.worst_k, shape.worst_ratio, shape.worst_p,
                  p >= alpha                  ? ""
                  : !scale_explanation.empty() ? " — " + scale_explanation
                                               : " — " + or_table(a, "the spectrum's shape differs from the case's" + shape_hint))));

  // Energy where the case puts (almost) none, in every frame: a fault can live in some frames
  // only (a mean level that oscillates and is zero at frame 0). Each frame's stray energy is a
  // weighted sum of exponentials under the case (what μ puts below the resolution floor) plus
  // the field's rounding; the frames are judged at α/F each (Bonferroni: they are not
  // independent, and the bound is conservative for that).
  const Sampling& sampling = a.sampling();
  const bool grid = !sampling.is_lattice();
  const Grid& g = sampling.grid();
  std::vector<double> weights;
  for (std::size_t e : a.stray_entries()) {
    const auto [nn, m] = sampling.wave_index(e);
    if (sampling.carries_energy(e) && in_half_plane(nn, m) && a.mu()[e] > 0) weights.push_back(2 * a.mu()[e]);
  }
  const auto& strays = a.frame_strays();
  const double frames = double(strays.size());
  // At the frames' measured level (MeasuredLevel): what μ puts below the floor scales with the
  // sea, and a scale error is energy's to name, not stray energy.
  const double level_scale = level.rings >= 4 && level.level > 0 ? level.level : 1.0;
  const double sampling_bound =
      weights.empty() ? 0.0 : level_scale * stats::WeightedExponentialSum(weights).quantile(1 - alpha / frames);
  // The field's own rounding (u per value, amplified by log2 N through a transform) may all
  // land there.
  // land there; and all of the storage's (half: at most storage² of the energy).
  const double rounding_share = std::pow(rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n()), 2) +
                                a.storage_roundoff() * a.storage_roundoff();
  auto bound_of = [&](const FrameStray& s) { return sampling_bound + rounding_share * s.mean_square; };
  std::size_t worst = 0, failing = 0, heaving = 0;
  for (std::size_t f = 0; f < strays.size(); ++f) {
    if (strays[f].energy / bound_of(strays[f]) > strays[worst].energy / bound_of(strays[worst])) worst = f;
    failing += strays[f].energy > bound_of(strays[f]);
    // The mean level alone would fail this frame.
    heaving += strays[f].mean_level * strays[f].mean_level > bound_of(strays[f]);
  }
  const FrameStray& s = strays[worst];
  const double bound = bound_of(s);
  const bool ok = s.energy <= bound;
  const auto [stray_n, stray_m] = sampling.wave_index(s.largest_at);
  std::string where = fmt::format("largest at (n, m) = ({}, {})", stray_n, stray_m);
  if (grid && (Grid::is_nyquist(stray_n, g.nx) || Grid::is_nyquist(stray_m, g.ny))) {
    where += ", the Nyquist row/column";
  } else if (grid && s.nyquist > bound) {
    // Spread thin over 2n entries, a filled Nyquist row and column is rarely the largest single
    // entry; alone it exceeds the bound, where the case puts nothing.
    where += fmt::format("; the Nyquist row and column alone carry {:.2g} of the energy, more than "
                         "the whole bound",
                         s.nyquist / std::max(s.mean_square, 1e-300));
  }
  if (!grid && s.largest_at != 0 && sampling.conjugate(s.largest_at) == s.largest_at) {
    where += ", the lattice's self-conjugate class N/2";
  }
  // A (−1)^(i+j) factor shifts the spectrum by (nx/2, ny/2): the waves pile up around the
  // Nyquist corner.
  if (s.corner > 0.5 * s.energy) {
    where += fmt::format("; {:.0f} % of it near the Nyquist corner — a checkerboard (−1)^(i+j)",
                         100 * s.corner / s.energy);
  }
  // Heave: k = 0 is the mean level. An artist sees the whole patch rise and fall (or sit
  // offset), not "energy at (0, 0)"; named whenever the mean level alone fails some frame.
  if (!ok && heaving > 0) {
    double level_square = 0, level_min = 1e300, level_max = -1e300, largest_share = 0;
    for (const FrameStray& x : strays) {
      level_square += x.mean_level * x.mean_level;
      level_min = std::min(level_min, x.mean_level);
      level_max = std::max(level_max, x.mean_level);
      largest_share = std::max(largest_share, x.mean_level * x.mean_level / x.mean_square);
    }
    const double rms = std::sqrt(level_square / frames);
    const double rounding_level = rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n()) * std::sqrt(a.mean_square0());
    const std::string in_frames =
        strays.size() > 1 ? fmt::format(" in {} of {} frames", heaving, strays.size()) : "";
    if (strays.size() > 1 && level_max - level_min > rounding_level) {
      where = fmt::format("k = 0 carries up to {:.0f} % of the height variance{}: the mean level moves "
                          "(heave) — the whole patch rises and falls, rms {:.3g} m, from {:.3g} to {:.3g} m "
                          "over the frames",
                          100 * largest_share, in_frames, rms, level_min, level_max);
    } else {
      where = fmt::format("k = 0 carries {:.0f} % of the height variance: the mean level sits at {:.3g} m "
                          "instead of 0",
                          100 * largest_share, level_max);
    }
  }
  const std::string frame_note =
      strays.size() == 1 ? ""
      : ok               ? fmt::format(" (worst of {} frames: frame {})", strays.size(), worst)
                         : fmt::format(" at frame {} ({} of {} frames fail)", worst, failing, strays.size());
  out.push_back(bounded_check(
      "spectrum.unexpected_energy", a.subject(), s.energy / std::max(s.mean_square, 1e-300),
      bound / std::max(s.mean_square, 1e-300),
      fmt::format("fraction of mean h² where the case puts none ≤ {:.1e} in every frame (1 − α/frames "
                  "quantile + rounding)",
                  bound / s.mean_square),
      ok ? fmt::format("{:.1e} of the energy where the case puts none{}", s.energy / s.mean_square, frame_note)
         : fmt::format("{:.3g} of the energy sits where the case puts none{} ({})",
                       s.energy / s.mean_square, frame_note, where)));

  // Where the case puts exactly nothing (μ = 0: k = 0, a grid's Nyquist row and column, bins a
  // band or spreading leaves empty) only rounding may land, in every frame: an exact check, so
  // a filled Nyquist row is seen even where the unresolved waves' own sampling scatter (half
  // storage leaves many) would hide it in the sum above.
  std::size_t worst_empty = 0, failing_empty = 0;
  auto empty_bound = [&](const FrameStray& x) { return rounding_share * x.mean_square; };
  for (std::size_t f = 0; f < strays.size(); ++f) {
    const double ratio = strays[f].empty / std::max(empty_bound(strays[f]), 1e-300);
    if (ratio > strays[worst_empty].empty / std::max(empty_bound(strays[worst_empty]), 1e-300)) worst_empty = f;
    failing_empty += strays[f].empty > empty_bound(strays[f]);
  }
  const FrameStray& e = strays[worst_empty];
  const double e_bound = empty_bound(e), e_square = std::max(e.mean_square, 1e-300);
  const bool empty_ok = e.empty <= e_bound;
  std::string empty_where;
  if (!empty_ok) {
    const double level_power = e.mean_level * e.mean_level;
    if (grid && e.nyquist >= 0.5 * e.empty) {
      empty_where = fmt::format("the Nyquist row and column carry {:.2g} of it — a Nyquist bin filled (the "
                                "conventions leave it empty), or two fields packed in one complex "
                                "transform leaking there",
                                e.nyquist / e_square);
    } else if (level_power >= 0.5 * e.empty) {
      empty_where = fmt::format("k = 0 carries {:.2g} of it: the mean level sits at {:.3g} m (heave, "
                                "spectrum.unexpected_energy)",
                                level_power / e_square, e.mean_level);
    } else {
      empty_where = "wave vectors where the case's spectrum is zero";
    }
  }
  const std::string empty_note =
      strays.size() == 1 ? ""
      : empty_ok         ? fmt::format(" (worst of {} frames: frame {})", strays.size(), worst_empty)
                         : fmt::format(" at frame {} ({} of {} frames fail)", worst_empty, failing_empty, strays.size());
  out.push_back(bounded_check(
      "spectrum.empty_energy", a.subject(), e.empty / e_square, e_bound / e_square,
      fmt::format("fraction of mean h² where μ = 0 ≤ {:.1e} in every frame (rounding)", e_bound / e_square),
      empty_ok ? fmt::format("{:.1e} of the energy where the case puts exactly none{}", e.empty / e_square, empty_note)
               : fmt::format("{:.3g} of the energy sits where the case puts exactly none{}: {}", e.empty / e_square,
                             empty_note, empty_where)));
  return out;
}

}  // namespace swell::validation::ocean_analysis
