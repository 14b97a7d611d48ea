#include "swell/impls/synthesizer.hpp"

#include <omp.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "swell/reference/errors.hpp"
#include "swell/reference/wave_noise.hpp"

namespace swell::impls {
namespace {

using reference::Field;
using reference::Grid;
using reference::OceanCase;

// The eight real fields one frame needs, in the order they are packed: (h, ∂h/∂x),
// (∂h/∂y, λDx), (λDy, λ∂Dx/∂x), (λ∂Dy/∂y, λ∂Dx/∂y). The last three only feed J.
constexpr int kRealFields = 8;
constexpr int kComplexPairs = kRealFields / 2;

std::complex<double> amplitude(const reference::DirectionalSpectrum& spectrum,
                               const OceanCase& c, int n, int m) {
  if (!c.grid.carries_energy(n, m)) return 0.0;
  const double dkx = c.grid.dkx(), dky = c.grid.dky();
  const double psi = spectrum.psi(n * dkx, m * dky);
  const auto xi = reference::wave_noise(c.seed, n, m);
  // conventions §Amplitudes: (ξ1 + iξ2)/√2 · √(Ψ Δkx Δky / 2), so E|h̃0|² = ½ Ψ Δk².
  return std::complex<double>(xi.xi1, xi.xi2) * std::sqrt(0.5 * psi * dkx * dky * 0.5);
}

}  // namespace

std::string to_string(Packing packing) {
  switch (packing) {
    case Packing::complex_pairs: return "complex_pairs";
    case Packing::real: return "real";
    case Packing::automatic: return "automatic";
  }
  return "?";
}

Packing packing_from_string(const std::string& name) {
  if (name == "complex_pairs") return Packing::complex_pairs;
  if (name == "real") return Packing::real;
  if (name == "automatic") return Packing::automatic;
  throw InvalidInput("unknown packing '" + name + "'; valid: complex_pairs, real, automatic");
}

std::complex<double> initial_amplitude(const OceanCase& ocean_case, int n, int m) {
  return amplitude(*ocean_case.directional_spectrum(), ocean_case, n, m);
}

// What does not change from frame to frame, per wave vector k in FFT order: the two waves
// a = h̃0(k) travelling along +k and b = conj(h̃0(−k)) along −k, and ω(|k|).
struct Synthesizer::State {
  OceanCase ocean_case;
  SynthesizerOptions options;
  Packing packing = Packing::complex_pairs;
  std::unique_ptr<Backend> backend;
  std::unique_ptr<Plan> plan;
  int nx = 0, ny = 0;
  // Rows of the spectra the transforms take: nx (c2c) or nx/2 + 1 (c2r).
  int spectrum_columns = 0;
  std::vector<std::complex<double>> forward_wave, backward_wave;  // a, b per spectrum entry
  std::vector<double> omega;
  std::vector<double> kx, ky, inverse_k;  // per column / per row, and 1/|k| per entry
  // The packed spectra, and the fields the transforms make of them (the same buffer when the
  // backend transforms in place).
  std::unique_ptr<Buffer> spectra, transformed_storage;
  Buffer& transformed() const { return transformed_storage ? *transformed_storage : *spectra; }

  std::size_t real_bytes() const { return real_size(options.precision); }

  template <typename Real>
  void assemble(double t) const;
  template <typename Real>
  void unpack(std::byte* fields) const;
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
  s.packing = s.options.packing == Packing::automatic ? Packing::complex_pairs : s.options.packing;
  if (s.packing == Packing::real && !s.backend->capabilities().real_transforms) {
    throw InvalidInput("backend " + s.backend->name() + " has no c2r transform; use packing complex_pairs");
  }
  const Grid& grid = s.ocean_case.grid;
  s.nx = grid.nx;
  s.ny = grid.ny;

  TransformSpec spec;
  spec.nx = grid.nx;
  spec.ny = grid.ny;
  spec.precision = s.options.precision;
  spec.direction = Direction::inverse;
  if (s.packing == Packing::complex_pairs) {
    spec.kind = Kind::c2c;
    spec.howmany = kComplexPairs;
    spec.placement = s.backend->capabilities().in_place ? Placement::in_place : Placement::out_of_place;
    s.spectrum_columns = grid.nx;
  } else {
    spec.kind = Kind::c2r;
    spec.howmany = kRealFields;
    s.spectrum_columns = grid.nx / 2 + 1;
  }
  s.plan = s.backend->plan(spec);
  s.spectra = s.backend->allocate(spec.input_bytes());
  if (spec.placement == Placement::out_of_place) {
    s.transformed_storage = s.backend->allocate(spec.output_bytes());
  }

  const auto spectrum = s.ocean_case.directional_spectrum();
  const std::size_t entries = std::size_t(s.spectrum_columns) * s.ny;
  s.forward_wave.assign(entries, 0.0);
  s.backward_wave.assign(entries, 0.0);
  s.omega.assign(entries, 0.0);
  s.inverse_k.assign(entries, 0.0);
  s.kx.resize(s.spectrum_columns);
  s.ky.resize(s.ny);
  for (int i = 0; i < s.spectrum_columns; ++i) s.kx[i] = Grid::signed_index(i, s.nx) * grid.dkx();
  for (int j = 0; j < s.ny; ++j) s.ky[j] = Grid::signed_index(j, s.ny) * grid.dky();

#pragma omp parallel for num_threads(s.options.threads) schedule(dynamic, 4)
  for (int j = 0; j < s.ny; ++j) {
    const int m = Grid::signed_index(j, s.ny);
    for (int i = 0; i < s.spectrum_columns; ++i) {
      const int n = Grid::signed_index(i, s.nx);
      const std::size_t e = std::size_t(j) * s.spectrum_columns + i;
      if (!grid.carries_energy(n, m)) continue;
      const double k = std::hypot(s.kx[i], s.ky[j]);
      s.forward_wave[e] = amplitude(*spectrum, s.ocean_case, n, m);
      s.backward_wave[e] = std::conj(amplitude(*spectrum, s.ocean_case, -n, -m));
      s.omega[e] = s.ocean_case.omega(k);
      s.inverse_k[e] = 1.0 / k;
    }
  }
}

Synthesizer::~Synthesizer() = default;

const OceanCase& Synthesizer::ocean_case() const { return state_->ocean_case; }
const SynthesizerOptions& Synthesizer::options() const { return state_->options; }
Packing Synthesizer::packing() const { return state_->packing; }

std::vector<TransformSpec> Synthesizer::transforms_per_frame() const {
  return {state_->plan->spec()};
}

std::size_t Synthesizer::frame_bytes() const {
  return reference::kAllFields.size() * std::size_t(state_->nx) * state_->ny *
         state_->real_bytes();
}

// h̃(k, t) = a e^(−iωt) + b e^(+iωt), times each field's multiplier (conventions §Derived
// fields, with λ in the displacement terms):
//   h: 1   ∂h/∂x: i kx   ∂h/∂y: i ky   λDx: iλ kx/k   λDy: iλ ky/k
//   λ∂Dx/∂x: −λ kx²/k   λ∂Dy/∂y: −λ ky²/k   λ∂Dx/∂y: −λ kx ky/k
// Packed as A + iB, two real fields per complex spectrum: the inverse transform of Â + iB̂
// with Â and B̂ Hermitian is a + ib, so its real and imaginary parts are the two fields.
template <typename Real>
void Synthesizer::State::assemble(double t) const {
  using Complex = std::complex<Real>;
  auto* out = static_cast<Complex*>(spectra->host_data());
  const std::size_t plane = std::size_t(spectrum_columns) * ny;
  const double lambda = ocean_case.choppiness;
  const bool pairs = packing == Packing::complex_pairs;
#pragma omp parallel for num_threads(options.threads) schedule(static)
  for (int j = 0; j < ny; ++j) {
    const double ky_j = ky[j];
    for (int i = 0; i < spectrum_columns; ++i) {
      const std::size_t e = std::size_t(j) * spectrum_columns + i;
      // Phase in double: ωt reaches 10⁴ rad and more over long runs.
      const double phase = omega[e] * t;
      const double c = std::cos(phase), s = std::sin(phase);
      const std::complex<double> h =
          forward_wave[e] * std::complex<double>(c, -s) + backward_wave[e] * std::complex<double>(c, s);
      const double kx_i = kx[i], lk = lambda * inverse_k[e];
      if (pairs) {
        out[e] = Complex(h * std::complex<double>(1.0 - kx_i, 0.0));
        out[plane + e] = Complex(h * std::complex<double>(-lk * kx_i, ky_j));
        out[2 * plane + e] = Complex(h * std::complex<double>(0.0, lk * ky_j - lk * kx_i * kx_i));
        out[3 * plane + e] = Complex(h * std::complex<double>(-lk * ky_j * ky_j, -lk * kx_i * ky_j));
      } else {
        const std::complex<double> ih(-h.imag(), h.real());  // i h̃
        out[e] = Complex(h);
        out[plane + e] = Complex(kx_i * ih);
        out[2 * plane + e] = Complex(ky_j * ih);
        out[3 * plane + e] = Complex(lk * kx_i * ih);
        out[4 * plane + e] = Complex(lk * ky_j * ih);
        out[5 * plane + e] = Complex(-lk * kx_i * kx_i * h);
        out[6 * plane + e] = Complex(-lk * ky_j * ky_j * h);
        out[7 * plane + e] = Complex(-lk * kx_i * ky_j * h);
      }
    }
  }
}

// The transformed spectra hold the eight real fields; copy the five output fields and form
// J = (1 + λ∂Dx/∂x)(1 + λ∂Dy/∂y) − (λ∂Dx/∂y)².
template <typename Real>
void Synthesizer::State::unpack(std::byte* fields) const {
  const std::size_t count = std::size_t(nx) * ny;
  Real* field[6];
  for (int f = 0; f < 6; ++f) field[f] = reinterpret_cast<Real*>(fields) + f * count;
  const bool pairs = packing == Packing::complex_pairs;
  const Real* data = static_cast<const Real*>(transformed().host_data());
  // Real field r (packing order) at sample p.
  auto value = [&](int r, std::size_t p) -> Real {
    return pairs ? data[2 * ((r / 2) * count + p) + (r % 2)] : data[r * count + p];
  };
#pragma omp parallel for num_threads(options.threads) schedule(static)
  for (std::ptrdiff_t p = 0; p < std::ptrdiff_t(count); ++p) {
    // Packing order h, ∂h/∂x, ∂h/∂y, λDx, λDy; output order h, sx, sy, dx, dy.
    for (int f = 0; f < 5; ++f) field[f][p] = value(f, p);
    const Real dxx = value(5, p), dyy = value(6, p), dxy = value(7, p);
    field[5][p] = (Real(1) + dxx) * (Real(1) + dyy) - dxy * dxy;
  }
}

void Synthesizer::evaluate(double t, std::span<std::byte> fields) const {
  const auto& s = *state_;
  if (fields.size() < frame_bytes()) {
    throw InvalidInput("Synthesizer::evaluate: output of " + std::to_string(fields.size()) +
                       " bytes for a frame of " + std::to_string(frame_bytes()));
  }
  require(std::isfinite(t), "frame time", "finite (s)", t);
  const bool f32 = s.options.precision == Precision::f32;
  if (f32) s.assemble<float>(t); else s.assemble<double>(t);
  s.plan->execute(*s.spectra, s.transformed());
  if (f32) s.unpack<float>(fields.data()); else s.unpack<double>(fields.data());
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
  sequence.unit_roundoff = state_->options.precision == Precision::f32 ? 0x1p-24 : 0x1p-53;
  for (int f = 0; f < state_->ocean_case.frames; ++f) {
    sequence.frames.push_back(frame(state_->ocean_case.time(f)));
  }
  return sequence;
}

}  // namespace swell::impls
