#pragma once
// What every ocean check reads (ocean_checks.hpp): one analysis of a surface's frames against
// its case — μ(k) and τ(k) on the samples, frame 0's spectrum, the resolved wave vectors, and,
// made once on first use, every frame's spectrum at them and the two-wave fit per wave vector —
// and the helpers the checks share. One file per check beside it.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include "common/parallel_tasks.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/validation/stats/wave_fit.hpp"

namespace swell::validation::ocean_analysis {

using reference::Field;
using reference::FrameSequence;
using reference::Grid;
using reference::Sampling;
using reference::OceanCase;
using Complex = std::complex<double>;

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = 180.0 / kPi;
constexpr double kFp64Roundoff = 0x1p-53;

double mean_square(const std::vector<double>& v);
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
std::vector<const std::vector<double>*> heights(const FrameSequence& frames);
std::string verdict(bool passed);

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

// The spectrum.shape test of the normalized periodogram u = I/μ of independent Exp(1) ordinates:
// sorted by |k| into rings of n wave vectors (at most 24, at least 64 each where there are that
// many), Σu over a ring ~ Gamma(n, 1) exactly; the rings' two-sided p-values combine by
// Fisher's method.
struct RingShape {
  double p = 1;                       // Fisher's combined p
  int rings = 0;
  double low_ratio = 1, high_ratio = 1;  // the least and greatest ring mean of u
  double worst_ratio = 1, worst_k = 0, worst_p = 1;
  std::vector<double> ratios;  // each ring's mean of u, by |k|
  std::vector<int> counts;     // and its wave vectors
};
struct NormalizedOrdinate {
  double k = 0;  // |k|, rad/m
  double u = 0;  // I(k)/μ(k)
};
RingShape ring_shape(std::vector<NormalizedOrdinate> ordinates);

// Integer frames with a coarse quantization step (8-bit PNG, or 16-bit over a range far wider
// than the values) come here, from the gate and from swell synth alike.
[[noreturn]] void throw_rounding_hides_every_wave(double u, const OceanCase& c);
// The resolution floor of the analysis: a wave vector is resolved when the model puts 10⁶
// times the rounding noise there (white over the N wave vectors: u² mean(h²)/N per k), so that
// rounding moves its periodogram by < 10⁻⁶ relative.
double resolution_floor(double u, double mean_square_height, std::size_t count);
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

// One frame's energy where the case puts none: at k = 0, on wave vectors the sampling leaves
// empty (a grid's Nyquist row and column) and where μ is below the resolution floor —
// mean-square units (Σ |ĥ|² over those wave vectors).
struct FrameStray {
  double energy = 0;
  double corner = 0;       // of it, within a quarter of the Nyquist corner on both axes (grids)
  double nyquist = 0;      // of it, on a grid's Nyquist row and column
  double empty = 0;        // of it, where μ is exactly 0 (k = 0, the Nyquist row and column, …)
  double largest = 0;      // the largest single entry's power,
  std::size_t largest_at = 0;  // and its position in FFT order
  double mean_level = 0;   // ĥ(0): the frame's mean level, m
  double mean_square = 0;  // the frame's mean h², m²
};

// The level of the frames' spectrum against the case's, read from frame 0's rings of |k| (those
// of spectrum.shape): the median of the rings' mean I/μ. Each ring's mean is an equal-count
// average, so a handful of energetic waves near the peak, which make the total energy's ratio
// noisy, move it no more than any other ring. scale.cpp.
struct MeasuredLevel {
  double level = 1;            // the rings' median
  double low = 1, high = 1;    // its ±3 sd range (the median's sd: 1.2533 σ/√rings)
  double lowest_ring = 1, highest_ring = 1;
  int rings = 0;
  bool uniform = false;        // every ring agrees with one factor (Gamma p ≥ 10⁻³/rings each)
  // A level the rings resolve and that is not 1.
  bool off() const { return rings >= 4 && (low > 1 || high < 1); }
};

class Analysis;
std::string diagnose_table_declarations(const Analysis& a);
MeasuredLevel measure_level(const Analysis& a);
// The cause of an energy factor measured as `ratio` with sampling range [low, high]: the known
// single causes, and, where the factor is one on every wave (`one_factor`), the convention
// factors and their products (× 8 = 2 × 2 × 2). Empty when the range holds none.
std::string name_scale_cause(const Analysis& a, double ratio, double low, double high, bool one_factor);

class Analysis {
 public:
  // `travelling`: τ(k) of the case on its samples (expected_travelling_power), evaluated once by
  // whoever runs the checks. `threads` (≥ 1) for the shared work below (wave_series, wave_fits).
  Analysis(const OceanCase& ocean_case, const FrameSequence& frames,
           const OceanCheckOptions& options, std::vector<double> travelling, int threads = 1)
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
    storage_ = frames.storage_roundoff;
    for (const auto& frame : frames.frames) times_.push_back(frame.time);

    if (travelling.size() != sampling_.size()) {
      throw InternalError("Analysis: travelling power of the wrong size");
    }
    shared_->tau = std::move(travelling);
    // Two independent parts side by side (the second is an FFT): run_tasks rethrows the first
    // part's error before the second's, so the error reported is the one a sequential run meets
    // first.
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
    // Half storage: its rounding, at most storage_² of the energy, white over the wave vectors,
    // moves a resolved one's periodogram by < 10⁻⁴ relative — far below what a statistical check
    // sees even summed over 10⁶ wave vectors (relative 10⁻³). Relative to the case's energy: the
    // frames' own (mean h²) over their level (mean h² / Σμ), so that a scale error in the frames
    // does not move which waves are resolved.
    floor_ = std::max(floor_, 1e4 * storage_ * storage_ * expected_total / double(count_));

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
    for (std::size_t e = 0; e < count_; ++e) {
      if (!sampling_.carries_energy(e) || shared_->mu[e] < floor_) shared_->stray.push_back(e);
    }
    if (shared_->resolved.empty()) {
      const bool rounding_hides_all = std::any_of(
          shared_->half_plane.begin(), shared_->half_plane.end(), [](const Wave& w) { return w.mu > 0; });
      if (rounding_hides_all) throw_rounding_hides_every_wave(std::max(u_, storage_), c_);  // coarse integer frames
      throw InvalidInput("no wave vector of the sampling carries resolvable energy under the case's "
                         "spectrum (" + c_.describe() + ")");
    }
  }

  const OceanCase& ocean_case() const { return c_; }
  const FrameSequence& frames() const { return frames_; }
  const OceanCheckOptions& options() const { return options_; }
  const Sampling& sampling() const { return sampling_; }
  std::size_t count() const { return count_; }
  double log2n() const { return log2n_; }
  double unit_roundoff() const { return u_; }
  // The stored values' own relative error where coarser than the arithmetic (half: 2⁻¹⁰), else
  // 0 (FrameSequence::storage_roundoff).
  double storage_roundoff() const { return storage_; }
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
      frame_strays_.assign(frames, FrameStray{});
      const double scale = 1.0 / double(count_);
      const bool grid = !sampling_.is_lattice();
      auto tally_stray = [&](std::size_t f, auto coefficient) {
        FrameStray& s = frame_strays_[f];
        for (std::size_t e : shared_->stray) {
          const double power = std::norm(coefficient(e));
          s.energy += power;
          if (!(shared_->mu[e] > 0)) s.empty += power;
          if (power > s.largest) {
            s.largest = power;
            s.largest_at = e;
          }
          if (grid) {
            const auto [n, m] = sampling_.wave_index(e);
            if (std::abs(n) >= sampling_.grid().nx / 4 && std::abs(m) >= sampling_.grid().ny / 4) s.corner += power;
            if (Grid::is_nyquist(n, sampling_.grid().nx) || Grid::is_nyquist(m, sampling_.grid().ny)) s.nyquist += power;
          }
        }
        s.mean_level = coefficient(0).real();
        s.mean_square = double(spectral_energies_[f]) / double(count_);
      };
      constexpr std::size_t kFramesPerTask = 4;
      detail::run_tasks((frames + kFramesPerTask - 1) / kFramesPerTask, threads_, [&](std::size_t task) {
        const std::size_t first = task * kFramesPerTask, last = std::min(frames, first + kFramesPerTask);
        thread_local std::vector<Complex> block;  // block[i × waves + w]: frame first + i
        block.resize((last - first) * waves);
        for (std::size_t f = first; f < last; ++f) {
          Complex* values = block.data() + (f - first) * waves;
          if (f == 0) {
            for (std::size_t w = 0; w < waves; ++w) values[w] = shared_->spectrum0[shared_->resolved[w].index];
            tally_stray(f, [&](std::size_t e) { return shared_->spectrum0[e]; });
            continue;
          }
          const auto transform =
              analysis_transform(frames_.field(int(f), Field::height), sampling_, &spectral_energies_[f]);
          for (std::size_t w = 0; w < waves; ++w) values[w] = transform[shared_->resolved[w].index] * scale;
          tally_stray(f, [&](std::size_t e) { return transform[e] * scale; });
        }
        for (std::size_t w = 0; w < waves; ++w) {
          for (std::size_t f = first; f < last; ++f) series_.at(w, f) = block[(f - first) * waves + w];
        }
        release_analysis_scratch();
      });
    });
    return series_;
  }

  // Each frame's energy where the case puts none, made with the wave series.
  const std::vector<FrameStray>& frame_strays() const {
    wave_series();
    return frame_strays_;
  }
  // The entries (FFT order) where the case puts no resolvable energy.
  const std::vector<std::size_t>& stray_entries() const { return shared_->stray; }

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

  // The declaration of a tabulated spectrum (model = "table") that explains frame 0 where the
  // case's own does not (table_declarations.cpp), as a clause for a failed check's reason:
  // empty when no other reading of the file explains the frames. Made once, on first use.
  const std::string& misdeclared_table() const {
    std::call_once(table_once_, [this] { misdeclared_table_ = diagnose_table_declarations(*this); });
    return misdeclared_table_;
  }
  // The measured level of frame 0's spectrum (MeasuredLevel), made once on first use: the
  // scale-dependent checks normalize by it, energy and shape name it.
  const MeasuredLevel& measured_level() const {
    std::call_once(level_once_, [this] { level_ = measure_level(*this); });
    return level_;
  }
  int threads() const { return threads_; }

 private:
  const OceanCase& c_;
  const FrameSequence& frames_;
  OceanCheckOptions options_;
  Sampling sampling_;
  std::size_t count_ = 0;
  double log2n_ = 1, u_ = kFp64Roundoff, storage_ = 0, scale_ = 1, floor_ = 0, mean_square0_ = 0;
  long double spectral_energy0_ = 0;
  int threads_ = 1;
  std::vector<double> times_;
  struct Shared {
    std::vector<double> mu, tau;
    std::vector<Complex> spectrum0;
    std::vector<Wave> resolved, half_plane;
    std::vector<std::size_t> stray;
  };
  std::shared_ptr<Shared> shared_ = std::make_shared<Shared>();
  mutable WaveSeries series_;
  mutable std::vector<long double> spectral_energies_;
  mutable std::vector<FrameStray> frame_strays_;
  mutable std::vector<WaveFit> fits_;
  mutable std::string misdeclared_table_;
  mutable MeasuredLevel level_;
  mutable std::once_flag series_once_, fits_once_, table_once_, level_once_;
};

// A failed check's explanation: the misdeclared table's reading where one explains the
// frames, else the check's own `meaning`.
inline std::string or_table(const Analysis& a, const std::string& meaning) {
  return a.misdeclared_table().empty() ? meaning : a.misdeclared_table();
}

using Results = std::vector<CheckResult>;

// The checks, one file each (checks/ocean/<name>.cpp); ocean_checks.cpp's table runs them.
Results check_hermitian(const Analysis& a, OceanCheckReport& report);
Results check_parseval(const Analysis& a, OceanCheckReport& report);
Results check_energy(const Analysis& a, OceanCheckReport& report);
Results check_spectrum(const Analysis& a, OceanCheckReport& report);
Results check_moments(const Analysis& a, OceanCheckReport& report);
Results check_dispersion(const Analysis& a, OceanCheckReport& report);
Results check_direction(const Analysis& a, OceanCheckReport& report);
Results check_randomness(const Analysis& a, OceanCheckReport& report);
Results check_statistics(const Analysis& a, OceanCheckReport& report);
Results check_derived(const Analysis& a, OceanCheckReport& report);

}  // namespace swell::validation::ocean_analysis
