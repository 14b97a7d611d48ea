#pragma once
// Edits the gate's tests make to right frames to make them wrong the way engines are: one
// definition of each, shared by the catalogue (gate/gate_catalogue_test.cpp) and the Godot
// conventions (godot_engine.hpp).
#include <cmath>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/reference/grid.hpp"

namespace swell::test {

// The rms of a field's values.
inline double rms(const std::vector<double>& values) {
  double sum = 0;
  for (double x : values) sum += x * x;
  return values.empty() ? 0 : std::sqrt(sum / double(values.size()));
}

// The rms of a field over a frame sequence's frame 0.
inline double rms_of(const reference::FrameSequence& frames, reference::Field field) {
  return rms(frames.field(0, field));
}

// c (−1)^i + c (−1)^j: energy on a grid field's Nyquist column and row, as an engine that draws
// those bins like any other (or packs two fields per complex transform) leaves them.
inline void add_nyquist(std::vector<double>& field, const reference::Grid& grid, double c) {
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      field[std::size_t(j) * grid.nx + i] += c * ((i % 2 ? -1.0 : 1.0) + (j % 2 ? -1.0 : 1.0));
    }
  }
}

// The energy × factor: every linear field × √factor; the Jacobian, which is not linear in
// them, dropped.
inline void scale_energy(reference::FieldFrame& frame, double factor) {
  frame.fields.erase(reference::Field::jacobian);
  for (auto& [field, values] : frame.fields) {
    for (double& v : values) v *= std::sqrt(factor);
  }
}

inline void scale_energy(reference::FrameSequence& frames, double factor) {
  for (auto& frame : frames.frames) scale_energy(frame, factor);
}

}  // namespace swell::test
