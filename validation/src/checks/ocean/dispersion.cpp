#include <array>
#include <functional>

#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"
#include "swell/reference/phase.hpp"

namespace swell::validation::ocean_analysis {
namespace {

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

// Mixed frequencies: when one frequency pair ±ω(k) per wave vector leaves much of
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
std::string explain_mixed_frequencies(const Analysis& a) {
  const DispersionPass& d = a.dispersion_pass();
  const std::vector<const WaveFit*>& strongest = d.strongest;
  const double max_omega = d.max_omega;
  const auto& times = a.times();
  if (strongest.empty()) return "";
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  // The series of strongest[i] is d.series[i].
  auto series_of = [&](const WaveFit* f) -> std::span<const Complex> {
    return d.series[std::size_t(std::find(strongest.begin(), strongest.end(), f) - strongest.begin())];
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

}  // namespace

Results check_dispersion(const Analysis& a, OceanCheckReport& report) {
  if (a.times().size() < 3) {
    report.skipped.push_back({"dispersion", SkipReason::too_few_frames, "needs ≥ 3 frames (the fit has 2 complex unknowns per k)"});
    return {};
  }
  const auto& fits = a.wave_fits();
  if (fits.empty()) {
    report.skipped.push_back({"dispersion", SkipReason::unidentifiable_times, "no wave vector's two waves are identifiable from these "
                             "frame times (2ω dt ≈ 0 mod 2π everywhere)"});
    return {};
  }
  // The second pass over the frames fills each fit's residual.
  const DispersionPass& pass = a.dispersion_pass();
  double residual = 0, energy = 0;
  for (const WaveFit& f : fits) {
    residual += f.residual;
    energy += f.energy;
  }
  const double fraction = residual / std::max(energy, 1e-300);
  // Rounding alone leaves at most (u log2 N)² of the frames' energy, spread over every wave
  // vector; allow 64× that. The fits see about half of each frame's energy (the half plane)
  // when the waves that carry the sea are identifiable; where they are not (a loop period
  // quantizes the energetic waves' ω so low that the frames' span cannot tell their two waves
  // apart, and only weak waves are fitted), the fitted waves carry a sliver of the energy and
  // the rounding is judged against the frames' energy, frames_energy / (2 × fitted energy)
  // times the bound. Half storage adds an error of at most s² of each frame's energy
  // (s = 2⁻¹⁰), which the fit cannot absorb: at most Σ mean h² s² of what the fits see,
  // allowed 4× (its energy is bounded, not estimated).
  double frames_energy = 0;
  for (const FrameStray& s : a.frame_strays()) frames_energy += s.mean_square;
  const double s = a.storage_roundoff();
  const double unseen = std::max(1.0, frames_energy / (2 * std::max(energy, 1e-300)));
  const double bound = std::pow(rounding_budget(kCompoundRounding, a.unit_roundoff(), a.log2n()), 2) * unseen +
                       4 * s * s * frames_energy / std::max(energy, 1e-300);
  Results out;

  // ω per wave vector, for the most energetic wave vectors whose ω is below the frames'
  // Nyquist frequency π/dt (above it ω aliases): their series, from the dispersion pass.
  const std::vector<const WaveFit*>& strongest = pass.strongest;
  const double max_omega = pass.max_omega;
  std::vector<std::pair<double, double>> ratios;  // (ω measured / ω case, energy)
  std::vector<std::pair<double, double>> rounding;  // (what rounding can move that ratio by, energy)
  std::vector<MeasuredOmega> measured;
  // Rounding is noise on each wave vector's coefficient in each frame: the stored numbers'
  // (power u² mean(h²)/N, resolution_floor's) and the engine's own inverse transform's, which
  // is u log₂N of the field relative in L2 (the accuracy bound of every FFT, docs/transforms.md,
  // as the derived check allows it): power u² mean(h²) (1 + log₂²N)/N in all. It moves the phase
  // of a wave of power P by about √(noise/2P) a frame; a frequency fitted to F frames over a
  // span T moves by that × √(12/F)/T (the standard error of a regression slope). Six such
  // errors, relative to ω: far below 10⁻⁶ for the waves that carry a sea's energy, but not for
  // waves barely above the resolution floor, which are all a case leaves below the frames'
  // Nyquist frequency when its energy lies above it.
  const double frames = double(a.times().size());
  const double span = a.times().back() - a.times().front();
  const double stored = std::max(a.unit_roundoff(), a.storage_roundoff());
  const double noise = stored * stored * a.mean_square0() * (1 + a.log2n() * a.log2n()) / double(a.sample_count());
  for (std::size_t i = 0; i < strongest.size(); ++i) {
    const WaveFit* f = strongest[i];
    const double omega = best_omega(f->wave->omega, max_omega, a.times(), pass.series[i]);
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
    mixed = explain_mixed_frequencies(a);
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
  out.push_back(bounded_check(
      "dispersion.residual", a.subject(), fraction, bound,
      fmt::format("residual energy fraction ≤ {:.1e} (rounding)", bound),
      fmt::format("fit a e^(−iωt) + b e^(iωt) at ω(k) leaves {:.2e} of the energy over {} wave "
                  "vectors and {} frames{}",
                  fraction, fits.size(), a.times().size(), diagnosis)));
  if (!mixed.empty()) {
    // No single ratio exists: the measured ω is not one number per wave vector.
    const double omega_bound = std::max(1e-6, rounding_budget(kCompoundRounding, a.unit_roundoff(), a.log2n()));
    out.push_back(bounded_check("dispersion.omega", a.subject(), std::numeric_limits<double>::quiet_NaN(),
                          omega_bound,
                          fmt::format("|ω measured / ω(k) − 1| ≤ {:.1e} (energy-weighted median)", omega_bound),
                          "no single ω per wave vector — " + mixed));
  } else if (!ratios.empty()) {
    const double error = std::abs(ratio - 1);
    const double omega_bound = std::max({1e-6, rounding_budget(kCompoundRounding, a.unit_roundoff(), a.log2n()),
                                         energy_weighted_median(rounding)});
    out.push_back(bounded_check(
        "dispersion.omega", a.subject(), error, omega_bound,
        fmt::format("|ω measured / ω(k) − 1| ≤ {:.1e} (energy-weighted median)", omega_bound),
        fmt::format("measured ω / case ω = {:.6f} (median over the {} most energetic wave "
                    "vectors){}",
                    ratio, ratios.size(), error <= omega_bound ? "" : " — wrong dispersion relation")));
  } else {
    report.skipped.push_back({"dispersion.omega", SkipReason::above_nyquist, "every energetic ω is above the frames' Nyquist "
                             "frequency π/dt"});
  }
  return out;
}

}  // namespace swell::validation::ocean_analysis
