#pragma once
// Integer helpers shared by the lattice code (lattice.cpp, lattice_mesh.cpp): exact residues
// and Bézout coefficients, in 64-bit integers (the lattices have N ≤ 2^31 points).
#include <cstdint>
#include <utility>

namespace swell::reference::integer {

// value mod n in [0, n), for n > 0.
inline std::int64_t floor_mod(std::int64_t value, std::int64_t n) {
  const std::int64_t r = value % n;
  return r < 0 ? r + n : r;
}

// g = x·a + y·b = gcd(a, b) ≥ 0 (the extended Euclidean algorithm; |x| ≤ |b|, |y| ≤ |a|).
struct Bezout {
  std::int64_t gcd, x, y;
};
inline Bezout extended_gcd(std::int64_t a, std::int64_t b) {
  std::int64_t r0 = a, r1 = b, x0 = 1, x1 = 0, y0 = 0, y1 = 1;
  while (r1 != 0) {
    const std::int64_t q = r0 / r1;
    r0 = std::exchange(r1, r0 - q * r1);
    x0 = std::exchange(x1, x0 - q * x1);
    y0 = std::exchange(y1, y0 - q * y1);
  }
  if (r0 < 0) return {-r0, -x0, -y0};
  return {r0, x0, y0};
}

}  // namespace swell::reference::integer
