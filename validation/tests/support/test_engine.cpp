#include "test_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <span>

#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/wave_noise.hpp"
#include "swell/validation/stats/periodogram.hpp"

namespace swell::test {
namespace {

using reference::Dispersion;
using reference::Field;
using reference::Grid;
using reference::OceanCase;
using cplx = std::complex<double>;
constexpr cplx kI{0.0, 1.0};

struct BugName {
  EngineBug bug;
  const char* name;
};
constexpr std::array<BugName, 23> kBugNames = {{
    {EngineBug::none, "none"},
    {EngineBug::energy_doubled, "energy_doubled"},
    {EngineBug::independent_minus_k_real_part, "independent_minus_k_real_part"},
    {EngineBug::same_pair_for_minus_k, "same_pair_for_minus_k"},
    {EngineBug::deep_water_dispersion, "deep_water_dispersion"},
    {EngineBug::reversed_time, "reversed_time"},
    {EngineBug::jacobian_without_choppiness, "jacobian_without_choppiness"},
    {EngineBug::uniform_noise, "uniform_noise"},
    {EngineBug::checkerboard_sign, "checkerboard_sign"},
    {EngineBug::amplitude_without_dk, "amplitude_without_dk"},
    {EngineBug::sigma_wrong, "sigma_wrong"},
    {EngineBug::alpha_sqrt_g, "alpha_sqrt_g"},
    {EngineBug::omega_equals_gk, "omega_equals_gk"},
    {EngineBug::spreading_not_normalized, "spreading_not_normalized"},
    {EngineBug::displacement_sign_flipped, "displacement_sign_flipped"},
    {EngineBug::band_counted_twice, "band_counted_twice"},
    {EngineBug::standing_waves, "standing_waves"},
    {EngineBug::time_drift, "time_drift"},
    {EngineBug::transposed_height, "transposed_height"},
    {EngineBug::swapped_displacements, "swapped_displacements"},
    {EngineBug::half_bin_offset_lattice, "half_bin_offset_lattice"},
    {EngineBug::hash_collisions, "hash_collisions"},
    {EngineBug::heave, "heave"},
}};

bool is_jonswap_family(const OceanCase& c) {
  return c.spectrum.model == "jonswap" || c.spectrum.model == "tma";
}

// Everything the engine needs to know about one case and one bug, built once per render.
class Engine {
 public:
  Engine(const OceanCase& c, EngineBug bug) : c_(c), bug_(bug) {
    c_.validate();
    if (!engine_bug_applies(bug, c_)) {
      throw InvalidInput("test engine: bug '" + to_string(bug) + "' does not apply to the case " +
                         c_.describe() +
                         (bug == EngineBug::sigma_wrong ? " (needs spectrum jonswap or tma)"
                                                        : " (needs a spreading model)"));
    }
    psi_ = build_psi();
    if (bug_ == EngineBug::spreading_not_normalized) {
      // Ψ of every spread model is a SpreadSpectrum (only phillips is not, and it is excluded).
      spread_ = std::dynamic_pointer_cast<const reference::SpreadSpectrum>(psi_);
      if (!spread_) throw InvalidInput("test engine: spreading_not_normalized needs a spread Ψ");
    }
    sampling_ = c_.sampling();
    const reference::Sampling& g = sampling_;
    const double k_min = std::min(g.dkx(), g.dky());
    double k_max = 0;  // the largest |k| carrying energy (a grid's corner below Nyquist)
    for (std::size_t e = 0; e < g.size(); ++e) {
      if (!g.carries_energy(e)) continue;
      const auto [n, m] = g.wave_index(e);
      k_max = std::max(k_max, std::hypot(n * g.dkx(), m * g.dky()));
    }
    band_lo_ = k_min + (k_max - k_min) / 3.0;
    band_hi_ = k_min + 2.0 * (k_max - k_min) / 3.0;
    h0_ = draw_amplitudes(0);
    // The independent draw that replaces h̃0(−k) in the conj term (stream 1 is free for tests).
    if (bug_ == EngineBug::independent_minus_k_real_part) g0_ = draw_amplitudes(1);
  }

  const OceanCase& ocean_case() const { return c_; }
  EngineBug bug() const { return bug_; }

  // h̃0 per coefficient of the sampling (a grid's FFT order, index j·nx + i of signed (n, m);
  // a lattice's class m).
  const std::vector<cplx>& initial_amplitudes() const { return h0_; }

  // h̃(k, t) at (n, m): what the engine's spectrum holds at time t.
  cplx amplitude(int n, int m, double t) const {
    const reference::Sampling& g = sampling_;
    if (!carries_energy(n, m)) return 0.0;
    if (bug_ == EngineBug::half_bin_offset_lattice) {
      const auto [kx, ky] = offset_wave_vector(n, m);
      const double w = omega(std::hypot(kx, ky));
      // The "−k" partner one bin off, and no conjugate.
      return h0_[index(n, m)] * std::exp(cplx(0.0, -w * t)) +
             h0_[index(-n - 1, -m - 1)] * std::exp(cplx(0.0, w * t));
    }
    const double w = omega(std::hypot(n * g.dkx(), m * g.dky()));
    const cplx plus = h0_[index(n, m)];
    const cplx minus =
        bug_ == EngineBug::independent_minus_k_real_part ? g0_[index(-n, -m)] : h0_[index(-n, -m)];
    const cplx forward = std::exp(cplx(0.0, -w * t)), backward = std::exp(cplx(0.0, w * t));
    cplx value;
    switch (bug_) {
      case EngineBug::reversed_time:
        value = plus * backward + std::conj(minus) * forward;
        break;
      case EngineBug::standing_waves:
        value = (plus + std::conj(minus)) * std::cos(w * t);
        break;
      default:
        value = plus * forward + std::conj(minus) * backward;
    }
    if (bug_ == EngineBug::time_drift) {
      const double span = c_.frames * c_.dt;
      if (span > 0) value *= 1.0 + 0.2 * (t - c_.t0) / span;
    }
    return value;
  }

  // The wave vector bin (n, m) stands for: the grid's, or the half-bin-offset plugin's
  // ((2n + 1) Δkx, (2m + 1) Δky).
  std::pair<double, double> offset_wave_vector(int n, int m) const {
    const reference::Sampling& g = sampling_;
    if (bug_ == EngineBug::half_bin_offset_lattice) return {(2 * n + 1) * g.dkx(), (2 * m + 1) * g.dky()};
    return {n * g.dkx(), m * g.dky()};
  }

 private:
  // The coefficient of wave index (n, m): a grid's FFT-order entry; a lattice's residue class
  // (n, m)·g mod N (for the k_m and −k_m the engine asks about, their own classes).
  std::size_t index(int n, int m) const {
    if (c_.is_lattice()) {
      const std::int64_t k[2] = {n, m};
      return static_cast<std::size_t>(c_.lattice->residue(std::span<const std::int64_t>(k, 2)));
    }
    const Grid& g = c_.grid;
    return std::size_t((m + g.ny) % g.ny) * g.nx + std::size_t((n + g.nx) % g.nx);
  }
  bool carries_energy(int n, int m) const {
    return c_.is_lattice() ? sampling_.carries_energy(index(n, m)) : c_.grid.carries_energy(n, m);
  }

  std::vector<cplx> draw_amplitudes(std::uint32_t stream) const {
    std::vector<cplx> out(sampling_.size(), 0.0);
    for (std::size_t e = 0; e < out.size(); ++e) {
      const auto [n, m] = sampling_.wave_index(e);
      out[e] = initial_amplitude(n, m, stream);
    }
    return out;
  }

  // h̃0 at (n, m) from noise stream `stream`.
  cplx initial_amplitude(int n, int m, std::uint32_t stream) const {
    const reference::Sampling& g = sampling_;
    if (!carries_energy(n, m)) return 0.0;
    const auto [kx, ky] = offset_wave_vector(n, m);
    const double dk2 = bug_ == EngineBug::amplitude_without_dk ? 1.0 : g.dkx() * g.dky();
    double scale = std::sqrt(psi(kx, ky) * dk2 / 2.0) / std::numbers::sqrt2;
    if (bug_ == EngineBug::energy_doubled) scale *= std::numbers::sqrt2;
    if (bug_ == EngineBug::band_counted_twice) {
      const double k = std::hypot(kx, ky);
      if (k >= band_lo_ && k < band_hi_) scale *= std::numbers::sqrt2;
    }
    const auto [xi1, xi2] = noise(n, m, stream);
    return cplx(xi1, xi2) * scale;
  }

  reference::DirectionalSpectrumPtr build_psi() const {
    if (bug_ == EngineBug::sigma_wrong) {
      OceanCase wrong = c_;
      wrong.spectrum.numbers["sigma_a"] = 0.7;
      wrong.spectrum.numbers["sigma_b"] = 0.7;
      return wrong.directional_spectrum();
    }
    if (bug_ == EngineBug::deep_water_dispersion) {
      if (c_.spectrum.model == "phillips") {
        // Phillips' Ψ(k) is defined in k; only its L = V²/g and its S(ω) see the dispersion.
        OceanCase deep = c_;
        deep.depth = reference::kInfiniteDepth;
        return deep.directional_spectrum();
      }
      // The case's S(ω) (TMA keeps its depth factor) and D, mapped to k by ω² = g k.
      const auto frequency = reference::make_frequency_spectrum(c_.full_spectrum_spec());
      const auto spreading = reference::make_spreading(c_.spreading, frequency->peak_omega());
      return reference::SpreadSpectrum::create(frequency, spreading, Dispersion::deep(c_.gravity),
                                               c_.wind_dir_deg * std::numbers::pi / 180.0);
    }
    return c_.directional_spectrum();
  }

  double psi(double kx, double ky) const {
    double value = psi_->psi(kx, ky);
    if (bug_ == EngineBug::alpha_sqrt_g) value *= std::pow(c_.gravity, -1.5);
    if (bug_ == EngineBug::spreading_not_normalized) {
      const double w = spread_->dispersion().omega(std::hypot(kx, ky));
      value /= spread_->spreading()(w, 0.0);
    }
    return value;
  }

  reference::NormalPair noise(int n, int m, std::uint32_t stream) const {
    if (bug_ == EngineBug::same_pair_for_minus_k && !validation::in_half_plane(n, m)) {
      n = -n;
      m = -m;
    }
    if (bug_ == EngineBug::hash_collisions) {
      std::uint32_t x = std::uint32_t(n) * 73856093u ^ std::uint32_t(m) * 19349663u;
      x ^= x >> 15;
      x *= 0x2c1b3c6du;
      x ^= x >> 12;
      return reference::wave_noise(c_.seed, int(x & 0xffffu), 0, stream);  // 2¹⁶ buckets
    }
    if (bug_ == EngineBug::uniform_noise) {
      const auto [u1, u2] = reference::wave_uniforms(c_.seed, n, m, stream);
      const double r3 = std::sqrt(3.0);
      return {r3 * (2.0 * u1 - 1.0), r3 * (2.0 * u2 - 1.0)};
    }
    return reference::wave_noise(c_.seed, n, m, stream, static_cast<std::uint32_t>(c_.cascade));
  }

  double omega(double k) const {
    switch (bug_) {
      case EngineBug::deep_water_dispersion:
        return reference::quantize_omega(std::sqrt(c_.gravity * k), c_.loop_period);
      case EngineBug::omega_equals_gk:
        return reference::quantize_omega(c_.gravity * k, c_.loop_period);
      default:
        return c_.omega(k);
    }
  }

  OceanCase c_;
  reference::Sampling sampling_;
  EngineBug bug_;
  reference::DirectionalSpectrumPtr psi_;
  std::shared_ptr<const reference::SpreadSpectrum> spread_;
  double band_lo_ = 0, band_hi_ = 0;
  std::vector<cplx> h0_, g0_;
};

// The complex inverse Σk X(k) e^(ik·x). field_from_spectrum returns Re Σ X e^(ik·x); since
// Re Σ (−iX) e^(ik·x) = Re(−i z) = Im z, the imaginary part is field_from_spectrum(−i X).
struct ComplexField {
  std::vector<double> re, im;
};
ComplexField complex_inverse(const std::vector<cplx>& spectrum, const reference::Sampling& grid,
                             bool with_imaginary) {
  ComplexField out;
  out.re = validation::field_from_spectrum(spectrum, grid);
  if (with_imaginary) {
    std::vector<cplx> rotated(spectrum.size());
    for (std::size_t i = 0; i < spectrum.size(); ++i) rotated[i] = -kI * spectrum[i];
    out.im = validation::field_from_spectrum(rotated, grid);
  }
  return out;
}

// The eight spectra one frame needs, in the order below.
enum Part { kH, kSx, kSy, kDx, kDy, kDxx, kDyy, kDxy, kParts };

reference::FieldFrame render_frame(const Engine& engine, double t, bool keep_imaginary) {
  const OceanCase& c = engine.ocean_case();
  const reference::Sampling g = c.sampling();
  const std::size_t count = g.size();
  const EngineBug bug = engine.bug();
  // Tessendorf's −i flips D and, consistently, its derivatives.
  const double d_sign = bug == EngineBug::displacement_sign_flipped ? -1.0 : 1.0;

  std::array<std::vector<cplx>, kParts> spectra;
  for (auto& s : spectra) s.assign(count, 0.0);
  for (std::size_t at = 0; at < count; ++at) {
    if (!g.carries_energy(at)) continue;  // k = 0 and Nyquist: 0 in every field
    const auto [n, m] = g.wave_index(at);
    const auto [kx, ky] = engine.offset_wave_vector(n, m);
    const double k = std::hypot(kx, ky);
    const cplx h = engine.amplitude(n, m, t);
    spectra[kH][at] = h;
    spectra[kSx][at] = kI * kx * h;
    spectra[kSy][at] = kI * ky * h;
    spectra[kDx][at] = d_sign * kI * (kx / k) * h;
    spectra[kDy][at] = d_sign * kI * (ky / k) * h;
    spectra[kDxx][at] = d_sign * (-kx * kx / k) * h;
    spectra[kDyy][at] = d_sign * (-ky * ky / k) * h;
    spectra[kDxy][at] = d_sign * (-kx * ky / k) * h;
  }

  if (bug == EngineBug::heave) {
    // The mean level and the mean displacement move together: 0.8 √(2 m0) cos(2π t / 8 s).
    double m0 = 0;
    for (std::size_t at = 0; at < count; ++at) {
      if (g.carries_energy(at)) m0 += std::norm(engine.amplitude(g.wave_index(at)[0], g.wave_index(at)[1], 0.0));
    }
    const double level = 0.8 * std::sqrt(2 * m0) * std::cos(2 * std::numbers::pi * t / 8.0);
    spectra[kH][0] = level;
    spectra[kDx][0] = level / c.choppiness;  // stored λD: the sway equals the heave
    spectra[kDy][0] = level / c.choppiness;
  }

  std::array<ComplexField, kParts> parts;
  for (int p = 0; p < kParts; ++p) parts[p] = complex_inverse(spectra[p], g, keep_imaginary);

  if (bug == EngineBug::checkerboard_sign) {
    const Grid& grid = c.grid;  // only on grids (engine_bug_applies)
    for (auto& part : parts) {
      for (int j = 0; j < grid.ny; ++j) {
        for (int i = 0; i < grid.nx; ++i) {
          if ((i + j) % 2 == 0) continue;
          const std::size_t at = std::size_t(j) * grid.nx + i;
          part.re[at] = -part.re[at];
          if (keep_imaginary) part.im[at] = -part.im[at];
        }
      }
    }
  }

  const double lambda = c.choppiness;
  const double lambda_j = bug == EngineBug::jacobian_without_choppiness ? 1.0 : lambda;
  reference::FieldFrame frame;
  frame.time = t;
  auto scaled = [&](const std::vector<double>& v, double factor) {
    std::vector<double> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = factor * v[i];
    return out;
  };
  frame.fields[Field::height] = parts[kH].re;
  frame.fields[Field::slope_x] = parts[kSx].re;
  frame.fields[Field::slope_y] = parts[kSy].re;
  frame.fields[Field::disp_x] = scaled(parts[kDx].re, lambda);
  frame.fields[Field::disp_y] = scaled(parts[kDy].re, lambda);
  std::vector<double> jacobian(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double dxx = parts[kDxx].re[i], dyy = parts[kDyy].re[i], dxy = parts[kDxy].re[i];
    jacobian[i] = (1.0 + lambda_j * dxx) * (1.0 + lambda_j * dyy) - lambda_j * lambda_j * dxy * dxy;
  }
  frame.fields[Field::jacobian] = std::move(jacobian);

  if (bug == EngineBug::swapped_displacements) {
    std::swap(frame.fields[Field::disp_x], frame.fields[Field::disp_y]);
  }
  if (bug == EngineBug::transposed_height) {
    const Grid& grid = c.grid;  // square (engine_bug_applies)
    auto& h = frame.fields[Field::height];
    std::vector<double> transposed(h.size());
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) transposed[std::size_t(i) * grid.nx + j] = h[std::size_t(j) * grid.nx + i];
    }
    h = std::move(transposed);
  }
  if (keep_imaginary) {
    frame.imaginary[Field::height] = parts[kH].im;
    frame.imaginary[Field::slope_x] = parts[kSx].im;
    frame.imaginary[Field::slope_y] = parts[kSy].im;
    frame.imaginary[Field::disp_x] = scaled(parts[kDx].im, lambda);
    frame.imaginary[Field::disp_y] = scaled(parts[kDy].im, lambda);
    std::vector<double> jacobian_im(count);
    for (std::size_t i = 0; i < count; ++i) {
      const cplx dxx(parts[kDxx].re[i], parts[kDxx].im[i]);
      const cplx dyy(parts[kDyy].re[i], parts[kDyy].im[i]);
      const cplx dxy(parts[kDxy].re[i], parts[kDxy].im[i]);
      const cplx j_complex =
          (1.0 + lambda_j * dxx) * (1.0 + lambda_j * dyy) - lambda_j * lambda_j * dxy * dxy;
      jacobian_im[i] = j_complex.imag();
    }
    frame.imaginary[Field::jacobian] = std::move(jacobian_im);
  }
  return frame;
}

}  // namespace

std::string to_string(EngineBug bug) {
  for (const auto& [b, name] : kBugNames) {
    if (b == bug) return name;
  }
  return "unknown";
}

EngineBug engine_bug_from_string(const std::string& name) {
  std::string valid;
  for (const auto& [bug, bug_name] : kBugNames) {
    if (name == bug_name) return bug;
    valid += (valid.empty() ? "" : ", ") + std::string(bug_name);
  }
  throw InvalidInput("unknown engine bug '" + name + "' (valid: " + valid + ")");
}

std::vector<EngineBug> all_engine_bugs() {
  std::vector<EngineBug> bugs;
  for (const auto& [bug, name] : kBugNames) {
    if (bug != EngineBug::none) bugs.push_back(bug);
  }
  return bugs;
}

bool engine_bug_applies(EngineBug bug, const OceanCase& ocean_case) {
  // The checkerboard (−1)^(i+j) is a fix-up of grid indices; a lattice has none.
  if (bug == EngineBug::checkerboard_sign) return !ocean_case.is_lattice();
  if (bug == EngineBug::transposed_height) {
    return !ocean_case.is_lattice() && ocean_case.grid.nx == ocean_case.grid.ny &&
           ocean_case.grid.lx == ocean_case.grid.ly;
  }
  if (bug == EngineBug::half_bin_offset_lattice || bug == EngineBug::hash_collisions ||
      bug == EngineBug::heave) {
    return !ocean_case.is_lattice();
  }
  if (bug == EngineBug::sigma_wrong) return is_jonswap_family(ocean_case);
  if (bug == EngineBug::spreading_not_normalized) return !ocean_case.spreading.model.empty();
  return true;
}

std::vector<std::complex<double>> engine_initial_amplitudes(const OceanCase& ocean_case,
                                                            EngineBug bug) {
  return Engine(ocean_case, bug).initial_amplitudes();
}

reference::FrameSequence render_surface(const OceanCase& ocean_case, EngineBug bug,
                                        EngineOptions options) {
  const Engine engine(ocean_case, bug);
  reference::FrameSequence sequence;
  sequence.grid = ocean_case.grid;
  sequence.lattice = ocean_case.lattice;
  sequence.unit_roundoff = 0x1p-53;
  sequence.frames.reserve(std::size_t(ocean_case.frames));
  for (int f = 0; f < ocean_case.frames; ++f) {
    sequence.frames.push_back(render_frame(engine, ocean_case.time(f), options.keep_imaginary));
  }
  return sequence;
}

double keep_rgb_fields(reference::FrameSequence& frames) {
  double largest = 0;
  for (auto& frame : frames.frames) {
    for (Field dropped : {Field::slope_x, Field::slope_y, Field::jacobian}) frame.fields.erase(dropped);
    for (const auto& [field, values] : frame.fields) {
      for (double v : values) largest = std::max(largest, std::abs(v));
    }
  }
  return largest;
}

}  // namespace swell::test
