#pragma once
// A sampling of a periodic patch (docs/conventions.md §2.1): a grid or a rank-1 lattice. It gives
// the sample points (metres), the integer wave vector of every spectral coefficient, which
// coefficients carry energy, and which coefficient holds the conjugate wave. Everything that
// judges frames works on a sampling: a lattice frame is judged by the same code as a grid frame.
//
//   grid     nx·ny samples, sample p = j·nx + i at (i lx/nx, j ly/ny); coefficient c = j·nx + i
//            of the 2-D FFT has the signed wave index (n, m) of (i, j) in FFT order (grid.hpp).
//   lattice  N samples, sample p = n at lattice.point(n); coefficient c = m (the residue class
//            m = k·g mod N of the 1-D FFT over n) has the minimal wave vector k_m (lattice.hpp).
//
// Both analyses divide by the number of samples: ĥ_c = (1/N) Σ_p h_p e^(−2πi …), so Σ_c |ĥ_c|²
// = mean h² and a coefficient at K has the expectation a grid's has at K (Δkx Δky = 4π²/(lx ly)
// on both: the N classes tile the wave-number plane once).
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include "swell/reference/grid.hpp"
#include "swell/reference/lattice.hpp"

namespace swell::reference {

class Sampling {
 public:
  Sampling() = default;
  explicit Sampling(const Grid& grid) : grid_(grid) {}
  // A 2-D lattice (a 3-D one is a space-time sampling, not a patch: InvalidInput).
  explicit Sampling(std::shared_ptr<const RankOneLattice> lattice);

  bool is_lattice() const { return lattice_ != nullptr; }
  // The grid (lengths only, nx = ny = 0, for a lattice) and the lattice (null for a grid).
  const Grid& grid() const { return grid_; }
  const std::shared_ptr<const RankOneLattice>& lattice() const { return lattice_; }

  // Samples per field, which is also the number of spectral coefficients.
  std::size_t size() const;
  double lx() const { return grid_.lx; }
  double ly() const { return grid_.ly; }
  double dkx() const { return grid_.dkx(); }  // 2π/lx, rad/m
  double dky() const { return grid_.dky(); }

  // Signed integer wave vector (n, m) of coefficient c: K = (n·dkx, m·dky).
  std::array<int, 2> wave_index(std::size_t c) const {
    if (lattice_) {
      const auto k = lattice_->wave_vector(static_cast<std::int64_t>(c));
      return {k[0], k[1]};
    }
    const int nx = grid_.nx;
    return {Grid::signed_index(static_cast<int>(c % nx), nx),
            Grid::signed_index(static_cast<int>(c / nx), grid_.ny)};
  }
  // The coefficient holding −k (itself for k = 0, the Nyquist entries and a lattice's N/2).
  std::size_t conjugate(std::size_t c) const {
    if (lattice_) {
      const auto n = static_cast<std::size_t>(lattice_->points());
      return (n - c) % n;
    }
    const auto nx = static_cast<std::size_t>(grid_.nx), ny = static_cast<std::size_t>(grid_.ny);
    return ((ny - c / nx) % ny) * nx + (nx - c % nx) % nx;
  }
  // False for k = 0 and the self-conjugate coefficients (a grid's Nyquist row and column, a
  // lattice's class N/2 for even N): they carry no energy by the conventions.
  bool carries_energy(std::size_t c) const {
    if (lattice_) return lattice_->carries_energy(static_cast<std::int64_t>(c));
    const auto [n, m] = wave_index(c);
    return grid_.carries_energy(n, m);
  }
  // Sample p's position in metres.
  std::array<double, 2> point(std::size_t p) const;

  // "256×256 grid over 200×200 m", "korobov N=4096 g=(1,1159) over 200×200 m".
  std::string describe() const;
  // The same samples: equal kinds, sizes and generators, lengths within a relative 1e-9.
  bool same_as(const Sampling& other) const;

 private:
  Grid grid_;
  std::shared_ptr<const RankOneLattice> lattice_;
};

}  // namespace swell::reference
