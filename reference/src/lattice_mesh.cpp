#include "swell/reference/lattice_mesh.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>

#include "integer_arithmetic.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/huge_pages.hpp"

namespace swell::reference {
namespace {

constexpr std::int64_t kMaxPoints = std::int64_t{1} << 31;
// See delaunay_superbase: a Delaunay edge (a, c) with |a| ≤ N beats its rival (a ∓ 2N, c) by
// 4/(N (1 + (ly/lx)²)) of its squared length. With N ≤ 2^31 and an aspect ratio up to 1e4 that
// is ≥ 2e-17, some 200 times the long double rounding of a squared length (2 ulps of 5.4e-20).
constexpr double kMaxAspect = 1e4;
static_assert(std::numeric_limits<long double>::digits >= 64,
              "the reduction's metric needs at least the x87 extended precision");

using integer::floor_mod;

// (a·b) mod n for a, b in [0, n), n ≤ 2^31: the product is below 2^62.
std::int64_t mul_mod(std::int64_t a, std::int64_t b, std::int64_t n) { return (a * b) % n; }

// The reduction works on lattice vectors with their index offsets; integer coordinates are
// combined with overflow checks. They cannot overflow for valid input (the vectors of Gauss's
// algorithm never grow beyond the longer start vector, |a| ≲ N·(1 + ly/lx) < 2^46), so an
// overflow is a bug.
SuperbaseVector combine(const SuperbaseVector& v, std::int64_t q, const SuperbaseVector& w,
                        std::int64_t n) {
  SuperbaseVector r;
  std::int64_t qa = 0, qc = 0;
  if (__builtin_mul_overflow(q, w.a, &qa) || __builtin_mul_overflow(q, w.c, &qc) ||
      __builtin_sub_overflow(v.a, qa, &r.a) || __builtin_sub_overflow(v.c, qc, &r.c)) {
    throw InternalError("periodic_delaunay: lattice reduction overflowed 64-bit integers");
  }
  r.offset = floor_mod(v.offset - mul_mod(floor_mod(q, n), w.offset, n), n);
  return r;
}

SuperbaseVector negated(const SuperbaseVector& v, std::int64_t n) {
  return {-v.a, -v.c, v.offset == 0 ? 0 : n - v.offset};
}

// Reserves room for `count` elements and, for a large output, asks Linux for transparent huge
// pages. The triangles take 60 bytes per point (250 MB for 4M points), and writing them is cheap
// (~25 ms for 4M points) next to first touching fresh 4 KiB pages: on a virtual machine each
// such fault can cost ~15 µs (measured on a Firecracker VM: 250 MB touched in 0.96 s with
// 4 KiB pages, 0.02 s with 2 MiB pages). Only advice: where THP is off it changes nothing.
template <class T>
void reserve_large(std::vector<T>& v, std::size_t count) {
  v.reserve(count);
  advise_huge_pages(v.data(), count * sizeof(T));
}

void validate(std::int64_t points, std::int64_t g0, std::int64_t g1, double lx, double ly) {
  require(points >= 3 && points <= kMaxPoints, "lattice points", "in [3, 2^31]",
          static_cast<double>(points));
  require(std::isfinite(lx) && lx > 0, "patch length lx", "finite and positive (metres)", lx);
  require(std::isfinite(ly) && ly > 0, "patch length ly", "finite and positive (metres)", ly);
  require(lx / ly <= kMaxAspect && ly / lx <= kMaxAspect, "patch aspect ratio lx/ly",
          "within [1e-4, 1e4]", lx / ly);
  const std::int64_t r0 = floor_mod(g0, points), r1 = floor_mod(g1, points);
  const std::int64_t common = std::gcd(std::gcd(r0, r1), points);
  if (common != 1) {
    // n = N/common repeats point 0, so the N points are not distinct.
    throw InvalidInput(fmt::format(
        "lattice generator (g0, g1) = ({}, {}) must have gcd(g0, g1, points) = 1 so that the {} "
        "points are distinct (got gcd {}: point {} equals point 0)",
        g0, g1, points, common, points / common));
  }
}

}  // namespace

DelaunaySuperbase delaunay_superbase(std::int64_t points, std::int64_t g0, std::int64_t g1,
                                     double lx, double ly) {
  validate(points, g0, g1, lx, ly);
  const std::int64_t n = points;
  g0 = floor_mod(g0, n);
  g1 = floor_mod(g1, n);

  // A basis of Λ = ℤ·g + Nℤ² with its offsets (Hermite normal form). With e = gcd(g0, N) =
  // s·g0 + t·N: s·g ≡ (e, s·g1) (mod N), so v1 = (e, s·g1 mod N) with offset s. Every vector
  // with a = 0 is m·g with m a multiple of N/e, m = (N/e)·k: m·g1 ≡ (N/e)·k·g1, and as
  // gcd(g1, e) = gcd(g0, g1, N) = 1, k = g1⁻¹ mod e gives v2 = (0, N/e). det(v1, v2) = N.
  const integer::Bezout b0 = integer::extended_gcd(g0, n);
  const std::int64_t e = b0.gcd;
  const std::int64_t s = floor_mod(b0.x, n);
  SuperbaseVector v1{e, mul_mod(s, g1, n), s};
  const std::int64_t k = e == 1 ? 0 : floor_mod(integer::extended_gcd(g1 % e, e).x, e);
  SuperbaseVector v2{0, n / e, (n / e) * k};  // (N/e)·k < N

  // Lagrange–Gauss reduction in the metric of the patch: |(a, c)|² ∝ lx² a² + ly² c² (the 1/N²
  // dropped). Integer coordinates stay exact; only the comparisons use long double.
  const long double wx = static_cast<long double>(lx) * lx, wy = static_cast<long double>(ly) * ly;
  const auto dot = [&](const SuperbaseVector& u, const SuperbaseVector& v) {
    return wx * static_cast<long double>(u.a) * static_cast<long double>(v.a) +
           wy * static_cast<long double>(u.c) * static_cast<long double>(v.c);
  };
  long double n1 = dot(v1, v1), n2 = dot(v2, v2);
  // Each step shortens v2 strictly, so this ends; Gauss's algorithm needs O(log N) steps.
  for (int step = 0;; ++step) {
    if (step > 10000) throw InternalError("periodic_delaunay: lattice reduction did not end");
    if (n2 < n1) {
      std::swap(v1, v2);
      std::swap(n1, n2);
    }
    const long double d = dot(v1, v2);
    // Reduced when |⟨v1, v2⟩| ≤ |v1|²/2 (with ≤, not <: at exactly 1/2 subtracting v1 gives
    // an equally long vector, and the next step would add it back).
    if (2 * std::fabs(d) <= n1) break;
    const long double q = std::round(d / n1);
    if (!(std::fabs(q) < 0x1p62L)) throw InternalError("periodic_delaunay: reduction overflow");
    const SuperbaseVector candidate = combine(v2, static_cast<std::int64_t>(q), v1, n);
    const long double nc = dot(candidate, candidate);
    // A tie that rounding mistook for progress: the basis is as reduced as long double can see.
    if (!(nc < n2)) break;
    v2 = candidate;
    n2 = nc;
  }

  // The obtuse superbase (Selling): with ⟨v1, v2⟩ ≤ 0 (flip v2 if needed) and v3 = −(v1 + v2),
  // ⟨v1, v3⟩ = −|v1|² − ⟨v1, v2⟩ ≤ −|v1|²/2 and ⟨v2, v3⟩ = −|v2|² − ⟨v1, v2⟩ ≤ −|v2|²/2: every
  // pair is at ≥ 90°. ⟨v1, v2⟩ = 0 is a rectangular cell and ⟨v1, v2⟩ = −|v1|²/2 makes v1 ⊥ v3:
  // both are four points on one circle, and both diagonals are Delaunay; this takes v1 + v2.
  if (dot(v1, v2) > 0) v2 = negated(v2, n);
  // Counter-clockwise: det(v1, v2) = a1 c2 − c1 a2 = ±N, the same sign as the physical cross
  // product (lx·ly/N² > 0 times it). Swapping keeps the superbase obtuse.
  const long double det = static_cast<long double>(v1.a) * static_cast<long double>(v2.c) -
                          static_cast<long double>(v1.c) * static_cast<long double>(v2.a);
  if (det < 0) std::swap(v1, v2);
  DelaunaySuperbase base;
  base.e[0] = v1;
  base.e[1] = v2;
  base.e[2] = negated(combine(v1, -1, v2, n), n);  // −(v1 + v2)

  // Postconditions. Every Delaunay edge v is no longer than any other vector of v + 2Λ (the
  // midpoint v/2 lies on the Voronoi facet between 0 and v, so |v/2 − w| ≥ |v|/2 for all
  // w ∈ Λ), and (±N, 0), (0, ±N) ∈ Λ: hence |a| ≤ N and |c| ≤ N, which keeps every corner of
  // a triangle within one period of its first corner (periods in {−1, 0, 1}).
  for (const SuperbaseVector& v : base.e) {
    if (std::abs(v.a) > n || std::abs(v.c) > n || mul_mod(v.offset, g0, n) != floor_mod(v.a, n) ||
        mul_mod(v.offset, g1, n) != floor_mod(v.c, n)) {
      throw InternalError(fmt::format(
          "periodic_delaunay: superbase vector ({}, {}) offset {} is not a Delaunay edge of the "
          "lattice N = {}, g = ({}, {}), {} × {} m",
          v.a, v.c, v.offset, n, g0, g1, lx, ly));
    }
  }
  std::int64_t ac = 0, ca = 0, det_exact = 0;
  if (__builtin_mul_overflow(base.e[0].a, base.e[1].c, &ac) ||
      __builtin_mul_overflow(base.e[0].c, base.e[1].a, &ca) ||
      __builtin_sub_overflow(ac, ca, &det_exact) || det_exact != n) {
    throw InternalError("periodic_delaunay: reduced basis does not span the lattice");
  }
  return base;
}

std::array<double, 2> LatticeMesh::position(std::int64_t n) const {
  return {lx * static_cast<double>(mul_mod(n, g0, points)) / static_cast<double>(points),
          ly * static_cast<double>(mul_mod(n, g1, points)) / static_cast<double>(points)};
}

std::array<double, 2> LatticeMesh::corner_position(std::size_t t, int corner) const {
  const auto [x, y] = position(triangles[t][corner]);
  return {x + corner_periods[t][corner][0] * lx, y + corner_periods[t][corner][1] * ly};
}

LatticeMesh periodic_delaunay(std::int64_t points, std::int64_t g0, std::int64_t g1, double lx,
                              double ly) {
  LatticeMesh mesh;
  mesh.superbase = delaunay_superbase(points, g0, g1, lx, ly);
  const std::int64_t n = points;
  mesh.points = n;
  mesh.g0 = floor_mod(g0, n);
  mesh.g1 = floor_mod(g1, n);
  mesh.lx = lx;
  mesh.ly = ly;

  // The corners' offsets from the triangle's first point: e1, e1 + e2 = −e3, e2.
  const SuperbaseVector& e1 = mesh.superbase.e[0];
  const SuperbaseVector& e2 = mesh.superbase.e[1];
  const SuperbaseVector e12 = negated(mesh.superbase.e[2], n);
  reserve_large(mesh.triangles, static_cast<std::size_t>(2 * n));
  reserve_large(mesh.corner_periods, static_cast<std::size_t>(2 * n));

  // Point n sits at the residues (r0, r1) ∈ [0, N)²; a corner at offset (a, c) sits at
  // (r0 + a, r1 + c), which |a|, |c| ≤ N keeps in [−N, 2N): its period is −1, 0 or 1, and its
  // point index is n + δ mod N. Residues and indices advance by one addition per point.
  const auto period = [n](std::int64_t u) -> std::int8_t { return u < 0 ? -1 : (u >= n ? 1 : 0); };
  const auto add = [n](std::int64_t i, std::int64_t d) { return i + d >= n ? i + d - n : i + d; };
  std::int64_t r0 = 0, r1 = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t i1 = add(i, e1.offset), i12 = add(i, e12.offset), i2 = add(i, e2.offset);
    const std::array<std::int8_t, 2> p1{period(r0 + e1.a), period(r1 + e1.c)};
    const std::array<std::int8_t, 2> p12{period(r0 + e12.a), period(r1 + e12.c)};
    const std::array<std::int8_t, 2> p2{period(r0 + e2.a), period(r1 + e2.c)};
    mesh.triangles.push_back({i, i1, i12});  // triangle 2i
    mesh.corner_periods.push_back({{{0, 0}, p1, p12}});
    mesh.triangles.push_back({i, i12, i2});  // triangle 2i + 1
    mesh.corner_periods.push_back({{{0, 0}, p12, p2}});
    r0 = add(r0, mesh.g0);
    r1 = add(r1, mesh.g1);
  }
  return mesh;
}

}  // namespace swell::reference
