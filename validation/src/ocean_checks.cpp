#include "swell/validation/ocean_checks.hpp"
#include "swell/validation/wave_fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <complex>
#include <functional>
#include <map>
#include <mutex>
#include <numbers>
#include <numeric>
#include <span>

#include "parallel_tasks.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/phase.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/periodogram.hpp"
#include "swell/validation/statistics.hpp"

namespace swell::validation {
namespace {

using reference::Field;
using reference::FrameSequence;
using reference::Grid;
using reference::Sampling;
using reference::OceanCase;
using Complex = std::complex<double>;

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = 180.0 / kPi;
constexpr double kFp64Roundoff = 0x1p-53;

double mean_square(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x * x;
  return sum / double(v.size());
}

// Σ x² over each of `fields`, accumulated in `Sum` (double: mean_square's sum; long double:
// parseval's), each exactly the sequential loop's sum — the same additions in the same order —
// but four fields side by side: a sequential sum waits ~4 cycles on each addition, and four
// independent ones hide behind each other (parseval and statistics.hs_steady sum every frame).
template <typename Sum>
std::vector<Sum> sums_of_squares(const std::vector<const std::vector<double>*>& fields) {
  std::vector<Sum> sums(fields.size(), Sum(0));
  std::size_t f = 0;
  for (; f + 4 <= fields.size(); f += 4) {
    const std::vector<double>&a = *fields[f], &b = *fields[f + 1], &c = *fields[f + 2], &d = *fields[f + 3];
    if (a.size() != b.size() || a.size() != c.size() || a.size() != d.size()) break;
    Sum sa = 0, sb = 0, sc = 0, sd = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      sa += Sum(a[i]) * a[i];
      sb += Sum(b[i]) * b[i];
      sc += Sum(c[i]) * c[i];
      sd += Sum(d[i]) * d[i];
    }
    sums[f] = sa, sums[f + 1] = sb, sums[f + 2] = sc, sums[f + 3] = sd;
  }
  for (; f < fields.size(); ++f) {
    for (double x : *fields[f]) sums[f] += Sum(x) * x;
  }
  return sums;
}

// The height field of every frame, in frame order.
std::vector<const std::vector<double>*> heights(const FrameSequence& frames) {
  std::vector<const std::vector<double>*> out;
  for (std::size_t f = 0; f < frames.frames.size(); ++f) out.push_back(&frames.field(int(f), Field::height));
  return out;
}

// An exact result: passed ⇔ error ≤ bound.
CheckResult bounded(std::string check, std::string subject, double error, double bound,
                    std::string criterion, std::string reason) {
  CheckResult r;
  r.check = std::move(check);
  r.subject = std::move(subject);
  r.measured = error;
  r.expected = 0;
  r.tolerance = bound;
  r.criterion = std::move(criterion);
  r.passed = error <= bound;
  r.reason = std::move(reason);
  return r;
}

std::string verdict(bool passed) { return passed ? "" : " — FAILED"; }

// One energy-carrying wave vector k of the half plane (its partner −k is implied).
struct Wave {
  std::size_t index = 0, minus_index = 0;  // positions of k and −k in FFT order
  double kx = 0, ky = 0, k = 0, omega = 0, theta = 0;
  double mu = 0;         // E I(k) = τ(k) + τ(−k)
  double tau_plus = 0;   // E|a|²: power travelling along +k
  double tau_minus = 0;  // E|b|²: power travelling along −k
};

// The travelling-wave amplitudes of one wave vector fitted over the frames:
// h̃(k, t) ≈ a e^(−iωt) + b e^(+iωt).
struct WaveFit {
  const Wave* wave = nullptr;
  Complex a, b;
  double energy = 0, residual = 0;  // Σf |h̃|², Σf |h̃ − fit|²
};

// Integer frames with a coarse quantization step (8-bit PNG, or 16-bit over a range far wider
// than the values) come here, from the gate and from swell synth alike.
[[noreturn]] void throw_rounding_hides_every_wave(double u, const OceanCase& c) {
  throw InvalidInput(fmt::format(
      "the stored values' rounding (unit roundoff {:.2g} relative to the height's rms) hides "
      "every wave vector: none carries 10⁶ times the rounding noise, so no check can judge these "
      "frames ({}); store floats, or 16-bit integers with a value_range close to the values' "
      "extent",
      u, c.describe()));
}

// The resolution floor of the analysis: a wave vector is resolved when the model puts 10⁶
// times the rounding noise there (white over the N wave vectors: u² mean(h²)/N per k), so that
// rounding moves its periodogram by < 10⁻⁶ relative.
double resolution_floor(double u, double mean_square_height, std::size_t count) {
  return 1e6 * u * u * mean_square_height / double(count);
}

// The distinct ω of a set of waves, for work that depends on ω alone (the phases e^(−iωt)):
// the wave vectors of one |k| share it — on a square grid (n, m), (−n, m), (m, n), (−m, n) and
// any other of the same n² + m² — so one per distinct ω is about a quarter as many as one per
// wave vector. `order` lists the waves by ω (ties in their own order), wave i's ω is
// omegas[group[i]].
struct OmegaGroups {
  std::vector<std::size_t> order, group;
  std::vector<double> omegas;
};

template <typename Waves>
OmegaGroups group_by_omega(const Waves& waves) {
  OmegaGroups out;
  out.order.resize(waves.size());
  std::iota(out.order.begin(), out.order.end(), std::size_t(0));
  std::stable_sort(out.order.begin(), out.order.end(),
                   [&](std::size_t x, std::size_t y) { return waves[x].omega < waves[y].omega; });
  out.group.resize(waves.size());
  for (std::size_t i : out.order) {
    if (out.omegas.empty() || !(out.omegas.back() == waves[i].omega)) out.omegas.push_back(waves[i].omega);
    out.group[i] = out.omegas.size() - 1;
  }
  return out;
}

// A series of `frames` values per resolved wave vector, all in one array: one allocation of
// 16 B × waves × frames (128 MiB at 512² × 64 frames), on huge pages where the kernel gives them,
// instead of one vector per wave vector, whose 131 072 allocations and page faults took a tenth
// of the gate's CPU at that size.
class WaveSeries {
 public:
  void assign(std::size_t waves, std::size_t frames) {
    frames_ = frames;
    // Not zeroed first: every entry is written, and zeroing 128 MiB on one thread (its page
    // faults) held the others up.
    buffer_ = std::make_unique<impls::HostBuffer>(std::max<std::size_t>(1, waves * frames) * sizeof(Complex),
                                                  impls::HostBuffer::Fill::none);
  }
  std::span<const Complex> operator[](std::size_t wave) const { return {data() + wave * frames_, frames_}; }
  Complex& at(std::size_t wave, std::size_t frame) { return data()[wave * frames_ + frame]; }

 private:
  Complex* data() const { return static_cast<Complex*>(buffer_->host_data()); }
  std::size_t frames_ = 0;
  std::unique_ptr<impls::HostBuffer> buffer_;
};

class Analysis {
 public:
  // `threads` (≥ 1) for Ψ over the grid here and the shared work below (wave_series, wave_fits).
  // `travelling`: τ(k) over the samples when the caller has it (run_ocean_check_groups); empty:
  // evaluated here.
  Analysis(const OceanCase& ocean_case, const FrameSequence& frames,
           const OceanCheckOptions& options, int threads = 1, std::vector<double> travelling = {})
      : c_(ocean_case), frames_(frames), options_(options), sampling_(ocean_case.sampling()),
        threads_(std::max(1, threads)) {
    const Sampling given = frames.sampling();
    if (!given.same_as(sampling_)) {
      throw InvalidInput(fmt::format("frames are on a {} but the case says {}", given.describe(),
                                     sampling_.describe()));
    }
    if (frames.frames.empty()) throw InvalidInput("no frames to check");
    if (!frames.has(Field::height)) {
      throw InvalidInput("the frames have no height field: every ocean check needs it");
    }
    require(options.alpha > 0 && options.alpha < 1, "alpha", "in (0, 1)", options.alpha);
    count_ = sampling_.size();
    log2n_ = std::max(1.0, std::log2(double(count_)));
    u_ = std::max(frames.unit_roundoff, kFp64Roundoff);
    for (const auto& frame : frames.frames) times_.push_back(frame.time);

    const auto spectrum = c_.directional_spectrum();
    if (travelling.empty()) {
      shared_->tau = expected_travelling_power(*spectrum, sampling_, threads_);
    } else if (travelling.size() == sampling_.size()) {
      shared_->tau = std::move(travelling);
    } else {
      throw InternalError("Analysis: travelling power of the wrong size");
    }
    // Two independent parts side by side (the second is an FFT): run_tasks rethrows the first
    // part's error before the second's, as when they ran one after the other.
    detail::run_tasks(2, threads_, [&](std::size_t part) {
      if (part == 0) {
        shared_->mu = expected_periodogram(shared_->tau, sampling_);  // τ(k) + τ(−k): Ψ evaluated once
        // The validity rule every command shares (reference/sampling_validity.hpp), in the
        // number format the frames were stored in: float32 (EXR, TIFF) or coarser (PNG) unless
        // they carry fp64's rounding.
        reference::require_valid_sampling(
            c_, frames.unit_roundoff > 2 * kFp64Roundoff ? reference::kFloat32 : reference::kFloat64,
            0, "", &shared_->tau);
      } else {
        field_spectrum(frames.field(0, Field::height), sampling_, shared_->spectrum0, &spectral_energy0_);
        mean_square0_ = mean_square(frames.field(0, Field::height));
      }
    });

    const double expected_total = std::accumulate(shared_->mu.begin(), shared_->mu.end(), 0.0);
    if (!(expected_total > 0)) {
      throw InvalidInput("the case's spectrum puts no energy on these samples (" + c_.describe() + ")");
    }
    // Rounding of the stored numbers moves a resolved wave vector's periodogram by < 10⁻⁶
    // relative — far below any sampling effect the checks test.
    floor_ = resolution_floor(u_, mean_square0_, count_);

    const double dkx = sampling_.dkx(), dky = sampling_.dky();
    // Room for every wave vector of the half plane at once (about half the samples): grown by
    // doubling, the copies touched twice the memory, a fresh array each time.
    shared_->half_plane.reserve(count_ / 2 + 1);
    for (std::size_t e = 0; e < count_; ++e) {
      if (!sampling_.carries_energy(e)) continue;
      const auto [n, m] = sampling_.wave_index(e);
      if (!in_half_plane(n, m)) continue;
      Wave w;
      w.index = e;
      w.minus_index = sampling_.conjugate(e);
      w.kx = n * dkx;
      w.ky = m * dky;
      w.k = std::hypot(w.kx, w.ky);
      w.omega = c_.omega(w.k);
      w.theta = std::atan2(w.ky, w.kx);
      w.mu = shared_->mu[e];
      w.tau_plus = shared_->tau[e];
      w.tau_minus = shared_->tau[w.minus_index];
      shared_->half_plane.push_back(w);
    }
    if (options.free_scale) {
      // The maximum-likelihood scale of exponential ordinates: the mean of I/μ over the
      // resolved half plane (Whittle), resolution judged with the model scaled to the data's
      // energy.
      double sum = 0;
      int used = 0;
      for (const Wave& w : shared_->half_plane) {
        if (!(w.mu > 0) || w.mu * mean_square0_ / expected_total < floor_) continue;
        sum += std::norm(shared_->spectrum0[w.index]) / w.mu;
        ++used;
      }
      scale_ = used > 0 ? sum / used : 0;
      if (!(scale_ > 0)) throw InvalidInput("free scale: the height field is identically zero");
      for (double& v : shared_->mu) v *= scale_;
      for (double& v : shared_->tau) v *= scale_;
      for (Wave& w : shared_->half_plane) {
        w.mu *= scale_;
        w.tau_plus *= scale_;
        w.tau_minus *= scale_;
      }
    }
    shared_->resolved.reserve(shared_->half_plane.size());
    for (const Wave& w : shared_->half_plane) {
      if (w.mu >= floor_ && w.mu > 0) shared_->resolved.push_back(w);
    }
    if (shared_->resolved.empty()) {
      const bool rounding_hides_all = std::any_of(
          shared_->half_plane.begin(), shared_->half_plane.end(), [](const Wave& w) { return w.mu > 0; });
      if (rounding_hides_all) throw_rounding_hides_every_wave(u_, c_);  // coarse integer frames
      throw InvalidInput("no wave vector of the sampling carries resolvable energy under the case's "
                         "spectrum (" + c_.describe() + ")");
    }
  }

  // The same analysis over other frames of the same surface, whose frame 0 is `base`'s (the
  // gate's two end frames): μ, τ, the waves and frame 0's spectrum are base's, shared rather
  // than computed again (Ψ over the grid and an FFT: about 7 % of the gate's work at 512²) or
  // copied (30 MB at 512²). Every scalar the main constructor sets must be copied here too (the
  // golden reports of GateGolden catch a derived check judged with a default-constructed one).
  Analysis(const Analysis& base, const FrameSequence& frames)
      : c_(base.c_), frames_(frames), options_(base.options_), sampling_(base.sampling_),
        count_(base.count_), log2n_(base.log2n_), u_(base.u_), scale_(base.scale_),
        floor_(base.floor_), mean_square0_(base.mean_square0_),
        spectral_energy0_(base.spectral_energy0_), threads_(base.threads_), shared_(base.shared_) {
    for (const auto& frame : frames.frames) times_.push_back(frame.time);
  }

  const OceanCase& ocean_case() const { return c_; }
  const FrameSequence& frames() const { return frames_; }
  const OceanCheckOptions& options() const { return options_; }
  const Sampling& sampling() const { return sampling_; }
  std::size_t count() const { return count_; }
  double log2n() const { return log2n_; }
  double unit_roundoff() const { return u_; }
  std::size_t sample_count() const { return count_; }
  double scale() const { return scale_; }
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& mu() const { return shared_->mu; }
  const std::vector<Complex>& spectrum0() const { return shared_->spectrum0; }
  double periodogram0(std::size_t e) const { return std::norm(shared_->spectrum0[e]); }
  double mean_square0() const { return mean_square0_; }
  double floor() const { return floor_; }
  const std::vector<Wave>& waves() const { return shared_->resolved; }
  const std::vector<Wave>& half_plane() const { return shared_->half_plane; }
  std::string subject() const { return c_.describe(); }

  // The height spectra of every frame at the resolved wave vectors, computed once.
  // Once, whichever check asks first (the gate runs checks on one analysis concurrently).
  // Frames are transformed on up to `threads_` threads, four at a time, each entry divided by N
  // as field_spectrum divides it. A wave's four values then fill one 64-byte line of its series
  // in one go: written one frame at a time, each line was fetched from memory four times.
  const WaveSeries& wave_series() const {
    std::call_once(series_once_, [this] {
      const std::size_t frames = times_.size(), waves = shared_->resolved.size();
      series_.assign(waves, frames);
      spectral_energies_.assign(frames, spectral_energy0_);
      const double scale = 1.0 / double(count_);
      constexpr std::size_t kFramesPerTask = 4;
      detail::run_tasks((frames + kFramesPerTask - 1) / kFramesPerTask, threads_, [&](std::size_t task) {
        const std::size_t first = task * kFramesPerTask, last = std::min(frames, first + kFramesPerTask);
        thread_local std::vector<Complex> block;  // block[i × waves + w]: frame first + i
        block.resize((last - first) * waves);
        for (std::size_t f = first; f < last; ++f) {
          Complex* values = block.data() + (f - first) * waves;
          if (f == 0) {
            for (std::size_t w = 0; w < waves; ++w) values[w] = shared_->spectrum0[shared_->resolved[w].index];
            continue;
          }
          const auto transform =
              analysis_transform(frames_.field(int(f), Field::height), sampling_, &spectral_energies_[f]);
          for (std::size_t w = 0; w < waves; ++w) values[w] = transform[shared_->resolved[w].index] * scale;
        }
        for (std::size_t w = 0; w < waves; ++w) {
          for (std::size_t f = first; f < last; ++f) series_.at(w, f) = block[(f - first) * waves + w];
        }
        release_analysis_scratch();
      });
    });
    return series_;
  }

  // Σ|X(k)|²/N of each frame's height transform X (field_spectrum's `energy`), made with the
  // wave series.
  const std::vector<long double>& spectral_energies() const {
    wave_series();
    return spectral_energies_;
  }

  // a and b per resolved wave vector whose two waves are identifiable from the frame times, in
  // the order of the resolved waves. The phases e^(−iωt_f) are made once per distinct ω
  // (group_by_omega), the waves taken in ω order. On up to `threads_` threads.
  const std::vector<WaveFit>& wave_fits() const {
    std::call_once(fits_once_, [this] {
      const auto& series = wave_series();
      const std::vector<std::size_t> by_omega = group_by_omega(shared_->resolved).order;
      std::vector<WaveFit> fit_of(shared_->resolved.size());
      std::vector<char> fitted(shared_->resolved.size(), 0);
      constexpr std::size_t kWavesPerTask = 4096;
      detail::run_tasks((by_omega.size() + kWavesPerTask - 1) / kWavesPerTask, threads_, [&](std::size_t task) {
        std::vector<Complex> phases;
        double phases_omega = std::numeric_limits<double>::quiet_NaN();
        const std::size_t end = std::min(by_omega.size(), (task + 1) * kWavesPerTask);
        for (std::size_t i = task * kWavesPerTask; i < end; ++i) {
          const std::size_t w = by_omega[i];
          if (!(shared_->resolved[w].omega == phases_omega)) {
            phases_omega = shared_->resolved[w].omega;
            two_wave_phases(phases_omega, times_, phases);
          }
          WaveFit& fit = fit_of[w];
          fit.wave = &shared_->resolved[w];
          if (!fit_two_waves(phases, series[w], fit.a, fit.b, fit.residual)) continue;
          for (const Complex& y : series[w]) fit.energy += std::norm(y);
          fitted[w] = 1;
        }
      });
      fits_.reserve(std::size_t(std::count(fitted.begin(), fitted.end(), char(1))));
      for (std::size_t w = 0; w < shared_->resolved.size(); ++w) {
        if (fitted[w]) fits_.push_back(fit_of[w]);
      }
    });
    return fits_;
  }


 private:
  const OceanCase& c_;
  const FrameSequence& frames_;
  OceanCheckOptions options_;
  Sampling sampling_;
  std::size_t count_ = 0;
  double log2n_ = 1, u_ = kFp64Roundoff, scale_ = 1, floor_ = 0, mean_square0_ = 0;
  long double spectral_energy0_ = 0;
  int threads_ = 1;
  std::vector<double> times_;
  // What the frames' analysis over other frames of the same surface shares with it.
  struct Shared {
    std::vector<double> mu, tau;
    std::vector<Complex> spectrum0;
    std::vector<Wave> resolved, half_plane;
  };
  std::shared_ptr<Shared> shared_ = std::make_shared<Shared>();
  mutable WaveSeries series_;
  mutable std::vector<long double> spectral_energies_;
  mutable std::vector<WaveFit> fits_;
  mutable std::once_flag series_once_, fits_once_;
};

using Results = std::vector<CheckResult>;

// ------------------------------------------------------------------ hermitian

// A real field's spectrum is Hermitian to rounding whatever the engine did; what an engine can
// get wrong shows in the imaginary part of a complex synthesis, when it hands that over. The
// imaginary residue of a right synthesis is the transform's rounding, ≲ u log2 N of the field.
Results check_hermitian(const Analysis& a, OceanCheckReport&) {
  Results out;
  double worst_residue = 0, worst_symmetry = 0;
  std::string residue_where = "none given", symmetry_where;
  bool any_imaginary = false;
  for (std::size_t f = 0; f < a.frames().frames.size(); ++f) {
    const auto& frame = a.frames().frames[f];
    for (const auto& [field, values] : frame.fields) {
      const auto imaginary = frame.imaginary.find(field);
      if (imaginary != frame.imaginary.end()) {
        any_imaginary = true;
        const double residue =
            std::sqrt(mean_square(imaginary->second) / std::max(mean_square(values), 1e-300));
        if (residue >= worst_residue) {
          worst_residue = residue;
          residue_where = fmt::format("{} frame {}", reference::field_name(field), f);
        }
      }
    }
    if (f == 0 || f + 1 == a.frames().frames.size()) {
      const auto& spectrum = f == 0 ? a.spectrum0()
                                    : field_spectrum(a.frames().field(int(f), Field::height), a.sampling());
      double largest = 0, asymmetry = 0;
      for (const Wave& w : a.half_plane()) {
        largest = std::max(largest, std::abs(spectrum[w.index]));
        asymmetry = std::max(asymmetry, std::abs(spectrum[w.index] - std::conj(spectrum[w.minus_index])));
      }
      const double relative = asymmetry / std::max(largest, 1e-300);
      if (relative >= worst_symmetry) {
        worst_symmetry = relative;
        symmetry_where = fmt::format("height frame {}", f);
      }
    }
  }
  const double symmetry_bound = 16 * kFp64Roundoff * a.log2n();
  out.push_back(bounded("hermitian.symmetry", a.subject(), worst_symmetry, symmetry_bound,
                        fmt::format("max|ĥ(k) − conj ĥ(−k)| / max|ĥ| ≤ {:.1e}", symmetry_bound),
                        fmt::format("height spectrum Hermitian to {:.1e} ({}){}", worst_symmetry,
                                    symmetry_where, verdict(worst_symmetry <= symmetry_bound))));
  if (any_imaginary) {
    const double bound = 16 * a.unit_roundoff() * a.log2n();
    const bool ok = worst_residue <= bound;
    out.push_back(bounded(
        "hermitian.imaginary_residue", a.subject(), worst_residue, bound,
        fmt::format("rms(Im) / rms(Re) ≤ {:.1e}", bound),
        ok ? fmt::format("imaginary residue {:.1e} of the field ({})", worst_residue, residue_where)
           : fmt::format("imaginary residue {:.2g} of the field ({}): h̃(−k) is not conj(h̃(k)) — "
                         "missing conjugate pairing",
                         worst_residue, residue_where)));
  }
  return out;
}

// ------------------------------------------------------------------ parseval

Results check_parseval(const Analysis& a, OceanCheckReport&) {
  const auto backend = impls::make_backend(a.options().analysis_backend);
  const double bound = 8 * kFp64Roundoff * a.log2n();
  auto result = [&](double worst) -> Results {
    return {bounded("parseval", a.subject() + " via " + backend->name(), worst, bound,
                    fmt::format("|Σh² − N Σ|ĥ|²| / Σh² ≤ {:.1e}", bound),
                    fmt::format("Parseval holds to {:.1e} over {} frames{}", worst,
                                a.frames().frames.size(), verdict(worst <= bound)))};
  };
  // Through the analysis's own backend the transforms are those the wave series made (the same
  // plan on the same values): their spectral sums are taken from there, not transformed again.
  if (a.options().analysis_backend == kAnalysisBackend) {
    const auto& spectral = a.spectral_energies();
    const std::vector<long double> spatial = sums_of_squares<long double>(heights(a.frames()));
    double worst = 0;
    for (std::size_t f = 0; f < spatial.size(); ++f) {
      worst = std::max(worst, double(std::abs(spatial[f] - spectral[f]) / std::max(spatial[f], 1e-300L)));
    }
    return result(worst);
  }
  impls::TransformSpec spec;
  // A lattice's analysis is one 1-D transform over its N samples (DESIGN.md §1 "Sampling").
  spec.nx = a.sampling().is_lattice() ? static_cast<int>(a.count()) : a.sampling().grid().nx;
  spec.ny = a.sampling().is_lattice() ? 1 : a.sampling().grid().ny;
  spec.kind = impls::Kind::c2c;
  spec.direction = impls::Direction::forward;
  spec.precision = impls::Precision::f64;
  const auto plan = backend->plan(spec);
  double worst = 0;
  // The backend's own (aligned) buffers: with other memory FFTW's execute copies through
  // aligned temporaries on every call. A device backend's buffers are staged through the host.
  const std::size_t bytes = a.count() * sizeof(Complex);
  const auto in_buffer = backend->allocate(bytes), out_buffer = backend->allocate(bytes);
  const bool on_host = in_buffer->host_data() && out_buffer->host_data();
  std::vector<Complex> staging_in(on_host ? 0 : a.count()), staging_out(on_host ? 0 : a.count());
  const std::span<Complex> in(on_host ? static_cast<Complex*>(in_buffer->host_data()) : staging_in.data(), a.count());
  const std::span<Complex> out(on_host ? static_cast<Complex*>(out_buffer->host_data()) : staging_out.data(), a.count());
  for (std::size_t f = 0; f < a.frames().frames.size(); ++f) {
    const auto& h = a.frames().field(int(f), Field::height);
    std::copy(h.begin(), h.end(), in.begin());
    if (!on_host) in_buffer->upload(in.data(), bytes);
    plan->execute(*in_buffer, *out_buffer);
    if (!on_host) out_buffer->download(out.data(), bytes);
    // Sums in long double, so that only the transform's rounding is measured.
    long double spatial = 0, spectral = 0;
    for (double x : h) spatial += (long double)x * x;
    for (const Complex& v : out) spectral += std::norm(v);
    spectral /= (long double)a.count();
    worst = std::max(worst, double(std::abs(spatial - spectral) / std::max(spatial, 1e-300L)));
  }
  return result(worst);
}

// ------------------------------------------------------------------ energy

// The energy ratio an engine gets when it uses D(ω, θ)/D(ω, 0) — the spreading's shape without
// its normalization: Σ μ/D(ω, 0) / Σ μ over the resolved waves. 0 when the case has no
// spreading model (Phillips).
double unnormalized_spreading_factor(const Analysis& a) {
  const auto spectrum = a.ocean_case().directional_spectrum();
  const auto spread = std::dynamic_pointer_cast<const reference::SpreadSpectrum>(spectrum);
  if (!spread) return 0;
  const auto dispersion = reference::Dispersion::finite_depth(a.ocean_case().depth, a.ocean_case().gravity);
  double weighted = 0, total = 0;
  for (const Wave& w : a.waves()) {
    const double peak = spread->spreading()(dispersion.omega(w.k), 0.0);
    if (!(peak > 0)) continue;
    weighted += w.mu / peak;
    total += w.mu;
  }
  return total > 0 ? weighted / total : 0;
}

// mean h² = Σk I(k) = Σ over the half plane of 2 I(k), I(k) ~ μ(k) Exp(1) independent: a
// weighted sum of exponentials, whose law the saddlepoint approximation gives.
Results check_energy(const Analysis& a, OceanCheckReport& report) {
  if (a.options().free_scale) {
    report.skipped.push_back("energy: the case declares a free spectrum scale");
    return {};
  }
  std::vector<double> weights;
  for (const Wave& w : a.half_plane()) weights.push_back(2 * w.mu);
  const stats::WeightedExponentialSum law(weights);
  const double measured = a.mean_square0();
  const double p = law.two_sided_p(measured);
  const double ratio = measured / law.mean();
  const double alpha = a.options().alpha;
  const double z = (measured - law.mean()) / std::sqrt(law.variance());
  std::string reason = fmt::format("mean h² = {:.4g} m² is {:.3f}× the band-limited m0 {:.4g} m² "
                                   "(z = {:.2f}, p = {:.2g})",
                                   measured, ratio, law.mean(), z, p);
  if (p < alpha) {
    reason += fmt::format(": energy off by a factor {:.3g} (Hs by {:.3g})", ratio, std::sqrt(ratio));
    // The factors engines get wrong, when the sampling range of the ratio holds one.
    const double low = measured / law.quantile(1 - alpha / 2), high = measured / law.quantile(alpha / 2);
    const double g = a.ocean_case().gravity, dk2 = a.sampling().dkx() * a.sampling().dky();
    const std::vector<std::pair<double, std::string>> known = {
        {2.0, "twice the energy: Tessendorf's (ξ1 + iξ2)√(P/2) without the ½ of E|h̃0|² = ½ΨΔk², "
              "or both halves of each ±k pair counted"},
        {0.5, "half the energy: h̃(−k) not paired as conj(h̃(k)) with only the real part kept, "
              "or a ½ too many"},
        {1 / dk2, fmt::format("amplitudes without Δkx Δky (the energy then scales with the patch: "
                              "× {:.4g} here)", 1 / dk2)},
        {std::pow(g, -1.5), "α√g instead of α g² in the spectrum (× g^(−3/2))"},
    };
    auto candidates = known;
    if (const double factor = unnormalized_spreading_factor(a); factor > 0) {
      candidates.push_back({factor, fmt::format("the spreading function not normalized (its shape "
                                                "scaled to 1 along the mean direction: × {:.3g})",
                                                factor)});
    }
    // The candidate nearest the measured ratio (in log) among those its sampling range holds.
    double best = 1e300;
    std::string meaning;
    for (const auto& [factor, text] : candidates) {
      const double distance = std::abs(std::log(factor / ratio));
      if (factor >= low && factor <= high && distance < best) {
        best = distance;
        meaning = text;
      }
    }
    // A mean level carrying the excess is heave, not a factor on the waves.
    const double level = a.periodogram0(0);
    if (ratio > 1 && level > 0.5 * (measured - law.mean())) {
      meaning = fmt::format("{:.0f} % of mean h² is the mean level (k = 0): the whole patch heaves "
                            "(spectrum.unexpected_energy)",
                            100 * level / measured);
    }
    if (!meaning.empty()) reason += " — " + meaning;
  }
  return {statistical_check("energy", a.subject(), measured, law.mean(), p, alpha,
                      fmt::format("p ≥ α = {:.0e} (two-sided, exact law of Σ I)", alpha),
                      reason)};
}

// ------------------------------------------------------------------ spectrum shape

// u(k) = I(k)/μ(k) are independent Exp(1) over the resolved half plane. In rings of |k| with
// n wave vectors each, Σ u ~ Gamma(n, 1) exactly; the rings' two-sided p-values combine by
// Fisher's method. Energy where the case puts none (k = 0, Nyquist, μ below resolution) must
// stay within the sampling law of what μ puts there plus rounding.
Results check_spectrum(const Analysis& a, OceanCheckReport&) {
  const double alpha = a.options().alpha / 2;
  std::vector<const Wave*> order;
  for (const Wave& w : a.waves()) order.push_back(&w);
  std::sort(order.begin(), order.end(), [](const Wave* x, const Wave* y) { return x->k < y->k; });
  const int n = int(order.size());
  const int rings = std::clamp(n / 64, 1, 24);
  std::vector<double> p_values;
  double worst_ratio = 1, worst_k = 0, worst_p = 1;
  double low_ratio = 1e300, high_ratio = 0;
  for (int r = 0; r < rings; ++r) {
    const int begin = r * n / rings, end = (r + 1) * n / rings;
    double sum = 0;
    for (int i = begin; i < end; ++i) sum += a.periodogram0(order[i]->index) / order[i]->mu;
    const double count = end - begin;
    const double p = std::min(1.0, 2 * std::min(stats::gamma_lower_p(count, sum),
                                                stats::gamma_upper_p(count, sum)));
    p_values.push_back(p);
    const double ratio = sum / count;
    low_ratio = std::min(low_ratio, ratio);
    high_ratio = std::max(high_ratio, ratio);
    if (p <= worst_p) {
      worst_p = p;
      worst_ratio = ratio;
      worst_k = 0.5 * (order[begin]->k + order[end - 1]->k);
    }
  }
  const double p = stats::fisher_combined_p(p_values);
  // In the engine's terms: a band of |k| carrying twice its energy (two cascades overlapping).
  std::string shape_hint;
  if (p < alpha) {
    int doubled = 0;
    double lowest = 1e300;
    for (int r = 0; r < rings; ++r) {
      const int begin = r * n / rings, end = (r + 1) * n / rings;
      double energy = 0, observed = 0;
      for (int i = begin; i < end; ++i) {
        energy += order[i]->mu;
        observed += a.periodogram0(order[i]->index);
      }
      const double ratio = observed / energy;  // energy-weighted: what the ring carries
      doubled += std::abs(ratio - 2) < 0.3;
      lowest = std::min(lowest, ratio);
    }
    if (doubled >= 2 && lowest < 1.3) {
      shape_hint = fmt::format(" — {} rings of |k| carry twice their energy: a band counted twice "
                               "(overlapping cascades?)", doubled);
    }
  }
  Results out;
  out.push_back(statistical_check(
      "spectrum.shape", a.subject(), worst_ratio, 1.0, p, alpha,
      fmt::format("p ≥ α = {:.0e} (Gamma law per ring, Fisher's method over {} rings)", alpha, rings),
      fmt::format("periodogram/model {:.3f}…{:.3f} over {} rings of |k| ({} wave vectors); "
                  "worst ring at k = {:.4g} rad/m: {:.3f} (p = {:.2g}){}",
                  low_ratio, high_ratio, rings, n, worst_k, worst_ratio, worst_p,
                  p < alpha ? " — the spectrum's shape differs from the case's" + shape_hint : "")));

  // Energy where the case puts (almost) none.
  const Sampling& sampling = a.sampling();
  const bool grid = !sampling.is_lattice();
  const Grid& g = sampling.grid();
  double stray = 0, largest_stray = 0, stray_corner = 0;
  std::size_t largest_at = 0;
  std::vector<double> weights;
  for (std::size_t e = 0; e < a.count(); ++e) {
    const bool carries = sampling.carries_energy(e);
    const bool unresolved = !carries || a.mu()[e] < a.floor();
    if (!unresolved) continue;
    const auto [nn, m] = sampling.wave_index(e);
    const double power = a.periodogram0(e);
    stray += power;
    if (grid && std::abs(nn) >= g.nx / 4 && std::abs(m) >= g.ny / 4) stray_corner += power;
    if (power > largest_stray) {
      largest_stray = power;
      largest_at = e;
    }
    if (carries && in_half_plane(nn, m) && a.mu()[e] > 0) weights.push_back(2 * a.mu()[e]);
  }
  double bound = 0;
  if (!weights.empty()) bound = stats::WeightedExponentialSum(weights).quantile(1 - alpha);
  // The field's own rounding (u per value, amplified by log2 N through a transform) may all
  // land there.
  const double rounding = std::pow(16 * a.unit_roundoff() * a.log2n(), 2) * a.mean_square0();
  bound += rounding;
  const auto [stray_n, stray_m] = sampling.wave_index(largest_at);
  std::string where = fmt::format("largest at (n, m) = ({}, {})", stray_n, stray_m);
  if (grid && (Grid::is_nyquist(stray_n, g.nx) || Grid::is_nyquist(stray_m, g.ny))) {
    where += ", the Nyquist row/column";
  }
  if (!grid && largest_at != 0 && sampling.conjugate(largest_at) == largest_at) {
    where += ", the lattice's self-conjugate class N/2";
  }
  // A (−1)^(i+j) factor shifts the spectrum by (nx/2, ny/2): the waves pile up around the
  // Nyquist corner.
  if (stray_corner > 0.5 * stray) {
    where += fmt::format("; {:.0f} % of it near the Nyquist corner — a checkerboard (−1)^(i+j)",
                         100 * stray_corner / stray);
  }
  // Heave: k = 0 is the mean level. An artist sees the whole patch rise and fall (or sit
  // offset), not "energy at (0, 0)".
  if (largest_at == 0 && stray > bound) {
    const double share = a.periodogram0(0) / a.mean_square0();
    double level_sum = 0, level_square = 0, level_min = 1e300, level_max = -1e300;
    const auto frames = a.frames().frames.size();
    for (std::size_t f = 0; f < frames; ++f) {
      const auto& h = a.frames().field(int(f), Field::height);
      const double level = std::accumulate(h.begin(), h.end(), 0.0) / double(h.size());
      level_sum += level;
      level_square += level * level;
      level_min = std::min(level_min, level);
      level_max = std::max(level_max, level);
    }
    const double rms = std::sqrt(level_square / double(frames));
    const double rounding_level = 16 * a.unit_roundoff() * a.log2n() * std::sqrt(a.mean_square0());
    if (frames > 1 && level_max - level_min > rounding_level) {
      where = fmt::format("k = 0 carries {:.0f} % of the height variance: the mean level moves (heave) — "
                          "the whole patch rises and falls, rms {:.3g} m, from {:.3g} to {:.3g} m over the "
                          "frames",
                          100 * share, rms, level_min, level_max);
    } else {
      where = fmt::format("k = 0 carries {:.0f} % of the height variance: the mean level sits at {:.3g} m "
                          "instead of 0",
                          100 * share, level_sum / double(frames));
    }
  }
  const bool ok = stray <= bound;
  out.push_back(bounded(
      "spectrum.unexpected_energy", a.subject(), stray / a.mean_square0(), bound / a.mean_square0(),
      fmt::format("fraction of mean h² where the case puts none ≤ {:.1e} (1 − α quantile + rounding)",
                  bound / a.mean_square0()),
      ok ? fmt::format("{:.1e} of the energy where the case puts none", stray / a.mean_square0())
         : fmt::format("{:.3g} of the energy sits where the case puts none ({})",
                       stray / a.mean_square0(), where)));
  return out;
}

// ------------------------------------------------------------------ moments

Results check_moments(const Analysis& a, OceanCheckReport& report) {
  Results out;
  const bool free = a.options().free_scale;
  const double alpha = a.options().alpha / (free ? 3 : 4);
  // m_n = Σk ω^n I(k) = Σ half plane 2 ω^n I(k); expected with μ; Cov(m_a, m_b) = Σ 4 ω^(a+b) μ².
  std::array<double, 3> measured{}, expected{};
  std::array<std::array<double, 3>, 3> cov{};
  for (const Wave& w : a.half_plane()) {
    const double I = a.periodogram0(w.index);
    double power[3] = {1, w.omega, w.omega * w.omega};
    for (int x = 0; x < 3; ++x) {
      measured[x] += 2 * power[x] * I;
      expected[x] += 2 * power[x] * w.mu;
      for (int y = 0; y < 3; ++y) cov[x][y] += 4 * power[x] * power[y] * w.mu * w.mu;
    }
  }
  // Hs = 4 √m0 with m0's exact law.
  if (!free) {
    std::vector<double> weights;
    for (const Wave& w : a.half_plane()) weights.push_back(2 * w.mu);
    const stats::WeightedExponentialSum law(weights);
    const double lo = 4 * std::sqrt(law.quantile(alpha / 2)), hi = 4 * std::sqrt(law.quantile(1 - alpha / 2));
    const double hs = 4 * std::sqrt(measured[0]), hs_expected = 4 * std::sqrt(expected[0]);
    const double p = law.two_sided_p(measured[0]);
    out.push_back(statistical_check("moments.hs", a.subject(), hs, hs_expected, p, alpha,
                              fmt::format("p ≥ α = {:.1e}: Hs in [{:.4g}, {:.4g}] m", alpha, lo, hi),
                              fmt::format("Hs {:.4g} m against {:.4g} m (band-limited){}", hs,
                                          hs_expected, p < alpha ? " — wrong wave height" : "")));
  }
  // Periods as ratios of moments, T = 2π (m0/m_n)^exponent. The law of the ratio R = m0/m_n is
  // exact up to the saddlepoint: P(R ≤ r) = P(Σ 2μ(1 − r ωⁿ) E ≤ 0), a sum of exponentials of
  // both signs. (The delta method's normal law, used before, fails where few waves dominate —
  // a patch of 0.15 m holding only the spectrum's tail gave z = −5 on right surfaces; property
  // test, issue 10.) Its z is kept for the message. A period within rounding (64 u log2 N) of the
  // expected one passes whatever the law: one wave's period is exact and its law degenerate.
  auto period_check = [&](const char* name, int n, double exponent) {
    // d log T = exponent (d m0/m0 − d m_n/m_n).
    const double t = 2 * kPi * std::pow(measured[0] / measured[n], exponent);
    const double t_expected = 2 * kPi * std::pow(expected[0] / expected[n], exponent);
    const double ratio = measured[0] / measured[n];
    std::vector<double> coefficients;
    for (const Wave& w : a.half_plane()) {
      coefficients.push_back(2 * w.mu * (1 - ratio * (n == 1 ? w.omega : w.omega * w.omega)));
    }
    const double below = stats::mixed_exponential_sum_cdf_at_zero(coefficients);
    const double rounding = 64 * a.unit_roundoff() * a.log2n();
    const double var_log = exponent * exponent *
                           (cov[0][0] / (expected[0] * expected[0]) -
                            2 * cov[0][n] / (expected[0] * expected[n]) +
                            cov[n][n] / (expected[n] * expected[n])) +
                           std::pow(16 * a.unit_roundoff() * a.log2n(), 2);  // rounding (one wave: 0 variance)
    const double z = std::log(t / t_expected) / std::sqrt(var_log);
    const double p = std::abs(std::log(t / t_expected)) <= rounding
                         ? 1.0
                         : std::min(1.0, 2 * std::min(below, 1 - below));
    out.push_back(statistical_check(fmt::format("moments.{}", name), a.subject(), t, t_expected, p, alpha,
                              fmt::format("p ≥ α = {:.1e} (saddlepoint law of m0/m_n; delta-method z = {:.2f})", alpha, z),
                              fmt::format("{} {:.4g} s against {:.4g} s (z = {:.2f}){}", name, t,
                                          t_expected, z,
                                          p < alpha ? " — the spectrum's frequency content differs" : "")));
  };
  period_check("tm01", 1, 1.0);
  period_check("tm02", 2, 0.5);

  // Tp: the peak of the periodogram binned in ω (bins 4 % wide). Under the right spectrum, with
  // probability ≥ 1 − α every bin lies within its two-sided α/B band (Bonferroni); the
  // measured peak then falls among the bins whose upper bound reaches the largest lower bound.
  struct Bin {
    std::vector<double> weights;
    double observed = 0, expected_energy = 0, omega_weighted = 0;
  };
  std::map<int, Bin> bins;
  for (const Wave& w : a.waves()) {
    if (w.omega <= 0) continue;
    Bin& bin = bins[int(std::floor(std::log(w.omega) / std::log(1.04)))];
    bin.weights.push_back(2 * w.mu);
    bin.observed += 2 * a.periodogram0(w.index);
    bin.expected_energy += 2 * w.mu;
    bin.omega_weighted += 2 * w.mu * w.omega;
  }
  const double per_bin = alpha / double(2 * bins.size());
  double largest_lower = 0;
  std::map<int, std::pair<double, double>> band;
  for (auto& [key, bin] : bins) {
    const stats::WeightedExponentialSum law(bin.weights);
    band[key] = {law.quantile(per_bin), law.quantile(1 - per_bin)};
    largest_lower = std::max(largest_lower, band[key].first);
  }
  int peak = bins.begin()->first, expected_peak = peak;
  double t_lo = 1e300, t_hi = 0;
  for (auto& [key, bin] : bins) {
    if (bin.observed > bins[peak].observed) peak = key;
    if (bin.expected_energy > bins[expected_peak].expected_energy) expected_peak = key;
  }
  auto bin_period = [&](int key) { return 2 * kPi * bins[key].expected_energy / bins[key].omega_weighted; };
  for (auto& [key, bin] : bins) {
    if (band[key].second >= largest_lower) {
      t_lo = std::min(t_lo, bin_period(key));
      t_hi = std::max(t_hi, bin_period(key));
    }
  }
  const double tp = bin_period(peak), tp_expected = bin_period(expected_peak);
  const bool admissible = band[peak].second >= largest_lower;
  CheckResult tp_result = statistical_check(
      "moments.tp", a.subject(), tp, tp_expected, admissible ? 1.0 : 0.0, alpha,
      fmt::format("peak bin among those that can be the peak at α = {:.1e}: Tp in [{:.4g}, {:.4g}] s",
                  alpha, t_lo, t_hi),
      fmt::format("Tp {:.4g} s (peak of the periodogram in 4 % bins of ω) against {:.4g} s{}", tp,
                  tp_expected, admissible ? "" : " — the spectral peak is misplaced"));
  tp_result.p_value = std::numeric_limits<double>::quiet_NaN();  // a set test, not a p-value
  tp_result.passed = admissible;
  tp_result.tolerance = 0.5 * (t_hi - t_lo);
  out.push_back(tp_result);
  if (free) report.skipped.push_back("moments.hs: the case declares a free spectrum scale");
  return out;
}

// ------------------------------------------------------------------ dispersion

// Exact for a right surface: at each resolved k the frames are a e^(−iωt) + b e^(iωt) at the
// case's ω(k), to rounding. The residual energy fraction left by that fit and the ω that fits
// best, per wave vector, measure how far the engine's dispersion is from the case's.
double best_omega(double omega0, double max_omega, const std::vector<double>& times,
                  std::span<const Complex> y) {
  auto residual_at = [&](double omega) {
    Complex a, b;
    double residual = 0;
    if (!fit_two_waves(omega, times, y, a, b, residual)) return std::numeric_limits<double>::infinity();
    return residual;
  };
  const double lo = omega0 / 3, hi = std::min(3 * omega0, max_omega);
  const int steps = 1200;
  double best = omega0, best_residual = residual_at(omega0);
  for (int s = 0; s <= steps; ++s) {
    const double omega = lo * std::pow(hi / lo, double(s) / steps);
    const double r = residual_at(omega);
    if (r < best_residual) {
      best_residual = r;
      best = omega;
    }
  }
  // Golden-section refinement around the best grid point.
  double left = best * std::pow(hi / lo, -1.0 / steps), right = best * std::pow(hi / lo, 1.0 / steps);
  const double golden = 0.5 * (std::sqrt(5.0) - 1);
  for (int i = 0; i < 100 && right - left > 1e-14 * best; ++i) {
    const double x1 = right - golden * (right - left), x2 = left + golden * (right - left);
    if (residual_at(x1) < residual_at(x2)) right = x2; else left = x1;
  }
  return 0.5 * (left + right);
}

struct MeasuredOmega {
  double k = 0, omega = 0;
};

// What relation the measured ω(k) follows, in an engine developer's terms: another depth,
// ω = g k, or a loop period that quantizes ω. Empty when none fits to 10⁻³.
std::string explain_dispersion(const OceanCase& c, const std::vector<MeasuredOmega>& measured) {
  if (measured.empty()) return "";
  const double g = c.gravity;
  auto fits = [&](const std::function<double(double)>& omega_of_k) {
    for (const auto& m : measured) {
      if (!(std::abs(omega_of_k(m.k) - m.omega) <= 1e-3 * m.omega)) return false;
    }
    return true;
  };
  // Depth: ω² = g k tanh(k h) solved for h wave by wave; the median, then checked against all.
  std::vector<double> depths;
  for (const auto& m : measured) {
    const double x = m.omega * m.omega / (g * m.k);
    depths.push_back(x >= 1 ? reference::kInfiniteDepth : std::atanh(x) / m.k);
  }
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  const double depth = depths[depths.size() / 2];
  const auto at_depth = reference::Dispersion::finite_depth(depth, g);
  if (fits([&](double k) { return at_depth.omega(k); })) {
    const std::string found = std::isinf(depth) ? "deep water" : fmt::format("a depth of {:.3g} m", depth);
    const std::string said = std::isinf(c.depth) ? "deep water" : fmt::format("{:g} m", c.depth);
    return fmt::format("the frames follow the dispersion of {}; the case says {}", found, said);
  }
  if (fits([&](double k) { return g * k; })) return "the frames follow ω = g k: a missing square root";
  // A loop period T quantizes ω down to multiples of 2π/T: search T from the slowest wave's
  // period to 10⁴ s in steps of 10⁻⁵ relative.
  const auto unquantized = reference::Dispersion::finite_depth(c.depth, g);
  double slowest = 1e300;
  for (const auto& m : measured) slowest = std::min(slowest, m.omega);
  auto worst_error = [&](double period) {
    double worst = 0;
    for (const auto& m : measured) {
      const double predicted = reference::quantize_omega(unquantized.omega(m.k), period);
      worst = std::max(worst, std::abs(predicted - m.omega) / m.omega);
      if (worst > 1e-3) break;
    }
    return worst;
  };
  double best_period = 0, best_error = 1e-3;
  for (double period = 2 * kPi / (2 * slowest); period <= 1e4; period *= 1 + 1e-5) {
    const double error = worst_error(period);
    if (error <= best_error) {
      best_error = error;
      best_period = period;
    } else if (best_period > 0 && period > best_period * 1.01) {
      break;  // past the window of periods that fit
    }
  }
  if (best_period > 0) {
    return c.loop_period > 0
               ? fmt::format("ω is quantized by a loop period of {:.4g} s; the case says {:g} s",
                             best_period, c.loop_period)
               : fmt::format("ω is quantized by a loop period of {:.4g} s the case does not declare",
                             best_period);
  }
  if (c.loop_period > 0 && fits([&](double k) { return unquantized.omega(k); })) {
    return fmt::format("ω is not quantized by the case's loop period of {:g} s", c.loop_period);
  }
  return "";
}

// Least squares of a1 e^(−iω1t) + b1 e^(iω1t) + a2 e^(−iω2t) + b2 e^(iω2t) to y_f at t_f: the
// residual Σ |y − fit|² (infinite when the four columns are nearly dependent).
double two_frequency_residual(double omega1, double omega2, const std::vector<double>& times,
                              std::span<const Complex> y) {
  const std::size_t count = times.size();
  // Normal equations AᴴA x = Aᴴy of the four columns, solved by Gaussian elimination with
  // partial pivoting; a pivot below 10⁻⁹ of the largest diagonal means dependent columns.
  std::array<std::array<Complex, 5>, 4> m{};
  thread_local std::vector<std::array<Complex, 4>> rows;
  rows.resize(count);
  for (std::size_t f = 0; f < count; ++f) {
    const Complex e1 = reference::unit_phasor(-reference::reduced_phase(omega1, times[f]));
    const Complex e2 = reference::unit_phasor(-reference::reduced_phase(omega2, times[f]));
    rows[f] = {e1, std::conj(e1), e2, std::conj(e2)};
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) m[i][j] += std::conj(rows[f][i]) * rows[f][j];
      m[i][4] += std::conj(rows[f][i]) * y[f];
    }
  }
  const double scale = double(count);
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r) {
      if (std::abs(m[r][col]) > std::abs(m[pivot][col])) pivot = r;
    }
    if (std::abs(m[pivot][col]) < 1e-9 * scale) return std::numeric_limits<double>::infinity();
    std::swap(m[col], m[pivot]);
    for (int r = 0; r < 4; ++r) {
      if (r == col) continue;
      const Complex factor = m[r][col] / m[col][col];
      for (int c = col; c < 5; ++c) m[r][c] -= factor * m[col][c];
    }
  }
  std::array<Complex, 4> x{};
  for (int i = 0; i < 4; ++i) x[i] = m[i][4] / m[i][i];
  double residual = 0;
  for (std::size_t f = 0; f < count; ++f) {
    Complex fit = 0;
    for (int i = 0; i < 4; ++i) fit += rows[f][i] * x[i];
    residual += std::norm(y[f] - fit);
  }
  return residual;
}

// Mixed frequencies (issue 16): when one frequency pair ±ω(k) per wave vector leaves much of
// the energy, on the most energetic wave vectors:
//   1. two pairs at the frequencies an offset lattice makes, ω(|c k ± d (Δkx, Δky)|) for
//      (c, d) = (2, 1), (1, ½), (1, 1), explaining the frames to 10⁻⁶ of the energy on 4 in 5 wave
//      vectors, are named as such (over a short record two close frequencies also look like one
//      wrong ω to 10⁻³; these fits are exact);
//   2. one pair at a free ω (best_omega) explaining the frames (median residual < 10⁻³ of the
//      energy) is a single wrong dispersion relation — explain_dispersion names it; not mixed;
//   3. otherwise two free pairs (a log grid over [ω/4, 4ω]², coordinate golden-section
//      refinement), explaining them to 10⁻³ and both carrying ≥ 1 % of the energy, are reported
//      as ratios to ω(k).
// Empty when none applies.
std::string explain_mixed_frequencies(const Analysis& a, const std::vector<const WaveFit*>& strongest,
                                      double max_omega) {
  const auto& series = a.wave_series();
  const auto& times = a.times();
  if (strongest.empty()) return "";
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  auto series_of = [&](const WaveFit* f) -> std::span<const Complex> {
    return series[std::size_t(f->wave - a.waves().data())];
  };
  // 1. The offsets engines make: exact (10⁻⁶) where a single free ω explains only
  // approximately over a short record.
  const auto& c = a.ocean_case();
  const double dkx = a.sampling().dkx(), dky = a.sampling().dky();
  struct Hypothesis {
    double scale, offset;
    const char* text;
  };
  for (const Hypothesis& h : {Hypothesis{2, 1, "ω(|2k ± Δk|): the wave numbers are offset from the grid "
                                               "(2k + Δk for bin k, paired with a bin one off)"},
                              Hypothesis{1, 0.5, "ω(|k ± Δk/2|): the wave numbers are offset from the "
                                                 "grid by half a bin"},
                              Hypothesis{1, 1, "ω(|k ± Δk|): each bin is paired with a neighbour"}}) {
    int matching = 0;
    for (const WaveFit* f : strongest) {
      const double kx = f->wave->kx, ky = f->wave->ky;
      const double plus = c.omega(std::hypot(h.scale * kx + h.offset * dkx, h.scale * ky + h.offset * dky));
      const double minus = c.omega(std::hypot(h.scale * kx - h.offset * dkx, h.scale * ky - h.offset * dky));
      const double residual = two_frequency_residual(plus, minus, times, series_of(f));
      matching += residual <= 1e-6 * f->energy;
    }
    if (matching * 5 >= int(strongest.size()) * 4) {
      return fmt::format("each bin holds two frequencies, at {} ({} of the {} most energetic wave "
                         "vectors)",
                         h.text, matching, strongest.size());
    }
  }
  // 2. One free frequency.
  std::vector<double> single;
  for (const WaveFit* f : strongest) {
    const auto& y = series_of(f);
    const double omega = best_omega(f->wave->omega, max_omega, times, y);
    Complex p, q;
    double residual = 0;
    single.push_back(fit_two_waves(omega, times, y, p, q, residual) ? residual / std::max(f->energy, 1e-300)
                                                                    : 1.0);
  }
  if (median(single) < 1e-3) return "";
  // 3. Two free frequencies.
  std::vector<double> residuals, r1, r2;
  for (const WaveFit* f : strongest) {
    const auto& y = series_of(f);
    const double omega = f->wave->omega;
    const double lo = omega / 4, hi = std::min(4 * omega, max_omega);
    if (!(hi > lo)) continue;
    const int steps = 96;
    auto at = [&](int i) { return lo * std::pow(hi / lo, double(i) / steps); };
    double best = std::numeric_limits<double>::infinity(), w1 = omega, w2 = omega;
    for (int i = 0; i <= steps; ++i) {
      for (int j = i + 1; j <= steps; ++j) {
        const double r = two_frequency_residual(at(i), at(j), times, y);
        if (r < best) {
          best = r;
          w1 = at(i);
          w2 = at(j);
        }
      }
    }
    const double step = std::pow(hi / lo, 1.0 / steps);
    for (int round = 0; round < 4; ++round) {
      for (int which = 0; which < 2; ++which) {
        double& moving = which == 0 ? w1 : w2;
        double left = moving / step, right = moving * step;
        auto residual = [&](double x) {
          return which == 0 ? two_frequency_residual(x, w2, times, y) : two_frequency_residual(w1, x, times, y);
        };
        const double golden = 0.5 * (std::sqrt(5.0) - 1);
        for (int i = 0; i < 60 && right - left > 1e-13 * right; ++i) {
          const double x1 = right - golden * (right - left), x2 = left + golden * (right - left);
          if (residual(x1) < residual(x2)) right = x2; else left = x1;
        }
        moving = 0.5 * (left + right);
      }
    }
    // Each pair must carry its share: the second pair alone must explain ≥ 1 % more.
    Complex p, q;
    double alone1 = 0, alone2 = 0;
    if (!fit_two_waves(w1, times, y, p, q, alone1)) alone1 = f->energy;
    if (!fit_two_waves(w2, times, y, p, q, alone2)) alone2 = f->energy;
    const double both = two_frequency_residual(w1, w2, times, y);
    if (std::min(alone1, alone2) - both < 1e-2 * f->energy) continue;
    residuals.push_back(both / std::max(f->energy, 1e-300));
    r1.push_back(std::min(w1, w2) / omega);
    r2.push_back(std::max(w1, w2) / omega);
  }
  if (residuals.size() * 2 < strongest.size() || !(median(residuals) < 1e-3)) return "";
  return fmt::format("each bin holds two frequencies, at {:.3f}× and {:.3f}× ω(k) (medians over {} of "
                     "the most energetic wave vectors): the frames mix two wave numbers per bin",
                     median(r1), median(r2), residuals.size());
}

// The median of (value, weight) pairs by weight: the first value, in increasing order, at which
// the weights reach half their sum. Reorders `pairs`.
double energy_weighted_median(std::vector<std::pair<double, double>>& pairs) {
  std::sort(pairs.begin(), pairs.end());
  double total = 0, half = 0;
  for (const auto& p : pairs) total += p.second;
  for (const auto& p : pairs) {
    half += p.second;
    if (half >= total / 2) return p.first;
  }
  return pairs.back().first;
}

Results check_dispersion(const Analysis& a, OceanCheckReport& report) {
  if (a.times().size() < 3) {
    report.skipped.push_back("dispersion: needs ≥ 3 frames (the fit has 2 complex unknowns per k)");
    return {};
  }
  const auto& fits = a.wave_fits();
  if (fits.empty()) {
    report.skipped.push_back("dispersion: no wave vector's two waves are identifiable from these "
                             "frame times (2ω dt ≈ 0 mod 2π everywhere)");
    return {};
  }
  double residual = 0, energy = 0;
  for (const WaveFit& f : fits) {
    residual += f.residual;
    energy += f.energy;
  }
  const double fraction = residual / std::max(energy, 1e-300);
  // Rounding alone leaves at most (u log2 N)² of the energy; allow 64× that.
  const double bound = std::pow(64 * a.unit_roundoff() * a.log2n(), 2);
  Results out;

  // ω per wave vector, for the most energetic wave vectors whose ω is below the frames'
  // Nyquist frequency π/dt (above it ω aliases).
  double dt = 0;
  for (std::size_t f = 1; f < a.times().size(); ++f) dt = std::max(dt, a.times()[f] - a.times()[f - 1]);
  const double max_omega = 0.95 * kPi / dt;
  std::vector<const WaveFit*> strongest;
  for (const WaveFit& f : fits) {
    if (f.wave->omega > 0 && 3 * f.wave->omega / 2 < max_omega) strongest.push_back(&f);
  }
  std::sort(strongest.begin(), strongest.end(),
            [](const WaveFit* x, const WaveFit* y) { return x->energy > y->energy; });
  if (strongest.size() > 24) strongest.resize(24);
  const auto& series = a.wave_series();
  std::vector<std::pair<double, double>> ratios;  // (ω measured / ω case, energy)
  std::vector<std::pair<double, double>> rounding;  // (what rounding can move that ratio by, energy)
  std::vector<MeasuredOmega> measured;
  // The stored numbers' rounding is noise of power u² mean(h²)/N on each wave vector's
  // coefficient in each frame (resolution_floor's), which moves the phase of a wave of power P
  // by about √(noise/2P) a frame; a frequency fitted to F frames over a span T moves by that ×
  // √(12/F)/T (the standard error of a regression slope). Six such errors, relative to ω: far
  // below 10⁻⁶ for the waves that carry a sea's energy, but not for waves barely above the
  // resolution floor, which are all a case leaves below the frames' Nyquist frequency when its
  // energy lies above it.
  const double frames = double(a.times().size());
  const double span = a.times().back() - a.times().front();
  const double noise = a.unit_roundoff() * a.unit_roundoff() * a.mean_square0() / double(a.sample_count());
  for (const WaveFit* f : strongest) {
    const std::size_t w = std::size_t(f->wave - a.waves().data());
    const double omega = best_omega(f->wave->omega, max_omega, a.times(), series[w]);
    ratios.push_back({omega / f->wave->omega, f->energy});
    const double power = f->energy / frames;
    rounding.push_back({power > 0 ? 6 * std::sqrt(noise / (2 * power)) * std::sqrt(12 / frames) /
                                        (f->wave->omega * span)
                                  : 0.0,
                        f->energy});
    measured.push_back({f->wave->k, omega});
  }
  const double ratio = ratios.empty() ? 1 : energy_weighted_median(ratios);
  // More than 1 % left by one frequency pair: look for two.
  std::string mixed;
  if (fraction > std::max(bound, 1e-2) && a.times().size() >= 6) {
    mixed = explain_mixed_frequencies(a, strongest, max_omega);
  }
  std::string diagnosis;
  if (!mixed.empty()) {
    diagnosis = " — " + mixed;
  } else if (fraction > bound) {
    diagnosis = " — the waves do not evolve as the case's dispersion says";
    if (!ratios.empty() && std::abs(ratio - 1) > 1e-3) {
      diagnosis += fmt::format(" (ω is {:.3f}× the case's", ratio);
      const std::string explanation = explain_dispersion(a.ocean_case(), measured);
      diagnosis += explanation.empty() ? ")" : "; " + explanation + ")";
    } else if (!ratios.empty()) {
      diagnosis += " (ω is right: the amplitudes change from frame to frame)";
    }
  }
  out.push_back(bounded(
      "dispersion.residual", a.subject(), fraction, bound,
      fmt::format("residual energy fraction ≤ {:.1e} (rounding)", bound),
      fmt::format("fit a e^(−iωt) + b e^(iωt) at ω(k) leaves {:.2e} of the energy over {} wave "
                  "vectors and {} frames{}",
                  fraction, fits.size(), a.times().size(), diagnosis)));
  if (!mixed.empty()) {
    // No single ratio exists: the measured ω is not one number per wave vector.
    const double omega_bound = std::max(1e-6, 64 * a.unit_roundoff() * a.log2n());
    out.push_back(bounded("dispersion.omega", a.subject(), std::numeric_limits<double>::quiet_NaN(),
                          omega_bound,
                          fmt::format("|ω measured / ω(k) − 1| ≤ {:.1e} (energy-weighted median)", omega_bound),
                          "no single ω per wave vector — " + mixed));
  } else if (!ratios.empty()) {
    const double error = std::abs(ratio - 1);
    const double omega_bound = std::max({1e-6, 64 * a.unit_roundoff() * a.log2n(),
                                         energy_weighted_median(rounding)});
    out.push_back(bounded(
        "dispersion.omega", a.subject(), error, omega_bound,
        fmt::format("|ω measured / ω(k) − 1| ≤ {:.1e} (energy-weighted median)", omega_bound),
        fmt::format("measured ω / case ω = {:.6f} (median over the {} most energetic wave "
                    "vectors){}",
                    ratio, ratios.size(), error <= omega_bound ? "" : " — wrong dispersion relation")));
  } else {
    report.skipped.push_back("dispersion.omega: every energetic ω is above the frames' Nyquist "
                             "frequency π/dt");
  }
  return out;
}

// ------------------------------------------------------------------ direction

// dᵀ C⁺ d for a symmetric positive semi-definite C and d in C's column space, with the rank
// of C: Gaussian elimination with diagonal pivoting (LDLᵀ), pivots at or below 1e-10 of the
// largest diagonal are C's null space and are dropped. A few waves all along one line (a
// narrow Phillips spectrum on a small grid) make the harmonics' covariance singular; the
// statistic then has that many fewer degrees of freedom, not a NaN (property test, issue 10).
template <std::size_t D>
double quadratic_form(std::array<std::array<double, D>, D> c, std::array<double, D> d, int& rank) {
  double largest = 0;
  for (std::size_t i = 0; i < D; ++i) largest = std::max(largest, c[i][i]);
  double form = 0;
  rank = 0;
  for (std::size_t k = 0; k < D; ++k) {
    std::size_t pivot = k;
    for (std::size_t r = k + 1; r < D; ++r) {
      if (c[r][r] > c[pivot][pivot]) pivot = r;
    }
    std::swap(c[k], c[pivot]);
    for (auto& row : c) std::swap(row[k], row[pivot]);
    std::swap(d[k], d[pivot]);
    if (!(c[k][k] > 1e-10 * largest)) break;  // the rest is null space
    ++rank;
    for (std::size_t r = k + 1; r < D; ++r) {
      const double factor = c[r][k] / c[k][k];
      for (std::size_t j = k; j < D; ++j) c[r][j] -= factor * c[k][j];
      d[r] -= factor * d[k];
    }
    form += d[k] * d[k] / c[k][k];
  }
  return form;
}

// From the fitted travelling waves: |a|² is the power moving along +k (E = τ(k)), |b|² along
// −k (E = τ(−k)), all independent exponentials. T = Dᵀ C⁻¹ D of the score below ~ χ²(4)
// (central limit over the wave vectors). And a, b are independent: Re(a b) / √(τ+ τ− / 2)
// has mean 0 and variance 1.
Results check_direction(const Analysis& a, OceanCheckReport& report) {
  if (a.times().size() < 2) {
    report.skipped.push_back("direction: needs ≥ 2 frames (one frame cannot tell k from −k)");
    return {};
  }
  const auto& fits = a.wave_fits();
  if (fits.empty()) {
    report.skipped.push_back("direction: no wave vector's two waves are identifiable from these frame times");
    return {};
  }
  const double alpha = a.options().alpha / 2;
  struct Entry { double theta, power, tau; };
  std::vector<Entry> entries;
  for (const WaveFit& f : fits) {
    entries.push_back({f.wave->theta, std::norm(f.a), f.wave->tau_plus});
    entries.push_back({f.wave->theta + kPi, std::norm(f.b), f.wave->tau_minus});
  }
  auto harmonics = [](double theta) {
    return std::array<double, 4>{std::cos(theta), std::sin(theta), std::cos(2 * theta), std::sin(2 * theta)};
  };
  // Score test of a directional modulation τ (1 + β·g(θ)): with u = P/τ ~ Exp(1) independent,
  // D = Σ (u − 1)(g − ḡ) has mean 0 and covariance Σ (g − ḡ)(g − ḡ)ᵀ; equal weights per wave
  // make the central limit accurate even where a few waves carry most of the energy. Only
  // waves above the rounding floor take part.
  std::array<double, 4> mean_g{};
  int used = 0;
  for (const Entry& e : entries) {
    if (!(e.tau >= a.floor())) continue;
    const auto g = harmonics(e.theta);
    for (int i = 0; i < 4; ++i) mean_g[i] += g[i];
    ++used;
  }
  for (double& v : mean_g) v /= std::max(used, 1);
  std::array<double, 4> d{};
  std::array<std::array<double, 4>, 4> cov{};
  Complex measured_resultant = 0, expected_resultant = 0;
  double power_total = 0, tau_total = 0;
  for (const Entry& e : entries) {
    measured_resultant += e.power * std::polar(1.0, e.theta);
    expected_resultant += e.tau * std::polar(1.0, e.theta);
    power_total += e.power;
    tau_total += e.tau;
    if (!(e.tau >= a.floor())) continue;
    auto g = harmonics(e.theta);
    for (int i = 0; i < 4; ++i) g[i] -= mean_g[i];
    for (int i = 0; i < 4; ++i) {
      d[i] += (e.power / e.tau - 1) * g[i];
      for (int j = 0; j < 4; ++j) cov[i][j] += g[i] * g[j];
    }
  }
  int rank = 0;
  const double t = quadratic_form<4>(cov, d, rank);
  const double p = rank > 0 ? stats::chi_squared_upper_p(t, rank) : 1.0;
  const double theta_measured = std::arg(measured_resultant) * kDegree;
  const double theta_expected = std::arg(expected_resultant) * kDegree;
  const double spread_measured = std::sqrt(2 * (1 - std::abs(measured_resultant) / power_total)) * kDegree;
  const double spread_expected = std::sqrt(2 * (1 - std::abs(expected_resultant) / tau_total)) * kDegree;
  double turn = std::remainder(theta_measured - theta_expected, 360.0);
  std::string diagnosis;
  if (p < alpha) {
    if (std::abs(turn) > 135) {
      diagnosis = " — waves travel against the wind (time reversed or e^(+iωt) on h̃0(k))";
    } else if (std::abs(measured_resultant) < 0.25 * std::abs(expected_resultant)) {
      diagnosis = " — as much energy travels along −k as along +k: standing waves";
    } else {
      diagnosis = " — the directional distribution differs from the case's spreading";
    }
  }
  Results out;
  out.push_back(statistical_check(
      "direction.distribution", a.subject(), theta_measured, theta_expected, p, alpha,
      fmt::format("p ≥ α = {:.1e} (χ²({}) of the first two circular harmonics)", alpha, rank),
      fmt::format("mean direction {:.1f}° (spread {:.1f}°) against {:.1f}° ({:.1f}°), "
                  "T = {:.1f}{}",
                  theta_measured, spread_measured, theta_expected, spread_expected, t, diagnosis)));

  double sum = 0;
  int count = 0;
  for (const WaveFit& f : fits) {
    // Both waves must stand above the rounding floor: a wave the model makes 10⁻³⁰ of the
    // peak is pure rounding noise in the data, not a sample of its law.
    if (!(f.wave->tau_plus >= a.floor() && f.wave->tau_minus >= a.floor())) continue;
    const double product = f.wave->tau_plus * f.wave->tau_minus;
    sum += (f.a * f.b).real() / std::sqrt(0.5 * product);
    ++count;
  }
  if (count < 8) {
    report.skipped.push_back("direction.travelling: fewer than 8 wave vectors carry energy both "
                             "ways (one-sided spreading)");
    return out;
  }
  const double z = sum / std::sqrt(double(count));
  const double p_travel = stats::normal_two_sided_p(z);
  out.push_back(statistical_check(
      "direction.travelling", a.subject(), z, 0.0, p_travel, alpha,
      fmt::format("p ≥ α = {:.1e} (normal, {} wave vectors)", alpha, count),
      fmt::format("waves at k and −k independent: z = {:.2f}{}", z,
                  p_travel < alpha ? " — h̃0(k) and h̃0(−k) are correlated (the same random pair "
                                     "reused, or standing waves)"
                                   : "")));
  return out;
}

// ------------------------------------------------------------------ randomness

// Reused random numbers (issue 16): the initial amplitudes recovered from the frames — h̃0(k)
// and h̃0(−k) from the two-wave fit at every identifiable wave vector, or ĥ(k, 0) over the half
// plane from one frame at t = 0 — divided by their expected rms, z = h̃0/√τ, are independent
// unit complex normals on a right surface. Two distinct wave vectors that drew the same pair
// have the same z (up to the recovery's rounding σ). The check counts pairs closer than
// 8 √(σ1² + σ2²); for independent z, d = z1 − z2 ~ CN(0, 2) and P(|d| < ε) = 1 − e^(−ε²/2), so
// the count is Poisson with mean λ0 = Σ pairs (1 − e^(−ε²/2)) ≤ 32 (M − 1) Σ σ² (closed form),
// and p = P(Poisson(λ0) ≥ count). Only waves recovered to σ ≤ 10⁻⁵ enter (λ0 ≤ 32 M² 10⁻¹⁰).
// σ² = s²/(F τ): white rounding of variance s² = (16 u log2 N)² mean h² / N per coefficient
// and frame, through a least-squares fit over F frames.
Results check_randomness(const Analysis& a, OceanCheckReport& report) {
  struct Draw {
    Complex z;
    double sigma = 0;
    int n = 0, m = 0;
  };
  std::vector<Draw> draws;
  const double s2 = std::pow(16 * a.unit_roundoff() * a.log2n(), 2) * a.mean_square0() / double(a.count());
  constexpr double kLargestSigma = 1e-5;
  const auto frames = double(a.times().size());
  const Sampling& g = a.sampling();
  if (a.times().size() >= 2) {
    for (const WaveFit& f : a.wave_fits()) {
      const auto [n, m] = g.wave_index(f.wave->index);
      for (int side = 0; side < 2; ++side) {
        const double tau = side == 0 ? f.wave->tau_plus : f.wave->tau_minus;
        if (!(tau > 0)) continue;
        const double sigma = std::sqrt(s2 / (frames * tau));
        if (sigma > kLargestSigma) continue;
        const Complex amplitude = side == 0 ? f.a : std::conj(f.b);  // h̃0(k), h̃0(−k)
        draws.push_back({amplitude / std::sqrt(tau), sigma, side == 0 ? n : -n, side == 0 ? m : -m});
      }
    }
    if (draws.empty() && a.wave_fits().empty()) {
      report.skipped.push_back("randomness: no wave vector's two waves are identifiable from these "
                               "frame times");
      return {};
    }
  } else if (a.times().front() == 0) {
    for (const Wave& w : a.waves()) {
      const double sigma = std::sqrt(s2 / w.mu);
      if (sigma > kLargestSigma) continue;
      const auto [n, m] = g.wave_index(w.index);
      draws.push_back({a.spectrum0()[w.index] / std::sqrt(w.mu), sigma, n, m});
    }
  } else {
    report.skipped.push_back("randomness: one frame at t ≠ 0 cannot tell h̃0(k) from conj h̃0(−k)");
    return {};
  }
  // Close pairs, by a sweep in Re z.
  std::sort(draws.begin(), draws.end(), [](const Draw& x, const Draw& y) { return x.z.real() < y.z.real(); });
  double sigma_max = 0, sigma_sum = 0;
  // A z near 0 (a wave far weaker than its expected power: a field that is wrong otherwise) can
  // match nothing meaningfully; under the hypothesis P(|z| < 10⁻³) = 10⁻⁶.
  draws.erase(std::remove_if(draws.begin(), draws.end(), [](const Draw& d) { return std::abs(d.z) < 1e-3; }),
              draws.end());
  for (const Draw& d : draws) {
    sigma_max = std::max(sigma_max, d.sigma);
    sigma_sum += d.sigma * d.sigma;
  }
  const double reach = 8 * std::sqrt(2.0) * sigma_max;
  long long pairs = 0, mirror_pairs = 0;
  std::vector<char> shared(draws.size(), 0);
  for (std::size_t i = 0; i < draws.size(); ++i) {
    for (std::size_t j = i + 1; j < draws.size() && draws[j].z.real() - draws[i].z.real() <= reach; ++j) {
      const double epsilon = 8 * std::hypot(draws[i].sigma, draws[j].sigma);
      if (std::abs(draws[i].z - draws[j].z) > epsilon) continue;
      ++pairs;
      if (draws[i].n == -draws[j].n && draws[i].m == -draws[j].m) ++mirror_pairs;
      shared[i] = shared[j] = 1;
    }
  }
  const double count = double(draws.size());
  const double lambda0 = count > 1 ? 32 * (count - 1) * sigma_sum : 0;
  // P(Poisson(λ0) ≥ pairs) = regularized lower incomplete gamma P(pairs, λ0).
  const double p = pairs == 0 ? 1.0 : stats::gamma_lower_p(double(pairs), lambda0);
  const double alpha = a.options().alpha;
  const long long sharing = std::count(shared.begin(), shared.end(), 1);
  std::string reason = fmt::format("{} pairs of the {} recovered amplitudes coincide (chance: "
                                   "{:.2g} expected, p = {:.2g})",
                                   pairs, draws.size(), lambda0, p);
  if (p < alpha) {
    reason = mirror_pairs == pairs
                 ? fmt::format("h̃0(k) and h̃0(−k) share their random pair at {} wave vectors — the same "
                               "random numbers for k and −k; ",
                               pairs)
                 : fmt::format("{:.1f} % of the wave vectors ({} of {}) share their random pair with "
                               "another: reused random numbers (a hash of the index that collides, or "
                               "a seed per row?); ",
                               100 * double(sharing) / count, sharing, draws.size()) +
                       reason;
  }
  return {statistical_check(
      "randomness.reused_numbers", a.subject(), double(pairs), lambda0, p, alpha,
      fmt::format("p ≥ α = {:.1e} (coinciding pairs of h̃0/√τ, Poisson law, {} amplitudes)", alpha,
                  draws.size()),
      reason)};
}

// ------------------------------------------------------------------ statistics

Results check_statistics(const Analysis& a, OceanCheckReport& report) {
  Results out;
  const bool several_frames = a.times().size() >= 2;
  const double alpha = a.options().alpha / (several_frames ? 4 : 3);
  const auto& h = a.frames().field(0, Field::height);
  const double n = double(a.count());

  // Sample skewness and kurtosis of a Gaussian field on the torus: with covariance
  // C(d) = Σk μ(k) e^(ik·d), Var(mean h³) = (6/n) Σd C(d)³ and the kurtosis linearizes to
  // mean He4(h)/σ⁴ with Var = (24/n) Σd C(d)⁴ / σ⁸ (Isserlis; Σd C(d) = 0 as k = 0 is empty).
  std::vector<Complex> mu_complex(a.mu().begin(), a.mu().end());
  // On a lattice the differences of sample points are lattice points again (x_n − x_n' =
  // x_(n−n')), so C over them is the lattice's own inverse transform of μ.
  const auto covariance = field_from_spectrum(mu_complex, a.sampling());
  double sigma2 = covariance[0], c3 = 0, c4 = 0;
  for (double c : covariance) {
    c3 += c * c * c;
    c4 += c * c * c * c;
  }
  double m2 = 0, m3 = 0, m4 = 0;
  for (double x : h) {
    const double x2 = x * x;
    m2 += x2;
    m3 += x2 * x;
    m4 += x2 * x2;
  }
  m2 /= n;
  m3 /= n;
  m4 /= n;
  const double skewness = m3 / std::pow(m2, 1.5);
  const double kurtosis = m4 / (m2 * m2) - 3;
  // Plus the rounding of the normalized moments (64 u log2 N, the dispersion check's bound): a
  // law of zero variance (one wave pair: a sampled cosine's skewness is exactly 0) is judged
  // against rounding instead of dividing by zero; 16 u log2 N was measured too tight (a 16²
  // surface of one wave pair showed 550 u, property test of issue 10).
  const double moment_rounding = 64 * a.unit_roundoff() * a.log2n();
  const double sd_skew = std::hypot(std::sqrt(6 * std::max(c3, 0.0) / n) / std::pow(sigma2, 1.5),
                                    moment_rounding);
  const double sd_kurt = std::hypot(std::sqrt(24 * std::max(c4, 0.0) / n) / (sigma2 * sigma2),
                                    moment_rounding);
  const double z_skew = skewness / sd_skew, z_kurt = kurtosis / sd_kurt;
  const double p_skew = stats::normal_two_sided_p(z_skew), p_kurt = stats::normal_two_sided_p(z_kurt);
  out.push_back(statistical_check("statistics.skewness", a.subject(), skewness, 0.0, p_skew, alpha,
                            fmt::format("p ≥ α = {:.1e}, sd {:.3g} from the spectrum", alpha, sd_skew),
                            fmt::format("skewness of heights {:.3g} (z = {:.2f}){}", skewness, z_skew,
                                        p_skew < alpha ? " — heights are not Gaussian" : "")));
  out.push_back(statistical_check("statistics.kurtosis", a.subject(), kurtosis, 0.0, p_kurt, alpha,
                            fmt::format("p ≥ α = {:.1e}, sd {:.3g} from the spectrum", alpha, sd_kurt),
                            fmt::format("excess kurtosis of heights {:.3g} (z = {:.2f}){}", kurtosis,
                                        z_kurt, p_kurt < alpha ? " — heights are not Gaussian" : "")));

  // Gaussian amplitudes: u = I/μ are independent exponentials. Anderson–Darling against the
  // exponential law with its scale estimated (mean u), so that this part judges the shape of
  // the law only — an energy error is the energy check's to name.
  std::vector<double> u;
  double u_sum = 0;
  for (const Wave& w : a.waves()) {
    u.push_back(a.periodogram0(w.index) / w.mu);
    u_sum += u.back();
  }
  const double u_mean = u_sum / double(u.size());
  std::vector<double> cdf, log_survival;
  for (double x : u) {
    cdf.push_back(-std::expm1(-x / u_mean));
    log_survival.push_back(-x / u_mean);
  }
  const double a2 = stats::anderson_darling_statistic(cdf, log_survival);
  const double p_ad = stats::anderson_darling_exponential_p(a2, int(cdf.size()));
  out.push_back(statistical_check(
      "statistics.gaussian_amplitudes", a.subject(), a2, 1.0, p_ad, alpha,
      fmt::format("p ≥ α = {:.1e} (Anderson–Darling, I/μ exponential, scale fitted, n = {})", alpha,
                  cdf.size()),
      fmt::format("A² = {:.3g} for the normalized periodogram{}", a2,
                  p_ad < alpha ? " — the amplitudes are not complex Gaussian (|h̃|² not exponential: "
                                 "uniform noise, or h̃0(k) and h̃0(−k) correlated?)"
                               : "")));

  // Hs steady: m0(t) − m0(t0) = 4 Σ half plane Re(a b̄ (e^(−2iωt) − e^(−2iωt0))), mean 0,
  // variance 8 Σ τ+ τ− |e^(−2iωt) − e^(−2iωt0)|², plus rounding.
  if (!several_frames) {
    report.skipped.push_back("statistics.hs_steady: needs ≥ 2 frames");
    return out;
  }
  const auto& times = a.times();
  const double m0_first = a.mean_square0();
  double worst_z = 0, hs_min = 1e300, hs_max = 0;
  int worst_frame = 0;
  // e^(−2iωt) once per distinct ω and frame (group_by_omega; one per wave vector was 7 % of the
  // gate's CPU at 512² × 64 frames).
  const auto& waves = a.half_plane();
  const OmegaGroups by_omega = group_by_omega(waves);
  auto phases_at = [&](double t, std::vector<Complex>& phases) {
    phases.resize(by_omega.omegas.size());
    for (std::size_t g = 0; g < by_omega.omegas.size(); ++g) {
      phases[g] = reference::unit_phasor(-reference::reduced_phase(2 * by_omega.omegas[g], t));
    }
  };
  std::vector<Complex> first_phase;  // e^(−2iωt0) per distinct ω
  phases_at(times[0], first_phase);
  const std::vector<double> sums = sums_of_squares<double>(heights(a.frames()));
  // Σ over the waves for each frame, four frames side by side (each frame's sum sequential, as
  // in sums_of_squares, so that their addition latencies overlap).
  constexpr std::size_t kSideBySide = 4;
  std::vector<double> variances(times.size(), 0.0);
  std::vector<Complex> phase[kSideBySide];  // e^(−2iωt) per distinct ω of frames f … f + 3
  for (std::size_t f = 1; f < times.size(); f += kSideBySide) {
    const std::size_t together = std::min(kSideBySide, times.size() - f);
    for (std::size_t j = 0; j < together; ++j) phases_at(times[f + j], phase[j]);
    double sum[kSideBySide] = {};
    auto add = [&](std::size_t frames_here) {
      for (std::size_t i = 0; i < waves.size(); ++i) {
        const Wave& w = waves[i];
        const std::size_t g = by_omega.group[i];
        const double weight = 8 * w.tau_plus * w.tau_minus;
        for (std::size_t j = 0; j < frames_here; ++j) sum[j] += weight * std::norm(phase[j][g] - first_phase[g]);
      }
    };
    if (together == kSideBySide) {
      add(kSideBySide);  // a constant count: the four sums unrolled
    } else {
      add(together);
    }
    for (std::size_t j = 0; j < together; ++j) variances[f + j] = sum[j];
  }
  for (std::size_t f = 1; f < times.size(); ++f) {
    const double m0 = sums[f] / n;  // mean_square of frame f
    const double variance = variances[f] + std::pow(16 * a.unit_roundoff() * a.log2n() * m0_first, 2);
    const double z = (m0 - m0_first) / std::sqrt(variance);
    if (std::abs(z) >= std::abs(worst_z)) {
      worst_z = z;
      worst_frame = int(f);
    }
    hs_min = std::min(hs_min, 4 * std::sqrt(m0));
    hs_max = std::max(hs_max, 4 * std::sqrt(m0));
  }
  hs_min = std::min(hs_min, 4 * std::sqrt(m0_first));
  hs_max = std::max(hs_max, 4 * std::sqrt(m0_first));
  const double frames_compared = double(times.size() - 1);
  const double p_steady = std::min(1.0, frames_compared * stats::normal_two_sided_p(worst_z));
  out.push_back(statistical_check(
      "statistics.hs_steady", a.subject(), 4 * std::sqrt(m0_first), hs_max - hs_min, p_steady, alpha,
      fmt::format("p ≥ α = {:.1e} (Bonferroni over {} frames)", alpha, times.size() - 1),
      fmt::format("Hs {:.4g}…{:.4g} m over {} frames; largest change z = {:.2f} at frame {}{}", hs_min,
                  hs_max, times.size(), worst_z, worst_frame,
                  p_steady < alpha ? " — Hs drifts over the frames" : "")));
  return out;
}

// ------------------------------------------------------------------ derived fields

// Why a slope or displacement field disagrees with its definition from the height field, on
// frame 0 (issue 16): the field against four templates — its own definition and the other
// axis's, each from the height as given and from the height transposed (square grids) — each
// with its least-squares factor c (λ for displacements, 1 for slopes). A template explains the
// field when its residual's rms is within max(10 × the check's bound, 10⁻³) of the field's;
// then the message names it: swapped channels, a transposed field, another λ, a flipped sign.
// A mean (k = 0) that carries most of the misfit is a sway of the whole patch.
std::string explain_derived(const Analysis& a, Field field, double bound) {
  const Sampling& g = a.sampling();
  const bool displacement = field == Field::disp_x || field == Field::disp_y;
  const bool along_x = field == Field::slope_x || field == Field::disp_x;
  const double lambda = displacement ? a.ocean_case().choppiness : 1.0;
  const std::string name = reference::field_name(field);
  const std::string other_name =
      reference::field_name(displacement ? (along_x ? Field::disp_y : Field::disp_x)
                                         : (along_x ? Field::slope_y : Field::slope_x));
  const auto& got = a.frames().field(0, field);
  const double got_power = mean_square(got);
  // Sway: the field's mean carries most of what is wrong.
  const double mean = std::accumulate(got.begin(), got.end(), 0.0) / double(got.size());
  const auto& spectrum = a.spectrum0();
  auto template_field = [&](bool x_axis, bool transposed) {
    std::vector<Complex> s(spectrum.size());
    const int nx = g.grid().nx;
    for (std::size_t e = 0; e < spectrum.size(); ++e) {
      if (!g.carries_energy(e)) continue;
      const auto [n, m] = g.wave_index(e);
      const double kx = n * g.dkx(), ky = m * g.dky(), k = std::hypot(kx, ky);
      const double component = x_axis ? kx : ky;
      const Complex multiplier = displacement ? Complex(0, component / k) : Complex(0, component);
      // The transposed height's coefficient at (n, m) is the height's at (m, n).
      const std::size_t source =
          transposed ? std::size_t((n + nx) % nx) * nx + std::size_t((m + nx) % nx) : e;
      s[e] = multiplier * spectrum[source];
    }
    return field_from_spectrum(s, g);
  };
  struct Candidate {
    bool other_axis, transposed;
    double factor = 0, residual = 1e300;  // residual: rms misfit relative to the field's rms
  };
  std::vector<Candidate> candidates = {{false, false}, {true, false}};
  const auto& grid = g.grid();
  if (!g.is_lattice() && grid.nx == grid.ny && grid.lx == grid.ly) {
    candidates.push_back({false, true});
    candidates.push_back({true, true});
  }
  for (auto& c : candidates) {
    const auto t = template_field(c.other_axis ? !along_x : along_x, c.transposed);
    double tt = 0, gt = 0;
    for (std::size_t p = 0; p < t.size(); ++p) {
      tt += t[p] * t[p];
      gt += got[p] * (t[p]);
    }
    c.factor = tt > 0 ? gt / tt : 0;
    double left = 0;
    for (std::size_t p = 0; p < t.size(); ++p) left += std::pow(got[p] - c.factor * t[p], 2);
    c.residual = got_power > 0 ? std::sqrt(left / double(t.size()) / got_power) : 0;
  }
  const auto best = *std::min_element(candidates.begin(), candidates.end(),
                                      [](const Candidate& x, const Candidate& y) { return x.residual < y.residual; });
  const double explains = std::max(10 * bound, 1e-3);
  const double own_residual = candidates[0].residual;
  if (mean * mean > 0.5 * own_residual * own_residual * got_power && std::abs(mean) > 0) {
    return fmt::format("{} sways: its mean {:.3g} m moves the whole patch sideways (k = 0 carries "
                       "what the conventions leave empty)",
                       name, mean);
  }
  const std::string factor_name = displacement ? "λ" : "scale";
  const bool same_size = std::abs(std::abs(best.factor) / lambda - 1) < 1e-3;
  const bool flipped = best.factor * lambda < 0;
  if (best.residual <= explains) {
    std::string what;
    if (best.other_axis && best.transposed) {
      what = fmt::format("{} holds {}'s definition applied to the transposed height", name, other_name);
    } else if (best.other_axis) {
      what = fmt::format("{} and {} swapped ({} holds {}'s definition)", name, other_name, name,
                         other_name);
    } else if (best.transposed) {
      what = fmt::format("the field is transposed (x and y exchanged) relative to the height: {} "
                         "matches its definition from the transposed height",
                         name);
    }
    if (what.empty()) {  // its own definition, another factor
      if (flipped && same_size) {
        return fmt::format("sign flipped: the best-fit {} is {:.4g} against the case's {:g} "
                           "(conventions: D ↔ +i k/|k| h̃; Tessendorf's −i needs λ < 0)",
                           factor_name, best.factor, lambda);
      }
      return fmt::format("{} is {:.4g}, not the case's {:g} (least squares; it explains the "
                         "field to {:.1e})",
                         factor_name, best.factor, lambda, best.residual);
    }
    if (!same_size || flipped) {
      what += fmt::format(", with {} = {:.4g} (the case's {:g})", factor_name, best.factor, lambda);
    } else {
      what += fmt::format(" ({} = {:.4g}, the case's)", factor_name, best.factor);
    }
    return what;
  }
  return fmt::format("inconsistent with the height field: no {} explains it (the best, {} = {:.3g} "
                     "with its own definition, leaves {:.2g} of its rms){}",
                     factor_name, factor_name, candidates[0].factor, own_residual,
                     candidates[0].factor * lambda < 0 ? " — sign flipped?" : "");
}

// Each derived field against its definition applied to the height field (conventions
// §Derived fields). Rounding bound: the stored height's rounding, white with variance ≤ u²
// mean(h²), pushed through the field's multiplier, plus the field's own rounding; 10× that.
Results check_derived(const Analysis& a, OceanCheckReport& report) {
  const Sampling& g = a.sampling();
  const double lambda = a.ocean_case().choppiness;
  const std::vector<Field> derived = {Field::slope_x, Field::slope_y, Field::disp_x, Field::disp_y,
                                      Field::jacobian};
  std::vector<Field> present;
  for (Field f : derived) {
    if (a.frames().has(f)) present.push_back(f);
  }
  if (present.empty()) {
    report.skipped.push_back("derived: no slope, displacement or Jacobian field given");
    return {};
  }
  // Multipliers per wave vector in FFT order, of (kx, ky) and |k| = hypot(kx, ky).
  auto multiplier = [&](Field field, double kx, double ky, double k) -> Complex {
    if (k == 0) return 0;
    switch (field) {
      case Field::slope_x: return {0, kx};
      case Field::slope_y: return {0, ky};
      case Field::disp_x: return {0, lambda * kx / k};
      case Field::disp_y: return {0, lambda * ky / k};
      default: return 0;
    }
  };
  // kx, ky and |k| per entry, made once for the up to 14 derivations below (hypot in each of
  // their loops was a third of this check's time).
  const std::size_t count = a.count();
  std::vector<double> kx_of(count), ky_of(count), k_of(count);
  for (std::size_t e = 0; e < count; ++e) {
    const auto [nn, mm] = g.wave_index(e);
    kx_of[e] = nn * g.dkx();
    ky_of[e] = mm * g.dky();
    k_of[e] = std::hypot(kx_of[e], ky_of[e]);
  }
  std::map<Field, double> worst_error, bound_at_worst;
  std::vector<std::size_t> checked_frames = {0};
  if (a.frames().frames.size() > 1) checked_frames.push_back(a.frames().frames.size() - 1);
  const double u = a.unit_roundoff();
  for (std::size_t frame : checked_frames) {
    const auto& h = a.frames().field(int(frame), Field::height);
    const auto spectrum = frame == 0 ? a.spectrum0() : field_spectrum(h, g);
    const double h_power = mean_square(h);
    auto derive = [&](const auto& m, double& mean_m2) {
      std::vector<Complex> s(spectrum.size());
      mean_m2 = 0;
      for (std::size_t e = 0; e < spectrum.size(); ++e) {
        const Complex mult = g.carries_energy(e) ? m(kx_of[e], ky_of[e], k_of[e]) : 0.0;
        s[e] = mult * spectrum[e];
        mean_m2 += std::norm(mult);
      }
      mean_m2 /= double(spectrum.size());
      return field_from_spectrum(s, g);
    };
    for (Field field : present) {
      std::vector<double> expected;
      std::vector<double> got = a.frames().field(int(frame), field);
      double mean_m2 = 0, jacobian_products = 0;
      if (field == Field::jacobian) {
        double m_xx = 0, m_yy = 0, m_xy = 0;
        const auto dxx = derive([&](double kx, double, double k) { return Complex(-lambda * kx * kx / k); }, m_xx);
        const auto dyy = derive([&](double, double ky, double k) { return Complex(-lambda * ky * ky / k); }, m_yy);
        const auto dxy = derive([&](double kx, double ky, double k) { return Complex(-lambda * kx * ky / k); }, m_xy);
        expected.resize(dxx.size());
        jacobian_products = 0;
        for (std::size_t p = 0; p < dxx.size(); ++p) {
          const double product = (1 + dxx[p]) * (1 + dyy[p]), square = dxy[p] * dxy[p];
          expected[p] = product - square - 1;  // J − 1
          got[p] -= 1;
          // J = (1 + a)(1 + b) − c² rounds relative to its two products, which cancel where
          // the waves are nearly collinear (a narrow spreading: ab ≈ c²) and λ∂D ≫ 1.
          jacobian_products += product * product + square * square;
        }
        jacobian_products /= double(dxx.size());
        mean_m2 = m_xx + m_yy + 2 * m_xy;
      } else {
        expected = derive([&](double kx, double ky, double k) { return multiplier(field, kx, ky, k); }, mean_m2);
      }
      std::vector<double> difference(expected.size());
      for (std::size_t p = 0; p < expected.size(); ++p) difference[p] = got[p] - expected[p];
      const double scale = std::sqrt(std::max(mean_square(expected), 1e-300));
      const double error = std::sqrt(mean_square(difference)) / scale;
      const double own = field == Field::jacobian ? jacobian_products : mean_square(expected);
      // Rounding, in the stored numbers' unit roundoff u: of the stored height, carried into
      // the derived field by its multiplier (h_power·mean |m|²); of the stored field itself
      // (own); and of the engine's own inverse transform of this field, ≈ u log2 N relative in
      // L2 (the accuracy bound of every FFT, DESIGN.md §5) — which a J made of three
      // transformed λ∂D terms shows first (property test of the command line, issue 10).
      // (For J, each factor of its two products carries that error relative to itself.)
      const double transform = a.log2n() * a.log2n() *
                               (field == Field::jacobian ? std::max(mean_square(expected), jacobian_products)
                                                         : mean_square(expected));
      const double rounding = std::sqrt(u * u * (h_power * mean_m2 + own + transform)) / scale;
      const double bound = 10 * rounding + 64 * kFp64Roundoff * a.log2n();
      if (error / bound >= worst_error[field] / std::max(bound_at_worst[field], 1e-300) ||
          !worst_error.count(field)) {
        worst_error[field] = error;
        bound_at_worst[field] = bound;
      }
    }
  }
  Results out;
  for (Field field : present) {
    const double error = worst_error[field], bound = bound_at_worst[field];
    const bool ok = error <= bound;
    std::string diagnosis;
    if (!ok) {
      diagnosis = field == Field::jacobian
                      ? " — inconsistent with the height field (J built without λ, or from other "
                        "displacements)"
                      : " — " + explain_derived(a, field, bound);
    }
    out.push_back(bounded(fmt::format("derived.{}", reference::field_name(field)), a.subject(), error,
                          bound, fmt::format("rel rms error ≤ {:.1e} (rounding)", bound),
                          fmt::format("{} against its definition from h: rel rms error {:.2e}{}",
                                      reference::field_name(field), error, diagnosis)));
  }
  return out;
}

using CheckFunction = Results (*)(const Analysis&, OceanCheckReport&);
const std::vector<std::pair<std::string, CheckFunction>>& registry() {
  static const std::vector<std::pair<std::string, CheckFunction>> checks = {
      {"hermitian", check_hermitian},   {"parseval", check_parseval},
      {"energy", check_energy},         {"spectrum", check_spectrum},
      {"moments", check_moments},       {"dispersion", check_dispersion},
      {"direction", check_direction},   {"randomness", check_randomness},
      {"statistics", check_statistics}, {"derived", check_derived}};
  return checks;
}

}  // namespace

std::vector<std::string> ocean_check_names() {
  std::vector<std::string> names;
  for (const auto& [name, function] : registry()) names.push_back(name);
  return names;
}

void require_judgeable_rounding(const OceanCase& ocean_case, double unit_roundoff,
                                double mean_square_height) {
  const auto mu = expected_periodogram(*ocean_case.directional_spectrum(), ocean_case.sampling());
  const double floor = resolution_floor(unit_roundoff, mean_square_height, mu.size());
  if (std::none_of(mu.begin(), mu.end(), [&](double m) { return m > 0 && m >= floor; })) {
    throw_rounding_hides_every_wave(unit_roundoff, ocean_case);
  }
}

namespace {

void require_known(const std::vector<std::string>& checks) {
  for (const auto& name : checks) {
    const auto& all = registry();
    if (std::none_of(all.begin(), all.end(), [&](const auto& entry) { return entry.first == name; })) {
      std::string valid;
      for (const auto& n : ocean_check_names()) valid += (valid.empty() ? "" : ", ") + n;
      throw InvalidInput("unknown ocean check '" + name + "'; valid: " + valid);
    }
  }
}

OceanCheckReport run_on(const Analysis& analysis, const std::vector<std::string>& checks);

}  // namespace

OceanCheckReport run_ocean_checks(const OceanCase& ocean_case, const FrameSequence& frames,
                                  const OceanCheckOptions& options,
                                  const std::vector<std::string>& checks) {
  require_known(checks);
  return run_on(Analysis(ocean_case, frames, options), checks);
}

std::vector<OceanCheckReport> run_ocean_check_groups(const OceanCase& ocean_case,
                                                     const FrameSequence& frames,
                                                     const FrameSequence& ends,
                                                     const OceanCheckOptions& options,
                                                     const std::vector<OceanCheckGroup>& groups,
                                                     int threads,
                                                     std::vector<double> travelling_power) {
  for (const auto& group : groups) require_known(group.checks);
  // One analysis of the surface for every group (it was made once per group before: μ(k) from Ψ
  // over the grid, frame 0's spectrum and the waves, three times at 512²), and one over the
  // end frames that copies it when their frame 0 is the same field.
  const Analysis analysis(ocean_case, frames, options, threads, std::move(travelling_power));
  const bool same_first = &ends == &frames || ends.field(0, Field::height) == frames.field(0, Field::height);
  std::optional<Analysis> ends_analysis;
  const bool any_ends = std::any_of(groups.begin(), groups.end(), [](const OceanCheckGroup& g) { return g.ends_only; });
  if (any_ends && &ends != &frames) {
    if (same_first) {
      ends_analysis.emplace(analysis, ends);
    } else {
      ends_analysis.emplace(ocean_case, ends, options);
    }
  }
  // The wave series and per-wave fits the time-resolved checks read (and parseval, through the
  // analysis backend, the series' transforms), made first on every thread: a group that needed
  // them would otherwise make them on one thread while the other groups wait for them.
  static const std::vector<std::string> fit_readers = {"dispersion", "direction", "randomness"};
  const std::vector<std::string> series_readers =
      options.analysis_backend == kAnalysisBackend ? std::vector<std::string>{"parseval"}
                                                   : std::vector<std::string>{};
  auto needs = [&](const std::vector<std::string>& readers) {
    return std::any_of(groups.begin(), groups.end(), [&](const OceanCheckGroup& g) {
      return std::any_of(readers.begin(), readers.end(), [&](const std::string& name) {
        return g.checks.empty() || std::find(g.checks.begin(), g.checks.end(), name) != g.checks.end();
      });
    });
  };
  if (needs(fit_readers)) {
    analysis.wave_fits();
  } else if (needs(series_readers)) {
    analysis.wave_series();
  }
  std::vector<OceanCheckReport> parts(groups.size());
  detail::run_tasks(groups.size(), threads, [&](std::size_t g) {
    parts[g] = run_on(groups[g].ends_only && ends_analysis ? *ends_analysis : analysis, groups[g].checks);
  });
  return parts;
}

namespace {

OceanCheckReport run_on(const Analysis& analysis, const std::vector<std::string>& checks) {
  const OceanCheckOptions& options = analysis.options();
  OceanCheckReport report;
  report.fitted_scale = analysis.scale();
  for (const auto& [name, function] : registry()) {
    if (!checks.empty() && std::find(checks.begin(), checks.end(), name) == checks.end()) continue;
    for (auto& result : function(analysis, report)) report.results.push_back(std::move(result));
  }
  if (options.free_scale) {
    CheckResult scale;
    scale.check = "scale";
    scale.subject = analysis.subject();
    scale.measured = analysis.scale();
    scale.expected = 1;
    scale.criterion = "reported, not judged (free scale)";
    scale.passed = true;
    scale.reason = fmt::format("the engine's spectrum is {:.4g}× the case's (Hs × {:.4g})",
                               analysis.scale(), std::sqrt(analysis.scale()));
    report.results.insert(report.results.begin(), scale);
  }
  return report;
}

}  // namespace

void two_wave_phases(double omega, const std::vector<double>& times, std::vector<Complex>& phases) {
  phases.resize(times.size());
  for (std::size_t f = 0; f < times.size(); ++f) {
    phases[f] = reference::unit_phasor(-reference::reduced_phase(omega, times[f]));
  }
}

bool fit_two_waves(double omega, const std::vector<double>& times, std::span<const Complex> y,
                   Complex& a, Complex& b, double& residual) {
  // Per thread: the gate runs checks concurrently.
  thread_local std::vector<Complex> phases;
  two_wave_phases(omega, times, phases);
  return fit_two_waves(phases, y, a, b, residual);
}

bool fit_two_waves(std::span<const Complex> phases, std::span<const Complex> y, Complex& a,
                   Complex& b, double& residual) {
  const double frames = double(phases.size());
  Complex s = 0, r1 = 0, r2 = 0;
  for (std::size_t f = 0; f < phases.size(); ++f) {
    const Complex e = phases[f];
    s += std::conj(e) * std::conj(e);
    r1 += std::conj(e) * y[f];
    r2 += e * y[f];
  }
  // Normal equations [[F, S], [S*, F]] (a, b) = (r1, r2); eigenvalues F ± |S|.
  if (frames - std::abs(s) < 0.05 * frames) return false;
  const double det = frames * frames - std::norm(s);
  a = (frames * r1 - s * r2) / det;
  b = (frames * r2 - std::conj(s) * r1) / det;
  residual = 0;
  for (std::size_t f = 0; f < phases.size(); ++f) {
    const Complex e = phases[f];
    residual += std::norm(y[f] - a * e - b * std::conj(e));
  }
  return true;
}

}  // namespace swell::validation
