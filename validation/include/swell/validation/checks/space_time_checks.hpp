#pragma once
// The space-time dispersion check : a loop-periodic surface sampled on a 3-D
// rank-1 lattice over (Lx, Ly, T) is judged from its samples alone.
//
// A right surface is Σ_h c_h e^(2πi (h_0 x/Lx + h_1 y/Ly + h_2 t/T)) over the frequency vectors
// h = (n, m, ∓q(k)) of its band, q(k) = ω(k) T / 2π with ω the case's (quantized) dispersion.
// On the lattice x_n = (Lx, Ly, T) ∘ ((n g / N) mod 1) each exponential is
// e^(2πi ((h·g) mod N) n / N), so the forward 1-D FFT of the N samples, divided by N, is one
// coefficient per residue class r: ĉ_r = Σ_{h·g ≡ r} c_h. Every class that is not the image of a
// vector on the case's dispersion surface must then be empty, to rounding, whatever the
// amplitudes; a surface whose waves move with another ω puts energy into other classes.
//
// The check needs no injectivity to pass a right surface; injectivity on the case's vectors
// (impls::choose_space_time_korobov) makes every right class hold one wave. A wrong wave can
// still land in a class of the case's image (the lattice separates the case's vectors from each
// other, not from every other vector), so the off-surface fraction measured is a lower bound
// of the wrongly placed energy: a wrong surface fails with a fraction below its true one.
#include <array>
#include <cstdint>
#include <span>

#include "swell/reference/lattice.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

// check "space_time.dispersion": measured = Σ_{r off the image} |ĉ_r|² / Σ_r |ĉ_r|², passed when
// ≤ (16 u log2 N)² (the squared relative rounding error of a synthesis and an analysis of size
// N in unit roundoff u: docs/transforms.md's c·ε·log2 N bound with room for both transforms and
// the coefficients' own rounding).
//  samples       h at lattice.point(n), n = 0 … N − 1
//  lattice       3-D, lengths (Lx, Ly, T) = (case lx, case ly, case loop_period)
//  ocean_case    its dispersion and loop period T > 0 define the surface
//  wave_vectors  the band (n, m) the surface carries (impls::SpaceTimeBand::wave_vectors)
//  unit_roundoff of the samples as made (2⁻⁵³ fp64, 2⁻²⁴ fp32)
// InvalidInput when the sizes, the dimension or the lengths disagree, or T ≤ 0. A failure names
// the fraction and, when one explains the samples to rounding, the dispersion they follow (deep
// water for a finite-depth case, ω = g k, ω rounded to the nearest multiple of 2π/T).
CheckResult space_time_dispersion(std::span<const double> samples,
                                  const reference::RankOneLattice& lattice,
                                  const reference::OceanCase& ocean_case,
                                  std::span<const std::array<std::int32_t, 2>> wave_vectors,
                                  double unit_roundoff = 0x1p-53);

}  // namespace swell::validation
