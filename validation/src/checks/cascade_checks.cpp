// The checks of a cascade set as a whole (cascade_checks.hpp, docs/gate.md §10).
#include "swell/validation/stats/rounding.hpp"
#include "swell/validation/checks/cascade_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>

#include "common/parallel_tasks.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/phase.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/validation/stats/statistics.hpp"
#include "swell/validation/stats/wave_fit.hpp"

namespace swell::validation {
namespace {

using reference::Field;
using reference::Grid;
using reference::OceanCase;
using Complex = std::complex<double>;

// A periodogram ordinate below this fraction of its mean counts as empty: P(I < q μ) =
// 1 − e^(−q) ≈ q for the exponential law of one ordinate.
constexpr double kEmptyFraction = 1e-4;

// What the band checks need of one grid surface: frame 0's periodogram, and per entry |k|, the
// components and what the sea (no band weight) and the case put there.
struct SurfaceSpectrum {
  Grid grid;
  std::vector<double> power;      // I(k) of frame 0
  std::vector<double> mu;         // μ(k) of the case (band weight included)
  std::vector<double> mu_sea;     // μ(k) the sea would put there on this grid
  std::vector<double> k, kx, ky;  // rad/m
  double mean_square = 0;         // Σ I = mean h² of frame 0
  double rounding_power = 0;      // rounding: the stray energy a right surface may show
};

// `mu`: the case's μ(k) on its grid (expected_periodogram); `unit_roundoff`: the frames' stored
// precision, as every frame showed it.
SurfaceSpectrum surface_spectrum(const OceanCase& ocean, double unit_roundoff,
                                 const std::vector<Complex>& spectrum, std::vector<double> mu) {
  SurfaceSpectrum s;
  s.grid = ocean.grid;
  s.power.resize(spectrum.size());
  for (std::size_t e = 0; e < spectrum.size(); ++e) s.power[e] = std::norm(spectrum[e]);
  s.mu = std::move(mu);
  s.mu_sea = expected_periodogram(*ocean.sea_spectrum(), ocean.grid);
  const auto& g = ocean.grid;
  s.k.resize(s.power.size());
  s.kx.resize(s.power.size());
  s.ky.resize(s.power.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t e = std::size_t(j) * g.nx + i;
      s.kx[e] = Grid::signed_index(i, g.nx) * g.dkx();
      s.ky[e] = Grid::signed_index(j, g.ny) * g.dky();
      s.k[e] = std::hypot(s.kx[e], s.ky[e]);
    }
  }
  s.mean_square = std::accumulate(s.power.begin(), s.power.end(), 0.0);
  // As the spectrum check's stray energy: the field's own rounding (u per value, amplified by
  // log2 N through a transform) may all land where the case puts nothing.
  const double log2n = std::log2(double(g.nx) * g.ny);
  s.rounding_power = std::pow(rounding_budget(kTransformRounding, unit_roundoff, log2n), 2) * s.mean_square;
  return s;
}

bool carries(const Grid& g, std::size_t e) {
  return g.carries_energy(Grid::signed_index(int(e % g.nx), g.nx),
                          Grid::signed_index(int(e / g.nx), g.ny));
}

bool half_plane(const Grid& g, std::size_t e) {
  return in_half_plane(Grid::signed_index(int(e % g.nx), g.nx),
                       Grid::signed_index(int(e / g.nx), g.ny));
}

// The |k| range holding the middle 98 % of `energy` over `entries`.
std::pair<double, double> energy_range(const std::vector<std::size_t>& entries,
                                       const std::vector<double>& k,
                                       const std::vector<double>& energy) {
  std::vector<std::size_t> order = entries;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return k[a] < k[b]; });
  double total = 0;
  for (auto e : order) total += energy[e];
  double running = 0, lo = k[order.front()], hi = k[order.back()];
  bool have_lo = false;
  for (auto e : order) {
    running += energy[e];
    if (!have_lo && running >= 0.01 * total) {
      lo = k[e];
      have_lo = true;
    }
    if (running >= 0.99 * total) {
      hi = k[e];
      break;
    }
  }
  return {lo, hi};
}

std::string cascades_named(const std::vector<int>& list) {
  std::string out = list.size() == 1 ? "cascade " : "cascades ";
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (i > 0) out += i + 1 == list.size() ? " and " : ", ";
    out += std::to_string(list[i]);
  }
  return out;
}

// The members other than `self` whose band has weight somewhere in [a, b].
std::vector<int> covering(const std::vector<reference::CascadeMember>& members, int self, double a,
                          double b) {
  std::vector<int> out;
  for (const auto& m : members) {
    if (m.cascade == self) continue;
    if (m.band.support_lo() <= b && m.band.support_hi() > a) out.push_back(m.cascade);
  }
  return out;
}

// Runs of nearly empty ordinates among the entries where the case puts energy, in order of |k|
// over the half plane (one of each ±k pair): a right surface has P(I < q μ) = 1 − e^(−q) per
// ordinate, independently, so a run of L starting at any of M places has probability at most
// M (1 − e^(−q))^L (the union bound: the test keeps its false-alarm rate whatever the grid).
struct EmptyRuns {
  int longest = 0;
  int places = 0;
  double p_value = 1;
  double k_lo = 0, k_hi = 0;  // the |k| spanned by the runs the test rejects
  double lost_mu = 0;         // Σ μ over those runs (both halves)
};

EmptyRuns empty_runs(const SurfaceSpectrum& s, const std::vector<double>& mu, double alpha) {
  std::vector<std::size_t> order;
  for (std::size_t e = 0; e < mu.size(); ++e) {
    if (mu[e] > 0 && carries(s.grid, e) && half_plane(s.grid, e)) order.push_back(e);
  }
  std::sort(order.begin(), order.end(), [&](auto a, auto b) {
    return s.k[a] != s.k[b] ? s.k[a] < s.k[b] : a < b;
  });
  EmptyRuns out;
  out.places = int(order.size());
  const double q = -std::expm1(-kEmptyFraction);
  // The shortest run the test rejects at α.
  int rejected = 1;
  while (order.size() * std::pow(q, rejected) >= alpha && rejected < 1 << 20) ++rejected;
  out.k_lo = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < order.size();) {
    if (!(s.power[order[i]] < kEmptyFraction * mu[order[i]])) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < order.size() && s.power[order[j]] < kEmptyFraction * mu[order[j]]) ++j;
    const int length = int(j - i);
    out.longest = std::max(out.longest, length);
    if (length >= rejected) {
      out.k_lo = std::min(out.k_lo, s.k[order[i]]);
      out.k_hi = std::max(out.k_hi, s.k[order[j - 1]]);
      for (std::size_t r = i; r < j; ++r) out.lost_mu += 2 * mu[order[r]];
    }
    i = j;
  }
  out.p_value = out.longest == 0 ? 1.0 : std::min(1.0, order.size() * std::pow(q, out.longest));
  return out;
}

// The energy a surface shows where its case puts none (μ = 0 on a wave vector its grid
// carries): the total, and where it lies. What a cascade's band.outside and the sum's judge.
struct StrayEnergy {
  double total = 0;
  std::vector<std::size_t> entries;
};
StrayEnergy stray_energy(const SurfaceSpectrum& s) {
  StrayEnergy out;
  for (std::size_t e = 0; e < s.power.size(); ++e) {
    if (carries(s.grid, e) && s.mu[e] == 0) {
      out.total += s.power[e];
      out.entries.push_back(e);
    }
  }
  return out;
}

// The missing-energy result shared by a cascade and the summed surface.
// `where_empty(a, b, share)` says in the engine's terms who leaves |k| ∈ [a, b] empty.
CheckResult missing_result(const std::string& name, const std::string& subject,
                           const SurfaceSpectrum& s, const std::vector<double>& mu,
                           const OceanCase& ocean,
                           const std::function<std::string(double, double, double)>& where_empty,
                           double alpha) {
  const EmptyRuns runs = empty_runs(s, mu, alpha);
  const double m0 = reference::spectral_moment(ocean.sea_spectrum()->omnidirectional(), 0);
  std::string reason;
  if (runs.p_value >= alpha) {
    reason = fmt::format("longest run of empty wave vectors (I < {:g} μ) in order of |k|: {} of "
                         "{} (p = {:.2g})",
                         kEmptyFraction, runs.longest, runs.places, runs.p_value);
  } else {
    reason = fmt::format("{} (a run of {} empty wave vectors where the case puts energy, "
                         "p = {:.2g})",
                         where_empty(runs.k_lo, runs.k_hi, runs.lost_mu / m0), runs.longest,
                         runs.p_value);
  }
  return statistical_check(
      name, subject, runs.longest, 0, runs.p_value, alpha,
      fmt::format("p ≥ α = {:.0e} (runs of I < {:g} μ over {} wave vectors, union bound)", alpha,
                  kEmptyFraction, runs.places),
      reason);
}

bool height_only(int, Field field) { return field == Field::height; }

const std::vector<double>& height_of(const reference::FieldFrame& frame) {
  return frame.fields.at(Field::height);
}

// The initial amplitudes h̃0(k) of a surface recovered from its frames' heights (grid order):
// with frames at two or more times, the least-squares a of ĥ(k, t) = a e^(−iωt) + b e^(iωt) at
// the case's ω(k) (a = h̃0(k), b = conj h̃0(−k)); with one frame at t = 0, ĥ(k, 0) itself
// (h̃0(k) + conj h̃0(−k): `mixed`). `valid` is false where the fit is degenerate
// (2ω dt ≡ 0 mod 2π) or k carries no energy on the grid; `usable` false when neither applies
// (one frame at t ≠ 0), with the reason.
struct RecoveredAmplitudes {
  std::vector<std::complex<double>> a;
  std::vector<char> valid;
  bool mixed = false;
  bool usable = true;
  std::string reason;
};

// The sums of the two-wave fit (wave_fit.hpp) of a set of entries over the frames, added to
// frame by frame in frame order: those fit_two_waves makes of a whole series, bit for bit.
struct TwoWaveSums {
  std::vector<std::size_t> entries;  // grid order
  std::vector<double> omega;         // per entry
  std::vector<Complex> s, r1, r2;    // Σ conj(e)², Σ conj(e) y, Σ e y, e = e^(−iωt)
  void start() {
    s.assign(entries.size(), 0.0);
    r1.assign(entries.size(), 0.0);
    r2.assign(entries.size(), 0.0);
  }
  void add(double t, const std::vector<Complex>& spectrum) {
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const Complex e = reference::unit_phasor(-reference::reduced_phase(omega[i], t));
      const Complex y = spectrum[entries[i]];
      s[i] += std::conj(e) * std::conj(e);
      r1[i] += std::conj(e) * y;
      r2[i] += e * y;
    }
  }
};

// The patch check's fit of one cascade's frames with ω(k) from a patch length (lx, ly), k =
// 2π (n, m)/L, over the half plane's entries the case fills above rounding: Σ over them of the
// fit's residual (of |ĥ|² where the fit is degenerate), and of |ĥ|².
struct PatchFit {
  double lx = 0, ly = 0;
  TwoWaveSums sums;
  std::vector<Complex> a, b;
  std::vector<char> fitted;
  std::vector<double> residual;  // per entry, Σf |ĥ − a e − b conj e|²
  double left = 0, total = 0;
};

// What the set checks need of one cascade, gathered by streaming its frames: frame 0's
// spectral view, the amplitudes recovered from every frame (one pass), and, with three frames
// or more, the patch check's fits for every patch length of the set (their residuals: a second
// pass).
struct CascadeAnalysis {
  int index = 0;
  const OceanCase* ocean = nullptr;
  const FrameSource* frames = nullptr;
  std::size_t frame_count = 0;
  std::vector<double> t;
  SurfaceSpectrum s;
  RecoveredAmplitudes recovered;
  std::vector<PatchFit> patch;  // its own patch length first
};

// The spectrum of frame f's height, as field_spectrum makes it, into `spectrum`.
void height_spectrum(const reference::FieldFrame& frame, const Grid& grid, std::vector<Complex>& spectrum) {
  field_spectrum(height_of(frame), reference::Sampling(grid), spectrum);
}

// `patch_lengths`: every cascade's (lx, ly) in the set.
CascadeAnalysis analyse(const CascadeView& view, const std::vector<std::pair<double, double>>& patch_lengths) {
  CascadeAnalysis a;
  a.index = view.index;
  a.ocean = view.ocean;
  a.frames = view.frames;
  const FrameSource& source = *view.frames;
  const OceanCase& ocean = *view.ocean;
  const Grid& g = ocean.grid;
  a.frame_count = source.size();
  for (std::size_t f = 0; f < a.frame_count; ++f) a.t.push_back(source.time(f));
  const std::size_t count = std::size_t(g.nx) * g.ny;
  std::vector<double> mu = expected_periodogram(*ocean.directional_spectrum(), g);

  // The recovery's fit at the case's ω(k), on every entry the grid fills (two frames or more).
  TwoWaveSums recovery;
  if (a.frame_count >= 2) {
    for (std::size_t e = 0; e < count; ++e) {
      if (!carries(g, e)) continue;
      const int n = Grid::signed_index(int(e % g.nx), g.nx), m = Grid::signed_index(int(e / g.nx), g.ny);
      recovery.entries.push_back(e);
      recovery.omega.push_back(ocean.omega(std::hypot(n * g.dkx(), m * g.dky())));
    }
    recovery.start();
  }
  // The patch check's fits (three frames or more), on the half plane's filled entries with
  // μ > 0; those below the rounding floor, known once every frame's precision is, are left out
  // at the end.
  if (a.frame_count >= 3) {
    std::vector<std::pair<double, double>> lengths = {{g.lx, g.ly}};
    for (const auto& length : patch_lengths) {
      if (std::find(lengths.begin(), lengths.end(), length) == lengths.end()) lengths.push_back(length);
    }
    for (const auto& [lx, ly] : lengths) {
      PatchFit fit;
      fit.lx = lx;
      fit.ly = ly;
      for (std::size_t e = 0; e < count; ++e) {
        if (!carries(g, e) || !half_plane(g, e) || !(mu[e] > 0)) continue;
        const int n = Grid::signed_index(int(e % g.nx), g.nx), m = Grid::signed_index(int(e / g.nx), g.ny);
        fit.sums.entries.push_back(e);
        fit.sums.omega.push_back(ocean.omega(std::hypot(2 * M_PI * n / lx, 2 * M_PI * m / ly)));
      }
      fit.sums.start();
      a.patch.push_back(std::move(fit));
    }
  }
  std::vector<Complex> spectrum0, spectrum;
  source.stream(height_only, [&](std::size_t f, const reference::FieldFrame& frame) {
    height_spectrum(frame, g, spectrum);
    if (f == 0) spectrum0 = spectrum;
    if (!recovery.entries.empty()) recovery.add(a.t[f], spectrum);
    for (PatchFit& fit : a.patch) fit.sums.add(a.t[f], spectrum);
  });
  a.s = surface_spectrum(ocean, source.precision().unit_roundoff, spectrum0, std::move(mu));

  RecoveredAmplitudes& out = a.recovered;
  out.a.assign(count, 0.0);
  out.valid.assign(count, 0);
  if (a.frame_count == 1) {
    if (a.t[0] != 0) {
      out.usable = false;
      out.reason = "one frame at t ≠ 0 cannot tell h̃0(k) from conj h̃0(−k)";
    } else {
      out.mixed = true;
      out.a = spectrum0;
      for (std::size_t e = 0; e < count; ++e) out.valid[e] = carries(g, e);
    }
  }
  const double frames = double(a.frame_count);
  for (std::size_t i = 0; i < recovery.entries.size(); ++i) {
    Complex amplitude, b;
    if (solve_two_waves(frames, recovery.s[i], recovery.r1[i], recovery.r2[i], amplitude, b)) {
      out.a[recovery.entries[i]] = amplitude;
      out.valid[recovery.entries[i]] = 1;
    }
  }
  if (a.patch.empty()) return a;

  // The second pass: each patch length's residuals, entry by entry in frame order.
  std::vector<double> energy(a.patch.front().sums.entries.size(), 0.0);  // Σf |ĥ|² per entry
  for (PatchFit& fit : a.patch) {
    const std::size_t n = fit.sums.entries.size();
    fit.a.assign(n, 0.0);
    fit.b.assign(n, 0.0);
    fit.fitted.assign(n, 0);
    fit.residual.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      fit.fitted[i] = solve_two_waves(frames, fit.sums.s[i], fit.sums.r1[i], fit.sums.r2[i], fit.a[i], fit.b[i]);
    }
  }
  source.stream(height_only, [&](std::size_t f, const reference::FieldFrame& frame) {
    height_spectrum(frame, g, spectrum);
    const auto& entries = a.patch.front().sums.entries;
    for (std::size_t i = 0; i < entries.size(); ++i) energy[i] += std::norm(spectrum[entries[i]]);
    for (PatchFit& fit : a.patch) {
      for (std::size_t i = 0; i < entries.size(); ++i) {
        if (!fit.fitted[i]) continue;
        const Complex e = reference::unit_phasor(-reference::reduced_phase(fit.sums.omega[i], a.t[f]));
        fit.residual[i] += std::norm(spectrum[entries[i]] - fit.a[i] * e - fit.b[i] * std::conj(e));
      }
    }
  });
  const double per_entry_rounding = a.s.rounding_power / double(a.s.power.size());
  for (PatchFit& fit : a.patch) {
    const auto& entries = fit.sums.entries;
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (!(a.s.mu[entries[i]] > 1e4 * per_entry_rounding)) continue;
      fit.total += energy[i];
      fit.left += fit.fitted[i] ? fit.residual[i] : energy[i];
    }
    fit.sums = {};
    fit.a = {};
    fit.b = {};
    fit.residual = {};
  }
  return a;
}

std::vector<CheckResult> band_checks(const CascadeAnalysis& analysis,
                                     const std::vector<reference::CascadeMember>& members,
                                     double alpha);
CheckResult energy_check(const std::vector<CascadeAnalysis>& cascades, bool independent,
                         double alpha);
CheckResult independence_check(const std::vector<CascadeAnalysis>& cascades, double alpha);
CheckResult patch_check(const std::vector<CascadeAnalysis>& cascades);
CheckResult nested_check(const std::vector<CascadeAnalysis>& cascades);

}  // namespace

CascadeSetResults run_cascade_set_checks(const std::vector<CascadeView>& cascades,
                                         const std::vector<reference::CascadeMember>& members,
                                         const CascadeSetOptions& options) {
  // One analysis per cascade, on the gate's threads, each streaming its cascade's frames.
  std::vector<std::pair<double, double>> patch_lengths;
  for (const auto& view : cascades) patch_lengths.emplace_back(view.ocean->grid.lx, view.ocean->grid.ly);
  std::vector<CascadeAnalysis> analyses(cascades.size());
  detail::run_tasks(cascades.size(), options.threads,
                    [&](std::size_t c) { analyses[c] = analyse(cascades[c], patch_lengths); });
  CascadeSetResults out;
  if (reference::is_summed(options.relation)) {
    for (const auto& a : analyses) out.bands.push_back(band_checks(a, members, options.alpha_per_check));
    if (analyses.size() >= 2) {
      if (!options.free_scale) {
        out.set.push_back(energy_check(
            analyses, options.relation == reference::CascadeRelation::independent,
            options.alpha_per_check));
      }
      out.set.push_back(independence_check(analyses, options.alpha_per_check));
      out.set.push_back(patch_check(analyses));
    }
  } else if (analyses.size() >= 2) {
    out.set.push_back(nested_check(analyses));
  }
  return out;
}

namespace {

std::vector<CheckResult> band_checks(const CascadeAnalysis& cascade,
                                     const std::vector<reference::CascadeMember>& members,
                                     double alpha) {
  const OceanCase& ocean = *cascade.ocean;
  const SurfaceSpectrum& s = cascade.s;
  const auto& band = ocean.band;
  const std::string prefix = fmt::format("cascade{}.band", cascade.index);
  const std::string subject = fmt::format("cascade {}: {}×{} over {:g}×{:g} m, band {}",
                                          cascade.index, s.grid.nx, s.grid.ny, s.grid.lx,
                                          s.grid.ly, band.describe());
  std::vector<CheckResult> out;

  // Outside the band: nothing beyond rounding.
  const StrayEnergy found = stray_energy(s);
  const double stray = found.total;
  const std::vector<std::size_t>& outside = found.entries;
  const bool clean = stray <= s.rounding_power;
  std::string reason;
  if (clean) {
    reason = fmt::format("{:.1e} of mean h² outside the band", stray / s.mean_square);
  } else {
    std::vector<std::size_t> significant;
    const double per_entry = s.rounding_power / double(std::max<std::size_t>(1, outside.size()));
    for (auto e : outside) {
      if (s.power[e] > per_entry && s.power[e] > 1e-6 * s.mu_sea[e]) significant.push_back(e);
    }
    if (significant.empty()) significant = outside;
    const auto [a, b] = energy_range(significant, s.k, s.power);
    double observed = 0, sea = 0;
    for (auto e : significant) {
      observed += s.power[e];
      sea += s.mu_sea[e];
    }
    const double ratio = sea > 0 ? observed / sea : 0;
    // A square cut: the energy found is what max(|kx|, |ky|) ∈ [lo, hi) would carry, and the
    // ring outside that square is empty.
    auto in_square = [&](std::size_t e) {
      const double c = std::max(std::abs(s.kx[e]), std::abs(s.ky[e]));
      return c >= band.lo && c < band.hi;
    };
    double stray_outside_square = 0, square_observed = 0, square_sea = 0;
    double ring_not_square_observed = 0, ring_not_square_mu = 0;
    for (std::size_t e = 0; e < s.power.size(); ++e) {
      if (!carries(s.grid, e)) continue;
      if (s.mu[e] == 0) {
        if (in_square(e)) {
          square_observed += s.power[e];
          square_sea += s.mu_sea[e];
        } else {
          stray_outside_square += s.power[e];
        }
      } else if (!in_square(e)) {
        ring_not_square_observed += s.power[e];
        ring_not_square_mu += s.mu[e];
      }
    }
    const bool square = band.crossover == 1 && stray_outside_square <= s.rounding_power &&
                        square_sea > 0 && square_observed > 0.3 * square_sea &&
                        (ring_not_square_mu == 0 ||
                         ring_not_square_observed < 0.1 * ring_not_square_mu);
    const auto others = covering(members, cascade.index, a, b);
    if (square) {
      reason = fmt::format(
          "cascade {}'s band is cut as a square in (kx, ky) (max(|kx|, |ky|) in [{:.4g}, {:.4g})), "
          "not as a ring in |k|: {:.3g} of mean h² lies in the square's corners outside the band",
          cascade.index, band.lo, band.hi, stray / s.mean_square);
    } else if (!others.empty()) {
      std::vector<int> both = {cascade.index};
      both.insert(both.end(), others.begin(), others.end());
      std::sort(both.begin(), both.end());
      reason = fmt::format("{} both carry {:.4g}–{:.4g} rad/m (energy × {:.2g} there): cascade {} "
                           "carries {:.2g}× the sea's energy beyond its band {}",
                           cascades_named(both), a, b, 1 + ratio, cascade.index, ratio,
                           band.describe());
    } else {
      reason = fmt::format("cascade {} carries {:.4g}–{:.4g} rad/m, outside its band {} ({:.2g}× "
                           "the sea's energy there; {:.3g} of mean h²)",
                           cascade.index, a, b, band.describe(), ratio, stray / s.mean_square);
    }
  }
  out.push_back(exact_check(
      prefix + ".outside", subject, stray / s.mean_square, s.rounding_power / s.mean_square, clean,
      fmt::format("fraction of mean h² where w² = 0 ≤ {:.1e} (rounding)", s.rounding_power / s.mean_square),
      reason));

  // Inside the band: no stretch of |k| left empty.
  auto where_empty = [&](double a, double b, double share) {
    const auto others = covering(members, cascade.index, a, b);
    if (others.empty()) {
      return fmt::format("no cascade carries {:.4g}–{:.4g} rad/m ({:.3g} % of m0 lost): cascade "
                         "{}'s band {} is declared to",
                         a, b, 100 * share, cascade.index, band.describe());
    }
    return fmt::format("cascade {} leaves {:.4g}–{:.4g} rad/m of its band {} empty ({:.3g} % of "
                       "m0; {} weigh it too)",
                       cascade.index, a, b, band.describe(), 100 * share, cascades_named(others));
  };
  out.push_back(missing_result(prefix + ".missing", subject, s, s.mu, ocean, where_empty, alpha));
  return out;
}

CheckResult energy_check(const std::vector<CascadeAnalysis>& cascades, bool independent,
                         double alpha) {
  std::vector<double> all_weights;
  double measured = 0, expected = 0;
  struct Part {
    double measured = 0, expected = 0;
    std::vector<double> weights;
  };
  std::vector<Part> parts;
  for (const auto& c : cascades) {
    const SurfaceSpectrum& s = c.s;
    Part part;
    for (std::size_t e = 0; e < s.power.size(); ++e) {
      if (!carries(s.grid, e)) continue;
      part.measured += s.power[e];
      part.expected += s.mu[e];
      if (half_plane(s.grid, e) && s.mu[e] > 0) part.weights.push_back(2 * s.mu[e]);
    }
    measured += part.measured;
    expected += part.expected;
    all_weights.insert(all_weights.end(), part.weights.begin(), part.weights.end());
    parts.push_back(std::move(part));
  }
  const stats::WeightedExponentialSum law(all_weights);
  const double p = law.two_sided_p(measured);
  // The sea of the sum: the set's, or (independent seas) every cascade's added.
  double m0 = 0;
  for (const auto& c : cascades) {
    m0 += reference::spectral_moment(c.ocean->sea_spectrum()->omnidirectional(), 0);
    if (!independent) break;
  }
  std::string reason = fmt::format("Σ mean h_c² = {:.4g} m² against the {} band-limited "
                                   "{:.4g} m² ({:.3g} % of the sea's m0 {:.4g} m²); ratio {:.3f}",
                                   measured, independent ? "seas'" : "union's", expected,
                                   100 * expected / m0, m0, measured / expected);
  if (p < alpha) {
    // Which cascade is off, and whether another cascade's Δk explains its factor.
    std::size_t worst = 0;
    double worst_p = 2;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const double pi = stats::WeightedExponentialSum(parts[i].weights).two_sided_p(parts[i].measured);
      if (pi < worst_p) {
        worst_p = pi;
        worst = i;
      }
    }
    const auto& part = parts[worst];
    const auto& grid = cascades[worst].ocean->grid;
    const stats::WeightedExponentialSum own(part.weights);
    std::string explained;
    for (std::size_t d = 0; d < cascades.size(); ++d) {
      if (d == worst) continue;
      const auto& other = cascades[d].ocean->grid;
      const double factor = (other.dkx() * other.dky()) / (grid.dkx() * grid.dky());
      if (std::abs(factor - 1) < 1e-9) continue;
      if (own.two_sided_p(part.measured / factor) >= 1e-3) {
        explained = fmt::format("cascade {} is scaled with cascade {}'s Δk (energy × {:.4g})",
                                cascades[worst].index, cascades[d].index, factor);
        break;
      }
    }
    if (explained.empty()) {
      explained = fmt::format("cascade {} carries {:.3g}× its band's energy (p = {:.2g})",
                              cascades[worst].index, part.measured / part.expected, worst_p);
    }
    reason = explained + "; " + reason;
  }
  return statistical_check(
      "cascades.energy", fmt::format("{} cascades", cascades.size()), measured, expected, p, alpha,
      fmt::format("p ≥ α = {:.0e} (two-sided, exact law of Σ I over the cascades)", alpha), reason);
}

CheckResult independence_check(const std::vector<CascadeAnalysis>& cascades, double alpha) {
  // Per cascade: z(n, m) = h̃0 / √E|h̃0|², unit-variance complex normal on a right surface.
  struct Normalized {
    std::map<std::pair<int, int>, Complex> z;
    bool mixed = false;
  };
  std::vector<Normalized> normalized;
  std::string unusable;
  for (const auto& c : cascades) {
    const RecoveredAmplitudes& recovered = c.recovered;
    Normalized out;
    out.mixed = recovered.mixed;
    if (!recovered.usable) {
      unusable = recovered.reason;
      normalized.push_back(out);
      continue;
    }
    const SurfaceSpectrum& s = c.s;
    const auto travelling = expected_travelling_power(*c.ocean->directional_spectrum(), s.grid);
    const double per_entry_rounding = s.rounding_power / double(s.power.size());
    for (std::size_t e = 0; e < s.power.size(); ++e) {
      if (!recovered.valid[e]) continue;
      // One frame at t = 0: ĥ = h̃0(k) + conj h̃0(−k), mean power μ(k), and ĥ(−k) = conj ĥ(k)
      // adds nothing: the half plane only.
      const double power = recovered.mixed ? s.mu[e] : travelling[e];
      if (recovered.mixed && !half_plane(s.grid, e)) continue;
      if (!(power > 1e4 * per_entry_rounding)) continue;  // rounding would dominate z
      const int n = Grid::signed_index(int(e % s.grid.nx), s.grid.nx);
      const int m = Grid::signed_index(int(e / s.grid.nx), s.grid.ny);
      out.z[{n, m}] = recovered.a[e] / std::sqrt(power);
    }
    normalized.push_back(std::move(out));
  }
  const std::size_t pairs = cascades.size() * (cascades.size() - 1) / 2;
  const double alpha_pair = alpha / double(std::max<std::size_t>(1, pairs));
  double worst_p = 1, worst_r = 0;
  std::string worst_text, findings;
  int compared = 0;
  for (std::size_t c = 0; c < cascades.size(); ++c) {
    for (std::size_t d = c + 1; d < cascades.size(); ++d) {
      Complex cross = 0;
      double norm_c = 0, norm_d = 0;
      long long count = 0;
      for (const auto& [key, zc] : normalized[c].z) {
        const auto it = normalized[d].z.find(key);
        if (it == normalized[d].z.end()) continue;
        cross += zc * std::conj(it->second);
        norm_c += std::norm(zc);
        norm_d += std::norm(it->second);
        ++count;
      }
      if (count < 2 || !(norm_c > 0) || !(norm_d > 0)) continue;
      ++compared;
      // For z_c uniform in direction on C^M and independent of z_d, |r|² ~ Beta(1, M − 1):
      // P(|r|² ≥ x) = (1 − x)^(M − 1), exact for Gaussian z whatever their common variance.
      const double r2 = std::norm(cross) / (norm_c * norm_d);
      const double p = std::pow(std::max(0.0, 1 - r2), double(count - 1));
      if (p < alpha_pair) {
        findings += fmt::format("{}cascades {} and {} share their random numbers (correlation "
                                "{:.3f} over {} common wave vectors (n, m), p = {:.2g})",
                                findings.empty() ? "" : "; ", cascades[c].index,
                                cascades[d].index, std::sqrt(r2), count, p);
      }
      if (p <= worst_p) {
        worst_p = p;
        worst_r = std::sqrt(r2);
        worst_text = fmt::format("largest correlation {:.3f}, cascades {} and {} over {} wave "
                                 "vectors (p = {:.2g})",
                                 worst_r, cascades[c].index, cascades[d].index, count, p);
      }
    }
  }
  std::string reason;
  if (compared == 0) {
    reason = unusable.empty() ? "no wave index (n, m) carries energy in two cascades: nothing to "
                                "compare"
                              : "amplitudes not recoverable: " + unusable;
  } else {
    reason = findings.empty() ? worst_text : findings;
  }
  // The p-value reported is the worst pair's, scaled by the pairs (Bonferroni).
  const double p_family = std::min(1.0, worst_p * double(std::max<std::size_t>(1, pairs)));
  return statistical_check(
      "cascades.independence", fmt::format("{} cascades", cascades.size()), worst_r, 0, p_family,
      alpha,
      fmt::format("p ≥ α = {:.0e} (|r|² ~ Beta(1, M − 1) per pair, Bonferroni over {} pairs)",
                  alpha, pairs),
      reason);
}

CheckResult patch_check(const std::vector<CascadeAnalysis>& cascades) {
  double worst_ratio = 1;
  std::string reason;
  for (const auto& c : cascades) {
    if (c.patch.empty()) continue;  // fewer than three frames
    const auto& g = c.ocean->grid;
    // The fit residual with ω from a patch length L (k = 2π (n, m)/L), relative to the energy.
    auto residual = [&](double lx, double ly) {
      for (const PatchFit& fit : c.patch) {
        if (fit.lx == lx && fit.ly == ly) return fit.total > 0 ? fit.left / fit.total : 0.0;
      }
      throw InternalError("patch_check: a patch length the cascade's analysis did not fit");
    };
    const double own = residual(g.lx, g.ly);
    for (const auto& d : cascades) {
      const auto& other = d.ocean->grid;
      if (&d == &c || (other.lx == g.lx && other.ly == g.ly)) continue;
      const double alternative = residual(other.lx, other.ly);
      // Another patch length explains the frames where their own does not.
      if (own > 1e-3 && alternative < 0.1 * own) {
        const double ratio = alternative / own;
        if (ratio < worst_ratio) {
          worst_ratio = ratio;
          reason = fmt::format(
              "cascade {}'s waves move at ω(k) of cascade {}'s patch length ({:g} m, not its own "
              "{:g} m): its k is 2π n/{:g} (fit residual {:.2g} of the energy with its own patch, "
              "{:.2g} with cascade {}'s)",
              c.index, d.index, other.lx, g.lx, other.lx, own, alternative, d.index);
        }
      }
    }
  }
  const bool ok = reason.empty();
  if (ok) reason = "every cascade moves at the ω(k) of its own patch (or no other patch explains it better)";
  return exact_check("cascades.patch", fmt::format("{} cascades", cascades.size()), worst_ratio,
                      0.1, ok,
                      "no other cascade's patch length fits a cascade's frames 10× better than "
                      "its own",
                      reason);
}

CheckResult nested_check(const std::vector<CascadeAnalysis>& cascades) {
  // The broad band: the grid with the most wave vectors; every other is its coarse part.
  std::size_t broad = 0;
  for (std::size_t c = 1; c < cascades.size(); ++c) {
    const auto& g = cascades[c].ocean->grid;
    const auto& b = cascades[broad].ocean->grid;
    if (double(g.nx) * g.ny > double(b.nx) * b.ny) broad = c;
  }
  const auto& bg = cascades[broad].ocean->grid;
  const FrameSource& bframes = *cascades[broad].frames;
  // Per coarse cascade, its frames against the broad band's, frame by frame: the broad band's
  // streamed once, each coarse cascade's frame f read beside it.
  struct Sums {
    Complex cross = 0;
    double low_power = 0, broad_power = 0, difference = 0, rounding_power = 0;
  };
  std::vector<Sums> sums(cascades.size());
  std::vector<std::size_t> compared;
  for (std::size_t c = 0; c < cascades.size(); ++c) {
    if (c != broad && cascades[c].frame_count == cascades[broad].frame_count) compared.push_back(c);
  }
  if (!compared.empty()) {
    std::vector<Complex> wide, low;
    bframes.stream(height_only, [&](std::size_t f, const reference::FieldFrame& frame) {
      height_spectrum(frame, bg, wide);
      for (std::size_t c : compared) {
        const auto& lg = cascades[c].ocean->grid;
        const FrameSource& lframes = *cascades[c].frames;
        height_spectrum(*lframes.frame(f, height_only), lg, low);
        Sums& sum = sums[c];
        double low_mean_square = 0, wide_mean_square = 0;
        for (const auto& x : low) low_mean_square += std::norm(x);
        for (const auto& x : wide) wide_mean_square += std::norm(x);
        const double u = std::max(lframes.precision().unit_roundoff, bframes.precision().unit_roundoff);
        sum.rounding_power += std::pow(rounding_budget(kTransformRounding, u, std::log2(double(bg.nx) * bg.ny)), 2) *
                              (low_mean_square + wide_mean_square);
        for (std::size_t e = 0; e < low.size(); ++e) {
          const int n = Grid::signed_index(int(e % lg.nx), lg.nx), m = Grid::signed_index(int(e / lg.nx), lg.ny);
          if (!lg.carries_energy(n, m)) continue;
          const std::size_t be = std::size_t((m + bg.ny) % bg.ny) * bg.nx + std::size_t((n + bg.nx) % bg.nx);
          sum.cross += low[e] * std::conj(wide[be]);
          sum.low_power += std::norm(low[e]);
          sum.broad_power += std::norm(wide[be]);
          sum.difference += std::norm(low[e] - wide[be]);
        }
      }
    });
  }
  double worst = 0, worst_bound = 0;
  std::string reason;
  bool ok = true;
  for (std::size_t c = 0; c < cascades.size(); ++c) {
    if (c == broad) continue;
    if (cascades[c].frame_count != cascades[broad].frame_count) {
      ok = false;
      reason = fmt::format("cascade {} has {} frames and the broad band (cascade {}) {}: nested "
                           "bands are two samplings of the same frames",
                           cascades[c].index, cascades[c].frame_count, cascades[broad].index,
                           cascades[broad].frame_count);
      continue;
    }
    const auto [cross, low_power, broad_power, difference, rounding_power] = sums[c];
    const double relative = broad_power > 0 ? std::sqrt(difference / broad_power) : 0;
    const double bound = broad_power > 0 ? std::sqrt(rounding_power / broad_power) : 0;
    if (relative > worst) {
      worst = relative;
      worst_bound = bound;
    }
    if (difference <= rounding_power) continue;
    ok = false;
    const double r = std::abs(cross) / std::sqrt(low_power * broad_power);
    const Complex beta = cross / broad_power;
    std::string why;
    if (r < 0.5) {
      why = fmt::format("its waves are not the broad band's at the same k (correlation {:.3f}): "
                        "different random numbers, or another seed",
                        r);
    } else if (std::abs(std::abs(beta) - 1) > 0.01) {
      why = fmt::format("it is the broad band's part × {:.4g} (amplitudes; correlation {:.3f})",
                        std::abs(beta), r);
    } else if (std::abs(std::arg(beta)) > 0.01) {
      why = fmt::format("it is the broad band's part with every wave's phase shifted by {:.3g}°",
                        std::arg(beta) * 180 / M_PI);
    } else {
      why = fmt::format("it differs from the broad band's part by {:.3g} of its rms (correlation "
                        "{:.4f})",
                        relative, r);
    }
    reason += fmt::format("{}cascade {} is not the broad band's (cascade {}) part at the same wave "
                          "vectors: {}",
                          reason.empty() ? "" : "; ", cascades[c].index, cascades[broad].index,
                          why);
  }
  if (ok) {
    reason = fmt::format("every coarse band equals the broad band's (cascade {}) part at the same "
                         "wave vectors, frame by frame ({:.2g} of its rms)",
                         cascades[broad].index, worst);
  }
  return exact_check("cascades.nested", fmt::format("{} nested cascades", cascades.size()),
                      worst, worst_bound, ok,
                      "|ĥ_low − ĥ_broad| over the low band ≤ rounding, every frame", reason);
}

}  // namespace

CheckResult check_band_sharing(const OceanCase& sea,
                               const std::vector<reference::CascadeMember>& members) {
  const auto problems = reference::band_coverage(sea, members);
  double largest = 0;
  bool overlap = false;
  std::string found;
  for (const auto& p : problems) {
    largest = std::max(largest, p.m0_share);
    if (p.m0_share <= reference::kSmallestEnergyFraction) continue;
    found += (found.empty() ? "" : "; ") + p.describe();
    overlap = overlap || p.weight_sum > 1;
  }
  std::string bands;
  for (const auto& m : members) bands += (bands.empty() ? "" : ", ") + m.band.describe();
  const std::string subject = fmt::format("{} cascades, bands {}", members.size(), bands);
  const bool ok = found.empty();
  std::string reason;
  if (!ok) {
    reason = found;
    // Engines that run whole seas in every cascade mean them to add: say how to declare that.
    if (overlap) {
      reason += "; cascades that are each a whole sea of their own are declared with "
                "relation = \"independent\"";
    }
  } else if (problems.empty()) {
    reason = "the bands share the spectrum out once (Σ w² = 1 wherever the cascades' grids hold it)";
  } else {
    reason = fmt::format("the bands share the spectrum out once; where Σ w² ≠ 1 lies at most "
                         "{:.2g} of m0",
                         largest);
  }
  return exact_check(
      "cascades.bands", subject, largest, reference::kSmallestEnergyFraction, ok,
      fmt::format("every range of |k| where Σ_c w_c² ≠ 1 holds ≤ {:g} of m0 (the declared bands "
                  "share the spectrum out once)",
                  reference::kSmallestEnergyFraction),
      reason);
}

std::vector<CheckResult> check_summed_bands(const OceanCase& summed, const FrameSource& frames, double alpha) {
  std::vector<Complex> spectrum0;
  height_spectrum(*frames.frame(0, height_only), summed.grid, spectrum0);
  const SurfaceSpectrum s = surface_spectrum(summed, frames.precision().unit_roundoff, spectrum0,
                                             expected_periodogram(*summed.directional_spectrum(), summed.grid));
  const auto& g = s.grid;
  const std::string subject = fmt::format("sum of {} cascades: {}×{} over {:g}×{:g} m",
                                          summed.members.size(), g.nx, g.ny, g.lx, g.ly);
  // Which cascades' grids hold fine entry e.
  auto holders = [&](std::size_t e) {
    std::vector<int> out;
    const int n = Grid::signed_index(int(e % g.nx), g.nx), m = Grid::signed_index(int(e / g.nx), g.ny);
    for (const auto& c : summed.members) {
      const long rx = std::lround(g.lx / c.grid.lx), ry = std::lround(g.ly / c.grid.ly);
      if (n % rx || m % ry) continue;
      const int nc = int(n / rx), mc = int(m / ry);
      if (nc < -(c.grid.nx / 2) || nc >= (c.grid.nx + 1) / 2 || mc < -(c.grid.ny / 2) ||
          mc >= (c.grid.ny + 1) / 2 || !c.grid.carries_energy(nc, mc)) {
        continue;
      }
      out.push_back(c.cascade);
    }
    return out;
  };
  const StrayEnergy found = stray_energy(s);
  const double stray = found.total;
  const std::vector<std::size_t>& outside = found.entries;
  const bool clean = stray <= s.rounding_power;
  std::string reason;
  if (clean) {
    reason = fmt::format("{:.1e} of mean h² where no cascade puts energy", stray / s.mean_square);
  } else {
    const double per_entry = s.rounding_power / double(std::max<std::size_t>(1, outside.size()));
    std::vector<std::size_t> significant;
    for (auto e : outside) {
      if (s.power[e] > per_entry) significant.push_back(e);
    }
    if (significant.empty()) significant = outside;
    const auto [a, b] = energy_range(significant, s.k, s.power);
    // Who holds the stray wave vectors, and whose band covers their |k|.
    std::map<int, double> held;
    double on_no_grid = 0;
    for (auto e : significant) {
      const auto list = holders(e);
      if (list.empty()) on_no_grid += s.power[e];
      for (int c : list) held[c] += s.power[e];
    }
    double observed = 0, expected = 0;
    for (std::size_t e = 0; e < s.power.size(); ++e) {
      if (carries(g, e) && s.k[e] >= a && s.k[e] <= b) {
        observed += s.power[e];
        expected += s.mu[e];
      }
    }
    double total = 0;
    for (auto e : significant) total += s.power[e];
    if (on_no_grid > 0.5 * total) {
      reason = fmt::format("{:.3g} of mean h² at {:.4g}–{:.4g} rad/m on wave vectors of no "
                           "cascade's grid: a cascade's k uses another patch length, or its grid "
                           "is not the declared one",
                           stray / s.mean_square, a, b);
    } else {
      std::vector<int> carriers;
      for (const auto& [c, energy] : held) {
        if (energy > 0.1 * total) carriers.push_back(c);
      }
      const auto others = covering(summed.members, carriers.empty() ? -1 : carriers.front(), a, b);
      std::vector<int> both = carriers;
      for (int c : others) {
        if (std::find(both.begin(), both.end(), c) == both.end()) both.push_back(c);
      }
      std::sort(both.begin(), both.end());
      if (both.size() >= 2) {
        reason = fmt::format("{} both carry {:.4g}–{:.4g} rad/m (energy × {:.2g} there)",
                             cascades_named(both), a, b, expected > 0 ? observed / expected : 0);
      } else {
        reason = fmt::format("{} carries {:.4g}–{:.4g} rad/m beyond its band ({:.3g} of mean h²)",
                             cascades_named(carriers), a, b, stray / s.mean_square);
      }
    }
  }
  std::vector<CheckResult> out;
  out.push_back(exact_check(
      "sum.band.outside", subject, stray / s.mean_square, s.rounding_power / s.mean_square, clean,
      fmt::format("fraction of mean h² where no cascade's grid and band put energy ≤ {:.1e} "
                  "(rounding)",
                  s.rounding_power / s.mean_square),
      reason));
  auto where_empty = [](double a, double b, double share) {
    return fmt::format("no cascade carries {:.4g}–{:.4g} rad/m ({:.3g} % of m0 lost)", a, b,
                       100 * share);
  };
  out.push_back(missing_result("sum.band.missing", subject, s, s.mu, summed, where_empty, alpha));
  return out;
}

}  // namespace swell::validation
