#include <map>

#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"

namespace swell::validation::ocean_analysis {
namespace {

// Why a slope or displacement field disagrees with its definition from the height field, on
// frame 0: the field against four templates — its own definition and the other
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

}  // namespace

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
    report.skipped.push_back({"derived", SkipReason::no_field, "no slope, displacement or Jacobian field given"});
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
      // L2 (the accuracy bound of every FFT, docs/transforms.md) — which a J made of three
      // transformed λ∂D terms shows first (the command line's property test).
      // (For J, each factor of its two products carries that error relative to itself.)
      const double transform = a.log2n() * a.log2n() *
                               (field == Field::jacobian ? std::max(mean_square(expected), jacobian_products)
                                                         : mean_square(expected));
      const double rounding = std::sqrt(u * u * (h_power * mean_m2 + own + transform)) / scale;
      const double bound = 10 * rounding + rounding_budget(kCompoundRounding, kFp64Roundoff, a.log2n());
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
    out.push_back(bounded_check(fmt::format("derived.{}", reference::field_name(field)), a.subject(), error,
                          bound, fmt::format("rel rms error ≤ {:.1e} (rounding)", bound),
                          fmt::format("{} against its definition from h: rel rms error {:.2e}{}",
                                      reference::field_name(field), error, diagnosis)));
  }
  return out;
}

}  // namespace swell::validation::ocean_analysis
