#include "swell/reference/cascade.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/reference/sampling_validity.hpp"

namespace swell::reference {
namespace {

// sin²(π(x + 1)/4) clamped to [0, 1] outside |x| ≤ 1: the rising half of a crossover at x = 0.
double rising(double x) {
  if (x <= -1) return 0;
  if (x >= 1) return 1;
  const double s = std::sin(std::numbers::pi * (x + 1) / 4);
  return s * s;
}

// Within 1e-9 relative of an integer, that integer; else 0.
long long integer_ratio(double ratio) {
  const double r = std::round(ratio);
  return r >= 1 && std::abs(ratio - r) <= 1e-9 * r ? static_cast<long long>(r) : 0;
}

// The |k| where grid g holds whole rings: from its Δk to its Nyquist (its corners beyond hold a
// ring only in part).
double grid_lowest(const Grid& g) { return std::min(g.dkx(), g.dky()); }
double grid_highest(const Grid& g) {
  return std::numbers::pi * std::min(g.nx / g.lx, g.ny / g.ly);
}

// w² of a member where its grid holds |k| = k, 0 elsewhere.
double carried_weight(const CascadeMember& m, double k) {
  if (k < grid_lowest(m.grid) || k >= grid_highest(m.grid)) return 0;
  return m.band.weight_squared(k);
}

std::string cascade_list(const std::vector<int>& cascades) {
  if (cascades.empty()) return "no cascade";
  std::string out = cascades.size() == 1 ? "cascade " : "cascades ";
  for (std::size_t i = 0; i < cascades.size(); ++i) {
    if (i > 0) out += i + 1 == cascades.size() ? " and " : ", ";
    out += std::to_string(cascades[i]);
  }
  return out;
}

}  // namespace

double BandWeight::weight_squared(double k) const {
  if (crossover == 1) return k >= lo && k < hi ? 1.0 : 0.0;
  const double log_r = std::log(crossover);
  const double up = lo > 0 ? rising(std::log(k / lo) / log_r) : 1.0;
  const double down = std::isinf(hi) ? 1.0 : 1.0 - rising(std::log(k / hi) / log_r);
  return up * down;
}

std::string BandWeight::describe() const {
  std::string out = std::isinf(hi) ? fmt::format("[{:.4g}, inf) rad/m", lo)
                                   : fmt::format("[{:.4g}, {:.4g}) rad/m", lo, hi);
  if (crossover != 1) out += fmt::format(", crossover ×{:g}", crossover);
  return out;
}

void BandWeight::validate(const std::string& what) const {
  if (!(std::isfinite(lo) && lo >= 0)) {
    throw InvalidInput(fmt::format("{}: band lower edge must be finite and ≥ 0 rad/m (got {:g})",
                                   what, lo));
  }
  if (!(hi > lo)) {
    throw InvalidInput(fmt::format("{}: band [{:g}, {:g}) is empty: the upper edge must exceed "
                                   "the lower (rad/m)",
                                   what, lo, hi));
  }
  if (!(std::isfinite(crossover) && crossover >= 1)) {
    throw InvalidInput(fmt::format("{}: crossover must be a ratio ≥ 1 (1: hard cuts; got {:g})",
                                   what, crossover));
  }
  if (crossover > 1 && lo > 0 && std::isfinite(hi) && hi / lo <= crossover * crossover) {
    throw InvalidInput(fmt::format(
        "{}: band [{:g}, {:g}) is too narrow for crossover ×{:g}: its two transitions "
        "[lo/r, lo·r] and [hi/r, hi·r] overlap (needs hi/lo > r² = {:g})",
        what, lo, hi, crossover, crossover * crossover));
  }
}

std::string to_string(CascadeRelation relation) {
  switch (relation) {
    case CascadeRelation::nested:
      return "nested";
    case CascadeRelation::independent:
      return "independent";
    case CascadeRelation::additive:
      break;
  }
  return "additive";
}

bool summed_grid(const std::vector<CascadeMember>& members, Grid& fine, std::string* why) {
  if (members.empty()) return false;
  double lx = 0, ly = 0, sx = std::numeric_limits<double>::infinity(), sy = sx;
  for (const auto& m : members) {
    lx = std::max(lx, m.grid.lx);
    ly = std::max(ly, m.grid.ly);
    sx = std::min(sx, m.grid.lx / m.grid.nx);
    sy = std::min(sy, m.grid.ly / m.grid.ny);
  }
  for (const auto& m : members) {
    if (!integer_ratio(lx / m.grid.lx) || !integer_ratio(ly / m.grid.ly)) {
      if (why) {
        *why = fmt::format("cascade {}'s patch {:g}×{:g} m does not divide the largest patch "
                           "{:g}×{:g} m a whole number of times",
                           m.cascade, m.grid.lx, m.grid.ly, lx, ly);
      }
      return false;
    }
  }
  const long long nx = integer_ratio(lx / sx), ny = integer_ratio(ly / sy);
  if (!nx || !ny || nx > (1 << 30) || ny > (1 << 30)) {
    if (why) {
      *why = fmt::format("the finest spacing {:g}×{:g} m does not divide the largest patch "
                         "{:g}×{:g} m a whole number of times",
                         sx, sy, lx, ly);
    }
    return false;
  }
  fine = Grid{int(nx), int(ny), lx, ly};
  return true;
}

std::string BandCoverageProblem::describe() const {
  const std::string range = fmt::format("{:.3g}–{:.3g} rad/m", k_lo, k_hi);
  const std::string share = fmt::format("{:.2g} % of m0", 100 * m0_share);
  if (weight_sum < 0.5 && cascades.empty()) {
    return fmt::format("no cascade carries {}: {} lost", range, share);
  }
  if (cascades.size() >= 2 && weight_sum > 1) {
    return fmt::format("{} {} carry {}: energy × {:.3g} there, {}", cascade_list(cascades),
                       cascades.size() == 2 ? "both" : "all", range, weight_sum, share);
  }
  return fmt::format("{} weigh{} {} with Σ w² = {:.3g}, not 1: energy × {:.3g} there, {}",
                     cascade_list(cascades), cascades.size() == 1 ? "s" : "", range, weight_sum,
                     weight_sum, share);
}

std::vector<BandCoverageProblem> band_coverage(const OceanCase& sea,
                                               const std::vector<CascadeMember>& members) {
  // The range to examine: from the lowest |k| a cascade carries to the highest, past the outer
  // edges' own transitions (a crossover there tapers the set's band as a grid's limits do; it
  // neither overlaps nor leaves a gap). Each cascade carries its band where its grid holds
  // whole rings of |k| (carried_weight), so bands declared over the whole spectrum end where
  // their grids do.
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  std::vector<double> edges;
  for (const auto& m : members) {
    const double g_lo = grid_lowest(m.grid), g_hi = grid_highest(m.grid);
    const double carried_lo = std::max(m.band.lo * m.band.crossover, g_lo);
    const double carried_hi = std::min(m.band.hi / m.band.crossover, g_hi);
    if (!(carried_hi > carried_lo)) continue;  // a band its grid cannot hold: carries nothing
    lo = std::min(lo, carried_lo);
    hi = std::max(hi, carried_hi);
    for (double e : {m.band.lo, m.band.hi}) {
      if (e > 0 && std::isfinite(e)) {
        edges.push_back(e / m.band.crossover);
        edges.push_back(e);
        edges.push_back(e * m.band.crossover);
      }
    }
    edges.push_back(g_lo);
    edges.push_back(g_hi);
  }
  if (!(hi > lo)) return {};
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  edges.erase(std::remove_if(edges.begin(), edges.end(),
                             [&](double e) { return e < lo || e > hi; }),
              edges.end());
  // Sample Σ w² on a fine logarithmic grid between consecutive edges (and just beside each edge,
  // where hard cuts jump), and group consecutive samples whose sum is not 1 into ranges.
  std::vector<double> ks;
  std::vector<double> cuts = edges;
  cuts.push_back(lo);
  cuts.push_back(hi);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (b <= a) continue;
    constexpr int kSamples = 64;
    for (int s = 0; s < kSamples; ++s) ks.push_back(a * std::pow(b / a, (s + 0.5) / kSamples));
  }
  const auto spectrum = sea.sea_spectrum();
  const auto& omni = spectrum->omnidirectional();
  const double m0 = spectral_moment(omni, 0);
  const auto dispersion = sea.dispersion();
  std::vector<BandCoverageProblem> problems;
  auto share = [&](double a, double b) {
    if (!(m0 > 0)) return 0.0;
    return spectral_moment(omni, 0, Band{dispersion.omega(a), dispersion.omega(b)}) / m0;
  };
  auto weights = [&](double k) {
    double sum = 0;
    std::vector<int> carrying;
    for (const auto& m : members) {
      const double w2 = carried_weight(m, k);
      sum += w2;
      if (w2 > 0) carrying.push_back(m.cascade);
    }
    return std::pair{sum, carrying};
  };
  for (std::size_t i = 0; i < ks.size();) {
    auto [sum, carrying] = weights(ks[i]);
    if (std::abs(sum - 1) <= 1e-9) {
      ++i;
      continue;
    }
    // A run of samples with the same carrying cascades and a sum off 1 on the same side.
    std::size_t j = i + 1;
    while (j < ks.size()) {
      auto [next_sum, next_carrying] = weights(ks[j]);
      if (std::abs(next_sum - 1) <= 1e-9 || next_carrying != carrying ||
          (next_sum > 1) != (sum > 1)) {
        break;
      }
      ++j;
    }
    // The range's ends: the edges enclosing the samples i … j − 1.
    const auto below = std::upper_bound(cuts.begin(), cuts.end(), ks[i]);
    const auto above = std::lower_bound(cuts.begin(), cuts.end(), ks[j - 1]);
    BandCoverageProblem p;
    p.k_lo = below == cuts.begin() ? ks[i] : *(below - 1);
    p.k_hi = above == cuts.end() ? ks[j - 1] : *above;
    p.weight_sum = weights(std::sqrt(ks[i] * ks[j - 1])).first;
    p.cascades = carrying;
    p.m0_share = share(p.k_lo, p.k_hi);
    if (!problems.empty() && problems.back().k_hi == p.k_lo &&
        problems.back().cascades == p.cascades &&
        (problems.back().weight_sum > 1) == (p.weight_sum > 1)) {
      problems.back().k_hi = p.k_hi;
      problems.back().m0_share = share(problems.back().k_lo, p.k_hi);
    } else {
      problems.push_back(p);
    }
    i = j;
  }
  return problems;
}

std::vector<BandCoverageProblem> band_sharing_problems(const OceanCase& sea,
                                                       const std::vector<CascadeMember>& members) {
  std::vector<BandCoverageProblem> out;
  for (auto& p : band_coverage(sea, members)) {
    if (p.m0_share > kSmallestEnergyFraction) out.push_back(std::move(p));
  }
  return out;
}

void require_bands_share_out(const OceanCase& sea, const std::vector<CascadeMember>& members) {
  const auto problems = band_sharing_problems(sea, members);
  if (problems.empty()) return;
  std::string list;
  for (const auto& p : problems) list += (list.empty() ? "" : "; ") + p.describe();
  throw InvalidInput(fmt::format(
      "the cascades' bands do not share the spectrum out once: {} (an additive set has "
      "Σ w² = 1 wherever its grids hold the spectrum, allowing {:g} of m0; relation = "
      "\"independent\" declares cascades that are each a whole sea of their own)",
      list, kSmallestEnergyFraction));
}

}  // namespace swell::reference
