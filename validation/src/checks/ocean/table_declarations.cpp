// Which declaration of a tabulated spectrum the frames follow, when it is not the case's own
// (docs/checks.md §Declared conventions). A table's file carries numbers; its frequency unit,
// direction convention and density unit are declared in the case (docs/case_files.md §Spectra
// from files), and a wrong declaration — in the case, or in the engine that read the same file —
// moves the whole sea: frequencies read in the other unit put the peak 2π away (k by (2π)² in
// deep water), directions in the other convention mirror the sea about 45°/225°, a density per
// degree read as per radian multiplies the energy by 180/π. The energy, shape and moment checks
// fail on all of these, each in its own terms; this names the one slip behind them.
//
// Every other reading of each table component — the frequency unit swapped, the direction
// convention swapped, both — is evaluated on the samples (one Ψ per reading), its energy scale
// fitted (Whittle: the mean of I/μ), and judged by spectrum.shape's own test (Gamma per ring of
// |k|, Fisher's method) at the check's α, with at most 10⁻³ of the frames' energy where that
// reading puts none. The declared geometry with a fitted scale is judged the same way, and is
// named only when the scale is a product of the density unit's factors (2π per Hz against per
// rad/s, 180/π per degree against per radian). A reading is named only when it passes where the
// declaration failed; the test is the shape check's, so a sea that truly follows that reading is
// missed with probability α/2 per reading.
#include <numbers>

#include "checks/ocean/analysis.hpp"
#include "swell/reference/spectrum_table.hpp"

namespace swell::validation::ocean_analysis {
namespace {

using reference::SpectrumTable;

// A reading of table component `component`: ω × omega_factor, θ mirrored between the two
// direction conventions.
struct Reading {
  std::size_t component = 0;
  double omega_factor = 1;
  bool mirrored = false;
};

// θ toward, counter-clockwise from +x, is 270° − θ nautical (from, clockwise from north); the
// map is its own inverse, so a table read in either convention as the other is mirrored so.
SpectrumTable reread(const SpectrumTable& table, const Reading& reading) {
  SpectrumTable out = table;
  for (double& w : out.omega) w *= reading.omega_factor;
  for (double& w : out.band_width) w *= reading.omega_factor;
  if (reading.mirrored && table.is_directional()) {
    const std::size_t nd = table.theta.size();
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t j = 0; j < nd; ++j) {
      double theta = std::remainder(1.5 * kPi - table.theta[j], 2 * kPi);
      if (theta < 0) theta += 2 * kPi;
      if (theta >= 2 * kPi) theta = 0;
      order.push_back({theta, j});
    }
    std::sort(order.begin(), order.end());
    for (std::size_t j = 0; j < nd; ++j) {
      out.theta[j] = order[j].first;
      for (std::size_t i = 0; i < table.omega.size(); ++i) {
        out.density[i * nd + j] = table.density[i * nd + order[j].second];
      }
    }
  }
  return out;
}

std::string other(const std::string& value, const std::string& a, const std::string& b) {
  return value == a ? b : a;
}

// A density unit's slip as a factor: 2π^a (180/π)^b with a, b in {−1, 0, 1}, not both 0, where
// |ln(scale/factor)| is within three standard errors of the Whittle scale (1/√n relative over
// n ordinates); empty when none is.
std::string density_factor(double scale, std::size_t n, bool directional) {
  const double tolerance = 3 / std::sqrt(double(std::max<std::size_t>(n, 1)));
  for (int a = -1; a <= 1; ++a) {
    for (int b = directional ? -1 : 0; b <= (directional ? 1 : 0); ++b) {
      if (a == 0 && b == 0) continue;
      const double factor = std::pow(2 * kPi, a) * std::pow(180 / kPi, b);
      if (std::abs(std::log(scale / factor)) > tolerance) continue;
      std::string parts;
      if (a != 0) parts += a > 0 ? "2π (per Hz read as per rad/s)" : "1/(2π) (per rad/s read as per Hz)";
      if (b != 0) {
        parts += parts.empty() ? "" : " × ";
        parts += b > 0 ? "180/π (per degree read as per radian)" : "π/180 (per radian read as per degree)";
      }
      return fmt::format("× {:.4g} = {}", factor, parts);
    }
  }
  return "";
}

struct Fit {
  bool explains = false;
  double scale = 1;
  std::size_t ordinates = 0;
};

// Whether frame 0's periodogram follows μ = scale · τ(k) + τ(−k) of `alternative`, its scale
// fitted.
Fit judge_reading(const Analysis& a, const OceanCase& alternative) {
  const auto tau = expected_travelling_power(alternative, a.threads());
  const auto mu = expected_periodogram(tau, a.sampling());
  const double total = std::accumulate(mu.begin(), mu.end(), 0.0);
  Fit fit;
  if (!(total > 0)) return fit;
  // Resolved as the analysis resolves: μ scaled to the frames' energy above the rounding floor.
  const double to_frames = a.mean_square0() / total;
  double sum = 0, energy = 0, unexplained = 0;
  std::vector<NormalizedOrdinate> ordinates;
  for (const Wave& w : a.half_plane()) {
    const double power = a.periodogram0(w.index);
    energy += power;
    if (!(mu[w.index] > 0) || mu[w.index] * to_frames < a.floor()) {
      unexplained += power;
      continue;
    }
    ordinates.push_back({w.k, power / mu[w.index]});
    sum += ordinates.back().u;
  }
  if (ordinates.empty() || !(energy > 0) || unexplained > 1e-3 * energy) return fit;
  fit.scale = sum / double(ordinates.size());
  fit.ordinates = ordinates.size();
  if (!(fit.scale > 0)) return fit;
  for (auto& o : ordinates) o.u /= fit.scale;
  fit.explains = ring_shape(std::move(ordinates)).p >= a.options().alpha / 2;
  return fit;
}

}  // namespace

std::string diagnose_table_declarations(const Analysis& a) {
  if (a.options().free_scale) return "";
  const OceanCase& declared = a.ocean_case();
  const auto components = declared.components();
  for (std::size_t i = 0; i < components.size(); ++i) {
    const auto& component = components[i];
    if (component.spectrum.model != "table" || !component.table) continue;
    const auto& choices = component.spectrum.choices;
    auto choice = [&](const char* key) {
      const auto it = choices.find(key);
      return it == choices.end() ? std::string() : it->second;
    };
    const std::string frequency_unit = choice("frequency_unit");
    const std::string convention = choice("direction_convention");
    const bool directional = component.table->is_directional();
    const std::string where = components.size() > 1 ? fmt::format("[spectrum {}]'s table", i) : "the table";
    // Frequencies declared in Hz were multiplied by 2π on reading; read as rad/s they are 2π
    // smaller, and the reverse.
    const double swap = frequency_unit == "Hz" ? 1 / (2 * kPi) : 2 * kPi;
    std::vector<Reading> readings = {{i, 1, false}, {i, swap, false}};
    if (directional) readings.push_back({i, 1, true}), readings.push_back({i, swap, true});
    for (const Reading& reading : readings) {
      OceanCase alternative = declared;
      auto parts = components;
      parts[i].table = std::make_shared<const SpectrumTable>(reread(*component.table, reading));
      alternative.set_components(parts);
      const Fit fit = judge_reading(a, alternative);
      if (!fit.explains) continue;
      const std::string factor = density_factor(fit.scale, fit.ordinates, directional);
      const bool unit_scale = std::abs(std::log(fit.scale)) <= 3 / std::sqrt(double(fit.ordinates));
      std::vector<std::string> slips;
      if (reading.omega_factor != 1) {
        slips.push_back(fmt::format("its frequencies in {}, not {} as declared (frequency_unit)",
                                    other(frequency_unit, "Hz", "rad/s"), frequency_unit));
      }
      if (reading.mirrored) {
        slips.push_back(fmt::format("its directions as {}, not {} as declared (direction_convention)",
                                    other(convention, "nautical_from", "toward_ccw_from_x"), convention));
      }
      if (!factor.empty()) {
        slips.push_back(fmt::format("its density in other units than the declared \"{}\" (density_unit): "
                                    "energy {}",
                                    choice("density_unit"), factor));
      } else if (!unit_scale) {
        if (slips.empty()) continue;  // the declared reading with a scale no unit explains
        slips.push_back(fmt::format("with energy × {:.3g}", fit.scale));
      }
      if (slips.empty()) continue;
      std::string joined;
      for (std::size_t s = 0; s < slips.size(); ++s) joined += (s == 0 ? "" : "; and ") + slips[s];
      return fmt::format("the frames follow {} ({}) read with {} — the case's declaration or the "
                         "engine's reading of the file is wrong",
                         where, component.table->source, joined);
    }
  }
  return "";
}

}  // namespace swell::validation::ocean_analysis
