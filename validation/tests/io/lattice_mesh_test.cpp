// The periodic Delaunay triangulation of 2-D rank-1 lattices (reference/lattice_mesh.hpp) and
// the tileable mesh files (validation/mesh_io.hpp).
//
// Each property is checked by code that does not share the implementation's reasoning: edges
// and areas in exact integer coordinates of the unwrapped corners, empty circumcircles against
// every lattice point and periodic image near the circle, the edge set against a brute-force
// search for empty circles, and the files through small readers written here. The lattices:
// Fibonacci (g = (1, F_{j−1}), N = F_j), Korobov (g = (1, a), N = 2^k), and degenerate ones
// (a square, a rectangular grid, points on one line), each on a square patch and on two
// oblong ones.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "swell/reference/errors.hpp"
#include "swell/reference/lattice_mesh.hpp"
#include "swell/validation/io/mesh_io.hpp"

namespace {

namespace fs = std::filesystem;
using swell::InvalidInput;
using swell::reference::LatticeMesh;
using swell::reference::periodic_delaunay;
using swell::validation::MeshSurface;

struct Lattice {
  std::int64_t n, g0, g1;
};
struct Patch {
  double lx, ly;
};

// Fibonacci lattices (some of them rotated squares: four points on one circle), Korobov
// lattices with N a power of two, and degenerate ones: N = 5, g = (1, 2) is a square lattice;
// N = 12, g = (4, 3) the 3 × 4 grid (a rectangle on any patch); g = (0, 1) puts the points on
// the line x = 0, so that the period (lx, 0) is a Delaunay edge and triangles name a point
// twice; N = 3 is the smallest lattice.
const std::vector<Lattice> kLattices = {
    {13, 1, 8},      {21, 1, 13},   {34, 1, 21},   {55, 1, 34},   {89, 1, 55}, {144, 1, 89},
    {233, 1, 144},   {377, 1, 233}, {610, 1, 377}, {987, 1, 610}, {64, 1, 19}, {1024, 1, 309},
    {4096, 1, 1159}, {5, 1, 2},     {12, 4, 3},    {7, 0, 1},     {3, 1, 1},   {100, 7, 30}};
const std::vector<Patch> kPatches = {{1.0, 1.0}, {200.0, 100.0}, {1.0, 3.0}};

std::string name(const Lattice& l, const Patch& p) {
  std::ostringstream s;
  s << "N = " << l.n << ", g = (" << l.g0 << ", " << l.g1 << "), patch " << p.lx << " x " << p.ly;
  return s.str();
}

std::int64_t floor_mod(std::int64_t a, std::int64_t n) { return ((a % n) + n) % n; }

// Integer coordinates of the lattice: point n at ((n·g0) mod N, (n·g1) mod N); a corner
// shifted by periods (px, py) at that plus (px·N, py·N). Physical = (lx·U/N, ly·V/N).
std::array<std::int64_t, 2> residues(const Lattice& l, std::int64_t n) {
  return {floor_mod(n * l.g0, l.n), floor_mod(n * l.g1, l.n)};
}
std::array<std::int64_t, 2> corner_integer(const Lattice& l, const LatticeMesh& mesh, std::size_t t,
                                           int k) {
  const auto r = residues(l, mesh.triangles[t][k]);
  return {r[0] + mesh.corner_periods[t][k][0] * l.n, r[1] + mesh.corner_periods[t][k][1] * l.n};
}

// A directed edge: its start point and its integer vector (unwrapped end − start); the same
// edge from its end is (end point, −vector). Keyed this way, an edge between a point and its
// own periodic image (the line lattice) or two edges between one pair of points (N = 3) stay
// apart.
using HalfEdge = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
HalfEdge reversed(const HalfEdge& e, std::int64_t end) {
  return {end, -std::get<1>(e), -std::get<2>(e)};
}

// Every half-edge of the mesh, with how often it occurs, and the end point of each.
struct Edges {
  std::map<HalfEdge, int> count;
  std::map<HalfEdge, std::int64_t> end;
};
Edges half_edges(const Lattice& l, const LatticeMesh& mesh) {
  Edges edges;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto u = corner_integer(l, mesh, t, k), v = corner_integer(l, mesh, t, (k + 1) % 3);
      const HalfEdge e{mesh.triangles[t][k], v[0] - u[0], v[1] - u[1]};
      ++edges.count[e];
      edges.end[e] = mesh.triangles[t][(k + 1) % 3];
    }
  }
  return edges;
}

TEST(LatticeMesh, HasTwoTrianglesPerPointWithCornersWithinOnePeriod) {
  for (const Lattice& l : kLattices) {
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const LatticeMesh mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
      ASSERT_EQ(mesh.points, l.n);
      ASSERT_EQ(mesh.triangles.size(), static_cast<std::size_t>(2 * l.n));
      ASSERT_EQ(mesh.corner_periods.size(), mesh.triangles.size());
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        // Triangles 2n and 2n+1 are point n's, which is their corner 0, unshifted.
        ASSERT_EQ(mesh.triangles[t][0], static_cast<std::int64_t>(t / 2));
        ASSERT_EQ(mesh.corner_periods[t][0][0], 0);
        ASSERT_EQ(mesh.corner_periods[t][0][1], 0);
        for (int k = 0; k < 3; ++k) {
          ASSERT_GE(mesh.triangles[t][k], 0);
          ASSERT_LT(mesh.triangles[t][k], l.n);
          for (const int period : mesh.corner_periods[t][k]) {
            ASSERT_TRUE(period >= -1 && period <= 1) << "triangle " << t << " corner " << k;
          }
        }
      }
      // position() is the lattice formula, and corner_position() the unwrapped corner.
      for (std::int64_t n = 0; n < l.n; n += 1 + l.n / 50) {
        const auto r = residues(l, n);
        const auto x = mesh.position(n);
        EXPECT_NEAR(x[0], p.lx * static_cast<double>(r[0]) / l.n, 1e-15 * p.lx);
        EXPECT_NEAR(x[1], p.ly * static_cast<double>(r[1]) / l.n, 1e-15 * p.ly);
      }
      for (std::size_t t = 0; t < mesh.triangles.size(); t += 1 + mesh.triangles.size() / 50) {
        for (int k = 0; k < 3; ++k) {
          const auto u = corner_integer(l, mesh, t, k);
          const auto x = mesh.corner_position(t, k);
          EXPECT_NEAR(x[0], p.lx * static_cast<double>(u[0]) / l.n, 1e-15 * 3 * p.lx);
          EXPECT_NEAR(x[1], p.ly * static_cast<double>(u[1]) / l.n, 1e-15 * 3 * p.ly);
        }
      }
    }
  }
}

// V − E + F = 0 on the torus, with E = 3N distinct undirected edges and every point of
// degree 6 (an edge from a point to its own image counts twice, as a loop does).
TEST(LatticeMesh, IsATorusWithDegreeSix) {
  for (const Lattice& l : kLattices) {
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const LatticeMesh mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
      const Edges edges = half_edges(l, mesh);
      std::set<HalfEdge> undirected;
      std::vector<int> degree(static_cast<std::size_t>(l.n), 0);
      for (const auto& [e, count] : edges.count) {
        const HalfEdge r = reversed(e, edges.end.at(e));
        if (undirected.insert(std::min(e, r)).second) {
          ++degree[static_cast<std::size_t>(std::get<0>(e))];
          ++degree[static_cast<std::size_t>(std::get<0>(r))];
        }
      }
      const auto v = l.n, e = static_cast<std::int64_t>(undirected.size());
      const auto f = static_cast<std::int64_t>(mesh.triangles.size());
      EXPECT_EQ(e, 3 * l.n);
      EXPECT_EQ(v - e + f, 0);
      for (std::size_t n = 0; n < degree.size(); ++n) ASSERT_EQ(degree[n], 6) << "point " << n;
    }
  }
}

TEST(LatticeMesh, EveryEdgeHasTwoTrianglesOfOppositeOrientation) {
  for (const Lattice& l : kLattices) {
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const LatticeMesh mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
      const Edges edges = half_edges(l, mesh);
      ASSERT_EQ(edges.count.size(), 3 * mesh.triangles.size());  // no half-edge twice
      for (const auto& [e, count] : edges.count) {
        const auto twin = edges.count.find(reversed(e, edges.end.at(e)));
        ASSERT_TRUE(twin != edges.count.end())
            << "edge from " << std::get<0>(e) << " by (" << std::get<1>(e) << ", " << std::get<2>(e)
            << ") has one triangle";
        ASSERT_EQ(twin->second, 1);
      }
    }
  }
}

// Areas in integer coordinates are exact: each triangle's doubled area is a positive integer
// (counter-clockwise), and they sum to 2N² (the patch, lx·ly = (lx/N)(ly/N)·N²). The physical
// areas from corner_position agree to rounding.
TEST(LatticeMesh, TrianglesAreCounterClockwiseAndCoverThePatchOnce) {
  for (const Lattice& l : kLattices) {
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const LatticeMesh mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
      std::int64_t doubled = 0;
      double area = 0;
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto a = corner_integer(l, mesh, t, 0), b = corner_integer(l, mesh, t, 1),
                   c = corner_integer(l, mesh, t, 2);
        const std::int64_t cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        ASSERT_GT(cross, 0) << "triangle " << t;
        doubled += cross;
        const auto x = mesh.corner_position(t, 0), y = mesh.corner_position(t, 1),
                   z = mesh.corner_position(t, 2);
        area += 0.5 * ((y[0] - x[0]) * (z[1] - x[1]) - (y[1] - x[1]) * (z[0] - x[0]));
      }
      EXPECT_EQ(doubled, 2 * l.n * l.n);
      EXPECT_NEAR(area, p.lx * p.ly, 1e-12 * p.lx * p.ly);
    }
  }
}

// No lattice point, periodic images included, lies strictly inside a triangle's circumcircle.
// Non-strict with a relative tolerance of 1e-9 on the squared radius: cocircular points (a
// rotated square, a rectangular grid) sit on the circle up to rounding of coordinates ≤ 3L,
// about 1e-16·(3L/R)² ≤ 1e-11 relative for these lattices, while a point of a lattice that is
// inside is so by at least ~1e-4 of R² (powers of lattice points are rationals with small
// denominators here). All points near the circle are found through a periodic bucket grid.
TEST(LatticeMesh, CircumcirclesAreEmpty) {
  constexpr double kTolerance = 1e-9;
  for (const Lattice& l : kLattices) {
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const LatticeMesh mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
      const auto g0 = std::max<std::int64_t>(1, std::llround(std::sqrt(l.n * p.lx / p.ly)));
      const auto g1 = std::max<std::int64_t>(1, l.n / g0);
      const double w0 = p.lx / g0, w1 = p.ly / g1;
      std::vector<std::vector<std::int64_t>> cells(static_cast<std::size_t>(g0 * g1));
      std::vector<std::array<double, 2>> x(static_cast<std::size_t>(l.n));
      for (std::int64_t n = 0; n < l.n; ++n) {
        const auto r = residues(l, n);
        x[n] = {p.lx * r[0] / l.n, p.ly * r[1] / l.n};
        const auto i = std::min(g0 - 1, static_cast<std::int64_t>(x[n][0] / w0));
        const auto j = std::min(g1 - 1, static_cast<std::int64_t>(x[n][1] / w1));
        cells[j * g0 + i].push_back(n);
      }
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        std::array<std::array<double, 2>, 3> c;
        for (int k = 0; k < 3; ++k) {
          const auto u = corner_integer(l, mesh, t, k);
          c[k] = {p.lx * u[0] / l.n, p.ly * u[1] / l.n};
        }
        // Circumcentre relative to corner 0.
        const double bx = c[1][0] - c[0][0], by = c[1][1] - c[0][1];
        const double cx = c[2][0] - c[0][0], cy = c[2][1] - c[0][1];
        const double d = 2 * (bx * cy - by * cx);
        const double ux = (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) / d;
        const double uy = (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) / d;
        const double r2 = ux * ux + uy * uy, r = std::sqrt(r2);
        const double ox = c[0][0] + ux, oy = c[0][1] + uy;
        for (auto i = static_cast<std::int64_t>(std::floor((ox - r) / w0));
             i <= static_cast<std::int64_t>(std::floor((ox + r) / w0)); ++i) {
          for (auto j = static_cast<std::int64_t>(std::floor((oy - r) / w1));
               j <= static_cast<std::int64_t>(std::floor((oy + r) / w1)); ++j) {
            const double sx = static_cast<double>((i - floor_mod(i, g0)) / g0) * p.lx;
            const double sy = static_cast<double>((j - floor_mod(j, g1)) / g1) * p.ly;
            for (const std::int64_t m : cells[floor_mod(j, g1) * g0 + floor_mod(i, g0)]) {
              const double ex = x[m][0] + sx - ox, ey = x[m][1] + sy - oy;
              ASSERT_GE(ex * ex + ey * ey, r2 * (1 - kTolerance))
                  << "point " << m << " shifted by (" << sx << ", " << sy
                  << ") is inside the circumcircle of triangle " << t;
            }
          }
        }
      }
    }
  }
}

// The Delaunay edges from point 0, by brute force over periodic images: the edge to q is
// Delaunay iff some circle through 0 and q has no point strictly inside. The circles through 0
// and q have centres q/2 + s·q⊥; point r is inside when |r|² − r·q − 2s r·q⊥ < 0, linear in s,
// so the circle exists iff an interval of s survives every point. An empty circle has radius
// at most the lattice's covering radius, which is at most that of the periods, D/2 with
// D = √(lx² + ly²): only such circles are tried, and then only points within D matter.
// `margin` > 0 asks for a circle empty by that much (an edge every Delaunay triangulation
// has), < 0 allows points on the circle up to |margin| (an edge some triangulation has).
// A lattice looks the same from every point, so point 0's edges give every point's.
std::set<std::array<std::int64_t, 2>> brute_force_delaunay(const Lattice& l, const Patch& p,
                                                           double margin) {
  const double diameter = std::hypot(p.lx, p.ly);
  const auto wrap0 = static_cast<std::int64_t>(std::ceil(diameter / p.lx)) + 1;
  const auto wrap1 = static_cast<std::int64_t>(std::ceil(diameter / p.ly)) + 1;
  std::vector<std::array<std::int64_t, 2>> near;  // integer coordinates
  std::vector<std::array<double, 2>> pos;
  for (std::int64_t n = 0; n < l.n; ++n) {
    const auto r = residues(l, n);
    for (std::int64_t i = -wrap0; i <= wrap0; ++i) {
      for (std::int64_t j = -wrap1; j <= wrap1; ++j) {
        const std::array<std::int64_t, 2> u{r[0] + i * l.n, r[1] + j * l.n};
        if (u[0] == 0 && u[1] == 0) continue;
        const std::array<double, 2> x{p.lx * u[0] / l.n, p.ly * u[1] / l.n};
        if (std::hypot(x[0], x[1]) > diameter * (1 + 1e-9)) continue;
        near.push_back(u);
        pos.push_back(x);
      }
    }
  }
  std::set<std::array<std::int64_t, 2>> edges;
  for (std::size_t qi = 0; qi < near.size(); ++qi) {
    const auto q = pos[qi];
    const double q2 = q[0] * q[0] + q[1] * q[1];
    // Radius² = q²/4 + s²q² ≤ D²/4.
    const double s_max = std::sqrt(std::max(0.0, (diameter * diameter - q2) / (4 * q2)));
    double lo = -s_max, hi = s_max;
    for (std::size_t ri = 0; ri < near.size() && lo <= hi; ++ri) {
      if (ri == qi) continue;
      const auto r = pos[ri];
      const double a = r[0] * r[0] + r[1] * r[1] - (r[0] * q[0] + r[1] * q[1]);
      const double b = 2 * (-r[0] * q[1] + r[1] * q[0]);  // 2 r·q⊥, q⊥ = (−qy, qx)
      // Need a − b·s ≥ margin.
      if (b > 0) {
        hi = std::min(hi, (a - margin) / b);
      } else if (b < 0) {
        lo = std::max(lo, (a - margin) / b);
      } else if (a < margin) {
        hi = lo - 1;
      }
    }
    if (lo <= hi) edges.insert(near[qi]);
  }
  return edges;
}

// The mesh's edges against the brute force, for every lattice with N ≤ 100 on every patch.
// Tolerance 1e-9 of the area per point on the powers (m²): their rounding is ~1e-16·D², below
// 1e-13 of it here. A non-degenerate lattice has exactly 6 Delaunay edge vectors, all in the
// mesh; a degenerate one 8 (both diagonals), of which the mesh must hold the 4 every
// triangulation has and 2 of the others.
TEST(LatticeMesh, EdgesAreTheBruteForceDelaunayEdges) {
  int degenerate = 0, regular = 0;
  for (const Lattice& l : kLattices) {
    if (l.n > 100) continue;
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const LatticeMesh mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
      const double tolerance = 1e-9 * p.lx * p.ly / l.n;
      const auto some = brute_force_delaunay(l, p, -tolerance);
      const auto every = brute_force_delaunay(l, p, tolerance);
      ASSERT_TRUE((some.size() == 6 && every.size() == 6) ||
                  (some.size() == 8 && every.size() == 4))
          << some.size() << " edges in some triangulation, " << every.size() << " in every one";
      ++(some.size() == 8 ? degenerate : regular);
      // The square, the grid and the line lattice are rectangles: four points on one circle.
      if (l.n == 12 || l.n == 7 || (l.n == 5 && p.lx == p.ly)) {
        EXPECT_EQ(some.size(), 8u);
      }
      std::vector<std::set<std::array<std::int64_t, 2>>> at(static_cast<std::size_t>(l.n));
      const Edges edges = half_edges(l, mesh);
      for (const auto& [e, count] : edges.count) {
        at[std::get<0>(e)].insert({std::get<1>(e), std::get<2>(e)});
      }
      for (std::int64_t n = 0; n < l.n; ++n) {
        ASSERT_EQ(at[n].size(), 6u) << "point " << n;
        for (const auto& v : at[n]) {
          ASSERT_TRUE(some.count(v))
              << "point " << n << ": edge (" << v[0] << ", " << v[1] << ") is not Delaunay";
        }
        for (const auto& v : every) {
          ASSERT_TRUE(at[n].count(v))
              << "point " << n << ": Delaunay edge (" << v[0] << ", " << v[1] << ") is missing";
        }
      }
    }
  }
  // Both kinds were seen (of these 33 meshes, 23 regular and 10 degenerate).
  EXPECT_EQ(degenerate, 10);
  EXPECT_EQ(regular, 23);
}

// Large lattices: the superbase's index offsets against exact products, and a sample of the
// triangles of a 2^20-point mesh against the lattice formula computed directly.
TEST(LatticeMesh, LargeLatticesKeepExactIndexArithmetic) {
  struct Big {
    std::int64_t n, g0, g1;
  };
  for (const Big& b : {Big{std::int64_t{1} << 31, 1, 1664525}, Big{2147483647, 1, 48271},
                       Big{2147483647, 16807, 2147483646}, Big{1836311903, 1, 1134903170}}) {
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(b.n);
      const auto base = swell::reference::delaunay_superbase(b.n, b.g0, b.g1, p.lx, p.ly);
      // |a|, |c| ≤ N ≤ 2^31 and offsets, generators < 2^31: every product below fits 63 bits;
      // the determinant's two products are exact in long double (64-bit mantissa).
      EXPECT_EQ(base.e[0].a + base.e[1].a + base.e[2].a, 0);
      EXPECT_EQ(base.e[0].c + base.e[1].c + base.e[2].c, 0);
      for (const auto& v : base.e) {
        ASSERT_TRUE(std::abs(v.a) <= b.n && std::abs(v.c) <= b.n && v.offset >= 0 &&
                    v.offset < b.n);
        EXPECT_EQ(v.offset * b.g0 % b.n, floor_mod(v.a, b.n));
        EXPECT_EQ(v.offset * b.g1 % b.n, floor_mod(v.c, b.n));
      }
      const long double det = static_cast<long double>(base.e[0].a) * base.e[1].c -
                              static_cast<long double>(base.e[0].c) * base.e[1].a;
      EXPECT_EQ(det, static_cast<long double>(b.n));
      // Pairwise non-acute in the patch's metric.
      for (int i = 0; i < 3; ++i) {
        const auto& u = base.e[i];
        const auto& v = base.e[(i + 1) % 3];
        const long double dot =
            (long double)p.lx * p.lx * u.a * v.a + (long double)p.ly * p.ly * u.c * v.c;
        EXPECT_LE(dot, 0.0L);
      }
    }
  }
  const Lattice l{std::int64_t{1} << 20, 1, 193365};  // odd a: distinct points
  const Patch p{300, 200};
  const LatticeMesh mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
  std::mt19937_64 random(7);
  std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles.size() - 1);
  for (int trial = 0; trial < 2000; ++trial) {
    const std::size_t t = pick(random);
    ASSERT_EQ(mesh.triangles[t][0], static_cast<std::int64_t>(t / 2));
    std::array<std::array<std::int64_t, 2>, 3> u;
    for (int k = 0; k < 3; ++k) u[k] = corner_integer(l, mesh, t, k);
    // Doubled area N (in integer coordinates): the unwrapped corners are the lattice's.
    const std::int64_t cross = (u[1][0] - u[0][0]) * (u[2][1] - u[0][1]) -
                               (u[1][1] - u[0][1]) * (u[2][0] - u[0][0]);
    ASSERT_EQ(cross, l.n) << "triangle " << t;
    // No angle above 90° in the patch's metric (exact integers): a lattice triangulation by
    // such triangles is Delaunay.
    for (int k = 0; k < 3; ++k) {
      const auto &o = u[k], &v = u[(k + 1) % 3], &w = u[(k + 2) % 3];
      const double dot = p.lx * p.lx * static_cast<double>((v[0] - o[0]) * (w[0] - o[0])) +
                         p.ly * p.ly * static_cast<double>((v[1] - o[1]) * (w[1] - o[1]));
      ASSERT_GE(dot, 0.0) << "triangle " << t << " is obtuse at corner " << k;
    }
  }
}

TEST(LatticeMesh, RefusesBadLattices) {
  const auto refuses = [](std::int64_t n, std::int64_t g0, std::int64_t g1, double lx, double ly,
                          const std::string& fragment) {
    try {
      periodic_delaunay(n, g0, g1, lx, ly);
      ADD_FAILURE() << "accepted N = " << n << ", g = (" << g0 << ", " << g1 << "), " << lx << " x "
                    << ly;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  refuses(2, 1, 1, 1, 1, "lattice points must be in [3, 2^31] (got 2)");
  refuses(0, 1, 1, 1, 1, "lattice points");
  refuses(-5, 1, 1, 1, 1, "lattice points");
  refuses((std::int64_t{1} << 31) + 1, 1, 1, 1, 1, "lattice points");
  // gcd(2, 4, 8) = 2: point 4 repeats point 0; gcd(0, 0, N) = N.
  refuses(8, 2, 4, 1, 1, "gcd(g0, g1, points) = 1");
  refuses(8, 2, 4, 1, 1, "point 4 equals point 0");
  refuses(9, 3, 6, 1, 1, "got gcd 3");
  refuses(9, 0, 0, 1, 1, "got gcd 9");
  refuses(10, 12, -4, 1, 1, "gcd");  // taken mod 10: (2, 6)
  refuses(13, 1, 8, 0, 1, "patch length lx must be finite and positive");
  refuses(13, 1, 8, 1, -1, "patch length ly must be finite and positive");
  refuses(13, 1, 8, std::nan(""), 1, "patch length lx");
  refuses(13, 1, 8, 1, HUGE_VAL, "patch length ly");
  refuses(13, 1, 8, 1, 1e5, "aspect ratio");
  EXPECT_THROW(swell::reference::delaunay_superbase(2, 1, 1, 1, 1), InvalidInput);
  // Generators are taken mod N: (14, −5) is (1, 8) for N = 13.
  const LatticeMesh a = periodic_delaunay(13, 14, -5, 2, 1), b = periodic_delaunay(13, 1, 8, 2, 1);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.g0, 1);
  EXPECT_EQ(a.g1, 8);
}

// ---- Files ----------------------------------------------------------------------------------

struct ReadMesh {
  std::vector<std::array<float, 3>> vertices;
  std::vector<std::array<std::int64_t, 3>> faces;  // 0-based
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A PLY reader for exactly what the file promises (and nothing more): the header line by line,
// then little-endian floats and (uchar 3, int, int, int) faces, to the last byte.
ReadMesh read_ply(const fs::path& path) {
  const std::string bytes = slurp(path);
  const std::size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  std::vector<std::string> lines;
  for (std::string line; std::getline(header, line);) {
    if (line.rfind("comment", 0) != 0) lines.push_back(line);
  }
  std::size_t vertices = 0, faces = 0;
  EXPECT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines.at(0), "ply");
  EXPECT_EQ(lines.at(1), "format binary_little_endian 1.0");
  EXPECT_EQ(std::sscanf(lines.at(2).c_str(), "element vertex %zu", &vertices), 1);
  EXPECT_EQ(lines.at(3), "property float x");
  EXPECT_EQ(lines.at(4), "property float y");
  EXPECT_EQ(lines.at(5), "property float z");
  EXPECT_EQ(std::sscanf(lines.at(6).c_str(), "element face %zu", &faces), 1);
  EXPECT_EQ(lines.at(7), "property list uchar int vertex_indices");
  std::size_t at = end + std::strlen("end_header\n");
  EXPECT_EQ(bytes.size(), at + 12 * vertices + 13 * faces);
  const auto u32 = [&](std::size_t offset) {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k)
      v |= std::uint32_t(static_cast<unsigned char>(bytes[offset + k])) << (8 * k);
    return v;
  };
  ReadMesh mesh;
  for (std::size_t i = 0; i < vertices && at + 12 <= bytes.size(); ++i, at += 12) {
    mesh.vertices.push_back({std::bit_cast<float>(u32(at)), std::bit_cast<float>(u32(at + 4)),
                             std::bit_cast<float>(u32(at + 8))});
  }
  for (std::size_t i = 0; i < faces && at + 13 <= bytes.size(); ++i, at += 13) {
    EXPECT_EQ(bytes[at], 3);
    mesh.faces.push_back({static_cast<std::int32_t>(u32(at + 1)),
                          static_cast<std::int32_t>(u32(at + 5)),
                          static_cast<std::int32_t>(u32(at + 9))});
  }
  return mesh;
}

ReadMesh read_obj(const fs::path& path) {
  std::ifstream in(path);
  ReadMesh mesh;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "v") {
      std::array<float, 3> v{};
      for (float& value : v) {
        std::string word;
        words >> word;
        const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
        EXPECT_TRUE(result.ec == std::errc() && result.ptr == word.data() + word.size()) << line;
      }
      mesh.vertices.push_back(v);
    } else if (kind == "f") {
      std::array<std::int64_t, 3> f{};
      for (auto& index : f) words >> index;
      EXPECT_TRUE(words && (words >> std::ws).eof()) << line;
      for (auto& index : f) {
        EXPECT_TRUE(index >= 1) << line;
        --index;
      }
      mesh.faces.push_back(f);
    } else {
      ADD_FAILURE() << "unexpected OBJ line: " << line;
    }
  }
  return mesh;
}

// A directory of this process and test, removed afterwards.
class TempDir {
 public:
  TempDir()
      : path_(fs::temp_directory_path() /
              ("swell_mesh_test_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    fs::create_directories(path_);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  fs::path operator/(const std::string& leaf) const { return path_ / leaf; }

 private:
  fs::path path_;
};

// A surface with displacement (small against the point spacing, so points stay apart).
MeshSurface make_surface(const Lattice& l, const Patch& p) {
  MeshSurface s;
  s.mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
  const double spacing = std::sqrt(p.lx * p.ly / l.n);
  for (std::int64_t n = 0; n < l.n; ++n) {
    s.h.push_back(0.5 * std::sin(0.7 * n) + 0.01 * n);
    s.dx.push_back(0.1 * spacing * std::cos(1.3 * n));
    s.dy.push_back(-0.1 * spacing * std::sin(0.4 * n));
  }
  return s;
}

// The file's faces are the mesh's triangles in order; each corner is the lattice point plus its
// displacement plus its period shift, in float. Vertex n < N is point n unshifted; the others
// are the distinct shifted corners, each used.
void expect_faithful(const ReadMesh& file, const MeshSurface& s, const Patch& p) {
  const LatticeMesh& mesh = s.mesh;
  std::set<std::array<std::int64_t, 3>> shifted;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto [px, py] = mesh.corner_periods[t][k];
      if (px != 0 || py != 0) shifted.insert({mesh.triangles[t][k], px, py});
    }
  }
  ASSERT_EQ(file.faces.size(), mesh.triangles.size());
  ASSERT_EQ(file.vertices.size(), static_cast<std::size_t>(mesh.points) + shifted.size());
  const double tolerance = 2e-7 * 3 * std::max(p.lx, p.ly);  // float rounding of coordinates ≤ 3L
  std::vector<bool> used(file.vertices.size(), false);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = file.faces[t][k];
      ASSERT_TRUE(v >= 0 && v < static_cast<std::int64_t>(file.vertices.size()));
      used[v] = true;
      const std::int64_t n = mesh.triangles[t][k];
      const auto [px, py] = mesh.corner_periods[t][k];
      if (px == 0 && py == 0) {
        ASSERT_EQ(v, n);
      }
      const double x =
          p.lx * static_cast<double>(floor_mod(n * mesh.g0, mesh.points)) / mesh.points;
      const double y =
          p.ly * static_cast<double>(floor_mod(n * mesh.g1, mesh.points)) / mesh.points;
      EXPECT_NEAR(file.vertices[v][0], x + s.dx[n] + px * p.lx, tolerance);
      EXPECT_NEAR(file.vertices[v][1], y + s.dy[n] + py * p.ly, tolerance);
      EXPECT_EQ(file.vertices[v][2], static_cast<float>(s.h[n]));
    }
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
}

// Tiling: 3 × 3 copies of the file at offsets (i·lx, j·ly). Vertices are merged by position
// (within float rounding, far below the distance between displaced points); then every edge of the
// middle copy must meet exactly one twin of opposite direction in the union — no gap, no overlap,
// along the seams too — and each shifted duplicate of the middle copy must coincide with an
// unshifted vertex of the neighbour copy it stands for.
void expect_tileable(const ReadMesh& file, const Patch& p, std::size_t points) {
  const double tolerance = 2e-7 * 4 * std::max(p.lx, p.ly);
  const double cell = 64 * tolerance;
  std::map<std::array<std::int64_t, 2>, std::vector<std::size_t>> buckets;
  std::vector<std::array<double, 2>> where;
  std::vector<std::size_t> id;  // merged id of copy c's vertex v: id[c·V + v]
  const std::size_t count = file.vertices.size();
  const auto find_or_add = [&](double x, double y) {
    const auto bx = static_cast<std::int64_t>(std::floor(x / cell));
    const auto by = static_cast<std::int64_t>(std::floor(y / cell));
    for (std::int64_t i = bx - 1; i <= bx + 1; ++i) {
      for (std::int64_t j = by - 1; j <= by + 1; ++j) {
        const auto it = buckets.find({i, j});
        if (it == buckets.end()) continue;
        for (const std::size_t m : it->second) {
          if (std::hypot(where[m][0] - x, where[m][1] - y) <= tolerance) return m;
        }
      }
    }
    where.push_back({x, y});
    buckets[{bx, by}].push_back(where.size() - 1);
    return where.size() - 1;
  };
  for (int c = 0; c < 9; ++c) {
    const double sx = (c % 3 - 1) * p.lx, sy = (c / 3 - 1) * p.ly;
    for (std::size_t v = 0; v < count; ++v) {
      id.push_back(find_or_add(file.vertices[v][0] + sx, file.vertices[v][1] + sy));
    }
  }
  // The middle copy is c = 4. Its duplicates coincide with a neighbour copy's vertex n < N.
  for (std::size_t v = points; v < count; ++v) {
    bool found = false;
    for (int c = 0; c < 9 && !found; ++c) {
      if (c == 4) continue;
      for (std::size_t n = 0; n < points && !found; ++n)
        found = id[c * count + n] == id[4 * count + v];
    }
    EXPECT_TRUE(found) << "duplicate vertex " << v << " lies on no vertex of a neighbour copy";
  }
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  for (int c = 0; c < 9; ++c) {
    for (const auto& f : file.faces) {
      for (int k = 0; k < 3; ++k) {
        ++directed[{id[c * count + f[k]], id[c * count + f[(k + 1) % 3]]}];
      }
    }
  }
  for (const auto& f : file.faces) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = id[4 * count + f[k]], b = id[4 * count + f[(k + 1) % 3]];
      ASSERT_EQ(directed[std::pair(a, b)], 1) << "an edge of the middle copy occurs twice";
      ASSERT_EQ(directed[std::pair(b, a)], 1)
          << "an edge of the middle copy has no twin: a seam is open";
    }
  }
}

TEST(MeshFiles, PlyHoldsTheSurfaceAndTiles) {
  const TempDir dir;
  for (const Lattice& l : kLattices) {
    if (l.n > 1100) continue;
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const MeshSurface s = make_surface(l, p);
      const fs::path path = dir / "surface.ply";
      swell::validation::write_ply(path, s);
      const ReadMesh file = read_ply(path);
      expect_faithful(file, s, p);
      expect_tileable(file, p, static_cast<std::size_t>(l.n));
      // tileable_mesh() numbers the vertices as the file does.
      const auto tiles = swell::validation::tileable_mesh(s.mesh);
      ASSERT_EQ(tiles.vertices.size(), file.vertices.size());
      ASSERT_EQ(tiles.faces.size(), file.faces.size());
      for (std::size_t t = 0; t < tiles.faces.size(); ++t) {
        for (int k = 0; k < 3; ++k) ASSERT_EQ(tiles.faces[t][k], file.faces[t][k]);
      }
      for (std::size_t v = 0; v < tiles.vertices.size(); ++v) {
        const auto& tv = tiles.vertices[v];
        const auto x = s.mesh.position(tv.point);
        const auto n = static_cast<std::size_t>(tv.point);
        ASSERT_EQ(file.vertices[v][0], static_cast<float>(x[0] + tv.px * p.lx + s.dx[n]));
        ASSERT_EQ(file.vertices[v][1], static_cast<float>(x[1] + tv.py * p.ly + s.dy[n]));
        ASSERT_TRUE(v >= static_cast<std::size_t>(l.n) ||
                    (tv.point == static_cast<std::int64_t>(v) && tv.px == 0 && tv.py == 0));
      }
    }
  }
}

TEST(MeshFiles, ObjHoldsWhatThePlyHolds) {
  const TempDir dir;
  for (const Lattice& l : {kLattices[0], kLattices[10], kLattices[15]}) {
    for (const Patch& p : kPatches) {
      SCOPED_TRACE(name(l, p));
      const MeshSurface s = make_surface(l, p);
      const fs::path ply = dir / "surface.ply", obj = dir / "surface.obj";
      swell::validation::write_ply(ply, s);
      swell::validation::write_obj(obj, s);
      const ReadMesh a = read_ply(ply), b = read_obj(obj);
      EXPECT_EQ(b.faces.size(), static_cast<std::size_t>(2 * l.n));
      EXPECT_EQ(a.vertices, b.vertices);  // the same floats: the OBJ's decimals round-trip
      EXPECT_EQ(a.faces, b.faces);        // 1-based in the file, in range
      for (const auto& f : b.faces) {
        for (const auto index : f) ASSERT_LT(index, static_cast<std::int64_t>(b.vertices.size()));
      }
      expect_faithful(b, s, p);
    }
  }
}

// Without horizontal displacement, the file's triangles are the lattice's: their areas sum to
// the patch exactly once.
TEST(MeshFiles, UndisplacedSurfaceCoversThePatchOnce) {
  const Lattice l{1024, 1, 309};
  const Patch p{200, 100};
  MeshSurface s;
  s.mesh = periodic_delaunay(l.n, l.g0, l.g1, p.lx, p.ly);
  s.h.assign(static_cast<std::size_t>(l.n), 0.25);
  const TempDir dir;
  const fs::path path = dir / "flat.ply";
  swell::validation::write_ply(path, s);
  const ReadMesh file = read_ply(path);
  double area = 0;
  for (const auto& f : file.faces) {
    const auto &a = file.vertices[f[0]], &b = file.vertices[f[1]], &c = file.vertices[f[2]];
    const double cross = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) -
                         (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
    ASSERT_GT(cross, 0);
    area += cross / 2;
  }
  EXPECT_NEAR(area, p.lx * p.ly, 1e-5 * p.lx * p.ly);
}

// Refusals name the field, rule and value, or the path and the system's reason; a failed write
// leaves no partial file behind.
TEST(MeshFiles, RefusesBadSurfacesAndUnwritablePaths) {
  const TempDir dir;
  const MeshSurface good = make_surface({13, 1, 8}, {2, 1});
  const auto refuses = [](const auto& write, const fs::path& path, const MeshSurface& s,
                          const std::string& fragment) {
    try {
      write(path, s);
      ADD_FAILURE() << "wrote " << path;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const auto ply = [](const fs::path& path, const MeshSurface& s) {
    swell::validation::write_ply(path, s);
  };
  const auto obj = [](const fs::path& path, const MeshSurface& s) {
    swell::validation::write_obj(path, s);
  };
  const fs::path missing = dir / "no_such_directory" / "mesh.ply";
  refuses(ply, missing, good,
          missing.string() + ": cannot open for writing: No such file or directory");
  refuses(obj, missing, good, "No such file or directory");
  fs::create_directories(dir / "a_directory");
  refuses(ply, dir / "a_directory", good, "a_directory: cannot open for writing: Is a directory");

  // A write that fails part way (the file-size limit, with SIGXFSZ ignored so that write()
  // returns EFBIG instead of killing the process): the reason is named and the partial file
  // removed. A 1024-point mesh is some 40 kB, above the 4 kB limit, in both formats.
  {
    const MeshSurface big = make_surface({1024, 1, 309}, {2, 1});
    rlimit saved{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
    ASSERT_TRUE(saved.rlim_max == RLIM_INFINITY || saved.rlim_max > 4096);
    rlimit small = saved;
    small.rlim_cur = 4096;
    const auto previous = std::signal(SIGXFSZ, SIG_IGN);
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    refuses(ply, dir / "big.ply", big, "big.ply: write failed: File too large");
    refuses(obj, dir / "big.obj", big, "big.obj: write failed: File too large");
    ::setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, previous);
    EXPECT_FALSE(fs::exists(dir / "big.ply"));
    EXPECT_FALSE(fs::exists(dir / "big.obj"));
    swell::validation::write_ply(dir / "big.ply", big);  // fine without the limit
    EXPECT_GT(fs::file_size(dir / "big.ply"), 4096u);
  }

  MeshSurface s = good;
  s.h.pop_back();
  refuses(ply, dir / "bad.ply", s,
          "surface h: number of values must be 13, one per lattice point (got 12)");
  EXPECT_FALSE(fs::exists(dir / "bad.ply"));  // checked before the file is opened
  s = good;
  s.dx.assign(5, 0.0);
  refuses(obj, dir / "bad.obj", s, "surface dx: number of values must be 13");
  s = good;
  s.dy[3] = std::nan("");
  refuses(ply, dir / "bad.ply", s, "surface dy[3] must be finite (got nan)");
  s = good;
  s.dx.clear();
  s.dy.clear();
  swell::validation::write_obj(dir / "plain.obj", s);  // no displacement: allowed
  s = good;
  s.mesh.triangles.pop_back();
  refuses(ply, dir / "bad.ply", s, "mesh: must have 2·points triangles");
  s = good;
  s.mesh.corner_periods[4][1][0] = 2;
  refuses(ply, dir / "bad.ply", s, "periods in {-1, 0, 1}");
  s = good;
  s.mesh.g1 = -8;
  refuses(ply, dir / "bad.ply", s, "a generator in [0, points)");
  s = good;
  s.mesh.triangles[5][2] = 13;
  refuses(obj, dir / "bad.obj", s, "must name a point in [0, 13)");
}

}  // namespace
