// The initial amplitudes of a case (synthesis/amplitudes.hpp, synthesizer.hpp).
#include "synthesis/amplitudes.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/wave_noise.hpp"

namespace swell::impls {
namespace synthesis {
namespace {

using reference::OceanCase;

// h̃0 of cascade `cascade` at its own wave index (n, m) on `grid`: the sea's Ψ times the band
// weight w², with the cascade's own Δk and random numbers.
std::complex<double> cascade_amplitude(const reference::DirectionalSpectrum& sea,
                                       const OceanCase& c, const reference::Grid& grid,
                                       const reference::BandWeight& band, int cascade, int n,
                                       int m) {
  const double dkx = grid.dkx(), dky = grid.dky();
  const double kx = n * dkx, ky = m * dky;
  const double w2 = band.everywhere() ? 1.0 : band.weight_squared(std::hypot(kx, ky));
  if (w2 == 0) return 0.0;
  const double psi = w2 * sea.psi(kx, ky);
  const auto xi = reference::wave_noise(c.seed, n, m, 0, static_cast<std::uint32_t>(cascade));
  // conventions §Amplitudes: (ξ1 + iξ2)/√2 · √(Ψ Δkx Δky / 2), so E|h̃0|² = ½ Ψ Δk².
  return std::complex<double>(xi.xi1, xi.xi2) * std::sqrt(0.5 * psi * dkx * dky * 0.5);
}

}  // namespace

// h̃0 at signed wave index (n, m) of the case's sampling, from the sea's (unweighted) Ψ. A
// summed cascade set adds every cascade whose grid holds the wave vector: cascade c's index is
// (n, m)·L_c/L, its weight, Δk and random numbers its own, and its Ψ its own when it is an
// independent sea (reference/cascade.hpp).
std::complex<double> amplitude(const reference::DirectionalSpectrum& sea, const OceanCase& c,
                               int n, int m) {
  // A lattice's caller asks only for the k_m of classes that carry energy (and their −k_m,
  // which are k_(N−m)); only k = 0 is empty by the rule itself.
  if (c.is_lattice() ? (n == 0 && m == 0) : !c.grid.carries_energy(n, m)) return 0.0;
  if (!c.is_summed_cascades()) return cascade_amplitude(sea, c, c.grid, c.band, c.cascade, n, m);
  std::complex<double> sum = 0.0;
  for (const auto& member : c.members) {
    const auto rx = static_cast<long long>(std::llround(c.grid.lx / member.grid.lx));
    const auto ry = static_cast<long long>(std::llround(c.grid.ly / member.grid.ly));
    if (n % rx != 0 || m % ry != 0) continue;
    const int nc = static_cast<int>(n / rx), mc = static_cast<int>(m / ry);
    const auto& g = member.grid;
    if (nc < -(g.nx / 2) || nc >= (g.nx + 1) / 2 || mc < -(g.ny / 2) || mc >= (g.ny + 1) / 2 ||
        !g.carries_energy(nc, mc)) {
      continue;
    }
    // Independent seas: each cascade's own Ψ (the set's sea is then their sum).
    const auto& psi = member.spectrum ? *member.spectrum : sea;
    sum += cascade_amplitude(psi, c, g, member.band, member.cascade, nc, mc);
  }
  return sum;
}

}  // namespace synthesis

using reference::OceanCase;
using synthesis::amplitude;

std::complex<double> initial_amplitude(const OceanCase& ocean_case, int n, int m) {
  return amplitude(*ocean_case.sea_spectrum(), ocean_case, n, m);
}

std::vector<std::complex<double>> initial_amplitudes(const OceanCase& ocean_case) {
  if (ocean_case.is_lattice()) {
    throw InvalidInput("initial_amplitudes: a grid case (a lattice's amplitudes are per class)");
  }
  const auto sea = ocean_case.sea_spectrum();
  const auto& g = ocean_case.grid;
  std::vector<std::complex<double>> out(std::size_t(g.nx) * g.ny);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      out[std::size_t(j) * g.nx + i] = amplitude(*sea, ocean_case, reference::Grid::signed_index(i, g.nx),
                                                 reference::Grid::signed_index(j, g.ny));
    }
  }
  return out;
}

}  // namespace swell::impls
