#pragma once
// Space-time synthesis on a 3-D rank-1 lattice (docs/conventions.md §2.1,
// "Dispersion" with the loop period T, "Amplitudes").
//
// A loop-periodic surface is a trigonometric polynomial in (x, y, t). With the loop period T,
// ω(k) = 2π q(k)/T for an integer q(k) ≥ 0 (OceanCase::omega quantizes down), so
//
//   h(x, t) = Σk h̃0(k) e^(i(k·x − ωt)) + conj(h̃0(−k)) e^(i(k·x + ωt))
//           = Σ_h c_h e^(2πi (h_0 x/Lx + h_1 y/Ly + h_2 t/T))
//
// over the space-time frequency vectors h = (n, m, ∓q(k)) in units (2π/Lx, 2π/Ly, 2π/T):
// (n, m, −q) carries h̃0(k) and (n, m, +q) carries conj(h̃0(−k)); for q = 0 the two coincide and
// are merged into one vector carrying their sum. The set is closed under h ↦ −h with conjugate
// coefficients (the surface is real).
//
// On a rank-1 lattice with N points x_n = (Lx, Ly, T) ∘ ((n g / N) mod 1) every exponential is
// e^(2πi ((h·g) n mod N) / N), so the N samples are one 1-D inverse FFT of size N of the array
// c[r] = Σ_{h·g ≡ r} c_h. That evaluation is exact for any N and g; for the samples to determine
// the surface (and for the space-time dispersion check to see every wave on its own) the map
// h ↦ h·g mod N must be injective on the set: no two frequency vectors in one residue class.
// choose_space_time_korobov() searches Korobov generators g = (1, a, a² mod N) for that.
//
// Arithmetic: classes (h·g) mod N are exact 64-bit integers (components reduced mod N first,
// so every product stays below 2^60); the lattice's point(n) uses exact integer residues too.
#include <array>
#include <complex>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "swell/impls/transform.hpp"
#include "swell/reference/lattice.hpp"
#include "swell/reference/ocean_case.hpp"

namespace swell::impls {

// Which wave vectors k (integer indices (n, m), K = (2π n/Lx, 2π m/Ly)) a surface carries.
struct SpaceTimeBand {
  enum class Kind { grid, disc };
  Kind kind = Kind::grid;
  int grid_points = 0;  // grid: the k of an n × n grid that carry energy (k ≠ 0, no Nyquist)
  double k_max = 0;     // disc: every integer k ≠ 0 with ‖K‖ ≤ k_max (rad/m)

  static SpaceTimeBand grid(int n);       // n ≥ 2, ≤ 2^15 (InvalidInput otherwise)
  static SpaceTimeBand disc(double k_max);  // finite, > 0
  // The band's k over lx × ly, k and −k both, sorted by (m, n). InvalidInput for a disc with
  // more than 2^26 wave vectors or an index beyond 2^15.
  std::vector<std::array<std::int32_t, 2>> wave_vectors(double lx, double ly) const;
  std::string describe() const;  // "64×64 grid band", "disc |K| ≤ 1.2 rad/m"
};

struct SpaceTimeWave {
  std::array<std::int32_t, 3> h{};  // (n, m, s): K = 2π (n/Lx, m/Ly), frequency s·2π/T
  std::complex<double> coefficient;
};

// The frequency set of a surface: its frequency vectors and their coefficients.
class SpaceTimeSet {
 public:
  // The waves of a loop-periodic case over a band: T = ocean_case.loop_period must be finite and
  // > 0 (InvalidInput otherwise); q(k) = ω(k) T / 2π with ω = ocean_case.omega(‖K‖); h̃0 by the
  // conventions (the same values as initial_amplitude(ocean_case, n, m), Philox keyed by
  // (seed, n, m)) over the case's patch lx × ly. Vectors sorted lexicographically.
  static SpaceTimeSet create(const reference::OceanCase& ocean_case, const SpaceTimeBand& band);
  // Any set over (Lx, Ly, T): distinct vectors with |components| < 2^31, closed under h ↦ −h
  // with c_(−h) = conj(c_h) to within 8 u of the largest |c| (a real surface). For surfaces
  // made some other way (a foreign engine's, or one with a wrong dispersion, for tests).
  static SpaceTimeSet from_waves(std::array<double, 3> lengths, std::vector<SpaceTimeWave> waves);

  const std::vector<SpaceTimeWave>& waves() const { return waves_; }
  std::size_t size() const { return waves_.size(); }
  const std::array<double, 3>& lengths() const { return lengths_; }  // (Lx, Ly, T)
  // max |h_d| over the set, per component: (max |n|, max |m|, q_max).
  const std::array<std::int32_t, 3>& max_abs() const { return max_abs_; }
  // Frames a per-frame grid synthesis needs over one loop to represent every frequency of the
  // set without aliasing: F = 2 q_max + 1 (frames t_f = f T / F resolve s mod F).
  std::int64_t grid_frames() const { return 2 * std::int64_t{max_abs_[2]} + 1; }
  // True when (n, m, s) ∈ set ⇔ (n, −m, s) ∈ set (any band with q a function of |K| is): then
  // under the Korobov multiplier N − a each vector falls where its mirror falls under a, so a
  // and N − a are injective together and the search skips N − a.
  bool mirror_symmetric() const { return mirror_symmetric_; }
  std::string describe() const;  // "7936 space-time frequency vectors, |n| ≤ 31, |m| ≤ 31, q ≤ 35"

 private:
  SpaceTimeSet() = default;
  void finish();  // validates, sorts, fills max_abs_ and mirror_symmetric_
  std::array<double, 3> lengths_{};
  std::vector<SpaceTimeWave> waves_;
  std::array<std::int32_t, 3> max_abs_{};
  bool mirror_symmetric_ = false;
};

// (h·g) mod N in [0, N), exact; generator has 3 components in [0, N).
std::int64_t space_time_class(const std::array<std::int32_t, 3>& h,
                              std::span<const std::int64_t> generator, std::int64_t points);

// Indices (into set.waves()) of the first two frequency vectors that share a class under the
// lattice, by the order of (class, index); nullopt when h ↦ h·g mod N is injective on the set.
// An independent path from the search's (a sort, not a stamp table).
std::optional<std::array<std::size_t, 2>> first_collision(const SpaceTimeSet& set,
                                                          const reference::RankOneLattice& lattice);
// InvalidInput naming the lattice, the two vectors and their class unless injective; also when
// the lattice is not 3-D or its lengths are not the set's (Lx, Ly, T).
void require_injective(const SpaceTimeSet& set, const reference::RankOneLattice& lattice);

// The generator search (deterministic). Candidate sizes N ≥ max(set size, min_points), in
// increasing order: powers of two, or the 5-smooth numbers 2^i 3^j 5^k (FFTW's fast sizes,
// about 48 per octave near 10^5: a finer ladder and a smaller N, at many more tries). For each
// N the Korobov multipliers a = 1, 2, … are tried in order (up to N/2 when the set is
// mirror_symmetric(), else N − 1); the first a with h ↦ h·g mod N injective wins. A try stops
// at its first collision: the set is visited in a fixed pseudo-random order (a SplitMix64 hash
// of h), which meets a collision after about √N vectors instead of after whole runs of
// neighbours. Gives up with InvalidInput (naming the set size, the sizes tried and the cap)
// after max_tries multipliers in all or beyond max_points. Measured (Release, this project's
// 2-core machine; JONSWAP, 200 m, T = 60 s, docs/lattice.md §Space-time lattices): the 64²
// band's 7936 vectors in 0.04 s (powers of two, N = 2^17) or 2.5–3 s (smooth, N = 96000); the
// 128² band's 32256 in 1.6–2.1 s (N = 2^20) or 66–73 s (smooth, N = 559872, 2.16·10^7 tries:
// above the default cap).
struct SpaceTimeSearch {
  enum class Sizes { powers_of_two, smooth };
  Sizes sizes = Sizes::powers_of_two;
  std::int64_t min_points = 0;
  std::int64_t max_points = reference::kMaxLatticePoints;
  std::int64_t max_tries = std::int64_t{1} << 24;
};
std::string to_string(SpaceTimeSearch::Sizes sizes);  // "powers_of_two", "smooth"

struct SpaceTimeChoice {
  std::int64_t points = 0;      // N
  std::int64_t multiplier = 0;  // a: g = (1, a, a² mod N)
  std::int64_t tries = 0;       // multipliers evaluated, all sizes together
  std::int64_t sizes_tried = 0; // candidate N evaluated, the winner included
};
SpaceTimeChoice choose_space_time_korobov(const SpaceTimeSet& set, const SpaceTimeSearch& search = {});
// The smallest Korobov multiplier for this N (the search's inner loop), or nullopt; `tries`
// (when given) is increased by the multipliers evaluated, and the loop stops at max_tries.
std::optional<std::int64_t> find_space_time_multiplier(const SpaceTimeSet& set, std::int64_t points,
                                                       std::int64_t max_tries = std::int64_t{1} << 62,
                                                       std::int64_t* tries = nullptr);
// korobov_lattice(N, a, {Lx, Ly, T}) of the choice (the lattice builds its O(N) wave-vector
// table: about 0.1 s at N = 2^20).
std::shared_ptr<const reference::RankOneLattice> space_time_lattice(const SpaceTimeSet& set,
                                                                    const SpaceTimeChoice& choice);

struct SpaceTimeOptions {
  std::string backend = "fftw";  // any registered backend with c2r of size N (fp64)
  // Refuse a lattice on which two vectors of the set share a class (require_injective). With
  // false, coincident vectors are summed into their class: the samples are still exact, but
  // they no longer determine the coefficients.
  bool require_injective = true;
};

// Heights at the N points of a 3-D lattice over (Lx, Ly, T): c[r] = Σ_{h·g ≡ r} c_h for
// r = 0 … ⌊N/2⌋ (the set is Hermitian, so c[N − r] = conj c[r] and the half spectrum is
// enough), then one c2r inverse FFT of size N, fp64. Sample n is at lattice.point(n) =
// (x, y, t). Like the grid Synthesizer on a host backend, it assembles into one buffer it owns:
// one thread per synthesizer.
class SpaceTimeSynthesizer {
 public:
  SpaceTimeSynthesizer(SpaceTimeSet set, std::shared_ptr<const reference::RankOneLattice> lattice,
                       SpaceTimeOptions options = {});
  ~SpaceTimeSynthesizer();
  SpaceTimeSynthesizer(const SpaceTimeSynthesizer&) = delete;
  SpaceTimeSynthesizer& operator=(const SpaceTimeSynthesizer&) = delete;

  const SpaceTimeSet& set() const { return set_; }
  const reference::RankOneLattice& lattice() const { return *lattice_; }
  std::int64_t points() const { return lattice_->points(); }
  // The class of each wave of set().waves(), in its order.
  const std::vector<std::int64_t>& classes() const { return classes_; }

  // The half spectrum c[0 … ⌊N/2⌋] (⌊N/2⌋ + 1 values): the transform's input.
  void place(std::span<std::complex<double>> half_spectrum) const;
  // h(lattice.point(n)) for n = 0 … N − 1 into `heights` (N values).
  void heights(std::span<double> heights) const;
  std::vector<double> heights() const;
  // The one transform (c2r inverse fp64 of size N), for timing it bare.
  const Plan& transform() const { return *plan_; }

 private:
  SpaceTimeSet set_;
  std::shared_ptr<const reference::RankOneLattice> lattice_;
  std::vector<std::int64_t> classes_;
  std::unique_ptr<Backend> backend_;
  std::unique_ptr<Plan> plan_;
  mutable std::vector<std::complex<double>> scratch_;
};

}  // namespace swell::impls
