#include "swell/validation/stats/periodogram.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <string>
#include <map>
#include <memory>
#include <mutex>

#include "common/parallel_tasks.hpp"
#include "swell/impls/transform.hpp"

namespace swell::validation {
namespace {

using reference::Grid;
using Complex = std::complex<double>;

// fp64 FFTW plans by (nx, ny, kind, direction), made once: estimate planning, as analysis runs
// on arbitrary sizes and must not pay MEASURE's planning cost.
const impls::Plan& analysis_plan(int nx, int ny, impls::Kind kind, impls::Direction direction) {
  static std::mutex mutex;
  static const auto backend = impls::make_backend(kAnalysisBackend);
  static std::map<std::tuple<int, int, impls::Kind, impls::Direction>, std::unique_ptr<impls::Plan>>
      plans;
  const std::lock_guard lock(mutex);
  auto& plan = plans[{nx, ny, kind, direction}];
  if (!plan) {
    impls::TransformSpec spec;
    spec.nx = nx;
    spec.ny = ny;
    spec.kind = kind;
    spec.direction = direction;
    spec.precision = impls::Precision::f64;
    plan = backend->plan(spec);
  }
  return *plan;
}

// An aligned scratch array of the calling thread, kept between calls, that each transform
// writes its input into and transforms over itself. FFTW's plans want the alignment they were
// planned with (else execute() goes through aligned copies), and a fresh multi-megabyte array
// costs its page faults again on every call: at 512² they took as long as the transform.
// Arrays above kKeepBytes are freed after use instead of kept.
constexpr std::size_t kKeepBytes = std::size_t(64) << 20;

// KeepAnalysisScratch guards alive on this thread: while any is, nothing is freed.
thread_local int keep_guards = 0;

class Scratch {
 public:
  // Not zeroed: every call writes the input whole before the transform.
  void* get(std::size_t bytes) {
    if (!buffer_ || buffer_->bytes() < bytes) buffer_ = std::make_unique<impls::HostBuffer>(bytes, impls::HostBuffer::Fill::none);
    return buffer_->host_data();
  }
  void release_if_large() {
    if (keep_guards == 0 && buffer_ && buffer_->bytes() > kKeepBytes) buffer_.reset();
  }

 private:
  std::unique_ptr<impls::HostBuffer> buffer_;
};

Scratch& scratch() {
  thread_local Scratch buffer;
  return buffer;
}

}  // namespace

// A c2c transform of the real field, not r2c with the other half filled in as conjugates: the
// Hermitian check measures how far ĥ(−k) is from conj ĥ(k), which r2c would make 0 by
// construction. (r2c measured 20 % faster at 512²; the scratch arrays gained 3–5×.)
namespace {
// X, the unnormalised transform of `field`, into `out` (count entries, FFTW's planned alignment
// or execute() copies); with `energy`, Σ|X(k)|²/N too (the order and precision of
// check_parseval's sum). The field is written into `out` as the transform's input and
// transformed over itself: no input array besides it, the same bits.
void transform_into(const std::vector<double>& field, const Grid& grid, Complex* out, long double* energy) {
  const std::size_t count = std::size_t(grid.nx) * grid.ny;
  if (field.size() != count) {
    throw InvalidInput("field of " + std::to_string(field.size()) + " values for a grid of " +
                       std::to_string(grid.nx) + "×" + std::to_string(grid.ny));
  }
  std::copy(field.begin(), field.end(), out);
  analysis_plan(grid.nx, grid.ny, impls::Kind::c2c, impls::Direction::forward).execute_over_input(out);
  if (energy) {
    long double sum = 0;
    for (std::size_t e = 0; e < count; ++e) sum += std::norm(out[e]);
    *energy = sum / (long double)count;
  }
}

// X in the calling thread's scratch().
const Complex* transform_into_scratch(const std::vector<double>& field, const Grid& grid,
                                      long double* energy) {
  auto* out = static_cast<Complex*>(scratch().get(std::size_t(grid.nx) * grid.ny * sizeof(Complex)));
  transform_into(field, grid, out, energy);
  return out;
}

// X straight into `spectrum`, then divided there by N: the same bits as X made in scratch()
// and copied out, without the scratch array.
void spectrum_into(const std::vector<double>& field, const Grid& grid,
                   std::vector<std::complex<double>>& spectrum, long double* energy = nullptr) {
  const std::size_t count = std::size_t(grid.nx) * grid.ny;
  spectrum.resize(count);
  transform_into(field, grid, spectrum.data(), energy);
  const double scale = 1.0 / double(count);
  for (std::size_t e = 0; e < count; ++e) spectrum[e] *= scale;
  release_analysis_scratch();
}
}  // namespace

std::vector<std::complex<double>> field_spectrum(const std::vector<double>& field,
                                                 const Grid& grid) {
  std::vector<std::complex<double>> spectrum;
  spectrum_into(field, grid, spectrum);
  return spectrum;
}

namespace {

// The inverse transform of what `fill` writes into the calling thread's scratch, over it.
// With `imaginary_field`, the imaginary part into it (two fields packed in one transform).
void field_from_filled_spectrum(const Grid& grid, const std::function<void(std::span<Complex>)>& fill,
                                std::vector<double>& field, std::vector<double>* imaginary_field = nullptr) {
  const std::size_t count = std::size_t(grid.nx) * grid.ny;
  auto* out = static_cast<Complex*>(scratch().get(count * sizeof(Complex)));
  fill({out, count});
  analysis_plan(grid.nx, grid.ny, impls::Kind::c2c, impls::Direction::inverse).execute_over_input(out);
  field.resize(count);
  for (std::size_t i = 0; i < count; ++i) field[i] = out[i].real();
  if (imaginary_field) {
    imaginary_field->resize(count);
    for (std::size_t i = 0; i < count; ++i) (*imaginary_field)[i] = out[i].imag();
  }
  scratch().release_if_large();
}

void field_from_spectrum_into(const std::vector<std::complex<double>>& spectrum, const Grid& grid,
                              std::vector<double>& field) {
  const std::size_t count = std::size_t(grid.nx) * grid.ny;
  if (spectrum.size() != count) throw InvalidInput("spectrum size does not match the grid");
  field_from_filled_spectrum(grid, [&](std::span<Complex> in) {
    std::copy(spectrum.begin(), spectrum.end(), in.begin());
  }, field);
}

}  // namespace

std::vector<double> field_from_spectrum(const std::vector<std::complex<double>>& spectrum,
                                        const Grid& grid) {
  std::vector<double> field;
  field_from_spectrum_into(spectrum, grid, field);
  return field;
}

bool in_half_plane(int n, int m) { return m > 0 || (m == 0 && n > 0); }

std::vector<double> expected_travelling_power(const reference::DirectionalSpectrum& spectrum,
                                              const Grid& grid, int threads) {
  std::vector<double> power(std::size_t(grid.nx) * grid.ny, 0.0);
  const double dk2 = grid.dkx() * grid.dky();
  // Rows in blocks of 16 on up to `threads` threads (models are immutable once built).
  constexpr int kRowsPerTask = 16;
  detail::run_tasks(std::size_t((grid.ny + kRowsPerTask - 1) / kRowsPerTask), threads, [&](std::size_t task) {
    for (int j = int(task) * kRowsPerTask; j < std::min(grid.ny, int(task + 1) * kRowsPerTask); ++j) {
      const int m = Grid::signed_index(j, grid.ny);
      for (int i = 0; i < grid.nx; ++i) {
        const int n = Grid::signed_index(i, grid.nx);
        if (!grid.carries_energy(n, m)) continue;
        // Where Ψ vanishes τ is 0 even when Δk² overflows (a 1e-300 m patch), as
        // summarize_sampling skips it.
        const double psi = spectrum.psi(n * grid.dkx(), m * grid.dky());
        if (psi != 0) power[std::size_t(j) * grid.nx + i] = 0.5 * psi * dk2;
      }
    }
  });
  return power;
}

std::vector<double> expected_periodogram(const std::vector<double>& travelling, const Grid& grid) {
  if (travelling.size() != std::size_t(grid.nx) * grid.ny) {
    throw InvalidInput("travelling power size does not match the grid");
  }
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

std::vector<double> expected_periodogram(const reference::DirectionalSpectrum& spectrum,
                                         const Grid& grid) {
  return expected_periodogram(expected_travelling_power(spectrum, grid), grid);
}

// A lattice's samples are one 1-D sequence over n: its analysis is the grid's with nx = N, ny = 1.
namespace {
Grid transform_shape(const reference::Sampling& sampling) {
  if (!sampling.is_lattice()) return sampling.grid();
  const auto points = sampling.lattice()->points();
  if (points > std::numeric_limits<int>::max()) {
    throw InvalidInput("a lattice of " + std::to_string(points) +
                       " points is beyond the analysis transform (at most 2^31 − 1)");
  }
  return Grid{static_cast<int>(points), 1, sampling.lx(), sampling.ly()};
}
}  // namespace

std::vector<std::complex<double>> field_spectrum(const std::vector<double>& field,
                                                 const reference::Sampling& sampling) {
  return field_spectrum(field, transform_shape(sampling));
}

void field_spectrum(const std::vector<double>& field, const reference::Sampling& sampling,
                    std::vector<std::complex<double>>& spectrum, long double* energy) {
  spectrum_into(field, transform_shape(sampling), spectrum, energy);
}

std::span<const std::complex<double>> analysis_transform(const std::vector<double>& field,
                                                         const reference::Sampling& sampling,
                                                         long double* energy) {
  return {transform_into_scratch(field, transform_shape(sampling), energy), field.size()};
}

KeepAnalysisScratch::KeepAnalysisScratch() { ++keep_guards; }
KeepAnalysisScratch::~KeepAnalysisScratch() { --keep_guards; }

void release_analysis_scratch() {
  scratch().release_if_large();
}

std::vector<double> field_from_spectrum(const std::vector<std::complex<double>>& spectrum,
                                        const reference::Sampling& sampling) {
  return field_from_spectrum(spectrum, transform_shape(sampling));
}

void field_from_spectrum(const std::vector<std::complex<double>>& spectrum,
                         const reference::Sampling& sampling, std::vector<double>& field) {
  field_from_spectrum_into(spectrum, transform_shape(sampling), field);
}

void field_from_spectrum(const reference::Sampling& sampling,
                         const std::function<void(std::span<std::complex<double>>)>& fill,
                         std::vector<double>& field) {
  field_from_filled_spectrum(transform_shape(sampling), fill, field);
}

void fields_from_spectrum(const reference::Sampling& sampling,
                          const std::function<void(std::span<std::complex<double>>)>& fill,
                          std::vector<double>& real_field, std::vector<double>& imaginary_field) {
  field_from_filled_spectrum(transform_shape(sampling), fill, real_field, &imaginary_field);
}

InverseTransformArrays::InverseTransformArrays() = default;
InverseTransformArrays::~InverseTransformArrays() = default;

std::span<const std::complex<double>> inverse_transform(
    const reference::Sampling& sampling, InverseTransformArrays& arrays,
    const std::function<void(std::span<std::complex<double>>)>& fill) {
  const Grid grid = transform_shape(sampling);
  const std::size_t count = std::size_t(grid.nx) * grid.ny;
  const std::size_t bytes = count * sizeof(Complex);
  if (!arrays.data_ || arrays.data_->bytes() != bytes) {
    arrays.data_ = std::make_unique<impls::HostBuffer>(bytes, impls::HostBuffer::Fill::none);
  }
  auto* data = static_cast<Complex*>(arrays.data_->host_data());
  fill({data, count});
  analysis_plan(grid.nx, grid.ny, impls::Kind::c2c, impls::Direction::inverse).execute_over_input(data);
  return {data, count};
}

std::vector<double> expected_travelling_power(const reference::DirectionalSpectrum& spectrum,
                                              const reference::Sampling& sampling, int threads) {
  if (!sampling.is_lattice()) return expected_travelling_power(spectrum, sampling.grid(), threads);
  std::vector<double> power(sampling.size(), 0.0);
  const double dk2 = sampling.dkx() * sampling.dky();
  for (std::size_t c = 0; c < power.size(); ++c) {
    if (!sampling.carries_energy(c)) continue;
    const auto [n, m] = sampling.wave_index(c);
    const double psi = spectrum.psi(n * sampling.dkx(), m * sampling.dky());
    if (psi != 0) power[c] = 0.5 * psi * dk2;
  }
  return power;
}

std::vector<double> expected_periodogram(const std::vector<double>& travelling,
                                         const reference::Sampling& sampling) {
  if (!sampling.is_lattice()) return expected_periodogram(travelling, sampling.grid());
  if (travelling.size() != sampling.size()) {
    throw InvalidInput("travelling power size does not match the sampling");
  }
  std::vector<double> mu(travelling.size(), 0.0);
  for (std::size_t c = 0; c < mu.size(); ++c) mu[c] = travelling[c] + travelling[sampling.conjugate(c)];
  return mu;
}

std::vector<double> expected_periodogram(const reference::DirectionalSpectrum& spectrum,
                                         const reference::Sampling& sampling) {
  return expected_periodogram(expected_travelling_power(spectrum, sampling), sampling);
}

}  // namespace swell::validation
