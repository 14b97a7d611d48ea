// Exact integer arithmetic, the patch metric's comparisons, and the reduction of lattice bases
// (lattice_internal.hpp).
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
#include "lattice/lattice_internal.hpp"
#include "swell/reference/errors.hpp"

namespace swell::reference {
namespace lattice_detail {

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

}  // namespace lattice_detail

}  // namespace swell::reference
