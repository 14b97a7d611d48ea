#include "swell/reference/ocean_case.hpp"

#include <cmath>
#include <fmt/format.h>

#include "swell/reference/errors.hpp"

namespace swell::reference {

ModelSpec OceanCase::full_spectrum_spec() const {
  ModelSpec spec = spectrum;
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
  spec.numbers["wind_dir"] = wind_dir_deg;
  return spec;
}

Dispersion OceanCase::dispersion() const { return Dispersion::finite_depth(depth, gravity); }

double OceanCase::omega(double k) const {
  return quantize_omega(Dispersion::finite_depth(depth, gravity).omega(k), loop_period);
}

DirectionalSpectrumPtr OceanCase::directional_spectrum() const {
  const auto frequency = make_frequency_spectrum(full_spectrum_spec());
  if (spectrum.model == "phillips") {
    if (!spreading.model.empty()) {
      throw InvalidInput("spectrum 'phillips' carries its own directional factor |k̂·ŵ|^p; "
                         "give no spreading model (got '" + spreading.model + "')");
    }
    return std::dynamic_pointer_cast<const Phillips>(frequency);
  }
  if (spreading.model.empty()) {
    throw InvalidInput("spectrum '" + spectrum.model +
                       "' needs a spreading model (cos2s, mitsuyasu, hasselmann, "
                       "donelan-banner, cos-power)");
  }
  const auto spread = make_spreading(spreading, frequency->peak_omega());
  return SpreadSpectrum::create(frequency, spread, dispersion(),
                                wind_dir_deg * 3.14159265358979323846 / 180.0);
}

void OceanCase::set_lattice(std::shared_ptr<const RankOneLattice> new_lattice) {
  const Sampling checked(new_lattice);  // 2-D only
  lattice = std::move(new_lattice);
  grid = Grid{0, 0, checked.lx(), checked.ly()};
}

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
  require(std::isfinite(t0), "t0", "finite (s)", t0);
  require(std::isfinite(dt) && dt >= 0, "dt", "finite and ≥ 0 (s)", dt);
  require(frames == 1 || dt > 0, "dt", "> 0 when there is more than one frame (s)", dt);
  require(std::isfinite(gravity) && gravity > 0, "gravity", "finite and > 0 (m/s²)", gravity);
  require(depth > 0 && !std::isnan(depth), "depth", "> 0 m or inf", depth);
  require(std::isfinite(wind_dir_deg), "wind_dir_deg", "finite (degrees)", wind_dir_deg);
  require(std::isfinite(choppiness), "choppiness", "finite", choppiness);
  require(std::isfinite(loop_period) && loop_period >= 0, "loop_period", "finite and ≥ 0 (s)",
          loop_period);
  (void)directional_spectrum();  // the spectrum and spreading parameters
}

std::string OceanCase::describe() const {
  auto params = [](const ModelSpec& spec) {
    std::string out = spec.model;
    for (const auto& [name, value] : spec.numbers) out += fmt::format(" {}={:g}", name, value);
    for (const auto& [name, value] : spec.choices) out += fmt::format(" {}={}", name, value);
    return out;
  };
  std::string out = params(spectrum);
  if (!spreading.model.empty()) out += " + " + params(spreading);
  if (lattice) {
    out += ", " + lattice->describe();
  } else {
    out += fmt::format(", {}×{} over {:g}×{:g} m", grid.nx, grid.ny, grid.lx, grid.ly);
  }
  if (std::isfinite(depth)) out += fmt::format(", depth {:g} m", depth);
  return out;
}

}  // namespace swell::reference
