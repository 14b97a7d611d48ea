#include "swell/reference/sampling.hpp"

#include <cmath>

#include <fmt/format.h>

#include "swell/reference/errors.hpp"

namespace swell::reference {

Sampling::Sampling(std::shared_ptr<const RankOneLattice> lattice) : lattice_(std::move(lattice)) {
  if (!lattice_) throw InvalidInput("sampling: no lattice given");
  if (lattice_->dimension() != 2) {
    throw InvalidInput(fmt::format(
        "sampling: a patch is sampled by a 2-D lattice; {} has dimension {} (a 3-D lattice "
        "samples space and time, see docs/lattice.md)",
        lattice_->describe(), lattice_->dimension()));
  }
  grid_.lx = lattice_->lengths()[0];
  grid_.ly = lattice_->lengths()[1];
}

std::size_t Sampling::size() const {
  if (lattice_) return static_cast<std::size_t>(lattice_->points());
  return static_cast<std::size_t>(grid_.nx) * static_cast<std::size_t>(grid_.ny);
}

std::array<double, 2> Sampling::point(std::size_t p) const {
  if (lattice_) {
    const auto x = lattice_->point(static_cast<std::int64_t>(p));
    return {x[0], x[1]};
  }
  const auto nx = static_cast<std::size_t>(grid_.nx);
  return {static_cast<double>(p % nx) * grid_.lx / grid_.nx,
          static_cast<double>(p / nx) * grid_.ly / grid_.ny};
}

std::string Sampling::describe() const {
  if (lattice_) return lattice_->describe();
  return fmt::format("{}×{} grid over {:g}×{:g} m", grid_.nx, grid_.ny, grid_.lx, grid_.ly);
}

bool Sampling::same_as(const Sampling& other) const {
  auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); };
  if (is_lattice() != other.is_lattice()) return false;
  if (!close(lx(), other.lx()) || !close(ly(), other.ly())) return false;
  if (lattice_) {
    return lattice_->points() == other.lattice_->points() &&
           lattice_->generator() == other.lattice_->generator();
  }
  return grid_.nx == other.grid_.nx && grid_.ny == other.grid_.ny;
}

}  // namespace swell::reference
