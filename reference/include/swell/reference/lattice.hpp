#pragma once
// Rank-1 lattices (Keller; docs/conventions.md §2.1): N points x_n = L ∘ ((n g / N) mod 1),
// n = 0…N−1, generator g ∈ ℤ^s (s = 2 or 3), box lengths L (metres; a third length may be a
// time period: it is then only an axis of the same "patch metric").
//
// The patch metric. An integer wave vector k is the wave number K = 2π k / L component-wise
// (rad/m) and is measured by ‖K‖₂. Everything below that says "shortest", "minimal" or
// "radius" means this norm, never ‖k‖ on the integers: with Lx ≠ Ly the two disagree.
//
// The dual lattice L⊥ = {h ∈ ℤ^s : h·g ≡ 0 (mod N)} is what a lattice cannot tell from zero: a
// wave at K and one at K + 2π h/L (h ∈ L⊥) take the same values on every point. Its index in
// ℤ^s is N, so the N residue classes m = (k·g) mod N are the N distinguishable waves, and
// coefficient m belongs to k_m, the shortest integer vector of class m (the class's point of the
// Voronoi cell of L⊥ around 0: the lattice's own "Brillouin zone").
//
// Arithmetic. Residues (k·g) mod N, phases (n g_d) mod N and everything that decides which k
// lies in which class are exact 64-bit (128-bit for products) integer arithmetic; floating point
// only ever measures lengths (STYLE.md "Integers where the mathematics is integral").
//
// Ties. Squared norms are compared as Σ_d k_d² w_d with w_d = (L_max / L_d)², first in double
// and, when two are within a relative 1e-12, again in long double (64-bit significand). k_d²
// is exact there (|k_d| < 2^31) and so is every product and sum when the w_d are integers or
// short dyadic fractions (equal lengths, ratios 2, 3, 1.5, …: 200×200, 200×100, 300×200 m), so
// ties of such patches are detected exactly; for other ratios two squared norms within 16 ulp
// of long double (relative 1.7e-18, far below the rounding of the lengths themselves) are
// declared tied. Among tied vectors the rule is lexicographic: smallest (k_0, then k_1, k_2).
//
// The wave-vector table (create()). Classes m = 1 … ⌊N/2⌋ are filled in order; class m's
// representative p_m is kept inside the fundamental parallelepiped of the reduced dual basis,
// in exact integers (p_{m+1} = p_m + u, minus a basis vector whenever a fractional coordinate
// wraps), and its shortest vector is found by Schnorr–Euchner enumeration (exact closest vector
// in L⊥): every lattice vector within the best squared distance × (1 + 1e-9) is visited, so
// every tied minimum is seen, and the winner is chosen by the rule above. Then
// k_{N−m} = −k_m exactly (m > N/2), k_0 = 0, and for even N class N/2 is its own conjugate (the
// rule picks the one of ±k with the smaller first nonzero component); m = 0 and m = N/2 carry
// no energy, like a grid's k = 0 and Nyquist row. Cost: O(N) time and N·s int32 of memory;
// measured on this project's 2-core machine (Release): N = 2^22, s = 2 in 0.16–0.19 s;
// N = 2^20, s = 3 in 0.06–0.10 s (LatticeScale in lattice_test prints the times).
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace swell::reference {

// Points beyond which create() refuses: the table is N·s int32 (2^30 points in 3-D is 12 GiB).
inline constexpr std::int64_t kMaxLatticePoints = std::int64_t{1} << 30;
// Largest ratio of two lengths: keeps every reduced basis vector below 2^52 in each component
// (|b_d| ≤ 2 N L_max/L_min), so all the integer arithmetic stays exact.
inline constexpr double kMaxLatticeLengthRatio = 1048576.0;  // 2^20

class RankOneLattice {
 public:
  // Validates and computes the wave-vector table once. Rules (InvalidInput names the field,
  // the rule and the value otherwise):
  //  - 2 ≤ points ≤ kMaxLatticePoints;
  //  - generator has 2 or 3 components (the dimension s), each in [0, points);
  //  - gcd(g_0, …, g_{s−1}, N) = 1. This is exactly the condition for N distinct points (the
  //    order of g in (ℤ_N)^s is N / gcd) and for every residue class to be reached; it is
  //    weaker than "one g_d coprime to N" (N = 6, g = (2, 3) passes);
  //  - lengths has s entries, each finite and > 0, within a factor kMaxLatticeLengthRatio.
  static RankOneLattice create(std::int64_t points, std::vector<std::int64_t> generator,
                               std::vector<double> lengths);

  std::int64_t points() const { return points_; }
  int dimension() const { return static_cast<int>(generator_.size()); }
  const std::vector<std::int64_t>& generator() const { return generator_; }
  const std::vector<double>& lengths() const { return lengths_; }

  // Point n (metres): L_d · ((n g_d) mod N) / N; unused components 0. n ∈ [0, N).
  std::array<double, 3> point(std::int64_t n) const;
  // (k·g) mod N in [0, N), exact; k has dimension() entries.
  std::int64_t residue(std::span<const std::int64_t> k) const;
  std::int64_t residue(std::span<const std::int32_t> k) const;
  // k_m (dimension() entries) and K_m = 2π k_m / L (rad/m, unused components 0); m ∈ [0, N).
  std::span<const std::int32_t> wave_vector(std::int64_t m) const;
  std::array<double, 3> wave_number(std::int64_t m) const;
  // The whole table, N rows of dimension() int32, row m = k_m (what a synthesizer uploads).
  std::span<const std::int32_t> wave_vectors() const { return table_; }
  // False exactly for m = 0 and, for even N, m = N/2.
  bool carries_energy(std::int64_t m) const;
  // "korobov N=4096 g=(1,1159) over 200×200 m" (family: rank-1, fibonacci or korobov).
  std::string describe() const;

  // The reduced basis of L⊥ in the patch metric (rows; Lagrange–Gauss in 2-D, LLL with
  // δ = 0.99 in 3-D), dimension() rows of dimension() entries (unused entries 0).
  const std::array<std::array<std::int64_t, 3>, 3>& dual_basis() const { return basis_; }
  // ‖2π k / L‖ (rad/m) of an integer vector with dimension() entries.
  double patch_norm(std::span<const std::int64_t> k) const;

 private:
  RankOneLattice() = default;
  std::int64_t points_ = 0;
  std::vector<std::int64_t> generator_;
  std::vector<double> lengths_;
  std::array<std::array<std::int64_t, 3>, 3> basis_{};
  std::vector<std::int32_t> table_;
  std::string family_ = "rank-1";

  friend RankOneLattice fibonacci_lattice(int j, double lx, double ly);
  friend RankOneLattice korobov_lattice(std::int64_t points, std::int64_t a,
                                        std::vector<double> lengths);
};

// F_1 = F_2 = 1, F_{j+1} = F_j + F_{j−1}; j ∈ [1, 92] (F_92 is the last below 2^63).
std::int64_t fibonacci_number(int j);
// N = F_j, g = (1, F_{j−1}) over lx × ly; j ∈ [3, 92] (and F_j ≤ kMaxLatticePoints for the
// table). With lx = ly and odd j its dual is a square lattice (F_{j−1}² ≡ −1 mod F_j, by
// Cassini's identity), so the lattice is a rotated square grid of spacing sqrt(lx ly / N).
RankOneLattice fibonacci_lattice(int j, double lx, double ly);
// The j ≥ 3 with F_j == points, or InvalidInput naming the Fibonacci numbers below and above.
int fibonacci_index(std::int64_t points);

// Korobov lattice g = (1, a, a² mod N)[0..s), s = lengths.size() ∈ {2, 3}; a ∈ [1, N), any N ≥ 2
// (powers of two included). With g_0 = 1 the gcd rule always holds.
RankOneLattice korobov_lattice(std::int64_t points, std::int64_t a, std::vector<double> lengths);
// The spectral test's Korobov multiplier: the a that maximizes λ₁, the shortest nonzero vector
// of L⊥ in the patch metric, over the admissible a: 1 ≤ a < N with gcd(a, N) = 1 (so every axis
// sees N distinct coordinates). λ₁ values within a relative 1e-12 (of λ₁²) tie and the smallest
// a wins. Only the smallest member of each orbit of a symmetry of the metric is evaluated:
//  - a ↔ N − a always (g ↦ g with axis 1 reflected, and in 3-D axis 2 unchanged since
//    (N − a)² ≡ a²: the dual is reflected in axis 1, which any diagonal metric preserves);
//  - a ↔ a⁻¹ mod N only when it is an isometry: in 2-D when L_0 = L_1 (the dual's axes swap),
//    in 3-D when L_0 = L_2 (a⁻¹ gives (1, a⁻¹, a⁻²) ∝ (a², a, 1): axes 0 and 2 swap). With
//    L_0 ≠ L_1 swapping axes changes λ₁, so a and a⁻¹ are both evaluated.
// Each candidate is reduced with early rejection (any lattice vector met during reduction that
// is shorter than the best λ₁ so far rejects a at once): Lagrange–Gauss in 2-D; LLL and
// Schnorr–Euchner enumeration in 3-D (exact λ₁). O(N) candidates, most rejected after a few
// reduction steps. Measured (Release, this project's 2-core machine): N = 2^22, s = 2 in
// 0.06–0.13 s; N = 2^20, s = 3 in 0.08–0.11 s.
std::int64_t korobov_spectral_choice(std::int64_t points, int dimension,
                                     std::vector<double> lengths);
// korobov_lattice(points, korobov_spectral_choice(points, lengths.size(), lengths), lengths).
RankOneLattice korobov_lattice(std::int64_t points, std::vector<double> lengths);

struct LatticeMerits {
  // h ∈ L⊥ \ {0} of minimal patch-metric norm; of the tied ones, the one whose first nonzero
  // component is positive and which is then lexicographically smallest.
  std::vector<std::int64_t> shortest_dual_vector;
  double lambda1 = 0;      // ‖2π h / L‖, rad/m (the spectral test)
  double zaremba_rho = 0;  // min over h ∈ L⊥ \ {0} of Π_d max(1, |h_d|) (exact; O(ρ log ρ))
  double p2 = 0;           // Sloan & Joe's P₂ (rank_one_p2)
};
LatticeMerits lattice_merits(const RankOneLattice& lattice);

// Sloan & Joe's P₂ = −1 + (1/N) Σ_n Π_d (1 + 2π² B₂({n g_d / N})), B₂(x) = x² − x + 1/6, with
// {n g_d / N} from exact integer residues and the sum in long double. Needs no wave-vector
// table (so a P₂ search over many generators is cheap); validates points ≥ 2, 1 to 3
// components in [0, points).
double rank_one_p2(std::int64_t points, std::span<const std::int64_t> generator);

// Band geometry in the patch metric, rad/m.
struct LatticeBand {
  // λ₁/2: every K with ‖K‖ < this is alone in its residue class (the alias-free disc/ball).
  double inscribed_radius = 0;
  // Circumradius of the Voronoi cell of L⊥: the largest ‖K_m‖ possible. Computed exactly, not
  // sampled: the reduced basis is turned into an obtuse superbase v_0 … v_s (Σ v_i = 0,
  // v_i·v_j ≤ 0; read off the Gauss-reduced basis in 2-D, by Selling's reduction in 3-D); every
  // lattice of dimension ≤ 3 has one, and its Voronoi-relevant vectors are among the
  // 2^{s+1} − 2 partial sums Σ_{i∈S} v_i (Voronoi; Conway & Sloane, Proc. R. Soc. A 436 (1992)
  // 55–68). The cell is the intersection of their bisecting half-spaces; its vertices are the
  // feasible intersections of s bisectors, and the covering radius is the largest vertex norm.
  // The k_m are integer vectors, so max_m ‖K_m‖ ≤ covering_radius and, since a point within
  // δ = ½‖(2π/L_0, …)‖ of any vertex is an integer vector, max_m ‖K_m‖ ≥ covering_radius − δ.
  double covering_radius = 0;
  // Volume of the inscribed disc/ball over the Voronoi cell's volume N·Π_d (2π/L_d): π/4 =
  // 0.785 for a square grid, at most π/(2√3) = 0.907 in 2-D (hexagonal), π/(3√2) = 0.740 in 3-D.
  double alias_free_fraction = 0;
};
LatticeBand lattice_band(const RankOneLattice& lattice);

}  // namespace swell::reference
