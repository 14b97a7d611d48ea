#include "swell/validation/periodogram.hpp"

#include <map>
#include <memory>
#include <mutex>

#include "swell/impls/transform.hpp"

namespace swell::validation {
namespace {

using reference::Grid;

// fp64 FFTW c2c plans by (nx, ny, direction), made once: estimate planning, as analysis runs
// on arbitrary sizes and must not pay MEASURE's planning cost.
const impls::Plan& analysis_plan(int nx, int ny, impls::Direction direction) {
  static std::mutex mutex;
  static const auto backend = impls::make_backend("fftw:planner=estimate");
  static std::map<std::tuple<int, int, impls::Direction>, std::unique_ptr<impls::Plan>> plans;
  const std::lock_guard lock(mutex);
  auto& plan = plans[{nx, ny, direction}];
  if (!plan) {
    impls::TransformSpec spec;
    spec.nx = nx;
    spec.ny = ny;
    spec.kind = impls::Kind::c2c;
    spec.direction = direction;
    spec.precision = impls::Precision::f64;
    plan = backend->plan(spec);
  }
  return *plan;
}

}  // namespace

std::vector<std::complex<double>> field_spectrum(const std::vector<double>& field,
                                                 const Grid& grid) {
  const std::size_t count = std::size_t(grid.nx) * grid.ny;
  if (field.size() != count) {
    throw InvalidInput("field of " + std::to_string(field.size()) + " values for a grid of " +
                       std::to_string(grid.nx) + "×" + std::to_string(grid.ny));
  }
  std::vector<std::complex<double>> in(field.begin(), field.end()), out(count);
  analysis_plan(grid.nx, grid.ny, impls::Direction::forward).execute(in.data(), out.data());
  const double scale = 1.0 / double(count);
  for (auto& value : out) value *= scale;
  return out;
}

std::vector<double> field_from_spectrum(const std::vector<std::complex<double>>& spectrum,
                                        const Grid& grid) {
  const std::size_t count = std::size_t(grid.nx) * grid.ny;
  if (spectrum.size() != count) throw InvalidInput("spectrum size does not match the grid");
  std::vector<std::complex<double>> out(count);
  analysis_plan(grid.nx, grid.ny, impls::Direction::inverse).execute(spectrum.data(), out.data());
  std::vector<double> field(count);
  for (std::size_t i = 0; i < count; ++i) field[i] = out[i].real();
  return field;
}

bool in_half_plane(int n, int m) { return m > 0 || (m == 0 && n > 0); }

std::vector<double> expected_travelling_power(const reference::DirectionalSpectrum& spectrum,
                                              const Grid& grid) {
  std::vector<double> power(std::size_t(grid.nx) * grid.ny, 0.0);
  const double dk2 = grid.dkx() * grid.dky();
  for (int j = 0; j < grid.ny; ++j) {
    const int m = Grid::signed_index(j, grid.ny);
    for (int i = 0; i < grid.nx; ++i) {
      const int n = Grid::signed_index(i, grid.nx);
      if (!grid.carries_energy(n, m)) continue;
      power[std::size_t(j) * grid.nx + i] = 0.5 * spectrum.psi(n * grid.dkx(), m * grid.dky()) * dk2;
    }
  }
  return power;
}

std::vector<double> expected_periodogram(const reference::DirectionalSpectrum& spectrum,
                                         const Grid& grid) {
  const auto travelling = expected_travelling_power(spectrum, grid);
  std::vector<double> mu(travelling.size(), 0.0);
  for (int j = 0; j < grid.ny; ++j) {
    const int jm = (grid.ny - j) % grid.ny;  // index of −m
    for (int i = 0; i < grid.nx; ++i) {
      const int im = (grid.nx - i) % grid.nx;
      mu[std::size_t(j) * grid.nx + i] =
          travelling[std::size_t(j) * grid.nx + i] + travelling[std::size_t(jm) * grid.nx + im];
    }
  }
  return mu;
}

}  // namespace swell::validation
