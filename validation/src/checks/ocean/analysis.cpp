#include "checks/ocean/analysis.hpp"
#include "checks/ocean/series_spill.hpp"
#include <chrono>

#include "swell/reference/phase.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::ocean_analysis {

double mean_square(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x * x;
  return sum / double(v.size());
}

namespace {

const std::vector<double>& height_of(const reference::FieldFrame& frame, std::size_t f) {
  const auto it = frame.fields.find(Field::height);
  if (it == frame.fields.end()) throw InvalidInput(fmt::format("frame {} has no height field", f));
  return it->second;
}

}  // namespace

Analysis::Analysis(const OceanCase& ocean_case, const FrameSource& frames, const OceanCheckOptions& options,
                   std::vector<double> travelling, int threads)
    : c_(ocean_case), frames_(frames), options_(options), sampling_(ocean_case.sampling()),
      threads_(std::max(1, threads)) {
  const Sampling given = frames.sampling();
  if (!given.same_as(sampling_)) {
    throw InvalidInput(fmt::format("frames are on a {} but the case says {}", given.describe(),
                                   sampling_.describe()));
  }
  if (frames.size() == 0) throw InvalidInput("no frames to check");
  if (!frames.has(Field::height)) {
    throw InvalidInput("the frames have no height field: every ocean check needs it");
  }
  require(options.alpha > 0 && options.alpha < 1, "alpha", "in (0, 1)", options.alpha);
  count_ = sampling_.size();
  log2n_ = std::max(1.0, std::log2(double(count_)));
  precision_ = frames.precision();
  u_ = std::max(precision_.unit_roundoff, kFp64Roundoff);
  storage_ = precision_.storage_roundoff;
  for (std::size_t f = 0; f < frames.size(); ++f) times_.push_back(frames.time(f));
  const auto first = frames.frame(0, [](int, Field field) { return field == Field::height; });
  const std::vector<double>& height0 = height_of(*first, 0);
  height_moments0_.add(height0, 0.0);

  if (travelling.size() != sampling_.size()) {
    throw InternalError("Analysis: travelling power of the wrong size");
  }
  shared_->tau = std::move(travelling);
  // The half plane's wave vectors in FFT order, made in chunks of the samples that the threads
  // take as they come free (hypot, ω and atan2 per wave were a second of one thread at 4096²):
  // each chunk's waves are counted first, then written at their place in one array of the
  // exact size. In FFT order the half plane (m > 0, and m = 0 with n > 0) is the first half of
  // a grid's rows, so the chunks are many, not one per thread.
  auto in_plane = [&](std::size_t e) {
    if (!sampling_.carries_energy(e)) return false;
    const auto [n, m] = sampling_.wave_index(e);
    return in_half_plane(n, m);
  };
  constexpr std::size_t kChunks = 64;
  const std::size_t chunks = std::min(kChunks, count_);
  const auto chunk_begin = [&](std::size_t c) { return c * count_ / chunks; };
  std::vector<std::size_t> first_wave(chunks + 1, 0);
  // Two independent parts side by side: μ, the sampling rule and the half plane's array (its
  // pages zeroed: 0.7 GB at 4096²), and frame 0's FFT. run_tasks rethrows the first part's
  // error before the second's, so the error reported is the one a sequential run meets first.
  detail::run_tasks(2, threads_, [&](std::size_t part) {
    if (part == 0) {
      shared_->mu = expected_periodogram(shared_->tau, sampling_);  // τ(k) + τ(−k): Ψ evaluated once
      // The validity rule every command shares (reference/sampling_validity.hpp), in the
      // number format the frames were stored in: float32 (EXR, TIFF) or coarser (PNG) unless
      // they carry fp64's rounding.
      reference::require_valid_sampling(
          c_, precision_.unit_roundoff > 2 * kFp64Roundoff ? reference::kFloat32 : reference::kFloat64,
          0, "", &shared_->tau);
      for (std::size_t c = 0; c < chunks; ++c) {
        std::size_t waves = 0;
        for (std::size_t e = chunk_begin(c); e < chunk_begin(c + 1); ++e) waves += in_plane(e);
        first_wave[c + 1] = first_wave[c] + waves;
      }
      shared_->half_plane.resize(first_wave[chunks]);
    } else {
      field_spectrum(height0, sampling_, shared_->spectrum0, &spectral_energy0_);
      mean_square0_ = mean_square(height0);
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
  detail::run_tasks(chunks, threads_, [&](std::size_t c) {
    std::size_t next = first_wave[c];
    for (std::size_t e = chunk_begin(c); e < chunk_begin(c + 1); ++e) {
      if (!in_plane(e)) continue;
      const auto [n, m] = sampling_.wave_index(e);
      Wave& w = shared_->half_plane[next++];
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
    }
  });
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
  {
    std::vector<std::size_t> positions;
    for (std::size_t i = 0; i < shared_->half_plane.size(); ++i) {
      const Wave& w = shared_->half_plane[i];
      if (w.mu >= floor_ && w.mu > 0) positions.push_back(i);
    }
    shared_->resolved = ResolvedWaves(shared_->half_plane, std::move(positions));
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

const FramePass& Analysis::pass() const {
  std::call_once(pass_once_, [this] { run_pass(); });
  return pass_;
}

// One frame at a time, in frame order: its height transformed once (frame 0's is spectrum0),
// then on up to `threads_` threads side by side: each derived field against its definition,
// the frame's own sums (strays, energies, Hermitian, Parseval), and the wave vectors' fit sums
// in chunks. Each sum over frames is added to in frame order, so it is the sum a whole series
// would give, bit for bit.
void Analysis::run_pass() const {
  FramePass& p = pass_;
  const std::size_t frames = times_.size(), waves = shared_->resolved.size();
  p.strays.assign(frames, FrameStray{});
  p.spectral_energies.assign(frames, spectral_energy0_);
  p.spatial_energies.assign(frames, 0);
  p.height_sums.assign(frames, 0);
  // Per resolved wave vector, the sums of fit_two_waves over the frames in frame order (the
  // same additions, so the fit is the one of the whole series): Σ conj(e) y, Σ e y and Σ|y|²;
  // per distinct ω, Σ conj(e)², e = e^(−iωt).
  std::vector<Complex> r1(waves), r2(waves);
  std::vector<double> energy(waves);
  std::vector<Complex> s;  // Σ conj(e)² per distinct ω, sized with the groups at frame 0
  // The dispersion pass (≥ 3 frames) reads each frame's ĥ at the resolved waves back from disk,
  // written a piece at a time.
  if (frames >= 3) p.spill = std::make_shared<SeriesSpill>(waves);
  constexpr std::size_t kSpillPiece = std::size_t(1) << 16;
  std::vector<Complex> spill_piece(p.spill && p.spill->ok() ? std::min(waves, kSpillPiece) : 0);
  p.derived.start(*this);
  if (options_.analysis_backend != kAnalysisBackend) p.parseval.start(*this);
  const bool grid = !sampling_.is_lattice();
  std::vector<Complex> spectrum;   // ĥ of the frame in hand (after frame 0)
  std::vector<Complex> phases;  // e^(−iωt) per distinct ω
  // Chunks of wave vectors, a few per thread, for whichever thread is free.
  const std::size_t wave_chunks = std::min<std::size_t>(waves, std::size_t(2 * threads_));
  const std::size_t derived_units = p.derived.units.size();
  {
    // The pool's threads, and with them their transform scratch, end with the stream.
    detail::TaskPool pool(threads_);
    const KeepAnalysisScratch keep_scratch;
    frames_.stream({}, [&](std::size_t f, const reference::FieldFrame& frame) {
      if (f == 0) {
        // The distinct ω, once the reading of frame 1 has begun (a sort of the half plane: a
        // fifth of a second at 2048²).
        p.half_plane_groups = group_by_omega(shared_->half_plane);
        p.groups = subset_groups(p.half_plane_groups, shared_->resolved.positions());
        s.assign(p.groups.omegas.size(), Complex{});
        phases.resize(p.groups.omegas.size());
      }
      const std::vector<double>& h = height_of(frame, f);
      std::span<const Complex> hat;
      if (f == 0) {
        hat = shared_->spectrum0;
      } else {
        field_spectrum(h, sampling_, spectrum, &p.spectral_energies[f]);
        hat = spectrum;
      }
      {
        long double spatial = 0;
        double sum = 0;
        for (double x : h) {
          spatial += (long double)x * x;
          sum += x * x;
        }
        p.spatial_energies[f] = spatial;
        p.height_sums[f] = sum;
      }
      for (std::size_t g = 0; g < phases.size(); ++g) {
        phases[g] = reference::unit_phasor(-reference::reduced_phase(p.groups.omegas[g], times_[f]));
        s[g] += std::conj(phases[g]) * std::conj(phases[g]);
      }
      const double height_power = p.height_sums[f] / double(count_);  // mean_square(h), bit for bit
      pool.run(derived_units + 1 + wave_chunks, [&](std::size_t task) {
        const KeepAnalysisScratch keep_task_scratch;  // a pool thread's, freed as the pool ends
        if (task < derived_units) {
          p.derived.add(*this, f, task, frame, hat, height_power);
          return;
        }
        if (task == derived_units) {
          FrameStray& s = p.strays[f];
          for (std::size_t e : shared_->stray) {
            const double power = std::norm(hat[e]);
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
          s.mean_level = hat[0].real();
          s.mean_square = double(p.spectral_energies[f]) / double(count_);
          p.hermitian.add(*this, f, frame, hat);
          if (p.parseval.state) p.parseval.add(*this, h);
          return;
        }
        const std::size_t chunk = task - derived_units - 1;
        const std::size_t begin = chunk * waves / wave_chunks, end = (chunk + 1) * waves / wave_chunks;
        for (std::size_t w = begin; w < end; ++w) {
          const Complex e = phases[p.groups.group[w]];
          const Complex y = hat[shared_->resolved[w].index];
          r1[w] += std::conj(e) * y;
          r2[w] += e * y;
          energy[w] += std::norm(y);
        }
      });
      for (std::size_t first = 0; first < waves && !spill_piece.empty(); first += spill_piece.size()) {
        const std::size_t n = std::min(spill_piece.size(), waves - first);
        for (std::size_t w = 0; w < n; ++w) spill_piece[w] = hat[shared_->resolved[first + w].index];
        p.spill->write(f, first, std::span<const Complex>(spill_piece.data(), n));
      }
      progress(f + 1 == frames, [&] { return fmt::format("frame {} of {} judged", f + 1, frames); });
    });
  }
  p.parseval.state.reset();
  p.derived.finish();
  release_analysis_scratch();
  fits_.reserve(waves);
  for (std::size_t w = 0; w < waves; ++w) {
    WaveFit fit;
    fit.wave = &shared_->resolved[w];
    fit.position = w;
    if (!solve_two_waves(double(frames), s[p.groups.group[w]], r1[w], r2[w], fit.a, fit.b)) continue;
    fit.energy = energy[w];
    fits_.push_back(fit);
  }
}

const std::vector<WaveFit>& Analysis::wave_fits() const {
  pass();
  return fits_;
}

const DispersionPass& Analysis::dispersion_pass() const {
  std::call_once(dispersion_once_, [this] { run_dispersion_pass(); });
  return dispersion_;
}

// Each frame's transform at the fitted wave vectors again: from the series the first pass wrote
// to disk, or, where it could not, from the heights streamed again (height only) and
// transformed as the first pass transformed them.
void Analysis::run_dispersion_pass() const {
  const auto& fits = wave_fits();
  const FramePass& p = pass();
  DispersionPass& d = dispersion_;
  const std::size_t frames = times_.size();
  double dt = 0;
  for (std::size_t f = 1; f < frames; ++f) dt = std::max(dt, times_[f] - times_[f - 1]);
  d.max_omega = 0.95 * kPi / dt;
  for (const WaveFit& f : fits) {
    if (f.wave->omega > 0 && 3 * f.wave->omega / 2 < d.max_omega) d.strongest.push_back(&f);
  }
  // The 24 most energetic, equal energies in the fits' order: a partial sort, not a sort of
  // every fit.
  const std::size_t strongest = std::min<std::size_t>(24, d.strongest.size());
  std::partial_sort(d.strongest.begin(), d.strongest.begin() + std::ptrdiff_t(strongest), d.strongest.end(),
                    [](const WaveFit* x, const WaveFit* y) { return x->energy > y->energy || (x->energy == y->energy && x < y); });
  d.strongest.resize(strongest);
  d.series.assign(d.strongest.size(), std::vector<Complex>(frames));
  for (WaveFit& fit : fits_) fit.residual = 0;
  const double scale = 1.0 / double(count_);
  std::vector<Complex> phases(p.groups.omegas.size());
  const std::size_t chunks = std::min<std::size_t>(fits.size(), std::size_t(2 * threads_));
  detail::TaskPool pool(threads_);
  // Frame f's residuals and strongest series from y(w), its transform at resolved wave w
  // exactly as the first pass saw it (frame 0's ĥ, or X(k) · (1/N)): the phases, then the
  // residuals, each in chunks on the pool's threads; `beside`, when given, runs as one more task
  // beside the residuals' chunks (the next frame's values read from the spill).
  const std::size_t phase_chunks = std::min<std::size_t>(phases.size(), std::size_t(2 * threads_));
  auto fold = [&](std::size_t f, const auto& y, const std::function<void()>& beside) {
    pool.run(phase_chunks, [&](std::size_t chunk) {
      const std::size_t begin = chunk * phases.size() / phase_chunks, end = (chunk + 1) * phases.size() / phase_chunks;
      for (std::size_t g = begin; g < end; ++g) {
        phases[g] = reference::unit_phasor(-reference::reduced_phase(p.groups.omegas[g], times_[f]));
      }
    });
    pool.run(chunks + (beside ? 1 : 0), [&](std::size_t chunk) {
      if (chunk == chunks) return beside();
      const std::size_t begin = chunk * fits_.size() / chunks, end = (chunk + 1) * fits_.size() / chunks;
      for (std::size_t i = begin; i < end; ++i) {
        WaveFit& fit = fits_[i];
        const std::size_t w = fit.position;
        const Complex e = phases[p.groups.group[w]];
        fit.residual += std::norm(y(w) - fit.a * e - fit.b * std::conj(e));
      }
    });
    for (std::size_t j = 0; j < d.strongest.size(); ++j) d.series[j][f] = y(d.strongest[j]->position);
  };
  if (p.spill && p.spill->ok()) {
    // Two arrays in turn: frame f + 1's values are read while frame f's are folded.
    std::array<std::vector<Complex>, 2> y;
    y[0].resize(shared_->resolved.size());
    bool whole = p.spill->read(0, y[0]);
    if (frames > 1) y[1].resize(shared_->resolved.size());
    for (std::size_t f = 0; f < frames && whole; ++f) {
      const std::vector<Complex>& values = y[f % 2];
      bool next_read = true;
      std::function<void()> read_next;
      if (f + 1 < frames) read_next = [&] { next_read = p.spill->read(f + 1, y[(f + 1) % 2]); };
      fold(f, [&](std::size_t w) { return values[w]; }, read_next);
      whole = next_read;
    }
    pass_.spill.reset();
    if (whole) return;
    for (WaveFit& fit : fits_) fit.residual = 0;  // the file failed part-way: from the frames
  }
  frames_.stream([](int, Field field) { return field == Field::height; },
                 [&](std::size_t f, const reference::FieldFrame& frame) {
    if (f == 0) {
      fold(f, [&](std::size_t w) { return shared_->spectrum0[shared_->resolved[w].index]; }, {});
    } else {
      const auto transform = analysis_transform(height_of(frame, f), sampling_);
      fold(f, [&](std::size_t w) { return transform[shared_->resolved[w].index] * scale; }, {});
    }
    progress(f + 1 == frames, [&] {
      return fmt::format("frame {} of {} fitted again (dispersion.residual)", f + 1, frames);
    });
  });
  release_analysis_scratch();
}

void Analysis::progress(bool last, const std::function<std::string()>& message) const {
  // At most one line a second, and the last frame's: a log of a long run stays readable.
  if (!options_.progress) return;
  const auto now = std::chrono::steady_clock::now();
  if (!last && now - last_progress_ < std::chrono::seconds(1)) return;
  last_progress_ = now;
  options_.progress(message());
}

[[noreturn]] void throw_rounding_hides_every_wave(double u, const OceanCase& c) {
  throw InvalidInput(fmt::format(
      "the stored values' rounding (unit roundoff {:.2g} relative to the height's rms) hides "
      "every wave vector: none carries 10⁶ times the rounding noise, so no check can judge these "
      "frames ({}); store floats, or 16-bit integers with a value_range close to the values' "
      "extent",
      u, c.describe()));
}

OmegaGroups subset_groups(const OmegaGroups& all, const std::vector<std::size_t>& positions) {
  constexpr std::size_t kAbsent = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> renumbered(all.omegas.size(), kAbsent);
  for (std::size_t i : positions) renumbered[all.group[i]] = 0;
  OmegaGroups out;
  for (std::size_t g = 0; g < all.omegas.size(); ++g) {
    if (renumbered[g] == kAbsent) continue;
    renumbered[g] = out.omegas.size();
    out.omegas.push_back(all.omegas[g]);
  }
  out.group.resize(positions.size());
  for (std::size_t w = 0; w < positions.size(); ++w) out.group[w] = renumbered[all.group[positions[w]]];
  return out;
}

double resolution_floor(double u, double mean_square_height, std::size_t count) {
  return 1e6 * u * u * mean_square_height / double(count);
}

std::vector<NormalizedOrdinate> Analysis::frame0_ordinates() const {
  std::vector<NormalizedOrdinate> ordinates;
  ordinates.reserve(waves().size());
  for (const Wave& w : waves()) ordinates.push_back({w.k, periodogram0(w.index) / w.mu});
  return ordinates;
}

RingShape ring_shape(std::vector<NormalizedOrdinate> ordinates) {
  std::sort(ordinates.begin(), ordinates.end(),
            [](const NormalizedOrdinate& x, const NormalizedOrdinate& y) { return x.k < y.k; });
  RingShape out;
  const int n = int(ordinates.size());
  if (n == 0) return out;
  out.rings = std::clamp(n / 64, 1, 24);
  std::vector<double> p_values;
  out.low_ratio = 1e300, out.high_ratio = 0;
  for (int r = 0; r < out.rings; ++r) {
    const int begin = r * n / out.rings, end = (r + 1) * n / out.rings;
    double sum = 0;
    for (int i = begin; i < end; ++i) sum += ordinates[i].u;
    const double count = end - begin;
    const double p = std::min(1.0, 2 * std::min(stats::gamma_lower_p(count, sum),
                                                stats::gamma_upper_p(count, sum)));
    p_values.push_back(p);
    const double ratio = sum / count;
    out.ratios.push_back(ratio);
    out.counts.push_back(int(count));
    out.low_ratio = std::min(out.low_ratio, ratio);
    out.high_ratio = std::max(out.high_ratio, ratio);
    if (p <= out.worst_p) {
      out.worst_p = p;
      out.worst_ratio = ratio;
      out.worst_k = 0.5 * (ordinates[begin].k + ordinates[end - 1].k);
    }
  }
  out.p = stats::fisher_combined_p(p_values);
  return out;
}

std::string verdict(bool passed) { return passed ? "" : " — FAILED"; }

}  // namespace swell::validation::ocean_analysis
