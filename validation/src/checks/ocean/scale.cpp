// The scale of the frames' spectrum against the case's: its level measured from the rings of
// |k| (MeasuredLevel), and the convention factors that name a scale error.
#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/statistics.hpp"

#include <algorithm>
#include <numbers>

namespace swell::validation::ocean_analysis {
namespace {

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

// A product of the convention factors engines multiply the energy by, e.g. "× 8 = 2 × 2 × 2".
struct ConventionProduct {
  double value = 1;
  // How unlikely the product is as an explanation: one per factor (two for 16, a specific slip
  // rather than a convention), and one more when it mixes factors and inverses. The cheapest
  // product the sampling range holds is named: × 8 is 2 × 2 × 2 (cost 3), not 16 × 1/2 (cost 4).
  int cost = 0;
  std::string text;   // the product and what each factor is
};

// Every product of up to four factors from: 2 (unit-variance real and imaginary parts, a √2
// on the amplitude, both halves of each ±k pair at full variance — or their inverses), 2π
// (a spectrum in Hz read as rad/s, or the reverse), 16 (Hs² used where Hs²/16 = m0 belongs) and
// Δk = √(Δkx Δky) (amplitudes with a Δk too few or too many under the root), each with its
// power.
std::vector<ConventionProduct> convention_products(double dk) {
  struct Factor {
    double value;
    const char* symbol;
    const char* meaning;
  };
  const Factor factors[] = {
      {2.0, "2", "2: unit-variance real and imaginary parts (E|ξ|² = 2), a √2 on the amplitude, "
                 "or both halves of each ±k pair at full variance"},
      {2 * std::numbers::pi, "2π", "2π: a spectrum per Hz read as per rad/s (S(f) = 2π S(ω))"},
      {16.0, "16", "16: Hs² where m0 = Hs²/16 belongs"},
      {1 / dk, "1/Δk", ""},  // its meaning names this grid's Δk: dk_meaning
  };
  const std::string dk_meaning =
      fmt::format("1/Δk = {:.4g}: one √(Δkx Δky) missing from the amplitudes (energy per Δk, "
                  "not per Δk²)", 1 / dk);
  std::vector<ConventionProduct> out;
  const int range[4][2] = {{-3, 3}, {-1, 1}, {-1, 1}, {-2, 2}};
  for (int a = range[0][0]; a <= range[0][1]; ++a) {
    for (int b = range[1][0]; b <= range[1][1]; ++b) {
      for (int c = range[2][0]; c <= range[2][1]; ++c) {
        for (int d = range[3][0]; d <= range[3][1]; ++d) {
          const int powers[4] = {a, b, c, d};
          const int count = std::abs(a) + std::abs(b) + std::abs(c) + std::abs(d);
          if (count < 2 || count > 4) continue;  // single causes are named on their own
          ConventionProduct p;
          const bool mixed = std::any_of(std::begin(powers), std::end(powers), [](int q) { return q > 0; }) &&
                             std::any_of(std::begin(powers), std::end(powers), [](int q) { return q < 0; });
          p.cost = count + std::abs(c) + (mixed ? 1 : 0);
          std::string terms, meanings;
          for (int f = 0; f < 4; ++f) {
            if (powers[f] == 0) continue;
            p.value *= std::pow(factors[f].value, powers[f]);
            for (int i = 0; i < std::abs(powers[f]); ++i) {
              const std::string symbol = factors[f].symbol;
              const std::string inverse = f == 3 ? std::string("Δk") : "1/" + symbol;
              terms += (terms.empty() ? "" : " × ") + (powers[f] > 0 ? symbol : inverse);
            }
            meanings += (meanings.empty() ? "" : "; ") +
                        (f == 3 ? dk_meaning : std::string(factors[f].meaning)) +
                        (powers[f] < 0 ? " (inverted)" : "");
          }
          p.text = fmt::format("× {:.4g} = {}: {}", p.value, terms, meanings);
          out.push_back(std::move(p));
        }
      }
    }
  }
  return out;
}

}  // namespace

MeasuredLevel measure_level(const Analysis& a) {
  const RingShape& shape = a.frame0_rings();
  MeasuredLevel out;
  out.rings = shape.rings;
  if (shape.ratios.empty()) return out;
  std::vector<double> sorted = shape.ratios;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t r = sorted.size();
  out.level = r % 2 ? sorted[r / 2] : 0.5 * (sorted[r / 2 - 1] + sorted[r / 2]);
  out.lowest_ring = sorted.front();
  out.highest_ring = sorted.back();
  // Each ring's mean of n exponentials has relative sd 1/√n; the median of r such, 1.2533 of
  // that over √r (its asymptotic efficiency against the mean).
  double inverse_counts = 0;
  for (int n : shape.counts) inverse_counts += 1.0 / n;
  const double relative_sd = 1.2533 * std::sqrt(inverse_counts / double(r)) / std::sqrt(double(r));
  out.low = out.level * (1 - 3 * relative_sd);
  out.high = out.level * (1 + 3 * relative_sd);
  // One factor on every ring: each ring's sum, divided by the level, is Gamma(n, 1).
  out.uniform = out.level > 0;
  for (std::size_t i = 0; i < r && out.uniform; ++i) {
    const double n = shape.counts[i], sum = n * shape.ratios[i] / out.level;
    const double p = 2 * std::min(stats::gamma_lower_p(n, sum), stats::gamma_upper_p(n, sum));
    out.uniform = p >= 1e-3 / double(r);
  }
  return out;
}

std::string name_scale_cause(const Analysis& a, double ratio, double low, double high, bool one_factor) {
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
  // Every cause its sampling range holds — a single one, or (when the excess is one factor on
  // every wave) a product of up to three convention factors (cost ≤ 3) — and of those the
  // nearest the measured ratio in log, the cheaper on a tie: on a handful of waves the range
  // can hold both 2π and 8, and the nearer is named.
  struct Cause {
    double value;
    int cost;
    std::string text;
  };
  std::vector<Cause> causes;
  for (const auto& [factor, text] : candidates) causes.push_back({factor, 1, text});
  // The convention factors, alone or in products, only where the excess is one factor on
  // every wave.
  if (one_factor) {
    const std::pair<double, std::string> conventions[] = {
        {2 * std::numbers::pi, "× 2π: a spectrum per Hz read as per rad/s (S(f) = 2π S(ω); a "
                               "table whose frequency_unit or density_unit is declared wrong)"},
        {1 / (2 * std::numbers::pi), "× 1/(2π): a spectrum per rad/s read as per Hz (a table "
                                     "whose frequency_unit or density_unit is declared wrong)"},
        {16.0, "× 16: Hs² where m0 = Hs²/16 belongs"},
        {1 / 16.0, "× 1/16: m0 divided by 16 twice (Hs²/256)"}};
    for (const auto& [factor, text] : conventions) causes.push_back({factor, 1, text});
  }
  for (const auto& product : convention_products(std::sqrt(dk2))) {
    if (product.cost > 3 || !one_factor) continue;
    causes.push_back({product.value, product.cost,
                      product.text + fmt::format(" (if the engine means it, declare "
                                                 "energy_factor = {:.4g} in the spectrum)",
                                                 product.value)});
  }
  std::vector<const Cause*> held;
  for (const auto& cause : causes) {
    if (cause.value >= low && cause.value <= high) held.push_back(&cause);
  }
  std::stable_sort(held.begin(), held.end(), [&](const Cause* x, const Cause* y) {
    const double dx = std::abs(std::log(x->value / ratio)), dy = std::abs(std::log(y->value / ratio));
    return dx != dy ? dx < dy : x->cost < y->cost;
  });
  return held.empty() ? std::string() : held[0]->text;
}

}  // namespace swell::validation::ocean_analysis
