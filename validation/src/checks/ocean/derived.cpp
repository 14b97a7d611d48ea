#include <map>

#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"

namespace swell::validation::ocean_analysis {
namespace {

bool is_displacement(Field field) { return field == Field::disp_x || field == Field::disp_y; }

// Where a field's energy outside the wave vectors the case fills lies: its mean (k = 0), a
// grid's Nyquist row and column, and the rest — as fractions of the field's mean square.
struct StrayEnergy {
  double mean = 0, nyquist = 0, other = 0;
  double total() const { return mean + nyquist + other; }
};

// Why a slope or displacement field disagrees with its definition from the height field, on the
// frame where it disagrees most. The field's spectrum G is compared, on the wave vectors the
// case fills (the grid's, less k = 0 and the Nyquist row and column), with four templates T —
// its own definition and the other axis's, each from the height as given and from the height
// transposed (square grids) — each with its least-squares factor c (λ for displacements, 1 for
// slopes). Fitting there alone lets a second fault that lives outside them (a Nyquist row and
// column an engine fills) leave the first one's diagnosis standing; the energy outside is named
// beside it. A template explains the field when its residual's rms is within
// max(10 × the check's bound, 10⁻³) of the field's.
std::string explain_derived(const Analysis& a, Field field, std::size_t frame, double bound) {
  const Sampling& g = a.sampling();
  const bool displacement = is_displacement(field);
  const bool along_x = field == Field::slope_x || field == Field::disp_x;
  const double lambda = displacement ? a.ocean_case().choppiness : 1.0;
  const std::string name = reference::field_name(field);
  const std::string other_name =
      reference::field_name(displacement ? (along_x ? Field::disp_y : Field::disp_x)
                                         : (along_x ? Field::slope_y : Field::slope_x));
  // The frame read again: only a failing field's worst frame is explained.
  const auto frame_fields = a.frames().frame(frame, [&](int, Field f) { return f == field || f == Field::height; });
  const auto& field_values = frame_fields->fields.at(field);
  const auto got = field_spectrum(field_values, g);
  const auto height = field_spectrum(frame_fields->fields.at(Field::height), g);
  const bool grid = !g.is_lattice();
  double power = 0;
  StrayEnergy stray;
  for (std::size_t e = 0; e < got.size(); ++e) {
    const double p = std::norm(got[e]);
    power += p;
    if (g.carries_energy(e)) continue;
    const auto [n, m] = g.wave_index(e);
    if (n == 0 && m == 0) {
      stray.mean += p;
    } else if (grid && (Grid::is_nyquist(n, g.grid().nx) || Grid::is_nyquist(m, g.grid().ny))) {
      stray.nyquist += p;
    } else {
      stray.other += p;
    }
  }
  if (!(power > 0)) return fmt::format("{} is zero everywhere", name);
  stray.mean /= power;
  stray.nyquist /= power;
  stray.other /= power;

  struct Candidate {
    bool other_axis, transposed;
    double factor = 0, residual = 1e300;  // residual: rms misfit on the filled wave vectors / the field's rms
  };
  std::vector<Candidate> candidates = {{false, false}, {true, false}};
  if (grid && g.grid().nx == g.grid().ny && g.grid().lx == g.grid().ly) {
    candidates.push_back({false, true});
    candidates.push_back({true, true});
  }
  const int nx = grid ? g.grid().nx : 0;
  for (auto& c : candidates) {
    const bool x_axis = c.other_axis ? !along_x : along_x;
    auto template_at = [&](std::size_t e) {
      const auto [n, m] = g.wave_index(e);
      const double kx = n * g.dkx(), ky = m * g.dky(), k = std::hypot(kx, ky);
      const double component = x_axis ? kx : ky;
      const Complex multiplier = displacement ? Complex(0, component / k) : Complex(0, component);
      // The transposed height's coefficient at (n, m) is the height's at (m, n).
      const std::size_t source =
          c.transposed ? std::size_t((n + nx) % nx) * std::size_t(nx) + std::size_t((m + nx) % nx) : e;
      return multiplier * height[source];
    };
    double tt = 0, tg = 0;
    for (std::size_t e = 0; e < got.size(); ++e) {
      if (!g.carries_energy(e)) continue;
      const Complex t = template_at(e);
      tt += std::norm(t);
      tg += (std::conj(t) * got[e]).real();
    }
    c.factor = tt > 0 ? tg / tt : 0;
    double left = 0;
    for (std::size_t e = 0; e < got.size(); ++e) {
      if (g.carries_energy(e)) left += std::norm(got[e] - c.factor * template_at(e));
    }
    c.residual = std::sqrt(left / power);
  }
  const auto best = *std::min_element(candidates.begin(), candidates.end(),
                                      [](const Candidate& x, const Candidate& y) { return x.residual < y.residual; });
  const double explains = std::max(10 * bound, 1e-3);
  const double own_misfit = candidates[0].residual * candidates[0].residual + stray.total();
  const double mean = got[0].real();
  if (stray.mean > 0.5 * own_misfit) {
    return fmt::format("{} sways: its mean {:.3g} m moves the whole patch sideways (k = 0 carries "
                       "what the conventions leave empty)",
                       name, mean);
  }
  // The energy outside the filled wave vectors, as a clause beside another diagnosis: named
  // when it alone is half the bound the field fails (the rounding's share there is ~2/n of it).
  std::string outside;
  if (std::sqrt(stray.total()) > 0.5 * bound) {
    const bool nyquist = stray.nyquist >= stray.other;
    outside = fmt::format(
        "{:.2g} of {}'s rms lies {}, where the case puts none{}", std::sqrt(stray.total()), name,
        nyquist ? "on the Nyquist row and column" : "outside the wave vectors the case fills",
        nyquist ? " (a Nyquist bin filled, or two fields packed in one complex transform leaking "
                  "into each other there)"
                : "");
  }
  // A normal map's slope: ∂h/∂x of the displaced surface, ∂h/∂x / (1 + λ∂Dx/∂x) — what an engine
  // that derives its normals after displacing (and stores them as slopes) hands over; with or
  // without the absolute value some engines take. Fitted in space (the division is no
  // multiplier), on the whole field; named where it explains the field and at least twice as
  // closely as the best linear template.
  if (!displacement) {
    const double choppiness = a.ocean_case().choppiness;
    std::vector<Complex> slope(got.size()), stretch(got.size());
    for (std::size_t e = 0; e < got.size(); ++e) {
      if (!g.carries_energy(e)) continue;
      const auto [n, m] = g.wave_index(e);
      const double kx = n * g.dkx(), ky = m * g.dky(), k = std::hypot(kx, ky);
      const double component = along_x ? kx : ky;
      slope[e] = Complex(0, component) * height[e];
      stretch[e] = -choppiness * component * component / k * height[e];
    }
    const auto s = field_from_spectrum(slope, g), d = field_from_spectrum(stretch, g);
    for (bool absolute : {true, false}) {
      double tt = 0, tg = 0, gg = 0;
      std::vector<double> t(s.size());
      for (std::size_t p = 0; p < s.size(); ++p) {
        t[p] = s[p] / (1 + (absolute ? std::abs(d[p]) : d[p]));
        tt += t[p] * t[p];
        tg += t[p] * field_values[p];
        gg += field_values[p] * field_values[p];
      }
      const double c = tt > 0 ? tg / tt : 0;
      double left = 0;
      for (std::size_t p = 0; p < s.size(); ++p) left += std::pow(field_values[p] - c * t[p], 2);
      const double residual = gg > 0 ? std::sqrt(left / gg) : 1;
      if (residual <= explains && residual < 0.5 * best.residual && std::abs(c - 1) < 0.05) {
        return fmt::format("{} is a normal map's slope: ∂h/∂{} of the displaced surface, divided by "
                           "1 + {}∂D{}/∂{}{} (it explains the field to {:.1e}), not ∂h/∂{} at the grid point",
                           name, along_x ? "x" : "y", absolute ? "|" : "", along_x ? "x" : "y",
                           along_x ? "x" : "y", absolute ? "|" : "", residual, along_x ? "x" : "y");
      }
    }
  }
  const std::string factor_name = displacement ? "λ" : "scale";
  if (lambda == 0) {
    // The case declares no displacement (docs/conventions.md: λ = 0).
    return fmt::format("λ = 0 declares no displacement, but {} is not zero: it holds {} × {}'s "
                       "definition (to {:.1e} of its rms){}",
                       name, fmt::format("{:.4g}", best.factor),
                       best.other_axis ? other_name : name, best.residual,
                       outside.empty() ? "" : "; " + outside);
  }
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
    if (what.empty()) {  // its own definition
      if (flipped && same_size) {
        what = fmt::format("sign flipped: the best-fit {} is {:.4g} against the case's {:g} "
                           "(conventions: D ↔ +i k/|k| h̃; Tessendorf's −i needs λ < 0)",
                           factor_name, best.factor, lambda);
      } else if (!same_size) {
        what = fmt::format("{} is {:.4g}, not the case's {:g} (least squares; it explains the "
                           "field to {:.1e})",
                           factor_name, best.factor, lambda, best.residual);
      } else if (!outside.empty()) {
        // Right on the wave vectors the case fills: what fails lies outside them.
        return fmt::format("{} follows its definition with the case's {} = {:g} on the wave "
                           "vectors the case fills, but {}",
                           name, factor_name, lambda, outside);
      } else {
        // The case's own factor, with a misfit above the bound but below 10⁻³: no convention
        // explains it; the field is computed or stored less exactly than declared.
        return fmt::format("{} follows its definition with the case's {} = {:g} to {:.1e} of its "
                           "rms: more than rounding of the declared precision allows, less than "
                           "any convention error",
                           name, factor_name, lambda, best.residual);
      }
    } else if (!same_size || flipped) {
      what += fmt::format(", with {} = {:.4g} (the case's {:g})", factor_name, best.factor, lambda);
    } else {
      what += fmt::format(" ({} = {:.4g}, the case's)", factor_name, best.factor);
    }
    return outside.empty() ? what : what + "; besides, " + outside;
  }
  return fmt::format("inconsistent with the height field: no {} explains it (the best, {} = {:.3g} "
                     "with its own definition, leaves {:.2g} of its rms on the wave vectors the "
                     "case fills){}{}",
                     factor_name, factor_name, candidates[0].factor, candidates[0].residual,
                     candidates[0].factor * lambda < 0 ? " — sign flipped?" : "",
                     outside.empty() ? "" : "; " + outside);
}

}  // namespace

// Each derived field against its definition applied to the height field (conventions
// §Derived fields), on every frame: a fault that lives in some frames only (a field written
// from another frame, a sway that starts late) fails the check like one in all of them; the
// frame judged worst is the one reported and explained. Rounding bound: the stored height's
// rounding, white with variance ≤ u² mean(h²), pushed through the field's multiplier, plus the
// field's own rounding; 10× that. λ = 0 declares no displacement: those fields must be zero, and
// their error is measured against what λ = 1 would put there.
namespace {

// Multipliers per wave vector in FFT order, of (kx, ky) and |k| = hypot(kx, ky), for a
// displacement factor `l`.
Complex multiplier(Field field, double l, double kx, double ky, double k) {
  if (k == 0) return 0;
  switch (field) {
    case Field::slope_x: return {0, kx};
    case Field::slope_y: return {0, ky};
    case Field::disp_x: return {0, l * kx / k};
    case Field::disp_y: return {0, l * ky / k};
    default: return 0;
  }
}

// A derived field's values where they lie: the real or the imaginary parts of an inverse
// transform's output (every second double), or a vector of their own.
struct FieldValues {
  const double* first = nullptr;
  std::size_t stride = 1, size = 0;
  double operator[](std::size_t p) const { return first[p * stride]; }
};

// std::complex<double> is an array of two doubles, real part first ([complex.numbers]).
FieldValues real_parts(std::span<const Complex> z) {
  return {reinterpret_cast<const double*>(z.data()), 2, z.size()};
}
FieldValues imaginary_parts(std::span<const Complex> z) {
  return {reinterpret_cast<const double*>(z.data()) + 1, 2, z.size()};
}
FieldValues values_of(const std::vector<double>& v) { return {v.data(), 1, v.size()}; }

// The sum mean_square(std::vector) takes, in its order.
double mean_square(FieldValues v) {
  double sum = 0;
  for (std::size_t p = 0; p < v.size; ++p) sum += v[p] * v[p];
  return sum / double(v.size);
}

void assign(FieldValues v, std::vector<double>& into) {
  into.resize(v.size);
  for (std::size_t p = 0; p < v.size; ++p) into[p] = v[p];
}

}  // namespace

DerivedFold::Scratch& DerivedFold::acquire() {
  std::lock_guard lock(*scratch_mutex);
  if (free_scratch.empty()) {
    scratch_sets.push_back(std::make_unique<Scratch>());
    return *scratch_sets.back();
  }
  Scratch* out = free_scratch.back();
  free_scratch.pop_back();
  return *out;
}

void DerivedFold::release(Scratch& scratch) {
  std::lock_guard lock(*scratch_mutex);
  free_scratch.push_back(&scratch);
}

void DerivedFold::finish() {
  free_scratch.clear();
  scratch_sets.clear();
}

void DerivedFold::start(const Analysis& a) {
  for (Field f : {Field::slope_x, Field::slope_y, Field::disp_x, Field::disp_y, Field::jacobian}) {
    if (a.frames().has(f)) present.push_back(f);
  }
  judged.assign(a.frame_count() * present.size(), Judged{});
  if (present.empty()) return;
  // One inverse transform per unit of work: for frames stored coarser than fp64 (float, half,
  // 16-bit), the slopes and the displacements in pairs (the real and imaginary parts of one
  // transform), the Jacobian's ∂Dx/∂x and ∂Dy/∂y too; any field without its partner alone. The
  // pair's fp64 rounding of the other field is far below the stored numbers' own; frames in
  // fp64, judged at fp64's rounding, keep a transform per field.
  paired = a.unit_roundoff() > 2 * kFp64Roundoff;
  auto position = [&](Field f) {
    const auto it = std::find(present.begin(), present.end(), f);
    return it == present.end() ? -1 : int(it - present.begin());
  };
  if (const int j = position(Field::jacobian); j >= 0) units.push_back({j, -1});
  for (const auto& [x, y] : {std::pair{Field::disp_x, Field::disp_y}, std::pair{Field::slope_x, Field::slope_y}}) {
    const int i = position(x), k = position(y);
    if (i >= 0 && k >= 0 && paired) {
      units.push_back({i, k});
    } else if (i >= 0 && k >= 0) {
      units.push_back({i, -1});
      units.push_back({k, -1});
    } else if (i >= 0 || k >= 0) {
      units.push_back({std::max(i, k), -1});
    }
  }
  // kx, ky and |k| made once for the up to 14 derivations of each frame (hypot in each of their
  // loops was a third of this check's time). On a grid kx depends on the column alone and ky on
  // the row: held per column and per row, only |k| per entry.
  const Sampling& g = a.sampling();
  const std::size_t count = a.count();
  ky_by_row = !g.is_lattice();
  rows = ky_by_row ? std::size_t(g.grid().ny) : 1;
  columns = count / rows;
  kx_of.resize(columns);
  ky_of.resize(ky_by_row ? rows : count);
  for (std::size_t column = 0; column < columns; ++column) {
    const auto [nn, mm] = g.wave_index(column);
    kx_of[column] = nn * g.dkx();
    if (!ky_by_row) ky_of[column] = mm * g.dky();
  }
  for (std::size_t row = 0; ky_by_row && row < rows; ++row) ky_of[row] = g.wave_index(row * columns)[1] * g.dky();
  // |k| in chunks of the samples on the analysis' threads (a hypot each: 0.4 s of one thread
  // at 4096²).
  k_of.resize(count);
  constexpr std::size_t kChunks = 64;
  const std::size_t chunks = std::min(kChunks, count);
  detail::run_tasks(chunks, a.threads(), [&](std::size_t c) {
    for (std::size_t e = c * count / chunks; e < (c + 1) * count / chunks; ++e) {
      const std::size_t row = e / columns, column = e % columns;
      k_of[e] = std::hypot(kx_of[column], ky_of[ky_by_row ? row : column]);
    }
  });
}

// Unit `unit` of `units` on frame f, from the frame's height spectrum; the pass calls it for
// each unit of each frame, the units of one frame side by side.
void DerivedFold::add(const Analysis& a, std::size_t frame, std::size_t unit, const reference::FieldFrame& values,
                      std::span<const Complex> spectrum, double h_power) {
  const Sampling& g = a.sampling();
  const double lambda = a.ocean_case().choppiness;
  const double u = a.unit_roundoff();
  // This call's arrays, from the fold's free sets: reused frame after frame (fresh arrays cost
  // their page faults and the kernel's zeroing each time), at most one set per thread.
  Scratch& scratch = acquire();
  struct Release {
    DerivedFold& fold;
    Scratch& scratch;
    ~Release() { fold.release(scratch); }
  } release_on_exit{*this, scratch};
  // The fields the multipliers m_a (and m_b) make of the height spectrum, as the real (and
  // imaginary) parts of one inverse transform in this call's array: the spectrum is written
  // straight into it, row by row (kx by column, ky by row on a grid), and transformed over
  // itself. Two fields share one transform as m_a ĥ + i m_b ĥ: each m ĥ is the spectrum of a
  // real field, so the real part of the result is the first field and the imaginary part the
  // second, each with the transform's rounding of the other besides its own. Judged where the
  // transform leaves them, not copied out: at 4096² each copy was 134 MB per thread.
  auto derive_into = [&](const auto& m_a, const auto* m_b, double& mean_a, double* mean_b) {
    mean_a = 0;
    if (mean_b) *mean_b = 0;
    auto fill = [&](std::span<Complex> s) {
      for (std::size_t row = 0, e = 0; row < rows; ++row) {
        for (std::size_t column = 0; column < columns; ++column, ++e) {
          if (!g.carries_energy(e)) {
            s[e] = 0;
            continue;
          }
          const double kx = kx_of[column], ky = ky_of[ky_by_row ? row : column], k = k_of[e];
          const Complex mult = m_a(kx, ky, k);
          mean_a += std::norm(mult);
          if (m_b) {
            const Complex second = (*m_b)(kx, ky, k);
            *mean_b += std::norm(second);
            s[e] = mult * spectrum[e] + Complex(0, 1) * (second * spectrum[e]);
          } else {
            s[e] = mult * spectrum[e];
          }
        }
      }
    };
    const auto fields = inverse_transform(g, scratch.arrays, fill);
    if (m_b) *mean_b /= double(spectrum.size());
    mean_a /= double(spectrum.size());
    return fields;
  };
  auto derive = [&](const auto& m, double& mean_m2) {
    return real_parts(derive_into(m, static_cast<decltype(&m)>(nullptr), mean_m2, nullptr));
  };
  auto derive_two = [&](const auto& m_a, const auto& m_b, double& mean_a, double& mean_b) {
    return derive_into(m_a, &m_b, mean_a, &mean_b);
  };
  // J − 1 from λ∂Dx/∂x (a), λ∂Dy/∂y (b), sharing one transform, and λ∂Dx/∂y (c) in another.
  // `leak`: the rms the shared transform's rounding of b brings into J through a, and of a
  // through b, in units of the analysis transform's relative rounding.
  auto jacobian_minus_one = [&](double l, double& mean_m2, double& products, double& leak,
                                std::vector<double>& out) {
    double m_xx = 0, m_yy = 0, m_xy = 0;
    std::vector<double>&dxx = scratch.dxx, &dyy = scratch.dyy, &dxy = scratch.dxy;
    auto m_a = [&](double kx, double, double k) { return Complex(-l * kx * kx / k); };
    auto m_b = [&](double, double ky, double k) { return Complex(-l * ky * ky / k); };
    if (paired) {
      const auto both = derive_two(m_a, m_b, m_xx, m_yy);
      assign(real_parts(both), dxx);
      assign(imaginary_parts(both), dyy);
    } else {
      assign(derive(m_a, m_xx), dxx);
      assign(derive(m_b, m_yy), dyy);
    }
    assign(derive([&](double kx, double ky, double k) { return Complex(-l * kx * ky / k); }, m_xy), dxy);
    out.resize(dxx.size());
    products = 0;
    // The stored height's rounding reaches J through δJ = (1 + b) δa + (1 + a) δb − 2c δc: each
    // δ is the height's rounding through its multiplier (m_xx, m_yy, m_xy), weighted by the
    // other factor — 1 while λ∂D ≪ 1, but λ∂D itself where it is large (a λ of 10¹¹ drawn by
    // the property test made the linear weights 10⁵ times too small).
    double weight_a = 0, weight_b = 0, weight_c = 0;
    for (std::size_t p = 0; p < dxx.size(); ++p) {
      const double product = (1 + dxx[p]) * (1 + dyy[p]), square = dxy[p] * dxy[p];
      out[p] = product - square - 1;  // J − 1
      // J = (1 + a)(1 + b) − c² rounds relative to its two products, which cancel where
      // the waves are nearly collinear (a narrow spreading: ab ≈ c²) and λ∂D ≫ 1.
      products += product * product + square * square;
      weight_a += std::pow(1 + std::abs(dyy[p]), 2);
      weight_b += std::pow(1 + std::abs(dxx[p]), 2);
      weight_c += square;
    }
    const double n = double(dxx.size());
    products /= n;
    mean_m2 = m_xx * weight_a / n + m_yy * weight_b / n + m_xy * (2 + 4 * weight_c / n);
    leak = paired ? std::sqrt(weight_a / n * mean_square(dyy)) + std::sqrt(weight_b / n * mean_square(dxx)) : 0.0;
  };
  // One field judged against `expected` (J − 1 for the Jacobian). `expected_power` measures the
  // error (the field's expected mean square, or what λ = 1 would put there where λ = 0 makes it
  // zero); `leak` is the rms of what a transform shared with another field brings in, in units
  // of the analysis transform's relative rounding (0 for a transform of its own).
  auto judge = [&](Field field, FieldValues expected, double mean_m2, double expected_power,
                   double jacobian_products, double leak) {
    const std::vector<double>& got = values.fields.at(field);
    const bool jacobian = field == Field::jacobian;
    // mean_square of the difference got − expected (J − 1 for the Jacobian), summed as it sums.
    double difference = 0;
    for (std::size_t p = 0; p < expected.size; ++p) {
      const double d = (jacobian ? got[p] - 1 : got[p]) - expected[p];
      difference += d * d;
    }
    difference /= double(expected.size);
    const double scale = std::sqrt(std::max(expected_power, 1e-300));
    const double error = std::sqrt(difference) / scale;
    const double expected_square = mean_square(expected);
    const double own = jacobian ? jacobian_products : expected_square;
    // Rounding, in the stored numbers' unit roundoff u: of the stored height, carried into
    // the derived field by its multiplier (h_power·mean |m|²); of the stored field itself
    // (own); and of the engine's own inverse transform of this field, ≈ u log2 N relative in
    // L2 (the accuracy bound of every FFT, docs/transforms.md) — which a J made of three
    // transformed λ∂D terms shows first (the command line's property test).
    // (For J, each factor of its two products carries that error relative to itself.)
    const double transform = a.log2n() * a.log2n() *
                             (jacobian ? std::max(expected_square, jacobian_products) : expected_square);
    const double rounding = std::sqrt(u * u * (h_power * mean_m2 + own + transform)) / scale;
    // Half storage: each stored value (the height's and the field's own) within s of itself,
    // s = 2⁻¹⁰; the height's error, white, carried by the multiplier. Its energy is bounded,
    // not estimated, so 3× (not 10×) covers the two adding in phase: an error 10× s still fails.
    const double s = a.storage_roundoff();
    const double storage = std::sqrt(s * s * (h_power * mean_m2 + own)) / scale;
    // The analysis' own fp64 transform: its rounding relative to the field, and to the field
    // that shares its transform (leak / scale).
    const double analysis = rounding_budget(kCompoundRounding, kFp64Roundoff, a.log2n());
    const std::size_t i = std::size_t(std::find(present.begin(), present.end(), field) - present.begin());
    judged[frame * present.size() + i] = {
        error, 10 * rounding + 3 * storage + (leak > 0 ? analysis * (1 + leak / scale) : analysis)};
  };

  const auto [first, second] = units[unit];
  if (present[first] == Field::jacobian) {
    double mean_m2 = 0, products = 0, leak = 0;
    jacobian_minus_one(lambda, mean_m2, products, leak, scratch.expected);
    double expected_power = mean_square(scratch.expected);
    if (lambda == 0) {
      double unit_m2 = 0, unit_products = 0, unit_leak = 0;
      jacobian_minus_one(1.0, unit_m2, unit_products, unit_leak, scratch.unit);
      expected_power = mean_square(scratch.unit);
    }
    judge(Field::jacobian, values_of(scratch.expected), mean_m2, expected_power, products, leak);
    return;
  }
  // A field's expected rms measures its error, or, where λ = 0 makes a displacement zero, what
  // λ = 1 would put there: that one derived first, as the field's own takes the same arrays.
  auto multiplier_of = [](Field field, double l) {
    return [field, l](double kx, double ky, double k) { return multiplier(field, l, kx, ky, k); };
  };
  const auto unit_scale = [&](Field field) {
    return lambda == 0 && field != Field::slope_x && field != Field::slope_y;
  };
  if (second < 0) {
    const Field field = present[first];
    double expected_power = 0;
    if (unit_scale(field)) {
      double unit_m2 = 0;
      expected_power = mean_square(derive(multiplier_of(field, 1.0), unit_m2));
    }
    double mean_m2 = 0;
    const FieldValues expected = derive(multiplier_of(field, lambda), mean_m2);
    if (!unit_scale(field)) expected_power = mean_square(expected);
    judge(field, expected, mean_m2, expected_power, 0, 0);
    return;
  }
  // A pair (slope_x, slope_y or disp_x, disp_y) in one transform.
  const Field field_a = present[first], field_b = present[std::size_t(second)];
  double expected_a = 0, expected_b = 0;
  if (unit_scale(field_a)) {
    double unit_a = 0, unit_b = 0;
    const auto unit_fields = derive_two(multiplier_of(field_a, 1.0), multiplier_of(field_b, 1.0), unit_a, unit_b);
    expected_a = mean_square(real_parts(unit_fields));
    expected_b = mean_square(imaginary_parts(unit_fields));
  }
  double mean_a = 0, mean_b = 0;
  const auto both = derive_two(multiplier_of(field_a, lambda), multiplier_of(field_b, lambda), mean_a, mean_b);
  const FieldValues got_a = real_parts(both), got_b = imaginary_parts(both);
  const double power_a = mean_square(got_a), power_b = mean_square(got_b);
  if (!unit_scale(field_a)) expected_a = power_a, expected_b = power_b;
  judge(field_a, got_a, mean_a, expected_a, 0, std::sqrt(power_b));
  judge(field_b, got_b, mean_b, expected_b, 0, std::sqrt(power_a));
}

// Each derived field against its definition applied to the height field (conventions
// §Derived fields), on every frame: a fault that lives in some frames only (a field written
// from another frame, a sway that starts late) fails the check like one in all of them; the
// frame judged worst is the one reported and explained. Rounding bound: the stored height's
// rounding, white with variance ≤ u² mean(h²), pushed through the field's multiplier, plus the
// field's own rounding; 10× that. λ = 0 declares no displacement: those fields must be zero, and
// their error is measured against what λ = 1 would put there.
Results check_derived(const Analysis& a, OceanCheckReport& report) {
  const double lambda = a.ocean_case().choppiness;
  const DerivedFold& fold = a.pass().derived;
  const std::vector<Field>& present = fold.present;
  if (present.empty()) {
    report.skipped.push_back({"derived", SkipReason::no_field, "no slope, displacement or Jacobian field given"});
    return {};
  }
  const std::size_t frames = a.frame_count();
  const auto& judged = fold.judged;
  using Judged = DerivedFold::Judged;
  Results out;
  for (std::size_t i = 0; i < present.size(); ++i) {
    const Field field = present[i];
    std::size_t worst = 0;
    for (std::size_t f = 1; f < frames; ++f) {
      const Judged& x = judged[f * present.size() + i];
      const Judged& w = judged[worst * present.size() + i];
      if (x.error / x.bound > w.error / w.bound) worst = f;
    }
    const auto [error, bound] = judged[worst * present.size() + i];
    const bool ok = error <= bound;
    std::size_t failing = 0;
    for (std::size_t f = 0; f < frames; ++f) {
      const Judged& x = judged[f * present.size() + i];
      failing += x.error > x.bound;
    }
    std::string diagnosis;
    if (!ok) {
      diagnosis = field == Field::jacobian
                      ? (lambda == 0 ? " — λ = 0 declares no displacement, so J = 1, and it is not"
                                     : " — inconsistent with the height field (J built without λ, "
                                       "or from other displacements)")
                      : " — " + explain_derived(a, field, worst, bound);
    }
    const std::string where =
        frames == 1 ? ""
        : ok        ? fmt::format(" (worst of {} frames: frame {})", frames, worst)
                    : fmt::format(" at frame {} ({} of {} frames fail)", worst, failing, frames);
    out.push_back(bounded_check(fmt::format("derived.{}", reference::field_name(field)), a.subject(), error,
                          bound, fmt::format("rel rms error ≤ {:.1e} (rounding), every frame", bound),
                          fmt::format("{} against its definition from h: rel rms error {:.2e}{}{}",
                                      reference::field_name(field), error, where, diagnosis)));
  }
  return out;
}

}  // namespace swell::validation::ocean_analysis
