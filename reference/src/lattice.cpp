#include "swell/reference/lattice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <string_view>
#include <utility>

#include "integer_arithmetic.hpp"
#include "swell/reference/errors.hpp"

namespace swell::reference {
namespace {

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

[[noreturn]] void refuse(std::string_view what, std::string_view rule, std::string_view got) {
  throw InvalidInput(fmt::format("{} must be {} (got {})", what, rule, got));
}

[[noreturn]] void bug(std::string_view what) {
  throw InternalError(fmt::format("rank-1 lattice: {} (a bug in swell)", what));
}

// ---------------------------------------------------------------------------------------------
// Exact integer arithmetic.

std::int64_t floor_mod(Int128 a, std::int64_t n) {
  const auto r = static_cast<std::int64_t>(a % n);
  return r < 0 ? r + n : r;
}

std::int64_t mul_mod(std::int64_t a, std::int64_t b, std::int64_t n) {
  return floor_mod(Int128{a} * b, n);
}

// The representative of r mod n in (−n/2, n/2].
std::int64_t centered(std::int64_t r, std::int64_t n) {
  r = floor_mod(r, n);
  return r > n / 2 ? r - n : r;
}

// a⁻¹ mod n for gcd(a, n) = 1 (0 when n = 1).
std::int64_t inverse_mod(std::int64_t a, std::int64_t n) {
  const integer::Bezout e = integer::extended_gcd(floor_mod(a, n), n);
  if (e.gcd != 1) bug("inverse of a non-unit");
  return floor_mod(e.x, n);
}

// G = gcd(v_0, …, v_{k−1}, n) and β with Σ β_j v_j ≡ G (mod n), β_j ∈ [0, n).
struct BezoutMod {
  std::int64_t gcd = 0;
  Vec coef{};
};

BezoutMod bezout_mod(std::span<const std::int64_t> values, std::int64_t n) {
  BezoutMod out;
  out.gcd = n;  // n ≡ 0 = Σ 0·v: the invariant Σ β v ≡ G holds from the start
  for (std::size_t j = 0; j < values.size(); ++j) {
    const integer::Bezout e = integer::extended_gcd(out.gcd, floor_mod(values[j], n));
    for (std::size_t i = 0; i < j; ++i) out.coef[i] = mul_mod(out.coef[i], e.x, n);
    out.coef[j] = floor_mod(e.y, n);
    out.gcd = e.gcd;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// The patch metric on integer vectors: ‖2π k / L‖² = unit² Σ_d k_d² w_d, w_d = (L_max / L_d)²
// ≥ 1 (so w_d is an integer whenever L_max / L_d is, and a nonzero k has Σ k² w ≥ 1).

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
int compare_norms(const Metric& m, const std::int64_t* a, const std::int64_t* b) {
  const double qa = m.q(a), qb = m.q(b);
  if (qa < qb * (1 - kDoubleTieWindow)) return -1;
  if (qb < qa * (1 - kDoubleTieWindow)) return 1;
  const long double la = m.ql(a), lb = m.ql(b);
  const long double tol = kLongDoubleTie * std::max(la, lb);
  if (la < lb - tol) return -1;
  if (lb < la - tol) return 1;
  return 0;
}

// The total order of the tie-break: norm (with ties), then lexicographic.
int compare_vectors(const Metric& m, const std::int64_t* a, const std::int64_t* b) {
  if (const int c = compare_norms(m, a, b); c != 0) return c;
  for (int d = 0; d < m.s; ++d) {
    if (a[d] != b[d]) return a[d] < b[d] ? -1 : 1;
  }
  return 0;
}

// v − q u, exact, refusing to wrap (the bounds in the header keep real lattices far from it).
void subtract_multiple(Vec& v, std::int64_t q, const Vec& u, int s) {
  for (int d = 0; d < s; ++d) {
    const Int128 x = Int128{v[d]} - Int128{q} * u[d];
    if (x > (Int128{1} << 62) || x < -(Int128{1} << 62)) bug("basis vector beyond 2^62");
    v[d] = static_cast<std::int64_t>(x);
  }
}

// ---------------------------------------------------------------------------------------------
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
void gauss_reduce(Basis& b, const Metric& m) {
  if (m.ql(b[1].data()) < m.ql(b[0].data())) std::swap(b[0], b[1]);
  for (int iteration = 0; iteration < 10000; ++iteration) {
    const long double mu = m.dotl(b[0].data(), b[1].data()) / m.ql(b[0].data());
    if (std::fabs(mu) > 0.5L) subtract_multiple(b[1], std::llround(mu), b[0], 2);
    if (m.ql(b[1].data()) < m.ql(b[0].data())) {
      std::swap(b[0], b[1]);
    } else {
      return;
    }
  }
  bug("Lagrange-Gauss reduction did not converge");
}

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

Gram<double> to_double(const Gram<long double>& g) {
  Gram<double> out;
  for (int i = 0; i < 3; ++i) {
    out.b2[i] = static_cast<double>(g.b2[i]);
    for (int j = 0; j < 3; ++j) out.mu[i][j] = static_cast<double>(g.mu[i][j]);
  }
  return out;
}

Vec combination(const Basis& b, const std::int64_t* c, int s) {
  Vec v{};
  for (int i = 0; i < s; ++i)
    for (int d = 0; d < s; ++d) v[d] += c[i] * b[i][d];
  return v;
}

// All shortest nonzero vectors of the lattice spanned by the (reduced) basis b.
std::vector<Vec> shortest_vectors(const Basis& b, int s, const Metric& m) {
  const Gram<double> g = to_double(gram_schmidt<long double>(b, s, m.wl));
  double radius2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < s; ++i) radius2 = std::min(radius2, m.q(b[i].data()));
  radius2 *= 1 + kEnumerationSlack;
  std::vector<Vec> found;
  const double zero[3] = {0, 0, 0};
  enumerate(s, g, zero, radius2, [&](const std::int64_t* c, double d2) {
    if (std::all_of(c, c + s, [](std::int64_t x) { return x == 0; })) return radius2;
    found.push_back(combination(b, c, s));
    radius2 = std::min(radius2, d2 * (1 + kEnumerationSlack));
    return radius2;
  });
  if (found.empty()) bug("no shortest vector found");
  const Vec* best = &found.front();
  for (const Vec& v : found)
    if (compare_norms(m, v.data(), best->data()) < 0) best = &v;
  std::vector<Vec> ties;
  for (const Vec& v : found)
    if (compare_norms(m, v.data(), best->data()) == 0) ties.push_back(v);
  return ties;
}

// The basis of L⊥ = {h : h·g ≡ 0 (mod N)} in Hermite normal form (upper triangular rows):
// row i = (0, …, 0, d_i, h_{i+1}, …) with d_i the least positive i-th coordinate of a dual
// vector whose first i coordinates vanish: with G_i = gcd(g_{i+1}, …, g_{s−1}, N) the tail
// Σ_{j>i} h_j g_j reaches exactly the multiples of G_i, so d_i = G_i / gcd(g_i, G_i), and the
// tail solving Σ_{j>i} h_j g_j ≡ −d_i g_i comes from Bézout. Π d_i = N / gcd(g, N) = N.
Basis hermite_dual_basis(std::int64_t n, const std::vector<std::int64_t>& g) {
  const int s = static_cast<int>(g.size());
  Basis b{};
  for (int i = 0; i < s; ++i) {
    const BezoutMod tail =
        bezout_mod(std::span<const std::int64_t>(g).subspan(static_cast<std::size_t>(i) + 1), n);
    const std::int64_t gi_gcd = std::gcd(g[i], tail.gcd);
    const std::int64_t d = tail.gcd / gi_gcd;
    const std::int64_t c = g[i] / gi_gcd;  // d g_i = c G_i
    b[i][i] = d;
    for (int j = i + 1; j < s; ++j)
      b[i][j] =
          centered(-mul_mod(c, tail.coef[j - i - 1], n), n);
  }
  Int128 det = 1;
  for (int i = 0; i < s; ++i) det *= b[i][i];
  if (det != n) bug("Hermite basis of the dual lattice has the wrong determinant");
  return b;
}

// Cofactors C[i][d] of the basis matrix (rows b_i), exact.
std::array<std::array<std::int64_t, 3>, 3> cofactors(const Basis& b, int s) {
  std::array<std::array<std::int64_t, 3>, 3> c{};
  auto fit = [](Int128 x) {
    if (x > (Int128{1} << 62) || x < -(Int128{1} << 62)) bug("cofactor beyond 2^62");
    return static_cast<std::int64_t>(x);
  };
  if (s == 2) {
    c[0][0] = b[1][1];
    c[0][1] = -b[1][0];
    c[1][0] = -b[0][1];
    c[1][1] = b[0][0];
    return c;
  }
  for (int i = 0; i < 3; ++i) {
    for (int d = 0; d < 3; ++d) {
      const int r0 = (i + 1) % 3, r1 = (i + 2) % 3, c0 = (d + 1) % 3, c1 = (d + 2) % 3;
      // Cyclic indices give the signed cofactor directly in 3×3.
      c[i][d] =
          fit(Int128{b[r0][c0]} *
                  b[r1][c1] -
              Int128{b[r0][c1]} *
                  b[r1][c0]);
    }
  }
  return c;
}

// ---------------------------------------------------------------------------------------------
// Validation.

void validate_lengths(const std::vector<double>& lengths, std::size_t s) {
  if (lengths.size() != s)
    refuse("lattice lengths", fmt::format("one per generator component ({})", s),
           fmt::format("{} lengths", lengths.size()));
  for (std::size_t d = 0; d < s; ++d) {
    if (!(std::isfinite(lengths[d]) && lengths[d] > 0))
      refuse(fmt::format("lattice length {}", d), "finite and > 0", fmt::format("{}", lengths[d]));
  }
  const auto [lo, hi] = std::minmax_element(lengths.begin(), lengths.end());
  if (*hi / *lo > kMaxLatticeLengthRatio)
    refuse("lattice length ratio max/min", "at most 2^20 = 1048576",
           fmt::format("{:g} / {:g} = {:g}", *hi, *lo, *hi / *lo));
}

void validate_points(std::int64_t points) {
  if (points < 2 || points > kMaxLatticePoints)
    refuse("lattice points N", fmt::format("in [2, 2^30 = {}]", kMaxLatticePoints),
           fmt::format("{}", points));
}

void validate_dimension(std::size_t s, std::string_view what) {
  if (s != 2 && s != 3) refuse(what, "2 or 3", fmt::format("{}", s));
}

// ---------------------------------------------------------------------------------------------
// The wave-vector table (header: "The wave-vector table").

void fill_table(std::int64_t n, const std::vector<std::int64_t>& g, const Basis& b,
                const Metric& m, std::vector<std::int32_t>& table) {
  const int s = static_cast<int>(g.size());
  const auto us = static_cast<std::size_t>(s);
  table.assign(static_cast<std::size_t>(n) * us, 0);

  // u with u·g ≡ 1: Bézout over (g, N), which the gcd rule makes 1.
  const BezoutMod bz = bezout_mod(g, n);
  if (bz.gcd != 1) bug("generator passed the gcd rule but has no inverse");
  const Vec u = bz.coef;

  // Fractional coordinates of u in the reduced basis: t(u) = u B⁻¹ = u adj(B) / det(B), and
  // det(B) = ±N, so A = N t(u) = ±Σ_d u_d C[i][d] is an exact integer vector.
  const auto cof = cofactors(b, s);
  Int128 det = 0;
  for (int d = 0; d < s; ++d) det += Int128{b[0][d]} * cof[0][d];
  if (det != n && det != -n) bug("reduced dual basis does not have determinant ±N");
  const int sign = det > 0 ? 1 : -1;
  std::int64_t a[3] = {0, 0, 0};
  Vec shifted = u;  // u − Σ ⌊t_i(u)⌋ b_i = Σ (a_i / N) b_i, inside the parallelepiped
  for (int i = 0; i < s; ++i) {
    Int128 big = 0;
    for (int d = 0; d < s; ++d) big += Int128{u[d]} * cof[i][d];
    big *= sign;
    a[i] = floor_mod(big, n);
    const auto whole = static_cast<std::int64_t>((big - a[i]) / n);
    subtract_multiple(shifted, whole, b[i], s);
  }
  for (int d = 0; d < s; ++d) {
    Int128 check = 0;
    for (int i = 0; i < s; ++i) check += Int128{a[i]} * b[i][d];
    if (check != Int128{shifted[d]} * n) bug("fractional coordinates of u");
  }

  const Gram<double> gram = to_double(gram_schmidt<long double>(b, s, m.wl));
  const double inv_n = 1.0 / static_cast<double>(n);
  Vec p{};                              // representative of class m, Σ (f_i / N) b_i
  std::int64_t f[3] = {0, 0, 0};
  const std::int64_t half = n / 2;
  for (std::int64_t cls = 1; cls <= half; ++cls) {
    for (int d = 0; d < s; ++d) p[d] += shifted[d];
    for (int i = 0; i < s; ++i) {
      f[i] += a[i];
      if (f[i] >= n) {
        f[i] -= n;
        for (int d = 0; d < s; ++d) p[d] -= b[i][d];
      }
    }
    const double t[3] = {static_cast<double>(f[0]) * inv_n, static_cast<double>(f[1]) * inv_n,
                         static_cast<double>(f[2]) * inv_n};
    std::int64_t best[3] = {0, 0, 0};
    bool have = false;
    double best_d2 = std::numeric_limits<double>::infinity();
    enumerate(s, gram, t, best_d2, [&](const std::int64_t* c, double d2) {
      std::int64_t k[3] = {0, 0, 0};
      for (int d = 0; d < s; ++d) {
        std::int64_t x = p[d];
        for (int i = 0; i < s; ++i) x -= c[i] * b[i][d];
        k[d] = x;
      }
      if (!have || compare_vectors(m, k, best) < 0) {
        std::copy(k, k + s, best);
        have = true;
      }
      best_d2 = std::min(best_d2, d2);
      return best_d2 * (1 + kEnumerationSlack);
    });
    std::int32_t* row = table.data() + static_cast<std::size_t>(cls) * us;
    std::int32_t* mirror = table.data() + static_cast<std::size_t>(n - cls) * us;
    for (int d = 0; d < s; ++d) {
      // |k_d| ≤ N/2 for a minimal vector (N e_d ∈ L⊥ bounds the Voronoi cell's slab).
      if (best[d] > n / 2 || best[d] < -(n / 2)) bug("wave vector outside the slab |k_d| ≤ N/2");
      row[d] = static_cast<std::int32_t>(best[d]);
      if (cls != n - cls) mirror[d] = static_cast<std::int32_t>(-best[d]);
    }
  }
  // The invariant everything downstream relies on, checked once in exact integers.
  for (std::int64_t cls = 0; cls < n; ++cls) {
    const std::int32_t* row = table.data() + static_cast<std::size_t>(cls) * us;
    Int128 dot = 0;
    for (int d = 0; d < s; ++d) dot += Int128{row[d]} * g[d];
    if (floor_mod(dot, n) != cls) bug("wave vector in the wrong residue class");
  }
}

// ---------------------------------------------------------------------------------------------
// The spectral search's λ₁² for one Korobov multiplier (weighted units, Σ h² w), or −1 when a
// dual vector shorter than reject_below turned up on the way.

double korobov_lambda1_sq_2d(std::int64_t n, std::int64_t a, const double* w, double reject_below) {
  // L⊥ for g = (1, a): h_0 ≡ −a h_1, basis (N, 0), (−a, 1).
  std::int64_t ux = n, uy = 0, vx = -a, vy = 1;
  auto q = [w](std::int64_t x, std::int64_t y) {
    const auto fx = static_cast<double>(x), fy = static_cast<double>(y);
    return fx * fx * w[0] + fy * fy * w[1];
  };
  double qu = q(ux, uy), qv = q(vx, vy);
  if (qv < reject_below) return -1;
  if (qv < qu) {
    std::swap(ux, vx);
    std::swap(uy, vy);
    std::swap(qu, qv);
  }
  for (int iteration = 0; iteration < 400; ++iteration) {
    const double dot = static_cast<double>(ux) * static_cast<double>(vx) * w[0] +
                       static_cast<double>(uy) * static_cast<double>(vy) * w[1];
    if (2 * std::fabs(dot) > qu) {
      const std::int64_t k = std::llround(dot / qu);
      vx -= k * ux;
      vy -= k * uy;
      qv = q(vx, vy);
      if (qv < reject_below) return -1;
    }
    if (qv < qu) {
      std::swap(ux, vx);
      std::swap(uy, vy);
      std::swap(qu, qv);
    } else {
      return qu;
    }
  }
  bug("Lagrange-Gauss reduction did not converge in the spectral search");
}

double korobov_lambda1_sq_3d(std::int64_t n, std::int64_t a, const double* w, double reject_below) {
  const std::int64_t a2 = mul_mod(a, a, n);
  Basis b{};
  b[0] = {n, 0, 0};
  b[1] = {centered(-a, n), 1, 0};
  b[2] = {centered(-a2, n), 0, 1};
  for (int i = 1; i < 3; ++i)
    if (weighted_q<double>(b[i], 3, w) < reject_below) return -1;
  if (!lll_reduce<double>(b, 3, w, reject_below)) return -1;
  const Gram<double> g = gram_schmidt<double>(b, 3, w);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) best = std::min(best, weighted_q<double>(b[i], 3, w));
  if (best < reject_below) return -1;
  bool rejected = false;
  const double zero[3] = {0, 0, 0};
  enumerate(3, g, zero, best * (1 + kEnumerationSlack), [&](const std::int64_t* c, double) {
    if (c[0] == 0 && c[1] == 0 && c[2] == 0) return best * (1 + kEnumerationSlack);
    const Vec h = combination(b, c, 3);
    const double qh = weighted_q<double>(h, 3, w);
    if (qh < reject_below) {
      rejected = true;
      return -1.0;
    }
    best = std::min(best, qh);
    return best * (1 + kEnumerationSlack);
  });
  return rejected ? -1 : best;
}

// ---------------------------------------------------------------------------------------------
// Covering radius (header: LatticeBand::covering_radius).

// An obtuse superbase v_0 … v_s (Σ v_i = 0, ⟨v_i, v_j⟩ ≤ 0 for i ≠ j) of the lattice.
std::vector<Vec> obtuse_superbase(const Basis& b, int s, const Metric& m) {
  auto sum = [s](const Vec& x, const Vec& y, std::int64_t sy) {
    Vec r{};
    for (int d = 0; d < s; ++d) r[d] = x[d] + sy * y[d];
    return r;
  };
  Vec zero{};
  if (s == 2) {
    // Gauss-reduced: if ⟨b_0, b_1⟩ ≤ 0, (b_0, b_1, −b_0 − b_1) is obtuse; otherwise
    // (b_0, −b_1, b_1 − b_0), since ⟨b_0, b_1⟩ ≤ ‖b_0‖²/2 ≤ ‖b_1‖²/2.
    if (m.dotl(b[0].data(), b[1].data()) <= 0)
      return {b[0], b[1], sum(sum(zero, b[0], -1), b[1], -1)};
    return {b[0], sum(zero, b[1], -1), sum(b[1], b[0], -1)};
  }
  // Selling's reduction: while some ⟨v_i, v_j⟩ > 0, v_i → −v_i and v_k → v_k + v_i for the
  // other two; Σ ‖v‖² drops by 2⟨v_i, v_j⟩ each time, so it ends (quickly from an LLL basis).
  std::vector<Vec> v = {sum(sum(sum(zero, b[0], -1), b[1], -1), b[2], -1), b[0], b[1], b[2]};
  for (int iteration = 0;; ++iteration) {
    if (iteration > 10000) bug("Selling reduction did not converge");
    bool changed = false;
    for (int i = 0; i < 4 && !changed; ++i) {
      for (int j = i + 1; j < 4 && !changed; ++j) {
        const long double p = m.dotl(v[i].data(), v[j].data());
        const long double scale = std::sqrt(m.ql(v[i].data()) * m.ql(v[j].data()));
        if (p <= 1e-15L * scale) continue;
        for (int k = 0; k < 4; ++k)
          if (k != i && k != j) v[k] = sum(v[k], v[i], 1);
        v[i] = sum(zero, v[i], -1);
        changed = true;
      }
    }
    if (!changed) return v;
  }
}

struct VoronoiCell {
  long double covering_radius = 0;  // rad/m
  long double shortest_relevant = 0;  // rad/m, min over the relevant vectors
};

VoronoiCell voronoi_cell(const Basis& b, int s, const Metric& m) {
  const std::vector<Vec> v = obtuse_superbase(b, s, m);
  // The 2^{s+1} − 2 partial sums, in Euclidean K coordinates (rad/m).
  std::vector<std::array<long double, 3>> rel;
  const int parts = s + 1;
  for (int mask = 1; mask < (1 << parts) - 1; ++mask) {
    std::array<long double, 3> y{};
    for (int i = 0; i < parts; ++i) {
      if (!(mask & (1 << i))) continue;
      for (int d = 0; d < s; ++d)
        y[d] += static_cast<long double>(v[i][d]) * m.root_w[d] * m.unit;
    }
    rel.push_back(y);
  }
  auto dot = [s](const std::array<long double, 3>& x, const std::array<long double, 3>& y) {
    long double r = 0;
    for (int d = 0; d < s; ++d) r += x[d] * y[d];
    return r;
  };
  VoronoiCell out;
  out.shortest_relevant = std::numeric_limits<long double>::infinity();
  for (const auto& y : rel) out.shortest_relevant = std::min(out.shortest_relevant, std::sqrt(dot(y, y)));
  // Vertices: x with ⟨x, y⟩ = ‖y‖²/2 for s of the relevant vectors, inside all the others'
  // half-spaces. Cramer's rule on s×s systems (long double); parallel planes are skipped.
  const std::size_t r = rel.size();
  long double best2 = 0;
  auto feasible = [&](const std::array<long double, 3>& x) {
    for (const auto& y : rel)
      if (dot(x, y) > dot(y, y) / 2 * (1 + 1e-12L)) return false;
    return true;
  };
  if (s == 2) {
    for (std::size_t i = 0; i < r; ++i) {
      for (std::size_t j = i + 1; j < r; ++j) {
        const auto& p = rel[i];
        const auto& q = rel[j];
        const long double det = p[0] * q[1] - p[1] * q[0];
        if (std::fabs(det) <= 1e-12L * std::sqrt(dot(p, p) * dot(q, q))) continue;
        const long double cp = dot(p, p) / 2, cq = dot(q, q) / 2;
        const std::array<long double, 3> x = {(cp * q[1] - cq * p[1]) / det, (p[0] * cq - q[0] * cp) / det, 0};
        if (feasible(x)) best2 = std::max(best2, dot(x, x));
      }
    }
  } else {
    for (std::size_t i = 0; i < r; ++i) {
      for (std::size_t j = i + 1; j < r; ++j) {
        for (std::size_t k = j + 1; k < r; ++k) {
          const auto& p = rel[i];
          const auto& q = rel[j];
          const auto& t = rel[k];
          // x = (c_p (q × t) + c_q (t × p) + c_t (p × q)) / det, det = p · (q × t).
          auto cross = [](const std::array<long double, 3>& x, const std::array<long double, 3>& y) {
            return std::array<long double, 3>{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                                              x[0] * y[1] - x[1] * y[0]};
          };
          const auto qt = cross(q, t), tp = cross(t, p), pq = cross(p, q);
          const long double det = dot(p, qt);
          if (std::fabs(det) <= 1e-12L * std::sqrt(dot(p, p) * dot(q, q) * dot(t, t))) continue;
          const long double cp = dot(p, p) / 2, cq = dot(q, q) / 2, ct = dot(t, t) / 2;
          std::array<long double, 3> x{};
          for (int d = 0; d < 3; ++d)
            x[d] = (cp * qt[d] + cq * tp[d] + ct * pq[d]) / det;
          if (feasible(x)) best2 = std::max(best2, dot(x, x));
        }
      }
    }
  }
  if (!(best2 > 0)) bug("Voronoi cell has no vertex");
  out.covering_radius = std::sqrt(best2);
  return out;
}

std::string join(const std::vector<std::int64_t>& g) {
  std::string out;
  for (std::size_t d = 0; d < g.size(); ++d) out += fmt::format("{}{}", d ? "," : "", g[d]);
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

RankOneLattice RankOneLattice::create(std::int64_t points, std::vector<std::int64_t> generator,
                                      std::vector<double> lengths) {
  validate_points(points);
  validate_dimension(generator.size(), "lattice dimension (generator components)");
  for (std::size_t d = 0; d < generator.size(); ++d) {
    if (generator[d] < 0 || generator[d] >= points)
      refuse(fmt::format("lattice generator component g_{}", d),
             fmt::format("in [0, N) = [0, {})", points), fmt::format("{}", generator[d]));
  }
  std::int64_t common = points;
  for (const std::int64_t gd : generator) common = std::gcd(common, gd);
  if (common != 1)
    refuse(fmt::format("lattice generator ({}) with N = {}", join(generator), points),
           "such that gcd(g_0, …, g_{s−1}, N) = 1 (else the N points repeat)",
           fmt::format("gcd {}", common));
  validate_lengths(lengths, generator.size());

  RankOneLattice out;
  out.points_ = points;
  out.generator_ = std::move(generator);
  out.lengths_ = std::move(lengths);
  const int s = out.dimension();
  const Metric m(out.lengths_);
  Basis b = hermite_dual_basis(points, out.generator_);
  if (s == 2) {
    gauss_reduce(b, m);
  } else {
    lll_reduce<long double>(b, s, m.wl, -1);
  }
  out.basis_ = b;
  fill_table(points, out.generator_, b, m, out.table_);
  return out;
}

std::array<double, 3> RankOneLattice::point(std::int64_t n) const {
  if (n < 0 || n >= points_)
    refuse("lattice point index n", fmt::format("in [0, N) = [0, {})", points_), fmt::format("{}", n));
  std::array<double, 3> x{};
  for (std::size_t d = 0; d < generator_.size(); ++d)
    x[d] = lengths_[d] * (static_cast<double>(mul_mod(n, generator_[d], points_)) / static_cast<double>(points_));
  return x;
}

std::int64_t RankOneLattice::residue(std::span<const std::int64_t> k) const {
  if (k.size() != generator_.size())
    refuse("wave vector for residue()", fmt::format("{} components", generator_.size()),
           fmt::format("{}", k.size()));
  Int128 dot = 0;
  for (std::size_t d = 0; d < k.size(); ++d) dot += Int128{k[d]} * generator_[d];
  return floor_mod(dot, points_);
}

std::int64_t RankOneLattice::residue(std::span<const std::int32_t> k) const {
  if (k.size() != generator_.size())
    refuse("wave vector for residue()", fmt::format("{} components", generator_.size()),
           fmt::format("{}", k.size()));
  std::array<std::int64_t, 3> wide{};
  std::copy(k.begin(), k.end(), wide.begin());
  return residue(std::span<const std::int64_t>(wide.data(), k.size()));
}

std::span<const std::int32_t> RankOneLattice::wave_vector(std::int64_t m) const {
  if (m < 0 || m >= points_)
    refuse("lattice coefficient index m", fmt::format("in [0, N) = [0, {})", points_), fmt::format("{}", m));
  const std::size_t s = generator_.size();
  return std::span<const std::int32_t>(table_).subspan(static_cast<std::size_t>(m) * s, s);
}

std::array<double, 3> RankOneLattice::wave_number(std::int64_t m) const {
  const auto k = wave_vector(m);
  std::array<double, 3> out{};
  for (std::size_t d = 0; d < k.size(); ++d)
    out[d] = static_cast<double>(kTwoPi * k[d] / static_cast<long double>(lengths_[d]));
  return out;
}

bool RankOneLattice::carries_energy(std::int64_t m) const {
  if (m < 0 || m >= points_)
    refuse("lattice coefficient index m", fmt::format("in [0, N) = [0, {})", points_), fmt::format("{}", m));
  return m != 0 && !(points_ % 2 == 0 && m == points_ / 2);
}

std::string RankOneLattice::describe() const {
  std::string box;
  for (std::size_t d = 0; d < lengths_.size(); ++d) box += fmt::format("{}{:g}", d ? "×" : "", lengths_[d]);
  return fmt::format("{} N={} g=({}) over {}{}", family_, points_, join(generator_), box,
                     lengths_.size() == 2 ? " m" : "");
}

double RankOneLattice::patch_norm(std::span<const std::int64_t> k) const {
  if (k.size() != generator_.size())
    refuse("wave vector for patch_norm()", fmt::format("{} components", generator_.size()),
           fmt::format("{}", k.size()));
  long double sum = 0;
  for (std::size_t d = 0; d < k.size(); ++d) {
    const long double x = kTwoPi * static_cast<long double>(k[d]) / static_cast<long double>(lengths_[d]);
    sum += x * x;
  }
  return static_cast<double>(std::sqrt(sum));
}

// ---------------------------------------------------------------------------------------------

std::int64_t fibonacci_number(int j) {
  if (j < 1 || j > 92)
    refuse("Fibonacci index j", "in [1, 92] (F_93 exceeds 2^63)", fmt::format("{}", j));
  std::int64_t previous = 0, current = 1;  // F_0, F_1
  for (int i = 1; i < j; ++i) previous = std::exchange(current, current + previous);
  return current;
}

RankOneLattice fibonacci_lattice(int j, double lx, double ly) {
  if (j < 3 || j > 92)
    refuse("Fibonacci lattice index j", "in [3, 92] (F_3 = 2 points; F_93 exceeds 2^63)", fmt::format("{}", j));
  RankOneLattice out =
      RankOneLattice::create(fibonacci_number(j), {1, fibonacci_number(j - 1)}, {lx, ly});
  out.family_ = "fibonacci";
  return out;
}

int fibonacci_index(std::int64_t points) {
  std::int64_t below = 0, above = 0;
  int below_j = 0;
  for (int j = 3; j <= 92; ++j) {
    const std::int64_t f = fibonacci_number(j);
    if (f == points) return j;
    if (f < points) {
      below = f;
      below_j = j;
    } else {
      above = f;
      break;
    }
  }
  std::string nearest;
  if (below_j == 0) {
    nearest = fmt::format("the smallest is F_3 = 2");
  } else if (above == 0) {
    nearest = fmt::format("the largest in int64 is F_92 = {}", below);
  } else {
    nearest = fmt::format("the nearest are F_{} = {} and F_{} = {}", below_j, below, below_j + 1, above);
  }
  refuse("lattice points", "a Fibonacci number F_j, j ≥ 3", fmt::format("{}; {}", points, nearest));
}

RankOneLattice korobov_lattice(std::int64_t points, std::int64_t a, std::vector<double> lengths) {
  validate_points(points);
  validate_dimension(lengths.size(), "Korobov lattice dimension (number of lengths)");
  if (a < 1 || a >= points)
    refuse("Korobov multiplier a", fmt::format("in [1, N) = [1, {})", points), fmt::format("{}", a));
  std::vector<std::int64_t> g = {1, a};
  if (lengths.size() == 3) g.push_back(mul_mod(a, a, points));
  RankOneLattice out = RankOneLattice::create(points, std::move(g), std::move(lengths));
  out.family_ = "korobov";
  return out;
}

std::int64_t korobov_spectral_choice(std::int64_t points, int dimension, std::vector<double> lengths) {
  validate_points(points);
  validate_dimension(static_cast<std::size_t>(std::max(dimension, 0)), "Korobov lattice dimension");
  validate_lengths(lengths, static_cast<std::size_t>(dimension));
  const Metric m(lengths);
  const bool inverse_is_isometry =
      dimension == 2 ? lengths[0] == lengths[1] : lengths[0] == lengths[2];
  double best_q = -1;
  std::int64_t best_a = 0;
  for (std::int64_t a = 1; a <= points / 2; ++a) {
    if (std::gcd(a, points) != 1) continue;
    if (inverse_is_isometry) {
      const std::int64_t inv = inverse_mod(a, points);
      if (std::min(inv, points - inv) < a) continue;  // its orbit's smallest member came first
    }
    const double reject_below = best_q < 0 ? -1 : best_q * (1 - kSearchTie);
    const double q = dimension == 2 ? korobov_lambda1_sq_2d(points, a, m.w, reject_below)
                                    : korobov_lambda1_sq_3d(points, a, m.w, reject_below);
    if (q > best_q * (1 + kSearchTie) || best_q < 0) {
      best_q = q;
      best_a = a;
    }
  }
  if (best_a == 0) bug("no admissible Korobov multiplier");
  return best_a;
}

RankOneLattice korobov_lattice(std::int64_t points, std::vector<double> lengths) {
  validate_dimension(lengths.size(), "Korobov lattice dimension (number of lengths)");
  const std::int64_t a = korobov_spectral_choice(points, static_cast<int>(lengths.size()), lengths);
  return korobov_lattice(points, a, std::move(lengths));
}

// ---------------------------------------------------------------------------------------------

double rank_one_p2(std::int64_t points, std::span<const std::int64_t> generator) {
  if (points < 2) refuse("lattice points N for P2", "at least 2", fmt::format("{}", points));
  if (generator.empty() || generator.size() > 3)
    refuse("generator for P2", "1 to 3 components", fmt::format("{}", generator.size()));
  for (std::size_t d = 0; d < generator.size(); ++d) {
    if (generator[d] < 0 || generator[d] >= points)
      refuse(fmt::format("generator component g_{} for P2", d), fmt::format("in [0, N) = [0, {})", points),
             fmt::format("{}", generator[d]));
  }
  // Π_d (1 + 2π² B₂(r_d/N)) − 1 summed in long double with Neumaier's compensation: the terms
  // are O(1) and cancel to N·P₂ (1e-4 at N = 2^22), so a plain double sum would lose the
  // answer's leading digits and even a plain long-double one some of its last.
  const long double two_pi2 = 2 * std::numbers::pi_v<long double> * std::numbers::pi_v<long double>;
  const auto nl = static_cast<long double>(points);
  std::int64_t r[3] = {0, 0, 0};
  long double sum = 0, compensation = 0;
  for (std::int64_t n = 0; n < points; ++n) {
    long double prod = 1;
    for (std::size_t d = 0; d < generator.size(); ++d) {
      const long double x = static_cast<long double>(r[d]) / nl;
      prod *= 1 + two_pi2 * (x * x - x + 1.0L / 6);
      r[d] += generator[d];
      if (r[d] >= points) r[d] -= points;
    }
    const long double term = prod - 1;
    const long double next = sum + term;
    compensation += std::fabs(sum) >= std::fabs(term) ? (sum - next) + term : (term - next) + sum;
    sum = next;
  }
  return static_cast<double>((sum + compensation) / nl);
}

LatticeMerits lattice_merits(const RankOneLattice& lattice) {
  const int s = lattice.dimension();
  const Metric m(lattice.lengths());
  const Basis& b = lattice.dual_basis();
  const std::int64_t n = lattice.points();
  const auto& g = lattice.generator();
  LatticeMerits out;

  // Spectral test: every shortest vector by exact enumeration, then the canonical one.
  std::vector<Vec> ties = shortest_vectors(b, s, m);
  for (Vec& v : ties) {
    const auto first = std::find_if(v.begin(), v.begin() + s, [](std::int64_t x) { return x != 0; });
    if (*first < 0)
      for (int d = 0; d < s; ++d) v[d] = -v[d];
  }
  const Vec h = *std::min_element(ties.begin(), ties.end(), [s](const Vec& x, const Vec& y) {
    return std::lexicographical_compare(x.begin(), x.begin() + s, y.begin(), y.begin() + s);
  });
  out.shortest_dual_vector.assign(h.begin(), h.begin() + s);
  out.lambda1 = static_cast<double>(m.norm(h.data()));

  // Zaremba ρ, exactly: enumerate the prefixes (h_0, …, h_{s−2}) with Π max(1, |h_d|) below
  // the best ρ so far (first nonzero positive: ±h have the same ρ) and solve for the last
  // coordinate: h_{s−1} g_{s−1} ≡ −c (mod N) has solutions iff G = gcd(g_{s−1}, N) divides c,
  // and then they are one class mod N/G, whose smallest |h_{s−1}| is taken. Cost O(ρ) prefixes
  // in 2-D, O(ρ log ρ) in 3-D (ρ ≤ N): 30 ms for the Korobov lattice of 2^22 points.
  const std::int64_t gl = g[s - 1];
  const std::int64_t big_g = std::gcd(gl, n);
  const std::int64_t mod_m = n / big_g;
  const std::int64_t inv = mod_m == 1 ? 0 : inverse_mod(gl / big_g, mod_m);
  auto rho_of = [](std::int64_t prefix_product, std::int64_t last) {
    return prefix_product * std::max<std::int64_t>(1, last < 0 ? -last : last);
  };
  // Start from N (h = N e_0 is dual) and the reduced basis vectors (products in 128 bits: a
  // basis vector of an extreme patch can have components near 2^51).
  std::int64_t best = n;
  for (int i = 0; i < s; ++i) {
    Int128 rho = 1;
    for (int d = 0; d < s; ++d) rho *= std::max<std::int64_t>(1, std::abs(b[i][d]));
    if (rho < best) best = static_cast<std::int64_t>(rho);
  }
  auto try_prefix = [&](std::int64_t c_mod_n, std::int64_t prefix_product, bool prefix_zero) {
    if (c_mod_n % big_g != 0) return;
    std::int64_t last = mul_mod(floor_mod(-c_mod_n / big_g, mod_m), inv, mod_m);  // in [0, M)
    if (prefix_zero) {
      best = std::min(best, mod_m);  // h = (0, …, 0, ±M)
      return;
    }
    const std::int64_t alt = last - mod_m;
    best = std::min({best, rho_of(prefix_product, last), rho_of(prefix_product, alt)});
  };
  if (s == 2) {
    for (std::int64_t h0 = 0; h0 < best; ++h0)
      try_prefix(mul_mod(h0, g[0], n), std::max<std::int64_t>(1, h0), h0 == 0);
  } else {
    for (std::int64_t h0 = 0; h0 < best; ++h0) {
      const std::int64_t p0 = std::max<std::int64_t>(1, h0);
      const std::int64_t c0 = mul_mod(h0, g[0], n);
      const std::int64_t reach = (best - 1) / p0;  // |h_1| ≤ reach keeps p0·max(1,|h1|) < best
      for (std::int64_t h1 = h0 == 0 ? 0 : -reach; h1 <= reach; ++h1) {
        const std::int64_t product = p0 * std::max<std::int64_t>(1, std::abs(h1));
        if (product >= best) continue;  // best may have dropped since reach was set
        const std::int64_t c = floor_mod(Int128{c0} + Int128{h1} * g[1], n);
        try_prefix(c, product, h0 == 0 && h1 == 0);
      }
    }
  }
  out.zaremba_rho = static_cast<double>(best);
  out.p2 = rank_one_p2(n, g);
  return out;
}

LatticeBand lattice_band(const RankOneLattice& lattice) {
  const int s = lattice.dimension();
  const Metric m(lattice.lengths());
  const std::vector<Vec> shortest = shortest_vectors(lattice.dual_basis(), s, m);
  const long double lambda1 = m.norm(shortest.front().data());
  const VoronoiCell cell = voronoi_cell(lattice.dual_basis(), s, m);
  // The shortest vector is always a strict Voronoi-relevant vector, so the superbase's partial
  // sums must contain it: two independent routes to λ₁ that have to agree.
  if (std::fabs(cell.shortest_relevant - lambda1) > 1e-12L * lambda1)
    bug(fmt::format("Voronoi vectors miss the shortest vector ({} vs {} rad/m)",
                    static_cast<double>(cell.shortest_relevant), static_cast<double>(lambda1)));
  LatticeBand out;
  out.inscribed_radius = static_cast<double>(lambda1 / 2);
  out.covering_radius = static_cast<double>(cell.covering_radius);
  long double cell_volume = static_cast<long double>(lattice.points());
  for (const double l : lattice.lengths()) cell_volume *= kTwoPi / static_cast<long double>(l);
  const long double r = lambda1 / 2;
  const long double pi = std::numbers::pi_v<long double>;
  const long double ball = s == 2 ? pi * r * r : 4 * pi * r * r * r / 3;
  out.alias_free_fraction = static_cast<double>(ball / cell_volume);
  return out;
}

}  // namespace swell::reference
