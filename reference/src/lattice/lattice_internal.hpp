#pragma once
// What lattice.cpp and its neighbours share (reduction.cpp, search.cpp, merits.cpp): exact
// integer vectors, the patch metric, and the lattice reductions every part of the rank-1
// lattice code builds on (docs/lattice.md).
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "swell/reference/lattice.hpp"

namespace swell::reference::lattice_detail {

// 128-bit products keep every (a·b) mod N exact for a, b < 2^63 (__extension__: GCC's
// __int128 is outside ISO C++, and -Wpedantic would say so at every use otherwise).
__extension__ using Int128 = __int128;
using Vec = std::array<std::int64_t, 3>;
using Basis = std::array<Vec, 3>;
constexpr long double kTwoPi = 2 * std::numbers::pi_v<long double>;
// Two squared norms closer than this (relative) are "maybe tied" in double and get a second
// look in long double; double's own rounding of Σ k² w is below 3e-16.
constexpr double kDoubleTieWindow = 1e-12;
// Two long-double squared norms within 16 ulp are tied (header: "Ties").
constexpr long double kLongDoubleTie = 16 * LDBL_EPSILON;
// Enumeration slack: every lattice vector within (best squared distance) × (1 + this) is
// visited, so that the double-precision Gram–Schmidt distances (relative error ~1e-15 on a
// reduced basis) can never hide a tied or shorter vector from the exact comparison.
constexpr double kEnumerationSlack = 1e-9;
// The spectral search's tie window on λ₁² (documented in the header).
constexpr double kSearchTie = 1e-12;

[[noreturn]] void refuse(std::string_view what, std::string_view rule, std::string_view got);

[[noreturn]] void bug(std::string_view what);

// Exact integer arithmetic (reduction.cpp).
std::int64_t floor_mod(Int128 a, std::int64_t n);
std::int64_t mul_mod(std::int64_t a, std::int64_t b, std::int64_t n);
// The representative of r mod n in (−n/2, n/2].
std::int64_t centered(std::int64_t r, std::int64_t n);
// a⁻¹ mod n for gcd(a, n) = 1 (0 when n = 1).
std::int64_t inverse_mod(std::int64_t a, std::int64_t n);

// G = gcd(v_0, …, v_{k−1}, n) and β with Σ β_j v_j ≡ G (mod n), β_j ∈ [0, n).
struct BezoutMod {
  std::int64_t gcd = 0;
  Vec coef{};
};
BezoutMod bezout_mod(std::span<const std::int64_t> values, std::int64_t n);

struct Metric {
  int s = 0;
  double w[3] = {0, 0, 0};
  long double wl[3] = {0, 0, 0};
  long double root_w[3] = {0, 0, 0};  // L_max / L_d
  long double unit = 0;               // 2π / L_max, rad/m

  Metric(const std::vector<double>& lengths) : s(static_cast<int>(lengths.size())) {
    const long double lmax = *std::max_element(lengths.begin(), lengths.end());
    for (int d = 0; d < s; ++d) {
      root_w[d] = lmax / static_cast<long double>(lengths[d]);
      wl[d] = root_w[d] * root_w[d];
      w[d] = static_cast<double>(wl[d]);
    }
    unit = kTwoPi / lmax;
  }

  double q(const std::int64_t* k) const {
    double sum = 0;
    for (int d = 0; d < s; ++d) {
      const auto x = static_cast<double>(k[d]);
      sum += x * x * w[d];
    }
    return sum;
  }
  long double ql(const std::int64_t* k) const {
    long double sum = 0;
    for (int d = 0; d < s; ++d) {
      const auto x = static_cast<long double>(k[d]);
      sum += x * x * wl[d];
    }
    return sum;
  }
  long double dotl(const std::int64_t* a, const std::int64_t* b) const {
    long double sum = 0;
    for (int d = 0; d < s; ++d)
      sum += static_cast<long double>(a[d]) * static_cast<long double>(b[d]) * wl[d];
    return sum;
  }
  // ‖2π k / L‖, rad/m.
  long double norm(const std::int64_t* k) const { return unit * std::sqrt(ql(k)); }
};

// −1, 0, +1 as ‖a‖ is shorter than, tied with, longer than ‖b‖ (header: "Ties").
int compare_norms(const Metric& m, const std::int64_t* a, const std::int64_t* b);

// The total order of the tie-break: norm (with ties), then lexicographic.
int compare_vectors(const Metric& m, const std::int64_t* a, const std::int64_t* b);

// v − q u, exact, refusing to wrap (the bounds in the header keep real lattices far from it).
void subtract_multiple(Vec& v, std::int64_t q, const Vec& u, int s);

// Gram–Schmidt, reduction and enumeration (rows b_0 … b_{s−1}).
template <class F>
struct Gram {
  F mu[3][3] = {};  // μ_ij = ⟨b_i, b_j*⟩ / ‖b_j*‖², j < i
  F b2[3] = {};     // ‖b_i*‖²
};

template <class F>
Gram<F> gram_schmidt(const Basis& b, int s, const F* w) {
  Gram<F> g;
  F star[3][3] = {};
  for (int i = 0; i < s; ++i) {
    for (int d = 0; d < s; ++d) star[i][d] = static_cast<F>(b[i][d]);
    for (int j = 0; j < i; ++j) {
      F dot = 0;
      for (int d = 0; d < s; ++d) dot += static_cast<F>(b[i][d]) * star[j][d] * w[d];
      g.mu[i][j] = dot / g.b2[j];
      for (int d = 0; d < s; ++d) star[i][d] -= g.mu[i][j] * star[j][d];
    }
    F n2 = 0;
    for (int d = 0; d < s; ++d) n2 += star[i][d] * star[i][d] * w[d];
    g.b2[i] = n2;
  }
  return g;
}

template <class F>
F weighted_q(const Vec& v, int s, const F* w) {
  F sum = 0;
  for (int d = 0; d < s; ++d) sum += static_cast<F>(v[d]) * static_cast<F>(v[d]) * w[d];
  return sum;
}

// LLL (δ = 0.99) in the weighted metric. Returns false as soon as a basis vector with squared
// norm below reject_below appears (the spectral search's early rejection; pass −1 for none).
template <class F>
bool lll_reduce(Basis& b, int s, const F* w, F reject_below) {
  const F delta = F(0.99);
  Gram<F> g = gram_schmidt(b, s, w);
  int k = 1;
  for (int iteration = 0; k < s; ++iteration) {
    if (iteration > 100000) bug("LLL did not converge");
    // Size reduction of b_k, repeated until |μ_kj| ≤ ½ holds on a fresh Gram–Schmidt (one pass
    // can leave a large μ slightly off when the coefficients are ~N).
    for (int pass = 0; pass < 8; ++pass) {
      bool changed = false;
      for (int j = k - 1; j >= 0; --j) {
        const F mu = g.mu[k][j];
        if (std::fabs(mu) <= F(0.5) + F(1e-9)) continue;
        const auto q = static_cast<std::int64_t>(std::llround(mu));
        subtract_multiple(b[k], q, b[j], s);
        for (int l = 0; l < j; ++l) g.mu[k][l] -= static_cast<F>(q) * g.mu[j][l];
        g.mu[k][j] -= static_cast<F>(q);
        changed = true;
      }
      if (!changed) break;
      g = gram_schmidt(b, s, w);
      if (weighted_q(b[k], s, w) < reject_below) return false;
    }
    if (g.b2[k] < (delta - g.mu[k][k - 1] * g.mu[k][k - 1]) * g.b2[k - 1]) {
      std::swap(b[k], b[k - 1]);
      g = gram_schmidt(b, s, w);
      k = std::max(k - 1, 1);
    } else {
      ++k;
    }
  }
  return true;
}

// Lagrange–Gauss reduction of a 2-D basis: afterwards ‖b_0‖ ≤ ‖b_1‖ and |μ| ≤ ½, so b_0 is a
// shortest vector and (b_0, b_1) a shortest basis.
void gauss_reduce(Basis& b, const Metric& m);

// Schnorr–Euchner enumeration: visits every c ∈ ℤ^s with
//   Σ_i ‖b_i*‖² (center_i − c_i)² ≤ radius2,  center_i = t_i + Σ_{j>i} (t_j − c_j) μ_ji,
// i.e. every lattice vector Σ c_i b_i within sqrt(radius2) of the point Σ t_i b_i, each level
// in zig-zag order from the nearest integer outwards (so the first leaf is Babai's point).
// leaf(c, d2) returns the new radius2 (smaller to prune, negative to stop).
template <class Leaf>
void enumerate(int s, const Gram<double>& g, const double* t, double radius2, Leaf&& leaf) {
  std::int64_t c[3] = {0, 0, 0}, dx[3] = {0, 0, 0}, ddx[3] = {0, 0, 0};
  double center[3] = {0, 0, 0}, partial[4] = {0, 0, 0, 0};
  int i = s - 1;
  center[i] = t[i];
  c[i] = std::llround(center[i]);
  dx[i] = ddx[i] = center[i] >= static_cast<double>(c[i]) ? 1 : -1;
  for (;;) {
    const double diff = center[i] - static_cast<double>(c[i]);
    const double d2 = partial[i + 1] + diff * diff * g.b2[i];
    if (d2 <= radius2) {
      if (i == 0) {
        radius2 = leaf(static_cast<const std::int64_t*>(c), d2);
        c[0] += dx[0];
        ddx[0] = -ddx[0];
        dx[0] = ddx[0] - dx[0];
      } else {
        partial[i] = d2;
        --i;
        double ctr = t[i];
        for (int j = i + 1; j < s; ++j) ctr += (t[j] - static_cast<double>(c[j])) * g.mu[j][i];
        center[i] = ctr;
        c[i] = std::llround(ctr);
        dx[i] = ddx[i] = ctr >= static_cast<double>(c[i]) ? 1 : -1;
      }
    } else {
      if (++i == s) return;
      c[i] += dx[i];
      ddx[i] = -ddx[i];
      dx[i] = ddx[i] - dx[i];
    }
  }
}

Gram<double> to_double(const Gram<long double>& g);

Vec combination(const Basis& b, const std::int64_t* c, int s);

// All shortest nonzero vectors of the lattice spanned by the (reduced) basis b.
std::vector<Vec> shortest_vectors(const Basis& b, int s, const Metric& m);

// The basis of L⊥ = {h : h·g ≡ 0 (mod N)} in Hermite normal form (upper triangular rows):
// row i = (0, …, 0, d_i, h_{i+1}, …) with d_i the least positive i-th coordinate of a dual
// vector whose first i coordinates vanish: with G_i = gcd(g_{i+1}, …, g_{s−1}, N) the tail
// Σ_{j>i} h_j g_j reaches exactly the multiples of G_i, so d_i = G_i / gcd(g_i, G_i), and the
// tail solving Σ_{j>i} h_j g_j ≡ −d_i g_i comes from Bézout. Π d_i = N / gcd(g, N) = N.
Basis hermite_dual_basis(std::int64_t n, const std::vector<std::int64_t>& g);

// Cofactors C[i][d] of the basis matrix (rows b_i), exact.
std::array<std::array<std::int64_t, 3>, 3> cofactors(const Basis& b, int s);

// Validation (lattice.cpp).
void validate_lengths(const std::vector<double>& lengths, std::size_t s);
void validate_points(std::int64_t points);
void validate_dimension(std::size_t s, std::string_view what);

void fill_table(std::int64_t n, const std::vector<std::int64_t>& g, const Basis& b,
                const Metric& m, std::vector<std::int32_t>& table);

std::string join(const std::vector<std::int64_t>& g);

// The spectral search (search.cpp).
double korobov_lambda1_sq_2d(std::int64_t n, std::int64_t a, const double* w, double reject_below);

double korobov_lambda1_sq_3d(std::int64_t n, std::int64_t a, const double* w, double reject_below);

// Covering radius (merits.cpp).
// An obtuse superbase v_0 … v_s (Σ v_i = 0, ⟨v_i, v_j⟩ ≤ 0 for i ≠ j) of the lattice.
std::vector<Vec> obtuse_superbase(const Basis& b, int s, const Metric& m);

struct VoronoiCell {
  long double covering_radius = 0;  // rad/m
  long double shortest_relevant = 0;  // rad/m, min over the relevant vectors
};
VoronoiCell voronoi_cell(const Basis& b, int s, const Metric& m);

}  // namespace swell::reference::lattice_detail
