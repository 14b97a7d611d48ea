#include "swell/impls/synthesizer.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numbers>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "device_frame.hpp"
#include "synthesis/amplitudes.hpp"
#include "synthesis/four_step.hpp"
#include "synthesis/kernels.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/phase.hpp"
#include "swell/reference/wave_noise.hpp"

namespace swell::impls {
namespace {

using reference::Field;
using reference::Grid;
using reference::OceanCase;

// Classes of a lattice's row per assembly task: the task's scratch (h̃, 8 bytes a class in fp32,
// 16 in fp64) stays in L1/L2.
constexpr int kLatticeBlock = 4096;

using synthesis::amplitude;
using synthesis::assemble_lattice_row;
using synthesis::assemble_row;
using synthesis::FourStep;
using synthesis::kComplexPairs;
using synthesis::kRealFields;
using synthesis::RowTask;
using synthesis::unpack_range;
using synthesis::UnpackTask;
using synthesis::Waves;

// Packing::automatic. Frame CPU time, complex_pairs / real, ms (docs/synthesis.md: medians
// of 5 in one run of bench/frame_bench.cpp, 2026-11-22, 2-core AMD EPYC VM, one thread):
//            fp32 512²   1024²       2048²      fp64 512²   1024²       2048²
//   fftw     4.98/4.70   20.6/45.3   93.8/200        8.44/10.1   35.2/77.7   167/297
//   radix2   4.07/7.96   20.0/31.1   89.3/278        6.69/12.8   34.8/87.0   165/420
// complex_pairs is 1.2× to 3× faster everywhere except fftw fp32 512², a tie (real/pairs 0.94
// here, 1.19 in a second run): radix2 (like naive) runs a c2r through a full complex transform,
// and FFTW destroys the input of a multi-dimensional c2r, so the fftw backend runs it on a
// fresh copy each time (FFTW's own eight c2r cost about what its four c2c do). Both packings
// compute the same N²/2 phases. real would pay only on a backend whose c2r costs less than half
// its c2c and needs no copy; none has one, so there is nothing to choose.
Packing automatic_packing(const Backend&) { return Packing::complex_pairs; }

}  // namespace




struct Synthesizer::State {
  OceanCase ocean_case;
  SynthesizerOptions options;
  Packing packing = Packing::complex_pairs;
  std::unique_ptr<Backend> backend;
  TransformSpec spec;          // the batch of inverse transforms of a frame
  std::unique_ptr<Plan> plan;  // its plan (host backends; a device frame builds its own program)
  int nx = 0, ny = 0;
  int half_columns = 0;       // nx/2 + 1: the half spectrum the waves are stored for
  int spectrum_columns = 0;   // of the spectra the transforms take: nx (c2c) or nx/2 + 1 (c2r)
  std::vector<double> omega;  // per half-spectrum entry
  double max_omega = 0;
  // Each of the eight real fields is synthesized times a power of two that brings its rms near
  // 1, and unpack divides it out (exactly). Two fields share a complex transform, whose
  // rounding is relative to the pair's larger field: unscaled, a patch of 0.5 m (|k| ~ 100
  // rad/m) puts slopes 100× above heights and displacements, and the smaller field of a pair
  // is off by 100 u; λ = 1e-18 leaves a displacement below its partner's rounding. Scaled, every
  // field carries its own precision (found by the property test of the command line). A field
  // that is zero by definition (λ = 0) gets inverse scale 0: its output is exactly 0, not its
  // partner's rounding.
  std::array<double, kRealFields> field_scale{}, inverse_scale{};
  std::array<float, kRealFields> field_scale32{}, inverse_scale32{};
  Waves<float> waves32;       // fp32 synthesizers
  Waves<double> waves64;      // fp64 synthesizers
  std::vector<float> kx32, ky32;  // per column of a full row (FFT order), per row
  std::vector<double> kx64, ky64;
  // A lattice case is one row of N classes (nx = N, ny = 1), class m at column m with its own
  // ky (ky_column, N entries; empty on grids): its frame is 1-D transforms of size N.
  bool lattice = false;
  std::vector<float> ky_column32;
  std::vector<double> ky_column64;
  // The packed spectra, and the fields the transforms make of them (the same buffer when the
  // backend transforms in place). Host backends only.
  std::unique_ptr<Buffer> spectra, transformed_storage;
  // A device-resident backend's frame (device_frame.hpp), which holds the waves on the device
  // and records the transforms of `spec` into its own submission.
  std::unique_ptr<DeviceFrame> device_frame;
  // A lattice frame's four-step transform (empty: one-pass 1-D plans, and on grids).
  std::unique_ptr<FourStep> four_step;
  Buffer& transformed() const { return transformed_storage ? *transformed_storage : *spectra; }

  std::size_t real_bytes() const { return real_size(options.precision); }

  template <typename Real>
  const Waves<Real>& waves() const {
    if constexpr (std::is_same_v<Real, float>) return waves32; else return waves64;
  }
  template <typename Real>
  const Real* scales(bool inverse) const {
    if constexpr (std::is_same_v<Real, float>) {
      return inverse ? inverse_scale32.data() : field_scale32.data();
    } else {
      return inverse ? inverse_scale.data() : field_scale.data();
    }
  }
  template <typename Real>
  const std::vector<Real>& kx() const {
    if constexpr (std::is_same_v<Real, float>) return kx32; else return kx64;
  }
  template <typename Real>
  const std::vector<Real>& ky() const {
    if constexpr (std::is_same_v<Real, float>) return ky32; else return ky64;
  }
  template <typename Real>
  const std::vector<Real>& ky_column() const {
    if constexpr (std::is_same_v<Real, float>) return ky_column32; else return ky_column64;
  }
  // The signed wave index (n, m) of half-spectrum entry (i, j) and whether it carries energy.
  std::array<int, 2> wave_index(int i, int j) const {
    if (lattice) {
      const auto k = ocean_case.lattice->wave_vector(i);
      return {k[0], k[1]};
    }
    return {Grid::signed_index(i, nx), Grid::signed_index(j, ny)};
  }
  bool carries_energy(int i, int j) const {
    if (lattice) return ocean_case.lattice->carries_energy(i);
    const auto [n, m] = wave_index(i, j);
    return ocean_case.grid.carries_energy(n, m);
  }
  template <typename Real>
  void fill_waves(Waves<Real>& waves);
  template <typename Real>
  void make_device_frame();
  template <typename Real>
  void assemble(double t) const;
  template <typename Real>
  bool unpack(std::byte* fields) const;  // false when some value is not finite
  std::string describe_non_finite(double t, std::span<const std::byte> fields) const;
};

Synthesizer::Synthesizer(OceanCase ocean_case, SynthesizerOptions options)
    : state_(std::make_unique<State>()) {
  ocean_case.validate();
  auto& s = *state_;
  s.ocean_case = std::move(ocean_case);
  s.options = std::move(options);
  require(s.options.threads >= 1, "synthesizer threads", "≥ 1", s.options.threads);
  if (s.options.precision == Precision::f80) {
    throw InvalidInput("the synthesizer runs in fp32 or fp64, not fp80");
  }
  s.backend = make_backend(s.options.backend);
  s.packing = s.options.packing == Packing::automatic ? automatic_packing(*s.backend)
                                                      : s.options.packing;
  if (s.packing == Packing::real && !s.backend->capabilities().real_transforms) {
    throw InvalidInput("backend " + s.backend->name() + " has no c2r transform; use packing complex_pairs");
  }
  const Grid& grid = s.ocean_case.grid;
  s.lattice = s.ocean_case.is_lattice();
  if (s.lattice) {
    const auto points = s.ocean_case.lattice->points();
    if (points > std::numeric_limits<int>::max()) {
      throw InvalidInput(fmt::format("a lattice of {} points is beyond the synthesizer's "
                                     "transforms (at most 2^31 − 1 points)", points));
    }
    s.nx = static_cast<int>(points);
    s.ny = 1;
  } else {
    s.nx = grid.nx;
    s.ny = grid.ny;
  }
  s.half_columns = s.nx / 2 + 1;

  TransformSpec spec;
  spec.nx = s.nx;
  spec.ny = s.ny;
  spec.precision = s.options.precision;
  spec.direction = Direction::inverse;
  if (s.packing == Packing::complex_pairs) {
    spec.kind = Kind::c2c;
    spec.howmany = kComplexPairs;
    spec.placement = s.backend->capabilities().in_place ? Placement::in_place : Placement::out_of_place;
    s.spectrum_columns = s.nx;
  } else {
    spec.kind = Kind::c2r;
    spec.howmany = kRealFields;
    s.spectrum_columns = s.half_columns;
  }
  s.spec = spec;
  // A device backend's fused frame (device_frame.hpp) is built for grids; a lattice frame
  // assembles on the host and runs the device's 1-D transforms through host memory.
  const bool on_device = s.backend->capabilities().device_resident && !s.lattice;
  // The backend's rules before the waves are computed (seconds for a large grid): a device
  // frame builds its program after them.
  s.backend->validate(spec);
  // A four-step lattice frame needs no plan of size N (FFTW measures one for half a minute
  // at 2^20 points).
  if (s.lattice && !on_device) {
    s.four_step = FourStep::make(s.options.lattice_transform, *s.backend, spec, s.packing);
  }
  if (!on_device) {
    if (!s.four_step) s.plan = s.backend->plan(spec);
    if (s.backend->capabilities().device_resident) {
      s.spectra = std::make_unique<HostBuffer>(spec.input_bytes());
      s.transformed_storage = std::make_unique<HostBuffer>(spec.output_bytes());
    } else {
      s.spectra = s.backend->allocate(spec.input_bytes());
      if (spec.placement == Placement::out_of_place) {
        s.transformed_storage = s.backend->allocate(spec.output_bytes());
      }
    }
  }

  s.kx64.resize(s.nx);
  s.ky64.resize(s.ny);
  if (s.lattice) {
    s.ky_column64.resize(s.nx);
    for (int i = 0; i < s.nx; ++i) {
      const auto [n, m] = s.wave_index(i, 0);
      s.kx64[i] = n * grid.dkx();
      s.ky_column64[i] = m * grid.dky();
    }
    s.ky_column32.assign(s.ky_column64.begin(), s.ky_column64.end());
  } else {
    for (int i = 0; i < s.nx; ++i) s.kx64[i] = Grid::signed_index(i, s.nx) * grid.dkx();
    for (int j = 0; j < s.ny; ++j) s.ky64[j] = Grid::signed_index(j, s.ny) * grid.dky();
  }
  s.kx32.assign(s.kx64.begin(), s.kx64.end());
  s.ky32.assign(s.ky64.begin(), s.ky64.end());
  if (s.options.precision == Precision::f32) s.fill_waves(s.waves32); else s.fill_waves(s.waves64);
  if (on_device) {
    if (s.options.precision == Precision::f32) s.make_device_frame<float>(); else s.make_device_frame<double>();
  }
}

// The waves go to the device once; the host's copies are then never read again and are freed
// (max_omega, which evaluate() checks times against, is kept).
template <typename Real>
void Synthesizer::State::make_device_frame() {
#ifdef SWELL_HAVE_VULKAN
  const auto& w = waves<Real>();
  DeviceFrameTables tables;
  tables.precision = options.precision;
  tables.pairs = packing == Packing::complex_pairs;
  tables.nx = nx;
  tables.ny = ny;
  tables.a_re = w.a_re.data();
  tables.a_im = w.a_im.data();
  tables.b_re = w.b_re.data();
  tables.b_im = w.b_im.data();
  tables.omega = omega.data();
  tables.choppiness = ocean_case.choppiness;
  tables.dkx = ocean_case.grid.dkx();
  tables.dky = ocean_case.grid.dky();
  tables.field_scale = scales<Real>(false);
  tables.inverse_scale = scales<Real>(true);
  device_frame = make_vulkan_frame(*backend, spec, tables);
  if constexpr (std::is_same_v<Real, float>) waves32 = {}; else waves64 = {};
  std::vector<double>().swap(omega);
#else
  throw InternalError("backend " + backend->name() + " is device resident in a build without Vulkan");
#endif
}



template <typename Real>
void Synthesizer::State::fill_waves(Waves<Real>& waves) {
  const auto spectrum = ocean_case.sea_spectrum();  // amplitude() applies band weights
  const std::size_t entries = std::size_t(half_columns) * ny;
  waves.resize(entries);
  omega.assign(entries, 0.0);
  const double lambda = ocean_case.choppiness;
#pragma omp parallel for num_threads(options.threads) schedule(dynamic, 4)
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < half_columns; ++i) {
      const auto [n, m] = wave_index(i, j);
      const std::size_t e = std::size_t(j) * half_columns + i;
      if (!carries_energy(i, j)) continue;  // a = b = 0, and ω = 0 keeps the phase finite
      const double k = std::hypot(kx64[i], lattice ? ky_column64[i] : ky64[j]);
      const auto a = amplitude(*spectrum, ocean_case, n, m);
      const auto b = std::conj(amplitude(*spectrum, ocean_case, -n, -m));
      waves.a_re[e] = Real(a.real());
      waves.a_im[e] = Real(a.imag());
      waves.b_re[e] = Real(b.real());
      waves.b_im[e] = Real(b.imag());
      waves.lambda_over_k[e] = Real(lambda / k);
      omega[e] = ocean_case.omega(k);
    }
  }
  for (double w : omega) max_omega = std::max(max_omega, std::abs(w));

  // The variance of each field (up to a common factor: half-spectrum entries stand for their
  // mirror too), from the waves' power and the fields' multipliers (field_spectra).
  std::array<double, kRealFields> variance{};
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < half_columns; ++i) {
      const double ky = lattice ? ky_column64[i] : ky64[j];
      const std::size_t e = std::size_t(j) * half_columns + i;
      const double power = double(waves.a_re[e]) * double(waves.a_re[e]) +
                           double(waves.a_im[e]) * double(waves.a_im[e]) +
                           double(waves.b_re[e]) * double(waves.b_re[e]) +
                           double(waves.b_im[e]) * double(waves.b_im[e]);
      if (power == 0) continue;
      const double kx = kx64[i], lk = double(waves.lambda_over_k[e]);
      const double multipliers[kRealFields] = {1, kx, ky, lk * kx, lk * ky,
                                               lk * kx * kx, lk * ky * ky, lk * kx * ky};
      for (int r = 0; r < kRealFields; ++r) variance[r] += multipliers[r] * multipliers[r] * power;
    }
  }
  for (int r = 0; r < kRealFields; ++r) {
    const double rms = std::sqrt(variance[r]);
    if (rms > 0 && std::isfinite(rms)) {
      field_scale[r] = std::ldexp(1.0, -std::ilogb(rms));
      inverse_scale[r] = std::ldexp(1.0, std::ilogb(rms));
    } else {
      field_scale[r] = 1;
      inverse_scale[r] = rms == 0 ? 0 : 1;
    }
    field_scale32[r] = float(field_scale[r]);
    inverse_scale32[r] = float(inverse_scale[r]);
  }
}

// The message of a frame with a non-finite value: which field, where, and the case — a case
// that passed its validity rule (reference/sampling_validity.hpp) never makes one.
std::string Synthesizer::State::describe_non_finite(double t,
                                                    std::span<const std::byte> fields) const {
  const State& s = *this;
  const std::size_t count = std::size_t(s.nx) * s.ny;
  const bool f32 = s.options.precision == Precision::f32;
  for (std::size_t f = 0; f < reference::kAllFields.size(); ++f) {
    for (std::size_t p = 0; p < count; ++p) {
      const std::size_t at = f * count + p;
      const double v = f32 ? double(reinterpret_cast<const float*>(fields.data())[at])
                           : reinterpret_cast<const double*>(fields.data())[at];
      if (std::isfinite(v)) continue;
      return fmt::format("the synthesizer made {} = {} at {}, t = {:g} s, {} {}, "
                         "for the case {}; the frame is not written",
                         reference::field_name(reference::kAllFields[f]), v,
                         s.lattice ? fmt::format("lattice point n = {}", p)
                                   : fmt::format("(i, j) = ({}, {})", p % s.nx, p / s.nx),
                         t, s.backend->name(), to_string(s.options.precision),
                         s.ocean_case.describe());
    }
  }
  return "the synthesizer's output check found a non-finite value it cannot locate";
}

Synthesizer::~Synthesizer() = default;

const OceanCase& Synthesizer::ocean_case() const { return state_->ocean_case; }
const SynthesizerOptions& Synthesizer::options() const { return state_->options; }
Packing Synthesizer::packing() const { return state_->packing; }
std::array<int, 2> Synthesizer::four_step_factors() const {
  if (!state_->four_step) return {0, 0};
  return {state_->four_step->n1(), state_->four_step->n2()};
}

std::vector<TransformSpec> Synthesizer::transforms_per_frame() const {
  return {state_->spec};
}

std::uint64_t Synthesizer::bytes_needed(const reference::Grid& grid, Precision precision) {
  // Per sample, in reals p of the precision: the four packed spectra (8p) and, out of place,
  // their transforms (8p); the frame (6p); the half spectrum's waves (5p/2) and ω (4 bytes);
  // the frame converted to double (48 bytes). Counted in double: a grid of 2²⁰ × 2²⁰ overflows
  // nothing here.
  const double p = double(real_size(precision));
  const double per_sample = 24.5 * p + 4 + 48;
  const double bytes = double(grid.nx) * double(grid.ny) * per_sample;
  return bytes >= 1.8e19 ? std::uint64_t(1.8e19) : std::uint64_t(bytes);
}

std::size_t Synthesizer::frame_bytes() const {
  return reference::kAllFields.size() * std::size_t(state_->nx) * state_->ny *
         state_->real_bytes();
}

// Row by row of the half spectrum; with complex_pairs each row also fills the right half
// (columns nx/2 + 1 … nx − 1) of its mirror row (ny − j) mod ny. Every entry is written by
// exactly one row, computed the same way whatever the thread count.
template <typename Real>
void Synthesizer::State::assemble(double t) const {
  const std::size_t plane = 2 * std::size_t(spectrum_columns) * ny;  // Reals per spectrum
  auto* out = static_cast<Real*>(spectra->host_data());
  const auto& w = waves<Real>();
  const auto& kxs = kx<Real>();
  const auto& kys = ky<Real>();
  const bool pairs = packing == Packing::complex_pairs;
  // A grid's task is one half row; a lattice's one block of its single row's classes: its
  // scratch then stays small (a whole row's at 2^22 points is 48 MB, beyond glibc's mmap
  // threshold, so every frame faulted in fresh zeroed pages: docs/lattice.md) and the threads
  // share the row.
  const int columns_per_task = lattice ? std::min(half_columns, kLatticeBlock) : half_columns;
#pragma omp parallel num_threads(options.threads)
  {
    std::vector<Real> h(2 * std::size_t(columns_per_task));
    RowTask<Real> task;
    task.width = half_columns;
    task.nx = nx;
    task.begin = 0;
    task.end = half_columns;
    task.pairs = pairs;
    task.t = t;
    task.kx = kxs.data();
    task.plane = plane;
    task.h_re = h.data();
    task.h_im = h.data() + columns_per_task;
    task.field_scale = scales<Real>(false);
    if (lattice) {
      task.ky_column = ky_column<Real>().data();
      task.omega = omega.data();
      task.a_re = w.a_re.data();
      task.a_im = w.a_im.data();
      task.b_re = w.b_re.data();
      task.b_im = w.b_im.data();
      task.lambda_over_k = w.lambda_over_k.data();
      task.out = out;
      task.out_mirror = out;
      const int blocks = (half_columns + kLatticeBlock - 1) / kLatticeBlock;
#pragma omp for schedule(static)
      for (int b = 0; b < blocks; ++b) {
        task.begin = b * kLatticeBlock;
        task.end = std::min(half_columns, task.begin + kLatticeBlock);
        assemble_lattice_row(task);
      }
    }
#pragma omp for schedule(static)
    for (int j = 0; j < (lattice ? 0 : ny); ++j) {
      const int mirror = (ny - j) % ny;
      const std::size_t e = std::size_t(j) * half_columns;
      task.omega = omega.data() + e;
      task.a_re = w.a_re.data() + e;
      task.a_im = w.a_im.data() + e;
      task.b_re = w.b_re.data() + e;
      task.b_im = w.b_im.data() + e;
      task.lambda_over_k = w.lambda_over_k.data() + e;
      task.ky = kys[j];
      task.ky_mirror = kys[mirror];
      task.out = out + 2 * std::size_t(j) * spectrum_columns;
      task.out_mirror = out + 2 * std::size_t(mirror) * spectrum_columns;
      assemble_row(task);
    }
  }
}

template <typename Real>
bool Synthesizer::State::unpack(std::byte* fields) const {
  const std::size_t count = std::size_t(nx) * ny;
  UnpackTask<Real> task;
  task.pairs = packing == Packing::complex_pairs;
  task.data = static_cast<const Real*>(transformed().host_data());
  task.count = count;
  task.data_plane = count;
  task.fields = reinterpret_cast<Real*>(fields);
  task.inverse_scale = scales<Real>(true);
  // Blocks of whole rows, a few per thread.
  const std::size_t block = ny == 1 ? 4096 : std::size_t(nx) * std::max(1, 4096 / nx);
  const std::ptrdiff_t blocks = std::ptrdiff_t((count + block - 1) / block);
  double probe = 0;
#pragma omp parallel for num_threads(options.threads) schedule(static) firstprivate(task) \
    reduction(+ : probe)
  for (std::ptrdiff_t b = 0; b < blocks; ++b) {
    task.begin = std::size_t(b) * block;
    task.end = std::min(count, task.begin + block);
    probe += double(unpack_range(task));
  }
  return std::isfinite(probe);
}

void Synthesizer::evaluate(double t, std::span<std::byte> fields) const {
  (void)evaluate_timed(t, fields);
}

FrameTimings Synthesizer::evaluate_timed(double t, std::span<std::byte> fields) const {
  const auto& s = *state_;
  if (fields.size() < frame_bytes()) {
    throw InvalidInput("Synthesizer::evaluate: output of " + std::to_string(fields.size()) +
                       " bytes for a frame of " + std::to_string(frame_bytes()));
  }
  require(std::isfinite(t), "frame time", "finite (s)", t);
  if (s.max_omega * std::abs(t) > reference::kLargestPhase) {
    throw InvalidInput(fmt::format(
        "frame time {:g} s: the fastest wave's phase ω t = {:.3g} rad exceeds the {:.3g} rad a "
        "phase can carry to double precision (reference/phase.hpp); ω ≤ {:.4g} rad/s on this grid",
        t, s.max_omega * std::abs(t), reference::kLargestPhase, s.max_omega));
  }
  FrameTimings timings;
  if (s.device_frame) {
    if (s.device_frame->evaluate(t, fields, timings) != 0) {
      throw InternalError(s.describe_non_finite(t, fields));
    }
    return timings;
  }
  const bool f32 = s.options.precision == Precision::f32;
  if (f32) s.assemble<float>(t); else s.assemble<double>(t);
  if (s.four_step) {
    double probe = 0;
    void* spectra = s.spectra->host_data();
    if (f32) {
      s.four_step->transform<float>(spectra, s.options.threads);
      probe = s.four_step->unpack<float>(spectra, fields.data(), s.scales<float>(true),
                                         s.options.threads);
    } else {
      s.four_step->transform<double>(spectra, s.options.threads);
      probe = s.four_step->unpack<double>(spectra, fields.data(), s.scales<double>(true),
                                          s.options.threads);
    }
    if (!std::isfinite(probe)) throw InternalError(s.describe_non_finite(t, fields));
    return timings;
  }
  if (s.backend->capabilities().device_resident) {
    s.plan->execute(s.spectra->host_data(), s.transformed().host_data());  // a lattice
  } else {
    s.plan->execute(*s.spectra, s.transformed());
  }
  const bool finite = f32 ? s.unpack<float>(fields.data()) : s.unpack<double>(fields.data());
  if (!finite) throw InternalError(s.describe_non_finite(t, fields));
  return timings;
}

reference::FieldFrame Synthesizer::frame(double t) const {
  std::vector<std::byte> bytes(frame_bytes());
  evaluate(t, bytes);
  const std::size_t count = std::size_t(state_->nx) * state_->ny;
  reference::FieldFrame frame;
  frame.time = t;
  for (std::size_t f = 0; f < reference::kAllFields.size(); ++f) {
    auto& out = frame.fields[reference::kAllFields[f]];
    out.resize(count);
    if (state_->options.precision == Precision::f32) {
      const auto* in = reinterpret_cast<const float*>(bytes.data()) + f * count;
      std::copy(in, in + count, out.begin());
    } else {
      const auto* in = reinterpret_cast<const double*>(bytes.data()) + f * count;
      std::copy(in, in + count, out.begin());
    }
  }
  return frame;
}

reference::FrameSequence Synthesizer::frames() const {
  reference::FrameSequence sequence;
  sequence.grid = state_->ocean_case.grid;
  sequence.lattice = state_->ocean_case.lattice;
  sequence.unit_roundoff = state_->options.precision == Precision::f32 ? 0x1p-24 : 0x1p-53;
  for (int f = 0; f < state_->ocean_case.frames; ++f) {
    sequence.frames.push_back(frame(state_->ocean_case.time(f)));
  }
  return sequence;
}

}  // namespace swell::impls
