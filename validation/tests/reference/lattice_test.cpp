// Rank-1 lattices (swell/reference/lattice.hpp) against independent values: brute force over
// integer boxes for every "minimal" and "shortest" claim, the Fourier-series form of P₂
// summed over the dual lattice, John Burkardt's P₂-optimal Korobov generators, and closed
// forms (Fibonacci lattices of odd index are rotated square grids; 3×4 and 2×3×5 grids
// written as rank-1 lattices).
#include "swell/reference/lattice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include "swell/reference/errors.hpp"

namespace swell::reference {
namespace {

__extension__ using Int128 = __int128;  // exact squared norms and residues in the oracles
using Vec = std::vector<std::int64_t>;

constexpr long double kPi = std::numbers::pi_v<long double>;

std::int64_t floor_mod(Int128 a, std::int64_t n) {
  const auto r = static_cast<std::int64_t>(a % n);
  return r < 0 ? r + n : r;
}

std::int64_t residue_of(const Vec& k, const std::vector<std::int64_t>& g, std::int64_t n) {
  Int128 dot = 0;
  for (std::size_t d = 0; d < g.size(); ++d) dot += Int128{k[d]} * g[d];
  return floor_mod(dot, n);
}

Vec to_vec(std::span<const std::int32_t> k) { return Vec(k.begin(), k.end()); }

std::string str(const Vec& k) {
  std::string out = "(";
  for (std::size_t d = 0; d < k.size(); ++d) {
    if (d) out += ',';
    out += std::to_string(k[d]);
  }
  return out + ")";
}

// Squared patch norm Σ (2π k_d / L_d)², long double, for any lengths.
long double norm2(const Vec& k, const std::vector<double>& lengths) {
  long double sum = 0;
  for (std::size_t d = 0; d < k.size(); ++d) {
    const long double x = 2 * kPi * static_cast<long double>(k[d]) / static_cast<long double>(lengths[d]);
    sum += x * x;
  }
  return sum;
}

// The squared norm in units of (2π/L_max)², exactly (Σ k_d² w_d, integer w_d = (L_max/L_d)²),
// for lengths with integer ratios: the oracle for ties.
struct ExactMetric {
  std::vector<std::int64_t> w;
  explicit ExactMetric(const std::vector<double>& lengths) {
    const double lmax = *std::max_element(lengths.begin(), lengths.end());
    for (const double l : lengths) {
      const double r = lmax / l;
      if (r != std::round(r)) ADD_FAILURE() << "ExactMetric needs integer length ratios";
      w.push_back(std::llround(r * r));
    }
  }
  Int128 q(const Vec& k) const {
    Int128 sum = 0;
    for (std::size_t d = 0; d < k.size(); ++d) sum += Int128{k[d]} * k[d] * w[d];
    return sum;
  }
};

// Calls f(k) for every k with |k_d| ≤ half[d], in lexicographic order.
template <class F>
void for_box(const Vec& half, F&& f) {
  Vec k(half.size());
  for (std::size_t d = 0; d < half.size(); ++d) k[d] = -half[d];
  for (;;) {
    f(k);
    std::size_t d = half.size();
    while (d > 0) {
      --d;
      if (++k[d] <= half[d]) break;
      k[d] = -half[d];
      if (d == 0) return;
    }
  }
}

// Every dual vector h ≠ 0 with ‖2π h / L‖ ≤ radius (rad/m), by brute force over its box.
std::vector<Vec> dual_vectors_within(const RankOneLattice& lat, long double radius) {
  Vec half;
  for (const double l : lat.lengths())
    half.push_back(static_cast<std::int64_t>(std::ceil(radius * l / (2 * kPi))));
  std::vector<Vec> out;
  for_box(half, [&](const Vec& h) {
    if (std::all_of(h.begin(), h.end(), [](std::int64_t x) { return x == 0; })) return;
    if (residue_of(h, lat.generator(), lat.points()) != 0) return;
    if (norm2(h, lat.lengths()) <= radius * radius) out.push_back(h);
  });
  return out;
}

struct Case {
  std::int64_t n;
  std::vector<std::int64_t> g;
  std::vector<double> lengths;
};

std::string name(const Case& c) {
  std::string out = "N=" + std::to_string(c.n) + " g=" + str(c.g) + " L=";
  for (std::size_t d = 0; d < c.lengths.size(); ++d) {
    if (d) out += 'x';
    out += std::to_string(c.lengths[d]);
  }
  return out;
}

// Small lattices for the brute-force checks, all with integer length ratios: Fibonacci
// lattices (odd index: square duals, full of ties), Korobov lattices, generators with no
// component coprime to N (N = 6, g = (2, 3); grids 3×4 and 2×3×5 as rank-1 lattices), a
// degenerate line (g = (1, 0)), anisotropic patches and a third axis.
std::vector<Case> small_cases() {
  std::vector<Case> cases;
  for (int j = 3; j <= 12; ++j) {
    cases.push_back({fibonacci_number(j), {1, fibonacci_number(j - 1)}, {1, 1}});
    cases.push_back({fibonacci_number(j), {1, fibonacci_number(j - 1)}, {200, 100}});
  }
  cases.push_back({64, {1, 27}, {1, 1}});
  cases.push_back({64, {1, 27}, {100, 300}});
  cases.push_back({100, {1, 37}, {1, 1}});
  cases.push_back({97, {1, 40}, {400, 100}});
  cases.push_back({6, {2, 3}, {1, 1}});
  cases.push_back({12, {4, 3}, {1, 1}});
  cases.push_back({8, {1, 0}, {1, 1}});
  cases.push_back({64, {1, 19, 41}, {1, 1, 1}});      // 19² = 361 ≡ 41 (mod 64)
  cases.push_back({60, {20, 15, 12}, {1, 1, 1}});     // the 3×4×5 grid
  cases.push_back({30, {15, 10, 6}, {1, 1, 1}});      // the 2×3×5 grid
  cases.push_back({101, {1, 12, 43}, {200, 100, 50}});  // 12² = 144 ≡ 43 (mod 101)
  cases.push_back({50, {1, 7, 49}, {100, 100, 50}});
  cases.push_back({16, {1, 0, 0}, {1, 1, 1}});   // a line along axis 0
  cases.push_back({15, {0, 5, 3}, {2, 1, 1}});   // a 3×5 grid in the plane x_0 = 0
  return cases;
}

// Expects f() to throw InvalidInput and returns its message.
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than InvalidInput: " << e.what();
    return {};
  }
  ADD_FAILURE() << "did not throw";
  return {};
}

#define EXPECT_MESSAGE_HAS(message, part) \
  EXPECT_NE((message).find(part), std::string::npos) << "message: " << (message)

// P₂ from its definition as a sum over the dual lattice (Sloan & Joe 1994, §4.3):
// P₂ = Σ_{h ∈ L⊥, h ≠ 0} Π_d max(1, |h_d|)^−2. Grouping h_d by residue r_d mod N, the sum over
// one residue class is closed: Σ_{j∈ℤ} (r + jN)^−2 = π² / (N² sin²(π r / N)) for r ≢ 0, and
// 1 + 2 Σ_{j≥1} (jN)^−2 = 1 + π²/(3N²) for r ≡ 0; the classes with r·g ≡ 0 are enumerated
// (g_0 = 1, so r_0 is solved). No B₂, no lattice points: an independent route to P₂. The all-zero
// residue tuple is split off so that nothing cancels.
long double p2_from_dual_sum(std::int64_t n, const std::vector<std::int64_t>& g) {
  const auto nl = static_cast<long double>(n);
  std::vector<long double> a(static_cast<std::size_t>(n));
  a[0] = 1 + kPi * kPi / (3 * nl * nl);
  for (std::int64_t r = 1; r < n; ++r) {
    const long double sn = std::sin(kPi * static_cast<long double>(r) / nl);
    a[static_cast<std::size_t>(r)] = kPi * kPi / (nl * nl * sn * sn);
  }
  const std::size_t s = g.size();
  // r = 0 class, minus h = 0: (1 + ε)^s − 1 without cancellation.
  long double sum = std::expm1(static_cast<long double>(s) * std::log1p(kPi * kPi / (3 * nl * nl)));
  const std::int64_t r2_end = s == 3 ? n : 1;
  for (std::int64_t r2 = 0; r2 < r2_end; ++r2) {
    for (std::int64_t r1 = 0; r1 < n; ++r1) {
      if (r1 == 0 && r2 == 0) continue;
      const std::int64_t r0 = floor_mod(-(Int128{r1} * g[1] + (s == 3 ? Int128{r2} * g[2] : 0)), n);
      long double term = a[static_cast<std::size_t>(r0)] * a[static_cast<std::size_t>(r1)];
      if (s == 3) term *= a[static_cast<std::size_t>(r2)];
      sum += term;
    }
  }
  return sum;
}

// ----------------------------------------------------------------------------------------------

TEST(LatticeFibonacci, NumbersAndIndex) {
  EXPECT_EQ(fibonacci_number(1), 1);
  EXPECT_EQ(fibonacci_number(2), 1);
  EXPECT_EQ(fibonacci_number(10), 55);
  EXPECT_EQ(fibonacci_number(20), 6765);
  EXPECT_EQ(fibonacci_number(92), 7540113804746346429);
  for (int j = 3; j <= 92; ++j) EXPECT_EQ(fibonacci_index(fibonacci_number(j)), j);
  const std::string m = refusal([] { fibonacci_index(100); });
  EXPECT_MESSAGE_HAS(m, "100");
  EXPECT_MESSAGE_HAS(m, "F_11 = 89");
  EXPECT_MESSAGE_HAS(m, "F_12 = 144");
  EXPECT_MESSAGE_HAS(refusal([] { fibonacci_index(1); }), "(got 1;");
  EXPECT_MESSAGE_HAS(refusal([] { fibonacci_index(7540113804746346430); }), "F_92");
}

TEST(LatticeBasics, PointsWaveNumbersAndDescription) {
  // Burkardt's lattice_rule_prb_output.txt (TEST14) lists the F_12 = 144 nodes over the unit
  // square: node 1 = (0.00694444, 0.618056), node 9 = (0.0625, 0.5625).
  const RankOneLattice f = fibonacci_lattice(12, 1, 1);
  EXPECT_NEAR(f.point(1)[0], 0.00694444, 5e-9);
  EXPECT_NEAR(f.point(1)[1], 0.618056, 5e-7);
  EXPECT_DOUBLE_EQ(f.point(9)[0], 0.0625);
  EXPECT_DOUBLE_EQ(f.point(9)[1], 0.5625);
  EXPECT_EQ(f.point(9)[2], 0.0);
  const RankOneLattice k = korobov_lattice(4096, 1159, {200, 200});
  EXPECT_EQ(k.describe(), "korobov N=4096 g=(1,1159) over 200×200 m");
  EXPECT_EQ(fibonacci_lattice(20, 200, 100).describe(), "fibonacci N=6765 g=(1,4181) over 200×100 m");
  EXPECT_EQ(RankOneLattice::create(60, {20, 15, 12}, {3, 4, 5}).describe(),
            "rank-1 N=60 g=(20,15,12) over 3×4×5");
  // Exact phases: point 4000 of the Korobov lattice is L ∘ ((4000·g) mod N)/N.
  EXPECT_DOUBLE_EQ(k.point(4000)[1], 200.0 * static_cast<double>((4000 * 1159) % 4096) / 4096);
  const RankOneLattice a = RankOneLattice::create(97, {1, 40}, {400, 100});
  for (std::int64_t m = 0; m < 97; ++m) {
    const auto kv = a.wave_vector(m);
    EXPECT_DOUBLE_EQ(a.wave_number(m)[0], 2 * std::numbers::pi * kv[0] / 400);
    EXPECT_DOUBLE_EQ(a.wave_number(m)[1], 2 * std::numbers::pi * kv[1] / 100);
    EXPECT_EQ(a.wave_number(m)[2], 0.0);
    EXPECT_NEAR(a.patch_norm(to_vec(kv)), std::hypot(a.wave_number(m)[0], a.wave_number(m)[1]), 1e-12);
  }
  EXPECT_EQ(a.wave_vectors().size(), 97u * 2);
}

TEST(LatticeRefusals, NameTheFieldTheRuleAndTheValue) {
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(1, {1, 0}, {1, 1}); }), "(got 1)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(-5, {1, 0}, {1, 1}); }), "(got -5)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create((std::int64_t{1} << 30) + 1, {1, 2}, {1, 1}); }),
                     "(got 1073741825)");
  const std::string range = refusal([] { RankOneLattice::create(64, {1, 64}, {1, 1}); });
  EXPECT_MESSAGE_HAS(range, "g_1");
  EXPECT_MESSAGE_HAS(range, "(got 64)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {-1, 3}, {1, 1}); }), "(got -1)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1}, {1}); }), "(got 1)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1, 2, 3, 4}, {1, 1, 1, 1}); }), "(got 4)");
  const std::string gcd = refusal([] { RankOneLattice::create(64, {2, 6}, {1, 1}); });
  EXPECT_MESSAGE_HAS(gcd, "gcd 2");
  EXPECT_MESSAGE_HAS(gcd, "(2,6)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1, 3}, {1, 0}); }), "length 1");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1, 3}, {-3, 1}); }), "(got -3)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1, 3}, {1, std::nan("")}); }), "nan");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1, 3}, {1, HUGE_VAL}); }), "inf");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1, 3}, {1, 1, 1}); }), "(got 3 lengths)");
  EXPECT_MESSAGE_HAS(refusal([] { RankOneLattice::create(64, {1, 3}, {1e-7, 1}); }), "1e+07");
  EXPECT_MESSAGE_HAS(refusal([] { fibonacci_lattice(2, 1, 1); }), "(got 2)");
  EXPECT_MESSAGE_HAS(refusal([] { fibonacci_lattice(93, 1, 1); }), "(got 93)");
  EXPECT_MESSAGE_HAS(refusal([] { fibonacci_number(0); }), "(got 0)");
  EXPECT_MESSAGE_HAS(refusal([] { fibonacci_lattice(50, 1, 1); }), "(got 12586269025)");  // F_50 > 2^30
  EXPECT_MESSAGE_HAS(refusal([] { korobov_lattice(64, 0, {1, 1}); }), "(got 0)");
  EXPECT_MESSAGE_HAS(refusal([] { korobov_lattice(64, 64, {1, 1}); }), "(got 64)");
  EXPECT_MESSAGE_HAS(refusal([] { korobov_lattice(64, 3, {1}); }), "(got 1)");
  EXPECT_MESSAGE_HAS(refusal([] { korobov_spectral_choice(64, 4, {1, 1, 1, 1}); }), "(got 4)");
  EXPECT_MESSAGE_HAS(refusal([] { korobov_spectral_choice(64, 2, {1, 1, 1}); }), "(got 3 lengths)");
  EXPECT_MESSAGE_HAS(refusal([] { korobov_spectral_choice(1, 2, {1, 1}); }), "(got 1)");
  const RankOneLattice lat = fibonacci_lattice(10, 1, 1);
  EXPECT_MESSAGE_HAS(refusal([&] { lat.wave_vector(55); }), "(got 55)");
  EXPECT_MESSAGE_HAS(refusal([&] { lat.wave_vector(-1); }), "(got -1)");
  EXPECT_MESSAGE_HAS(refusal([&] { lat.point(55); }), "(got 55)");
  EXPECT_MESSAGE_HAS(refusal([&] { lat.residue(Vec{1, 2, 3}); }), "(got 3)");
  EXPECT_MESSAGE_HAS(refusal([] { rank_one_p2(8, Vec{1, 8}); }), "(got 8)");
}

// k_m·g ≡ m for every m, k_{N−m} = −k_m exactly, k_0 = 0, energy everywhere but m = 0, N/2.
TEST(LatticeWaveVectors, ResiduesConjugatesAndEnergy) {
  std::vector<Case> cases = small_cases();
  cases.push_back({fibonacci_number(20), {1, fibonacci_number(19)}, {200, 100}});
  cases.push_back({4096, {1, 1159}, {200, 200}});
  cases.push_back({4095, {1, 1000}, {1, 0.7}});
  cases.push_back({3000, {1, 97, 409}, {200, 100, 60}});
  cases.push_back({3001, {1, 97, 404}, {1, 1, 1}});
  for (const Case& c : cases) {
    SCOPED_TRACE(name(c));
    const RankOneLattice lat = RankOneLattice::create(c.n, c.g, c.lengths);
    ASSERT_EQ(lat.points(), c.n);
    ASSERT_EQ(lat.dimension(), static_cast<int>(c.g.size()));
    for (std::int64_t m = 0; m < c.n; ++m) {
      const Vec k = to_vec(lat.wave_vector(m));
      ASSERT_EQ(residue_of(k, c.g, c.n), m) << "k_" << m << " = " << str(k);
      ASSERT_EQ(lat.residue(lat.wave_vector(m)), m);
      Vec minus = k;
      for (std::int64_t& x : minus) x = -x;
      if (2 * m == c.n) {
        // Self-conjugate: ±k are both in the class; the tie rule keeps the smaller.
        ASSERT_LT(k, minus) << "k_{N/2} = " << str(k);
      } else {
        ASSERT_EQ(to_vec(lat.wave_vector((c.n - m) % c.n)), minus) << "m = " << m;
      }
      ASSERT_EQ(lat.carries_energy(m), m != 0 && !(c.n % 2 == 0 && m == c.n / 2)) << "m = " << m;
    }
    for (const std::int32_t x : lat.wave_vector(0)) EXPECT_EQ(x, 0);
  }
}

// Brute force over every integer k in the box |k_d| ≤ N/2 — which holds every class's minimal
// vectors, since N e_d ∈ L⊥ and a k with |k_d| > N/2 is longer than k ∓ N e_d — gives each
// class's minimal squared norm exactly (Int128) and its lexicographically smallest minimizer.
// k_m must attain the minimum, be that minimizer for m ≤ N/2 (the tie rule), and −k_{N−m} above.
TEST(LatticeWaveVectors, MinimalRepresentativesAgainstBruteForce) {
  for (const Case& c : small_cases()) {
    SCOPED_TRACE(name(c));
    const RankOneLattice lat = RankOneLattice::create(c.n, c.g, c.lengths);
    const ExactMetric metric(c.lengths);
    std::vector<Int128> best(static_cast<std::size_t>(c.n), -1);
    std::vector<Vec> first(static_cast<std::size_t>(c.n));
    for_box(Vec(c.g.size(), c.n / 2), [&](const Vec& k) {
      const auto r = static_cast<std::size_t>(residue_of(k, c.g, c.n));
      const Int128 q = metric.q(k);
      if (best[r] < 0 || q < best[r]) {  // lexicographic visiting order: first = smallest
        best[r] = q;
        first[r] = k;
      }
    });
    for (std::int64_t m = 0; m < c.n; ++m) {
      const Vec k = to_vec(lat.wave_vector(m));
      const auto um = static_cast<std::size_t>(m);
      ASSERT_TRUE(metric.q(k) == best[um])
          << "k_" << m << " = " << str(k) << " is not minimal; brute force: " << str(first[um]);
      if (2 * m <= c.n) {
        EXPECT_EQ(k, first[um]) << "tie rule at m = " << m;
      }
    }
  }
}

// The same minimality where the length ratio is irrational-looking (1 × 0.7 m): no exact
// oracle for ties there, so only "no representative is shorter by more than rounding".
TEST(LatticeWaveVectors, MinimalWithAnUnroundLengthRatio) {
  const Case c{233, {1, 144}, {1, 0.7}};
  const RankOneLattice lat = RankOneLattice::create(c.n, c.g, c.lengths);
  std::vector<long double> best(static_cast<std::size_t>(c.n), -1);
  for_box(Vec{c.n / 2, c.n / 2}, [&](const Vec& k) {
    const auto r = static_cast<std::size_t>(residue_of(k, c.g, c.n));
    const long double q = norm2(k, c.lengths);
    if (best[r] < 0 || q < best[r]) best[r] = q;
  });
  for (std::int64_t m = 0; m < c.n; ++m)
    EXPECT_LE(norm2(to_vec(lat.wave_vector(m)), c.lengths), best[static_cast<std::size_t>(m)] * (1 + 1e-15L)) << m;
}

// No k_m gets shorter by adding a dual vector v: checked against every v with ‖v‖ ≤ 2R (R the
// covering radius), which holds all Voronoi-relevant vectors (‖v‖/2 is a point of the cell).
TEST(LatticeWaveVectors, NoDualVectorShortensAWaveVector) {
  for (const Case& c : small_cases()) {
    SCOPED_TRACE(name(c));
    const RankOneLattice lat = RankOneLattice::create(c.n, c.g, c.lengths);
    const ExactMetric metric(c.lengths);
    const LatticeBand band = lattice_band(lat);
    const std::vector<Vec> v = dual_vectors_within(lat, 2 * band.covering_radius * (1 + 1e-9));
    ASSERT_FALSE(v.empty());
    for (std::int64_t m = 0; m < c.n; ++m) {
      const Vec k = to_vec(lat.wave_vector(m));
      for (const Vec& h : v) {
        Vec shifted = k;
        for (std::size_t d = 0; d < k.size(); ++d) shifted[d] += h[d];
        ASSERT_TRUE(metric.q(k) <= metric.q(shifted)) << "k_" << m << " = " << str(k) << " + " << str(h);
      }
    }
  }
}

// The spectral test, the canonical shortest vector and Zaremba's ρ against brute force.
TEST(LatticeMerits, SpectralTestAndZarembaAgainstBruteForce) {
  for (const Case& c : small_cases()) {
    SCOPED_TRACE(name(c));
    const RankOneLattice lat = RankOneLattice::create(c.n, c.g, c.lengths);
    const LatticeMerits merits = lattice_merits(lat);
    const ExactMetric metric(c.lengths);
    // λ₁ ≤ ‖N e_d‖ = 2πN/L_d for every d, so |h_d| ≤ N L_d / L_max ≤ N bounds the search.
    Int128 best = -1;
    Vec canonical;
    std::int64_t rho = std::numeric_limits<std::int64_t>::max();
    for_box(Vec(c.g.size(), c.n), [&](const Vec& h) {
      if (std::all_of(h.begin(), h.end(), [](std::int64_t x) { return x == 0; })) return;
      if (residue_of(h, c.g, c.n) != 0) return;
      std::int64_t p = 1;
      for (const std::int64_t x : h) p *= std::max<std::int64_t>(1, std::abs(x));
      rho = std::min(rho, p);
      const auto first_nonzero = *std::find_if(h.begin(), h.end(), [](std::int64_t x) { return x != 0; });
      const Int128 q = metric.q(h);
      if (best < 0 || q < best) {
        best = q;
        canonical.clear();
      }
      if (q == best && first_nonzero > 0 && (canonical.empty() || h < canonical)) canonical = h;
    });
    EXPECT_EQ(merits.shortest_dual_vector, canonical);
    EXPECT_EQ(residue_of(merits.shortest_dual_vector, c.g, c.n), 0);
    EXPECT_NEAR(merits.lambda1, static_cast<double>(std::sqrt(norm2(canonical, c.lengths))), 1e-12 * merits.lambda1);
    EXPECT_EQ(merits.zaremba_rho, static_cast<double>(rho));
  }
}

// P₂ = −1 + (1/N) Σ_n Π (1 + 2π² B₂) against the dual-lattice Fourier sum in closed form.
TEST(LatticeP2, AgreesWithTheDualLatticeFourierSum) {
  std::vector<std::pair<std::int64_t, Vec>> cases;
  for (int j = 3; j <= 25; ++j) cases.push_back({fibonacci_number(j), {1, fibonacci_number(j - 1)}});
  cases.push_back({4096, {1, 1159}});
  cases.push_back({1024, {1, 298}});
  cases.push_back({64, {1, 19, 41}});
  cases.push_back({101, {1, 12, 43}});
  cases.push_back({997, {1, 133, 726}});
  for (const auto& [n, g] : cases) {
    const double implemented = rank_one_p2(n, g);
    const long double fourier = p2_from_dual_sum(n, g);
    EXPECT_NEAR(implemented, static_cast<double>(fourier), 1e-10 * static_cast<double>(fourier))
        << "N = " << n << " g = " << str(g);
  }
  // P₂ of the lattice object is the same number.
  EXPECT_EQ(lattice_merits(fibonacci_lattice(15, 3, 7)).p2, rank_one_p2(610, Vec{1, 377}));
}

// John Burkardt, lattice_rule_prb_output.txt (C++ version, 22 December 2011; the "FIND_Z20"
// test, jburkardt-cpp/lattice_rule), after Sloan & Joe, "Lattice Methods for Multiple
// Integration" (1994): the generators z = (1, l) that minimize P₂ over l = 1 … ⌊M/2⌋ for
// Fibonacci, 2^K, 3·2^K and prime M. Equivalent generators tie (l, M − l, l⁻¹ give the same
// P₂), so the test compares P₂ values: P₂(1, l_Burkardt) must equal our minimum over the same
// l range (relative 1e-12: the P₂ sums of equivalent generators differ only by rounding).
TEST(LatticeP2, BurkardtKorobovOptimaAttainTheMinimum) {
  struct Entry {
    std::int64_t m, l;
  };
  const Entry table[] = {
      {2, 1},      {3, 1},      {5, 2},      {8, 3},      {13, 5},     {21, 8},     {34, 10},
      {55, 21},    {4, 2},      {8, 3},      {16, 6},     {32, 14},    {64, 27},    {128, 54},
      {256, 94},   {512, 198},  {1024, 298}, {6, 2},      {12, 5},     {24, 10},    {48, 14},
      {96, 22},    {192, 73},   {384, 146},  {768, 225},  {1536, 674}, {3072, 849}, {113, 35},
      {173, 64},   {229, 94},   {281, 109},  {349, 135},  {409, 169},  {463, 179},  {541, 200}};
  for (const Entry& e : table) {
    double best = std::numeric_limits<double>::infinity();
    for (std::int64_t l = 1; l <= e.m / 2; ++l) best = std::min(best, rank_one_p2(e.m, Vec{1, l}));
    const double burkardt = rank_one_p2(e.m, Vec{1, e.l});
    EXPECT_NEAR(burkardt, best, 1e-12 * best) << "M = " << e.m << ", Burkardt's l = " << e.l;
  }
}

// Band geometry: inscribed radius, covering radius against a brute-force Voronoi cell, the
// bounds on max ‖K_m‖ and the alias-free fraction.
TEST(LatticeBand, CoveringRadiusAgainstBruteForceVoronoiCell) {
  for (const Case& c : small_cases()) {
    SCOPED_TRACE(name(c));
    const RankOneLattice lat = RankOneLattice::create(c.n, c.g, c.lengths);
    const LatticeBand band = lattice_band(lat);
    const LatticeMerits merits = lattice_merits(lat);
    const int s = lat.dimension();
    EXPECT_DOUBLE_EQ(band.inscribed_radius, merits.lambda1 / 2);
    // The cell from every dual vector within 3R: if the implemented R were too small, a
    // relevant vector between 6R and the true 2R' would be missing and the cell found here would
    // be too large (vertices beyond R); if R were too large the cell found here is exact, and
    // smaller. Either way the two disagree.
    std::vector<std::array<long double, 3>> y;
    for (const Vec& h : dual_vectors_within(lat, 3 * band.covering_radius)) {
      std::array<long double, 3> v{};
      for (int d = 0; d < s; ++d) v[static_cast<std::size_t>(d)] = 2 * kPi * h[static_cast<std::size_t>(d)] / c.lengths[static_cast<std::size_t>(d)];
      y.push_back(v);
    }
    auto dot = [](const std::array<long double, 3>& a, const std::array<long double, 3>& b) {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    // Keep only the Voronoi-relevant vectors (v is relevant iff v/2 is nearer to 0 and v than to
    // any other dual vector; such a w has ‖w‖ ≤ ‖v‖, so it is in y): the vertex search below is
    // cubic in their number (at most 14 in 3-D, 6 in 2-D) instead of in all of y.
    {
      std::vector<std::array<long double, 3>> relevant;
      for (const auto& v : y) {
        const std::array<long double, 3> half{v[0] / 2, v[1] / 2, v[2] / 2};
        const long double to_zero = dot(half, half);
        bool is_relevant = true;
        for (const auto& w : y) {
          if (w == v) continue;
          const std::array<long double, 3> d{half[0] - w[0], half[1] - w[1], half[2] - w[2]};
          if (dot(d, d) <= to_zero * (1 + 1e-12L)) { is_relevant = false; break; }
        }
        if (is_relevant) relevant.push_back(v);
      }
      EXPECT_LE(relevant.size(), s == 2 ? 6u : 14u);
      y = std::move(relevant);
    }
    long double radius2 = 0;
    auto consider = [&](const std::array<long double, 3>& x) {
      for (const auto& v : y)
        if (dot(x, v) > dot(v, v) / 2 * (1 + 1e-12L)) return;
      radius2 = std::max(radius2, dot(x, x));
    };
    for (std::size_t i = 0; i < y.size(); ++i) {
      for (std::size_t j = i + 1; j < y.size(); ++j) {
        const auto& p = y[i];
        const auto& q = y[j];
        if (s == 2) {
          const long double det = p[0] * q[1] - p[1] * q[0];
          if (std::fabs(det) < 1e-9L * std::sqrt(dot(p, p) * dot(q, q))) continue;
          const long double cp = dot(p, p) / 2, cq = dot(q, q) / 2;
          consider({(cp * q[1] - cq * p[1]) / det, (p[0] * cq - q[0] * cp) / det, 0});
          continue;
        }
        for (std::size_t k = j + 1; k < y.size(); ++k) {
          const auto& t = y[k];
          // Gaussian elimination on [p; q; t] x = ‖·‖²/2 (a different solver from the library's).
          long double a[3][4] = {{p[0], p[1], p[2], dot(p, p) / 2},
                                 {q[0], q[1], q[2], dot(q, q) / 2},
                                 {t[0], t[1], t[2], dot(t, t) / 2}};
          bool singular = false;
          for (int col = 0; col < 3 && !singular; ++col) {
            int pivot = col;
            for (int row = col + 1; row < 3; ++row)
              if (std::fabs(a[row][col]) > std::fabs(a[pivot][col])) pivot = row;
            if (std::fabs(a[pivot][col]) < 1e-9L * std::sqrt(dot(p, p))) singular = true;
            std::swap(a[col], a[pivot]);
            for (int row = 0; row < 3 && !singular; ++row) {
              if (row == col) continue;
              const long double f = a[row][col] / a[col][col];
              for (int x = col; x < 4; ++x) a[row][x] -= f * a[col][x];
            }
          }
          if (singular) continue;
          consider({a[0][3] / a[0][0], a[1][3] / a[1][1], a[2][3] / a[2][2]});
        }
      }
    }
    EXPECT_NEAR(band.covering_radius, static_cast<double>(std::sqrt(radius2)), 1e-9 * band.covering_radius);
    // max ‖K_m‖ ≤ R, and ≥ R − δ with δ = ½‖(2π/L_0, …)‖ (an integer point lies within δ of
    // the farthest vertex, and its class's minimum is no nearer to 0 than dist(point, L⊥)).
    long double kmax = 0, delta2 = 0;
    for (const double l : c.lengths) delta2 += (kPi / l) * (kPi / l);
    for (std::int64_t m = 0; m < c.n; ++m) kmax = std::max(kmax, std::sqrt(norm2(to_vec(lat.wave_vector(m)), c.lengths)));
    EXPECT_LE(kmax, band.covering_radius * (1 + 1e-12));
    EXPECT_GE(kmax, band.covering_radius - std::sqrt(delta2) - 1e-9);
    long double volume = static_cast<long double>(c.n);
    for (const double l : c.lengths) volume *= 2 * kPi / l;
    const long double r = band.inscribed_radius;
    EXPECT_NEAR(band.alias_free_fraction, static_cast<double>((s == 2 ? kPi * r * r : 4 * kPi * r * r * r / 3) / volume), 1e-12);
    EXPECT_LE(band.alias_free_fraction, (s == 2 ? std::numbers::pi / (2 * std::sqrt(3.0)) : std::numbers::pi / (3 * std::sqrt(2.0))) + 1e-12);
  }
}

// Fibonacci lattices of odd index over a square patch are rotated square grids (their dual is a
// square lattice: F_{j−1}² ≡ −1 mod F_j, Cassini), so the alias-free fraction is π/4 and the
// covering radius λ₁/√2; even indices are not square. The 3×4 grid written as the rank-1
// lattice N = 12, g = (4, 3) over 3 × 4 m is the grid: its wave vectors are the grid's, its
// fraction π/4, its covering radius the half-diagonal π√2.
TEST(LatticeBand, SquareDualsAndGrids) {
  for (int j = 5; j <= 25; ++j) {
    const LatticeBand band = lattice_band(fibonacci_lattice(j, 200, 200));
    if (j % 2 == 1) {
      EXPECT_NEAR(band.alias_free_fraction, std::numbers::pi / 4, 1e-12) << "j = " << j;
      EXPECT_NEAR(band.covering_radius, band.inscribed_radius * std::sqrt(2.0), 1e-12 * band.covering_radius);
    } else if (j >= 8) {  // F_6 = 8, g = (1, 5) happens to have λ₁² = det: π/4 without a square
      EXPECT_GT(std::fabs(band.alias_free_fraction - std::numbers::pi / 4), 1e-3) << "j = " << j;
    }
  }
  const RankOneLattice grid = RankOneLattice::create(12, {4, 3}, {3, 4});
  for (std::int64_t m = 0; m < 12; ++m) {
    const auto k = grid.wave_vector(m);
    EXPECT_LE(std::abs(k[0]), 1) << m;  // nx = 3: kx ∈ {−1, 0, 1}
    EXPECT_LE(std::abs(k[1]), 2) << m;  // ny = 4: ky ∈ {−2, …, 2}, ±2 tied (Nyquist)
  }
  EXPECT_EQ(to_vec(grid.wave_vector(6)), (Vec{0, -2}));  // the self-conjugate class: Nyquist
  const LatticeBand band = lattice_band(grid);
  EXPECT_NEAR(band.alias_free_fraction, std::numbers::pi / 4, 1e-12);
  EXPECT_NEAR(band.covering_radius, std::numbers::pi * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(band.inscribed_radius, std::numbers::pi, 1e-12);
}

// The spectral choice against brute force over every admissible a (gcd(a, N) = 1): its λ₁ is
// the largest, and it is the smallest a attaining it; the same call twice gives the same a.
TEST(LatticeKorobov, SpectralChoiceAgainstBruteForce) {
  struct Search {
    std::int64_t n;
    std::vector<double> lengths;
  };
  const Search searches[] = {{64, {1, 1}},        {64, {200, 100}},     {128, {1, 1}},
                             {97, {1, 1}},        {100, {100, 300}},    {144, {200, 100}},
                             {64, {1, 1, 1}},     {64, {200, 100, 50}}, {101, {1, 1, 1}},
                             {101, {50, 100, 50}}, {81, {100, 100, 100}}};
  for (const Search& sr : searches) {
    const int s = static_cast<int>(sr.lengths.size());
    SCOPED_TRACE("N = " + std::to_string(sr.n) + ", s = " + std::to_string(s));
    const ExactMetric metric(sr.lengths);
    // λ₁² of the Korobov lattice of a, exactly: g_0 = 1, so for every (h_1, h_2) the shortest
    // h_0 is the centred residue of −(a h_1 + a² h_2); |h_d| ≤ N L_d / L_max (as above).
    auto lambda1_sq = [&](std::int64_t a) {
      const std::int64_t a2 = a * a % sr.n;
      Vec half;
      for (int d = 1; d < s; ++d)
        half.push_back(static_cast<std::int64_t>(sr.n * sr.lengths[static_cast<std::size_t>(d)] /
                                                 *std::max_element(sr.lengths.begin(), sr.lengths.end())));
      Int128 best = -1;
      for_box(half, [&](const Vec& tail) {
        const Int128 c = Int128{a} * tail[0] + (s == 3 ? Int128{a2} * tail[1] : 0);
        std::int64_t h0 = floor_mod(-c, sr.n);
        if (h0 > sr.n / 2) h0 -= sr.n;
        Vec h = {h0};
        h.insert(h.end(), tail.begin(), tail.end());
        if (std::all_of(h.begin(), h.end(), [](std::int64_t x) { return x == 0; })) {
          h[0] = sr.n;  // the class of 0: the shortest nonzero h_0 is ±N
        }
        const Int128 q = metric.q(h);
        if (best < 0 || q < best) best = q;
      });
      return best;
    };
    Int128 top = -1;
    std::int64_t first_top = 0;
    for (std::int64_t a = 1; a < sr.n; ++a) {
      if (std::gcd(a, sr.n) != 1) continue;
      const Int128 q = lambda1_sq(a);
      if (q > top) {
        top = q;
        first_top = a;
      }
    }
    const std::int64_t chosen = korobov_spectral_choice(sr.n, s, sr.lengths);
    EXPECT_EQ(korobov_spectral_choice(sr.n, s, sr.lengths), chosen);
    EXPECT_TRUE(lambda1_sq(chosen) == top) << "chosen a = " << chosen << ", best a = " << first_top;
    EXPECT_EQ(chosen, first_top);
    const LatticeMerits merits = lattice_merits(korobov_lattice(sr.n, sr.lengths));
    long double unit = 2 * kPi / *std::max_element(sr.lengths.begin(), sr.lengths.end());
    EXPECT_NEAR(merits.lambda1, static_cast<double>(unit * std::sqrt(static_cast<long double>(top))), 1e-12 * merits.lambda1);
  }
}

// Scale: create() at 2^22 (s = 2) and 2^20 (s = 3), the spectral search at 2^22 (s = 2) and
// 2^20 (s = 3), with the times printed; every class checked. The bounds are 20× what this
// project's 2-core machine takes, there to catch an O(N²) slip, not to benchmark.
TEST(LatticeScale, LargeLatticesInLinearTime) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  auto t0 = Clock::now();
  const std::int64_t a2 = korobov_spectral_choice(std::int64_t{1} << 22, 2, {200, 100});
  const double search2 = seconds(t0);
  t0 = Clock::now();
  const RankOneLattice big2 = korobov_lattice(std::int64_t{1} << 22, a2, {200, 100});
  const double create2 = seconds(t0);
  t0 = Clock::now();
  const std::int64_t a3 = korobov_spectral_choice(std::int64_t{1} << 20, 3, {200, 200, 60});
  const double search3 = seconds(t0);
  t0 = Clock::now();
  const RankOneLattice big3 = korobov_lattice(std::int64_t{1} << 20, a3, {200, 200, 60});
  const double create3 = seconds(t0);
  std::printf("korobov_spectral_choice 2^22, s = 2: %.3f s (a = %lld); create: %.3f s\n", search2,
              static_cast<long long>(a2), create2);
  std::printf("korobov_spectral_choice 2^20, s = 3: %.3f s (a = %lld); create: %.3f s\n", search3,
              static_cast<long long>(a3), create3);
  EXPECT_LT(search2, 10.0);
  EXPECT_LT(create2, 10.0);
  EXPECT_LT(search3, 20.0);
  EXPECT_LT(create3, 20.0);
  for (const RankOneLattice* lat : {&big2, &big3}) {
    const std::int64_t n = lat->points();
    for (std::int64_t m = 0; m < n; ++m) {
      const auto k = lat->wave_vector(m);
      const auto c = lat->wave_vector((n - m) % n);
      ASSERT_EQ(residue_of(to_vec(k), lat->generator(), n), m);
      if (2 * m == n) continue;  // self-conjugate (checked above on small lattices)
      for (std::size_t d = 0; d < k.size(); ++d) ASSERT_EQ(c[d], -k[d]);
    }
  }
}

// The table of figures (printed): Fibonacci j = 10 … 20 and the spectral-test Korobov choice
// for N = 2^10 … 2^22, over 1 × 1 and 200 × 100 m. Asserted: λ₁/2 ≤ R, the 2-D packing bound.
TEST(LatticeTable, FibonacciAndKorobovFigures) {
  const double hexagonal = std::numbers::pi / (2 * std::sqrt(3.0));
  auto row = [&](const RankOneLattice& lat) {
    const LatticeMerits m = lattice_merits(lat);
    const LatticeBand b = lattice_band(lat);
    std::printf("%-44s %10.4f %10.0f %11.4e %10.4f %10.4f %7.4f\n", lat.describe().c_str(), m.lambda1,
                m.zaremba_rho, m.p2, b.inscribed_radius, b.covering_radius, b.alias_free_fraction);
    EXPECT_LE(b.inscribed_radius, b.covering_radius);
    EXPECT_LE(b.alias_free_fraction, hexagonal + 1e-12);
  };
  for (const std::vector<double>& l : {std::vector<double>{1, 1}, std::vector<double>{200, 100}}) {
    std::printf("%-44s %10s %10s %11s %10s %10s %7s\n", "lattice", "lambda1", "rho", "P2",
                "r_in", "R_cov", "frac");
    for (int j = 10; j <= 20; ++j) row(fibonacci_lattice(j, l[0], l[1]));
    for (int e = 10; e <= 22; ++e) row(korobov_lattice(std::int64_t{1} << e, l));
  }
}

}  // namespace
}  // namespace swell::reference
