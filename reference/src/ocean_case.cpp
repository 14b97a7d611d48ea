#include "swell/reference/ocean_case.hpp"

#include <cmath>
#include <memory>
#include <fmt/format.h>

#include "swell/reference/composite_spectrum.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/table_spectrum.hpp"

namespace swell::reference {
namespace {

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Ψ times a cascade's band weight w(|k|)². Its omnidirectional spectrum stays the sea's: the
// weight depends on |k| alone, so a cascade's S_c(ω) would be w(k(ω))² S(ω), but what reads it
// (the validity rule's m0, Tp) wants the sea.
class BandedSpectrum final : public DirectionalSpectrum {
 public:
  BandedSpectrum(DirectionalSpectrumPtr sea, BandWeight band) : sea_(std::move(sea)), band_(band) {}
  double psi(double kx, double ky) const override {
    const double w2 = band_.weight_squared(std::hypot(kx, ky));
    return w2 == 0 ? 0.0 : w2 * sea_->psi(kx, ky);
  }
  const Dispersion& dispersion() const override { return sea_->dispersion(); }
  const FrequencySpectrum& omnidirectional() const override { return sea_->omnidirectional(); }
  double mean_direction() const override { return sea_->mean_direction(); }

 private:
  DirectionalSpectrumPtr sea_;
  BandWeight band_;
};

// The summed surface of a set on its fine grid (lengths lx × ly): the wave vector
// K = (n Δkx, m Δky) carries, for every cascade whose grid holds K (K·L_c/2π integer, inside
// its band of indices, not its Nyquist), w_c² Ψ_c(K) Δk_c² — Ψ_c the cascade's own sea for
// independent seas, the set's otherwise; divided by the fine Δk² so that the checks'
// μ = ½(Ψ(k) + Ψ(−k)) Δk² comes out as the sum of the cascades' μ_c.
class SummedCascadeSpectrum final : public DirectionalSpectrum {
 public:
  SummedCascadeSpectrum(DirectionalSpectrumPtr sea, std::vector<CascadeMember> members, double lx,
                        double ly)
      : sea_(std::move(sea)), members_(std::move(members)), lx_(lx), ly_(ly) {}
  double psi(double kx, double ky) const override {
    double total = 0;
    const double fine_dk2 = (2 * M_PI / lx_) * (2 * M_PI / ly_);
    for (const auto& c : members_) {
      const double x = kx * c.grid.lx / (2 * M_PI), y = ky * c.grid.ly / (2 * M_PI);
      const double n = std::round(x), m = std::round(y);
      if (std::abs(x - n) > 1e-6 || std::abs(y - m) > 1e-6) continue;
      if (n < -(c.grid.nx / 2) || n >= (c.grid.nx + 1) / 2 || m < -(c.grid.ny / 2) ||
          m >= (c.grid.ny + 1) / 2 || !c.grid.carries_energy(int(n), int(m))) {
        continue;
      }
      const double w2 = c.band.weight_squared(std::hypot(kx, ky));
      const DirectionalSpectrum& psi = c.spectrum ? *c.spectrum : *sea_;
      if (w2 > 0) total += w2 * psi.psi(kx, ky) * c.grid.dkx() * c.grid.dky() / fine_dk2;
    }
    return total;
  }
  const Dispersion& dispersion() const override { return sea_->dispersion(); }
  const FrequencySpectrum& omnidirectional() const override { return sea_->omnidirectional(); }
  double mean_direction() const override { return sea_->mean_direction(); }

 private:
  DirectionalSpectrumPtr sea_;
  std::vector<CascadeMember> members_;
  double lx_, ly_;
};

}  // namespace

DirectionalSpectrumPtr OceanCase::directional_spectrum() const {
  auto sea = sea_spectrum();
  if (!members.empty()) {
    return std::make_shared<SummedCascadeSpectrum>(std::move(sea), members, grid.lx, grid.ly);
  }
  if (!band.everywhere()) return std::make_shared<BandedSpectrum>(std::move(sea), band);
  return sea;
}

std::vector<SeaComponent> OceanCase::components() const {
  std::vector<SeaComponent> out{
      {spectrum, spreading, wind_dir_deg, energy_factor, short_wave_fade, table}};
  out.insert(out.end(), more_components.begin(), more_components.end());
  return out;
}

void OceanCase::set_components(const std::vector<SeaComponent>& all) {
  if (all.empty()) throw InvalidInput("a sea needs at least one component");
  spectrum = all.front().spectrum;
  spreading = all.front().spreading;
  wind_dir_deg = all.front().wind_dir_deg;
  energy_factor = all.front().energy_factor;
  short_wave_fade = all.front().short_wave_fade;
  table = all.front().table;
  more_components.assign(all.begin() + 1, all.end());
}

ModelSpec OceanCase::full_spectrum_spec() const { return full_spectrum_spec(components().front()); }

ModelSpec OceanCase::full_spectrum_spec(const SeaComponent& component) const {
  ModelSpec spec = component.spectrum;
  for (const char* common : {"gravity", "depth", "wind_dir"}) {
    if (spec.numbers.count(common)) {
      throw InvalidInput(fmt::format(
          "spectrum parameter '{}' belongs to the case ([physics] gravity and depth, "
          "wind_dir_deg), not to the spectrum model",
          common));
    }
  }
  spec.numbers["gravity"] = gravity;
  spec.numbers["depth"] = depth;
  spec.numbers["wind_dir"] = component.wind_dir_deg;
  return spec;
}

Dispersion OceanCase::dispersion() const { return Dispersion::finite_depth(depth, gravity); }

double OceanCase::omega(double k) const {
  return quantize_omega(Dispersion::finite_depth(depth, gravity).omega(k), loop_period);
}

DirectionalSpectrumPtr OceanCase::component_spectrum(const SeaComponent& c) const {
  const double toward = c.wind_dir_deg * 3.14159265358979323846 / 180.0;
  if (c.table) {
    if (c.table->is_directional()) {
      if (!c.spreading.model.empty()) {
        throw InvalidInput("a 2-D spectrum table E(f, θ) carries its own directions; give no "
                           "spreading model (got '" + c.spreading.model + "')");
      }
      return adjusted_spectrum(table_directional_spectrum(c.table, dispersion()), c.energy_factor,
                               c.short_wave_fade);
    }
    if (c.spreading.model.empty()) {
      throw InvalidInput("a 1-D spectrum table S(f) needs a spreading model (" +
                         join_names(spreading_model_names()) + ")");
    }
    const auto frequency = table_frequency_spectrum(c.table);
    return adjusted_spectrum(
        SpreadSpectrum::create(frequency, make_spreading(c.spreading, frequency->peak_omega()),
                               dispersion(), toward),
        c.energy_factor, c.short_wave_fade);
  }
  const auto frequency = make_frequency_spectrum(full_spectrum_spec(c));
  if (c.spectrum.model == "phillips") {
    if (!c.spreading.model.empty()) {
      throw InvalidInput("spectrum 'phillips' carries its own directional factor |k̂·ŵ|^p; "
                         "give no spreading model (got '" + c.spreading.model + "')");
    }
    return adjusted_spectrum(std::dynamic_pointer_cast<const Phillips>(frequency),
                             c.energy_factor, c.short_wave_fade);
  }
  if (c.spreading.model.empty()) {
    throw InvalidInput("spectrum '" + c.spectrum.model +
                       "' needs a spreading model (" + join_names(spreading_model_names()) + ")");
  }
  // Horvath's wave age comes from the case's wind (its spectrum's u10) when the spreading does
  // not give one: U10/cp at the peak under the case's dispersion.
  ModelSpec spreading_spec = c.spreading;
  if (spreading_spec.model == "horvath" && !spreading_spec.numbers.count("wave_age") &&
      c.spectrum.numbers.count("u10")) {
    spreading_spec.numbers["wave_age"] =
        Horvath::wave_age(c.spectrum.numbers.at("u10"), frequency->peak_omega(), dispersion());
  }
  const auto spread = make_spreading(spreading_spec, frequency->peak_omega());
  return adjusted_spectrum(
      SpreadSpectrum::create(frequency, spread, dispersion(), toward),
      c.energy_factor, c.short_wave_fade);
}

DirectionalSpectrumPtr OceanCase::sea_spectrum() const {
  std::vector<DirectionalSpectrumPtr> parts;
  const auto all = components();
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all.size() == 1) {
      parts.push_back(component_spectrum(all[i]));
      continue;
    }
    try {
      parts.push_back(component_spectrum(all[i]));
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("[[spectrum]] component {}: {}", i, e.what()));
    }
  }
  return summed_spectrum(std::move(parts));
}

void OceanCase::set_lattice(std::shared_ptr<const RankOneLattice> new_lattice) {
  const Sampling checked(new_lattice);  // 2-D only
  lattice = std::move(new_lattice);
  grid = Grid{0, 0, checked.lx(), checked.ly()};
}

namespace {

// The sea's scalar rules, shared by validate() and validate_sea().
void require_sea_scalars(const OceanCase& c) {
  require(std::isfinite(c.t0), "t0", "finite (s)", c.t0);
  require(std::isfinite(c.dt) && c.dt >= 0, "dt", "finite and ≥ 0 (s)", c.dt);
  require(std::isfinite(c.gravity) && c.gravity > 0, "gravity", "finite and > 0 (m/s²)", c.gravity);
  require(c.depth > 0 && !std::isnan(c.depth), "depth", "> 0 m or inf", c.depth);
  for (const auto& part : c.components()) {
    require(std::isfinite(part.wind_dir_deg), "wind_dir_deg", "finite (degrees)", part.wind_dir_deg);
    require(std::isfinite(part.energy_factor) && part.energy_factor > 0, "energy_factor",
            "finite and > 0", part.energy_factor);
    require(std::isfinite(part.short_wave_fade) && part.short_wave_fade >= 0, "short_wave_fade",
            "finite and ≥ 0 (m)", part.short_wave_fade);
  }
  require(std::isfinite(c.choppiness), "choppiness", "finite", c.choppiness);
  require(std::isfinite(c.loop_period) && c.loop_period >= 0, "loop_period", "finite and ≥ 0 (s)",
          c.loop_period);
}

}  // namespace

void OceanCase::validate() const {
  if (lattice) {
    const Sampling checked(lattice);  // 2-D only
    if (grid.nx != 0 || grid.ny != 0 || grid.lx != checked.lx() || grid.ly != checked.ly()) {
      throw InvalidInput(fmt::format(
          "the case samples {} but its grid says {}×{} over {:g}×{:g} m (set_lattice keeps them "
          "in step)", checked.describe(), grid.nx, grid.ny, grid.lx, grid.ly));
    }
  } else {
    (void)Grid::create(grid.nx, grid.ny, grid.lx, grid.ly);
  }
  require(frames >= 1, "frames", "≥ 1", frames);
  require_sea_scalars(*this);
  require(frames == 1 || dt > 0, "dt", "> 0 when there is more than one frame (s)", dt);
  require(cascade >= 0, "cascade", "≥ 0 (the index that keys its random numbers)", cascade);
  band.validate(fmt::format("cascade {}", cascade));
  if (!members.empty()) {
    if (lattice) throw InvalidInput("a summed cascade set is a grid, not a lattice");
    Grid fine;
    std::string why;
    for (const auto& m : members) {
      (void)Grid::create(m.grid.nx, m.grid.ny, m.grid.lx, m.grid.ly);
      m.band.validate(fmt::format("cascade {}", m.cascade));
    }
    if (!summed_grid(members, fine, &why)) {
      throw InvalidInput("the cascades cannot be summed on one grid: " + why);
    }
    if (fine.nx != grid.nx || fine.ny != grid.ny || std::abs(fine.lx - grid.lx) > 1e-9 * grid.lx ||
        std::abs(fine.ly - grid.ly) > 1e-9 * grid.ly) {
      throw InvalidInput(fmt::format(
          "the summed surface of these cascades is {}×{} over {:g}×{:g} m (the finest spacing "
          "over the largest patch), not the case's {}×{} over {:g}×{:g} m",
          fine.nx, fine.ny, fine.lx, fine.ly, grid.nx, grid.ny, grid.lx, grid.ly));
    }
  }
  (void)directional_spectrum();  // the spectrum and spreading parameters
}

void OceanCase::validate_sea() const {
  require_sea_scalars(*this);
  (void)sea_spectrum();  // the spectrum and spreading parameters
}

std::string OceanCase::describe_sea() const {
  auto params = [](const ModelSpec& spec) {
    std::string out = spec.model;
    for (const auto& [name, value] : spec.numbers) out += fmt::format(" {}={:g}", name, value);
    for (const auto& [name, value] : spec.choices) out += fmt::format(" {}={}", name, value);
    return out;
  };
  std::string out;
  for (const auto& c : components()) {
    if (!out.empty()) out += " ⊕ ";
    out += params(c.spectrum);
    if (c.energy_factor != 1) out += fmt::format(" ×{:g}", c.energy_factor);
    if (c.short_wave_fade != 0) out += fmt::format(" fade {:g} m", c.short_wave_fade);
    if (!c.spreading.model.empty()) out += " + " + params(c.spreading);
    if (is_composite()) out += fmt::format(" toward {:g}°", c.wind_dir_deg);
  }
  return out;
}

std::string OceanCase::describe() const {
  std::string out = describe_sea();
  if (lattice) {
    out += ", " + lattice->describe();
  } else {
    out += fmt::format(", {}×{} over {:g}×{:g} m", grid.nx, grid.ny, grid.lx, grid.ly);
  }
  if (std::isfinite(depth)) out += fmt::format(", depth {:g} m", depth);
  if (!members.empty()) {
    out += fmt::format(", the sum of {} cascades", members.size());
  } else if (cascade != 0 || !band.everywhere()) {
    out += fmt::format(", cascade {} band {}", cascade, band.describe());
  }
  return out;
}

}  // namespace swell::reference
