#pragma once
// The periodic Delaunay triangulation of a 2-D rank-1 lattice (docs/conventions.md §2.1, §4
// lattice: "the periodic Delaunay triangulation from a reduced basis, two triangles per point").
//
// The lattice is taken as plain numbers: N points
//     x_n = (lx·((n·g0) mod N)/N, ly·((n·g1) mod N)/N),   n = 0 … N−1,
// on the torus [0, lx) × [0, ly). In integer coordinates u_n = ((n·g0) mod N, (n·g1) mod N) the
// points and all their periodic images form the planar lattice Λ = ℤ·(g0, g1) + N ℤ² of
// determinant N; a vector (a, c) ∈ Λ is the physical vector (lx·a/N, ly·c/N). Every lattice
// vector also has an index offset δ ∈ [0, N) with δ·(g0, g1) ≡ (a, c) (mod N), so that
// x_{(n+δ) mod N} = x_n + (lx·a/N, ly·c/N) on the torus. All of this is integer arithmetic;
// only the choice of the short vectors (the metric lx², ly²) uses floating point.
//
// A lattice is the same seen from every point, so its Delaunay triangulation is too: one obtuse
// superbase e1 + e2 + e3 = 0 (pairwise non-acute, found in O(log N) by Lagrange–Gauss reduction
// in the patch's metric) gives every point n the same two triangles
//     T(2n)   = (n, n + e1, n + e1 + e2),      T(2n+1) = (n, n + e1 + e2, n + e2),
// whose sides are ±e1, ±e2, ±e3. All their angles are ≤ 90°, which makes them Delaunay.
#include <array>
#include <cstdint>
#include <vector>

namespace swell::reference {

// A vector of the lattice Λ in integer coordinates: physical (lx·a/N, ly·c/N); `offset` is its
// index offset δ ∈ [0, N), δ·(g0, g1) ≡ (a, c) (mod N). A period (N, 0) has offset 0.
struct SuperbaseVector {
  std::int64_t a = 0, c = 0;
  std::int64_t offset = 0;
};

// The obtuse superbase of the lattice in the patch's metric: e[0] + e[1] + e[2] = 0, every two
// of them at an angle ≥ 90°, det(e[0], e[1]) = +N (counter-clockwise), and, as every Delaunay
// edge, |a| ≤ N and |c| ≤ N (no edge is longer than a period in either direction; see
// periodic_delaunay). e[0] and e[1] are a Lagrange–Gauss-reduced basis (up to signs).
struct DelaunaySuperbase {
  std::array<SuperbaseVector, 3> e{};
};

// The lattice as plain numbers, validated (throws InvalidInput naming the rule):
//  - points N in [3, 2^31] (so that a product of two residues fits in 64 bits);
//  - the generator any integers, taken mod N; gcd(g0, g1, N) = 1, which holds exactly when the
//    N points are distinct (n·g ≡ 0 (mod N) for n = N/gcd(g0, g1, N));
//  - lx, ly finite and positive, lx/ly within [1e-4, 1e4] (beyond it the reduction's long double
//    metric can no longer tell the Delaunay edges from their rivals for N up to 2^31).
DelaunaySuperbase delaunay_superbase(std::int64_t points, std::int64_t g0, std::int64_t g1,
                                     double lx, double ly);

struct LatticeMesh {
  std::int64_t points = 0;
  std::int64_t g0 = 0, g1 = 0;  // the generator, reduced mod points
  double lx = 0, ly = 0;        // metres
  DelaunaySuperbase superbase;
  // Two triangles per point, 2N in all: triangles 2n and 2n+1 are point n's (see above), each
  // three point indices, counter-clockwise in (x, y) when unwrapped. corner_periods: for each
  // corner the period it is shifted by so that the triangle's corners, unwrapped, lie next to
  // each other: corner position = x_n + (px·lx, py·ly), px, py ∈ {−1, 0, 1}. Corner 0 is the
  // triangle's own point, unshifted.
  //
  // A very anisotropic lattice (few points, or a patch far from square) can have a period
  // (N, 0) or (0, N) among its Delaunay edges: then a triangle names one point twice, at two
  // different periods (e.g. N points on the line x = 0, g = (0, 1)). That is still a
  // triangulation of the torus, and the tileable files hold it as such.
  std::vector<std::array<std::int64_t, 3>> triangles;
  std::vector<std::array<std::array<std::int8_t, 2>, 3>> corner_periods;

  // x_n (metres) for n in [0, N), in [0, lx) × [0, ly): exact integer residues, then
  // lx·r/N (two roundings).
  std::array<double, 2> position(std::int64_t n) const;
  // The unwrapped position of corner `corner` of triangle `t`: position(n) + (px·lx, py·ly).
  std::array<double, 2> corner_position(std::size_t t, int corner) const;
};

// The periodic Delaunay triangulation in O(N): delaunay_superbase, then two triangles per point
// by index arithmetic (residues advanced by one addition per point, no multiplication). The
// input rules are those of delaunay_superbase.
//
// Degenerate lattices, with four or more points on one empty circle (a rectangular lattice, a
// rotated square as some Fibonacci lattices are), have more than one Delaunay triangulation:
// this returns one of them, the diagonal e[0] + e[1] of the reduced basis.
LatticeMesh periodic_delaunay(std::int64_t points, std::int64_t g0, std::int64_t g1, double lx,
                              double ly);

}  // namespace swell::reference
