#pragma once
// The random numbers of a synthesized surface (docs/conventions.md §Random numbers): a pair of
// independent standard normals ξ1, ξ2 per wave vector, from Philox4x32-10 (Random123) keyed by
// the seed with the counter made of the signed wave-number indices (n, m). The same seed gives
// the same pair at the same (n, m) whatever the grid size or the order of traversal, so a
// surface on a coarser grid is exactly the band-limited part of a finer one.
//
// Mapping, fixed as part of the contract: key = {seed mod 2³², seed / 2³²}, counter =
// {n, m, stream, cascade} as 32-bit two's complement (cascade 0: the single-grid surface; each
// cascade of a set draws its own numbers, docs/conventions.md §2.2); the four output words (w0, w1, w2, w3) form two
// 64-bit integers (w0 + 2³² w1, w2 + 2³² w3), which r123::boxmuller turns into (ξ1, ξ2).
#include <cstdint>

namespace swell::reference {

struct NormalPair {
  double xi1 = 0, xi2 = 0;
};

// Stream 0 is the amplitude noise of conventions §Amplitudes; other streams are free for
// independent uses (test fixtures use stream 1).
NormalPair wave_noise(std::uint64_t seed, int n, int m, std::uint32_t stream = 0,
                      std::uint32_t cascade = 0);

// Two independent uniforms on (0, 1] from the same counter (for tests of non-Gaussian noise).
struct UniformPair {
  double u1 = 0, u2 = 0;
};
UniformPair wave_uniforms(std::uint64_t seed, int n, int m, std::uint32_t stream = 0);

}  // namespace swell::reference
