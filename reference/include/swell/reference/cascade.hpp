#pragma once
// Cascades (docs/conventions.md §2.2): an additive cascade set is h = Σ_c h_c,
// cascade c a Tessendorf surface on its own grid n_c over its own patch L_c, whose amplitudes are
// the conventions' times a band weight w_c(|k|), with Σ_c w_c(|k|)² = 1 wherever the spectrum
// has energy. Random numbers are keyed by (seed, cascade c, n, m): cascade 0 alone is the
// single-grid surface. A set of independent seas sums too, but each cascade carries a whole sea
// of its own (the set's, or its own spectrum), so the sum's spectrum is the sum of theirs.
//
// Band weights. A band [lo, hi) in |k| (rad/m) is a hard cut (w = 1 inside, 0 outside) or, with
// a crossover ratio r > 1, a smooth one whose w² rises across [lo/r, lo·r] and falls across
// [hi/r, hi·r] as sin² and cos² of π(x + 1)/4, x = ln(k/edge)/ln r: two bands that share an
// edge and the ratio r then have w_a² + w_b² = sin² + cos² = 1 at every |k| (a weighted
// overlap), and each weight is 1 outside its two transitions.
#include <limits>
#include <string>
#include <vector>

#include "swell/reference/directional.hpp"
#include "swell/reference/grid.hpp"

namespace swell::reference {

struct OceanCase;

struct BandWeight {
  double lo = 0;                                          // rad/m
  double hi = std::numeric_limits<double>::infinity();    // rad/m; inf: no upper cut
  double crossover = 1;                                   // r ≥ 1; 1: hard cuts

  // w(|k|)², in [0, 1].
  double weight_squared(double k) const;
  // Where the weight can be nonzero: [lo/r, hi·r).
  double support_lo() const { return lo / crossover; }
  double support_hi() const { return hi * crossover; }
  // True for the default band: w = 1 at every |k| (no weighting at all).
  bool everywhere() const { return lo == 0 && hi == std::numeric_limits<double>::infinity(); }
  // "[0.0629, 0.2516) rad/m" or "[0.0629, 0.2516) rad/m, crossover ×1.2".
  std::string describe() const;
  // Throws InvalidInput naming what is wrong (0 ≤ lo < hi, r ≥ 1 finite, transitions of the two
  // edges not overlapping: hi/lo > r²).
  void validate(const std::string& what) const;
  bool operator==(const BandWeight& other) const {
    return lo == other.lo && hi == other.hi && crossover == other.crossover;
  }
};

// One cascade of a summed set, as a summed surface sees it: its grid (and patch), its band, its
// index (the random numbers' key) and, for independent seas, its own Ψ.
struct CascadeMember {
  int cascade = 0;
  Grid grid;
  BandWeight band;
  DirectionalSpectrumPtr spectrum;  // the cascade's own sea (independent seas); null: the set's
};

enum class CascadeRelation {
  additive,     // h = Σ_c h_c, the bands share the spectrum out once
  nested,       // two samplings of one sea (Mitchell 2005): the coarse grid's waves are the fine one's
  independent,  // h = Σ_c h_c, each cascade a whole sea of its own: the spectra add
};
// The relations whose cascades are added into one surface (additive and independent).
inline bool is_summed(CascadeRelation relation) { return relation != CascadeRelation::nested; }
std::string to_string(CascadeRelation relation);

// The summed surface of an additive set lives on one grid, the finest spacing s over the largest
// patch L (per axis), when every ratio L/L_c and L/s is an integer (within 1e-9): cascade c's
// patch then tiles L, and its wave index (n, m) is the fine grid's (n·L/L_c, m·L/L_c), inside
// the fine grid's band since L/L_c · n_c/2 = L/(2 s_c) ≤ L/(2 s). Returns false (leaving `fine`
// alone) otherwise, with the reason in `why` when given.
bool summed_grid(const std::vector<CascadeMember>& members, Grid& fine, std::string* why = nullptr);

// How the declared bands share out the spectrum: the ranges of |k| where Σ_c w_c² is not 1
// within 1e-9, each with the share of the spectrum's m0 it holds. A cascade carries its band
// only where its grid holds whole rings of |k|, from its Δk = min(2π/Lx, 2π/Ly) to its Nyquist
// min(π nx/Lx, π ny/Ly) (the corners beyond hold a ring in part): so cascades declared over the
// whole spectrum overlap where their grids do. The ranges examined lie between the lowest |k|
// any cascade carries and the highest (past the outer edges' crossovers): beyond them the set
// tapers as one grid's limits do, which is neither an overlap nor a gap.
struct BandCoverageProblem {
  double k_lo = 0, k_hi = 0;   // rad/m
  double weight_sum = 0;       // Σ_c w_c² there (mid-range value): 0 a gap, 2 an overlap
  double m0_share = 0;         // ∫ over the range of the omnidirectional spectrum / m0
  std::vector<int> cascades;   // the cascades whose weight is nonzero there
  // "cascades 0, 1 and 2 all carry 0.393–8.04 rad/m: energy × 3 there, 4.1 % of m0"
  std::string describe() const;
};
std::vector<BandCoverageProblem> band_coverage(const OceanCase& sea,
                                               const std::vector<CascadeMember>& members);
// The problems of band_coverage that hold more than kSmallestEnergyFraction of m0: those an
// additive set must not have (smaller ones are below what any check resolves).
std::vector<BandCoverageProblem> band_sharing_problems(const OceanCase& sea,
                                                       const std::vector<CascadeMember>& members);
// Refuses (InvalidInput) an additive set with band_sharing_problems, naming every one; what
// swell synth asks of a set it makes (the gate judges such a set instead: cascades.bands).
void require_bands_share_out(const OceanCase& sea, const std::vector<CascadeMember>& members);

}  // namespace swell::reference
