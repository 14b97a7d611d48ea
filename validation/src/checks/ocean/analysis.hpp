#pragma once
// What every ocean check reads (ocean_checks.hpp): one analysis of a surface's frames against
// its case — μ(k) and τ(k) on the samples, frame 0's spectrum, the resolved wave vectors — and
// what one pass over the frames, made once, gathers for every check: per wave vector the sums
// of the two-wave fit, per frame the sums the checks judge (FramePass); and the second pass the
// dispersion residual needs. The frames stream through (io/frame_source.hpp), one at a time, so
// nothing here grows with their number but a few numbers per frame. One file per check beside it.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
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
#include "common/sorted_by_key.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/io/frame_source.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/validation/stats/sample_moments.hpp"
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
std::string verdict(bool passed);

// One energy-carrying wave vector k of the half plane (its partner −k is implied).
using Wave = HalfPlaneWave;

// The resolved wave vectors (Analysis::waves()): a view of the half plane's, in its order, held
// as their positions in it — one copy of each Wave (80 B), not two.
class ResolvedWaves {
 public:
  ResolvedWaves() = default;
  ResolvedWaves(const std::vector<Wave>& half_plane, std::vector<std::size_t> positions)
      : half_plane_(&half_plane), positions_(std::move(positions)) {}
  std::size_t size() const { return positions_.size(); }
  bool empty() const { return positions_.empty(); }
  const Wave& operator[](std::size_t i) const { return (*half_plane_)[positions_[i]]; }
  // Their positions in the half plane, ascending.
  const std::vector<std::size_t>& positions() const { return positions_; }

  class const_iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Wave;
    using difference_type = std::ptrdiff_t;
    using pointer = const Wave*;
    using reference = const Wave&;
    const_iterator(const ResolvedWaves* waves, std::size_t i) : waves_(waves), i_(i) {}
    const Wave& operator*() const { return (*waves_)[i_]; }
    const Wave* operator->() const { return &(*waves_)[i_]; }
    const_iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator==(const const_iterator& other) const { return i_ == other.i_; }

   private:
    const ResolvedWaves* waves_;
    std::size_t i_;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, positions_.size()}; }

 private:
  const std::vector<Wave>* half_plane_ = nullptr;
  std::vector<std::size_t> positions_;
};

// The travelling-wave amplitudes of one wave vector fitted over the frames:
// h̃(k, t) ≈ a e^(−iωt) + b e^(+iωt).
struct WaveFit {
  const Wave* wave = nullptr;
  std::size_t position = 0;  // of the wave in Analysis::waves()
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
// wave vector. Wave i's ω is omegas[group[i]], the omegas ascending.
struct OmegaGroups {
  std::vector<std::size_t> group;
  std::vector<double> omegas;
};

template <typename Waves>
OmegaGroups group_by_omega(const Waves& waves) {
  OmegaGroups out;
  // Sorted as (ω, position) pairs: a stable sort's order, without reaching into the waves for
  // every comparison.
  const auto order = detail::sorted_by_key(waves.size(), [&](std::size_t i) { return waves[i].omega; });
  out.group.resize(waves.size());
  for (const auto& [omega, i] : order) {
    if (out.omegas.empty() || !(out.omegas.back() == omega)) out.omegas.push_back(omega);
    out.group[i] = out.omegas.size() - 1;
  }
  return out;
}

// group_by_omega of a subset of the waves `all` groups, given as their positions in them
// (ascending): the same groups, numbered among those the subset holds, without a second sort.
OmegaGroups subset_groups(const OmegaGroups& all, const std::vector<std::size_t>& positions);

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
class SeriesSpill;
std::string diagnose_table_declarations(const Analysis& a);
MeasuredLevel measure_level(const Analysis& a);
// The cause of an energy factor measured as `ratio` with sampling range [low, high]: the known
// single causes, and, where the factor is one on every wave (`one_factor`), the convention
// factors and their products (× 8 = 2 × 2 × 2). Empty when the range holds none.
std::string name_scale_cause(const Analysis& a, double ratio, double low, double high, bool one_factor);

// What the pass over the frames gathers for one check, frame by frame, in frame order; each
// fold's add() lives in its check's file. `spectrum` is frame f's height spectrum ĥ = X/N.
struct HermitianFold {
  double worst_residue = 0, worst_symmetry = 0;
  std::string residue_where = "none given", symmetry_where;
  bool any_imaginary = false;
  void add(const Analysis& a, std::size_t f, const reference::FieldFrame& frame,
           std::span<const Complex> spectrum);
};
// Parseval through another backend than the analysis's own (OceanCheckOptions::analysis_backend):
// each frame's height transformed by it. Through the analysis's own, the pass's spectral
// energies serve.
struct ParsevalFold {
  std::shared_ptr<void> state;  // the backend, its plan and buffers (parseval.cpp)
  double worst = 0;
  std::string backend_name;
  void start(const Analysis& a);
  void add(const Analysis& a, const std::vector<double>& height);
};
// Each derived field against its definition from the height, every frame (derived.cpp).
struct DerivedFold {
  struct Judged {
    double error = 0, bound = 0;
  };
  std::vector<Field> present;
  std::vector<Judged> judged;              // judged[frame × present + field]
  // The pass's units of work, one inverse transform each (two or three for the Jacobian):
  // positions in `present`, the second −1 for a field alone; `paired` where two fields share a
  // transform (frames stored coarser than fp64).
  std::vector<std::array<int, 2>> units;
  bool paired = false;
  // kx per column, ky per row (per entry on a lattice: ky_by_row false, one row), |k| per
  // entry in FFT order; made once.
  std::vector<double> kx_of, ky_of, k_of;
  std::size_t rows = 0, columns = 0;
  bool ky_by_row = false;
  void start(const Analysis& a);
  // Unit `unit` of `units` on frame f.
  void add(const Analysis& a, std::size_t f, std::size_t unit, const reference::FieldFrame& frame,
           std::span<const Complex> spectrum, double height_power);
  void finish();  // frees the arrays the pass reused

  // The arrays one add() works in, kept for the next: its inverse transform's input and output
  // (the fields are judged there), and the Jacobian's own.
  struct Scratch {
    InverseTransformArrays arrays;
    std::vector<double> expected, dxx, dyy, dxy, unit;
  };
  Scratch& acquire();
  void release(Scratch& scratch);
  std::vector<std::unique_ptr<Scratch>> scratch_sets;
  std::vector<Scratch*> free_scratch;
  std::shared_ptr<std::mutex> scratch_mutex = std::make_shared<std::mutex>();
};

// Everything the checks read of the frames beyond frame 0, gathered in one pass.
struct FramePass {
  std::vector<FrameStray> strays;                      // per frame
  std::vector<long double> spectral_energies;          // Σ|X(k)|²/N of each frame's height
  std::vector<long double> spatial_energies;           // Σh² of each frame, in long double (parseval)
  std::vector<double> height_sums;                     // Σh² of each frame, in double (statistics)
  HermitianFold hermitian;
  ParsevalFold parseval;
  DerivedFold derived;
  // The distinct ω of the resolved waves (group_by_omega), whose phases e^(−iωt) the passes
  // compute once per frame. The two-wave fit's sums per wave vector live in the pass alone:
  // what the checks read of them is Analysis::wave_fits().
  OmegaGroups groups;
  // The distinct ω of the whole half plane (statistics.hs_steady's); `groups` is made from it.
  // Both are made while frame 1 is read.
  OmegaGroups half_plane_groups;
  // Each frame's ĥ at the resolved waves, on disk for the dispersion pass (≥ 3 frames;
  // series_spill.hpp); null or not ok() when it could not be written.
  std::shared_ptr<SeriesSpill> spill;
};

// The second pass, for dispersion.residual: Σf |y_f − a e_f − b conj e_f|² per fitted wave
// (recomputed from the first pass's sums it would cancel to 10⁻¹⁶ of the energy, far above the
// 10⁻²⁶ a float64 surface's bound asks), and the series of the most energetic waves whose ω is
// below the frames' Nyquist frequency, which the measured ω and the mixed-frequency diagnosis fit.
struct DispersionPass {
  double max_omega = 0;                   // 0.95 π / largest dt
  std::vector<const WaveFit*> strongest;  // ≤ 24, by energy
  std::vector<std::vector<Complex>> series;  // per strongest, per frame
};

class Analysis {
 public:
  // `travelling`: τ(k) of the case on its samples (expected_travelling_power), evaluated once by
  // whoever runs the checks. `threads` (≥ 1) for the passes over the frames.
  Analysis(const OceanCase& ocean_case, const FrameSource& frames, const OceanCheckOptions& options,
           std::vector<double> travelling, int threads = 1);

  const OceanCase& ocean_case() const { return c_; }
  const FrameSource& frames() const { return frames_; }
  std::size_t frame_count() const { return times_.size(); }
  const OceanCheckOptions& options() const { return options_; }
  const Sampling& sampling() const { return sampling_; }
  std::size_t count() const { return count_; }
  double log2n() const { return log2n_; }
  double unit_roundoff() const { return u_; }
  // The stored values' own relative error where coarser than the arithmetic (half: 2⁻¹⁰), else
  // 0 (FrameSequence::storage_roundoff).
  double storage_roundoff() const { return storage_; }
  // The precision this analysis was made with: a file source may learn another once it has
  // read every frame, and the analysis is then made again.
  FramePrecision precision() const { return precision_; }
  std::size_t sample_count() const { return count_; }
  double scale() const { return scale_; }
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& mu() const { return shared_->mu; }
  // τ(k) over the samples: the case's, times scale() with a free scale.
  const std::vector<double>& travelling_power() const { return shared_->tau; }
  const std::vector<Complex>& spectrum0() const { return shared_->spectrum0; }
  // Frame 0's height moments about 0 (statistics' skewness and kurtosis): the height itself is
  // not kept.
  const stats::SampleMoments<double>& height_moments0() const { return height_moments0_; }
  double periodogram0(std::size_t e) const { return std::norm(shared_->spectrum0[e]); }
  double mean_square0() const { return mean_square0_; }
  double floor() const { return floor_; }
  const ResolvedWaves& waves() const { return shared_->resolved; }
  const std::vector<Wave>& half_plane() const { return shared_->half_plane; }
  std::string subject() const { return c_.describe(); }

  // The pass over every frame, made once, whichever check asks first (the gate makes it
  // before running checks concurrently).
  const FramePass& pass() const;
  // Each frame's energy where the case puts none, made by the pass.
  const std::vector<FrameStray>& frame_strays() const { return pass().strays; }
  // The entries (FFT order) where the case puts no resolvable energy.
  const std::vector<std::size_t>& stray_entries() const { return shared_->stray; }
  // Σ|X(k)|²/N of each frame's height transform X (field_spectrum's `energy`).
  const std::vector<long double>& spectral_energies() const { return pass().spectral_energies; }

  // a and b per resolved wave vector whose two waves are identifiable from the frame times, in
  // the order of the resolved waves, made by the pass from its sums; `residual` is filled by
  // the dispersion pass.
  const std::vector<WaveFit>& wave_fits() const;
  // The second pass (DispersionPass), made once.
  const DispersionPass& dispersion_pass() const;

  // The declaration of a tabulated spectrum (model = "table") that explains frame 0 where the
  // case's own does not (table_declarations.cpp), as a clause for a failed check's reason:
  // empty when no other reading of the file explains the frames. Made once, on first use.
  const std::string& misdeclared_table() const {
    std::call_once(table_once_, [this] { misdeclared_table_ = diagnose_table_declarations(*this); });
    return misdeclared_table_;
  }
  // The rings of |k| of frame 0's normalized periodogram u = I/μ over the resolved waves
  // (ring_shape), made once on first use: spectrum.shape judges them and measure_level reads
  // the level from them (a sort of the resolved waves by |k|: half a second at 4096²).
  const RingShape& frame0_rings() const {
    std::call_once(rings_once_, [this] { rings0_ = ring_shape(frame0_ordinates()); });
    return rings0_;
  }
  // u = I/μ of frame 0 at each resolved wave, with its |k|, in the resolved waves' order.
  std::vector<NormalizedOrdinate> frame0_ordinates() const;
  // The measured level of frame 0's spectrum (MeasuredLevel), made once on first use: the
  // scale-dependent checks normalize by it, energy and shape name it.
  const MeasuredLevel& measured_level() const {
    std::call_once(level_once_, [this] { level_ = measure_level(*this); });
    return level_;
  }
  int threads() const { return threads_; }

 private:
  void run_pass() const;
  void run_dispersion_pass() const;
  // OceanCheckOptions::progress, at most once a second and for the `last` frame.
  void progress(bool last, const std::function<std::string()>& message) const;

  const OceanCase& c_;
  const FrameSource& frames_;
  OceanCheckOptions options_;
  Sampling sampling_;
  FramePrecision precision_;
  std::size_t count_ = 0;
  double log2n_ = 1, u_ = kFp64Roundoff, storage_ = 0, scale_ = 1, floor_ = 0, mean_square0_ = 0;
  long double spectral_energy0_ = 0;
  int threads_ = 1;
  std::vector<double> times_;
  stats::SampleMoments<double> height_moments0_;
  struct Shared {
    std::vector<double> mu, tau;
    std::vector<Complex> spectrum0;
    std::vector<Wave> half_plane;
    ResolvedWaves resolved;  // of half_plane
    std::vector<std::size_t> stray;
  };
  std::shared_ptr<Shared> shared_ = std::make_shared<Shared>();
  mutable FramePass pass_;
  mutable DispersionPass dispersion_;
  mutable std::vector<WaveFit> fits_;
  mutable std::string misdeclared_table_;
  mutable MeasuredLevel level_;
  mutable RingShape rings0_;
  mutable std::chrono::steady_clock::time_point last_progress_ = std::chrono::steady_clock::now();
  mutable std::once_flag pass_once_, dispersion_once_, table_once_, level_once_, rings_once_;
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
