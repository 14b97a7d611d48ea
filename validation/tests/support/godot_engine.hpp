#pragma once
// A test engine with the conventions of the compute-shader ocean of an open Godot 4 project
// (run headless on lavapipe from its unmodified shaders), each of which the gate must name —
// alone and together. Built on the test engine (test_engine.hpp) by what that engine does
// differently:
//   energy × 8        unit-variance real and imaginary parts, √2 on the amplitude, both halves
//                     of each ±k pair at full variance: 2 × 2 × 2;
//   against the wind  e^(+iωt) on h̃0(k) (the test engine's reversed_time);
//   Nyquist filled    the spectrum's Nyquist row and column drawn like any other bin: every
//                     linear field carries c (−1)^i + c (−1)^j, c = 3·10⁻³ of its rms;
//   packed leak       two fields packed in one complex transform (x + i z displacement): the
//                     Nyquist column of one leaks into the other, 5.5·10⁻³ of disp_y's rms;
//   normal map        its "slopes" are the normal map's, ∂h/∂x divided by 1 + |∂Dx/∂x|;
//   half              every texture stored in half, rounded toward zero.
#include <cmath>
#include <complex>
#include <map>
#include <numbers>

#include "frame_edits.hpp"
#include "half_rounding.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "test_engine.hpp"

namespace swell::test {

struct GodotConventions {
  bool energy_times_8 = false, against_wind = false, nyquist_filled = false, packed_leak = false,
       normal_map = false, half = false;
};

namespace godot_detail {

// ∂f/∂x (along_x) or ∂f/∂y of a grid field, spectrally.
inline std::vector<double> derivative(const std::vector<double>& f, const reference::Grid& grid, bool along_x) {
  auto spectrum = validation::field_spectrum(f, grid);
  for (std::size_t e = 0; e < spectrum.size(); ++e) {
    const int i = int(e % std::size_t(grid.nx)), j = int(e / std::size_t(grid.nx));
    const int n = i < grid.nx / 2 ? i : i - grid.nx, m = j < grid.ny / 2 ? j : j - grid.ny;
    const bool nyquist = (along_x && 2 * i == grid.nx) || (!along_x && 2 * j == grid.ny);
    spectrum[e] *= nyquist ? 0.0 : std::complex<double>(0, along_x ? n * grid.dkx() : m * grid.dky());
  }
  return validation::field_from_spectrum(spectrum, grid);
}

}  // namespace godot_detail

// The case's surface as that engine renders it (height, slopes, displacements; no Jacobian).
inline reference::FrameSequence render_godot(const reference::OceanCase& c, const GodotConventions& godot) {
  using reference::Field;
  auto frames = render_surface(c, godot.against_wind ? EngineBug::reversed_time : EngineBug::none);
  for (auto& frame : frames.frames) {
    frame.fields.erase(Field::jacobian);
    if (godot.energy_times_8) scale_energy(frame, 8.0);
    // The normal map from the displacement the engine outputs (× 8 included).
    if (godot.normal_map) {
      for (Field slope : {Field::slope_x, Field::slope_y}) {
        const bool along_x = slope == Field::slope_x;
        const auto& d = frame.fields.at(along_x ? Field::disp_x : Field::disp_y);
        const auto dd = godot_detail::derivative(d, c.grid, along_x);  // λ ∂D/∂x: the stored D holds λ
        auto& s = frame.fields.at(slope);
        for (std::size_t p = 0; p < s.size(); ++p) s[p] /= 1 + std::abs(dd[p]);
      }
    }
  }
  // Levels from frame 0's fields, as the engine's bins are filled at a fixed level.
  std::map<Field, double> levels;
  for (const auto& [field, values] : frames.frames.front().fields) levels[field] = rms(values);
  for (auto& frame : frames.frames) {
    if (godot.nyquist_filled) {
      for (auto& [field, values] : frame.fields) add_nyquist(values, c.grid, 3e-3 * levels[field]);
    }
    if (godot.packed_leak) {  // the Nyquist column alone: c (−1)^i
      auto& z = frame.fields.at(Field::disp_y);
      const double leak = 5.5e-3 * levels[Field::disp_y];
      for (std::size_t p = 0; p < z.size(); ++p) z[p] += (p % std::size_t(c.grid.nx)) % 2 ? -leak : leak;
    }
  }
  if (godot.half) store_in_half(frames, true);
  return frames;
}

}  // namespace swell::test
