// swell.synth: a case's frames (or probe series) into NumPy arrays, from the same synthesizers
// as `swell synth`, after the same validity rule. The synthesizer writes each frame in its own
// precision; the fields are copied into their arrays without conversion.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>
#include <thread>

#include "bindings.hpp"
#include "swell/impls/probe_synthesis.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/reference/cascade.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/probe_sea.hpp"
#include "swell/reference/sampling_validity.hpp"

namespace swell::python {
namespace {

using reference::Field;

// `fields` of one surface's frames, (frames, ny, nx) or on a lattice (frames, N).
py::dict synth_surface(const reference::OceanCase& ocean, const std::string& impl, impls::Precision precision,
                       const std::vector<Field>& fields) {
  const bool f64 = precision == impls::Precision::f64;
  const std::size_t item = f64 ? 8 : 4;
  const std::size_t samples = ocean.sampling().size();
  const reference::Grid shape = ocean.is_lattice()
                                    ? reference::Grid{static_cast<int>(samples), 1, ocean.grid.lx, ocean.grid.ly}
                                    : ocean.grid;
  const double array_bytes = double(samples) * double(fields.size()) * double(ocean.frames) * double(item);
  reference::require_valid_sampling(
      ocean, f64 ? reference::kFloat64 : reference::kFloat32,
      impls::Synthesizer::bytes_needed(shape, precision) + std::uint64_t(std::min(array_bytes, 1e18)),
      "swell.synth");
  std::vector<py::ssize_t> dims = {ocean.frames};
  if (ocean.is_lattice()) {
    dims.push_back(py::ssize_t(samples));
  } else {
    dims.push_back(ocean.grid.ny);
    dims.push_back(ocean.grid.nx);
  }
  py::dict out;
  std::vector<std::pair<std::size_t, std::byte*>> targets;  // position in kAllFields, array data
  for (Field field : fields) {
    py::array array(py::dtype(f64 ? "<f8" : "<f4"), dims);
    const auto position = std::size_t(std::find(reference::kAllFields.begin(), reference::kAllFields.end(), field) -
                                      reference::kAllFields.begin());
    targets.emplace_back(position, static_cast<std::byte*>(array.mutable_data()));
    out[py::str(reference::field_name(field))] = array;
  }
  {
    py::gil_scoped_release release;
    impls::SynthesizerOptions options;
    options.backend = impl;
    options.precision = precision;
    const impls::Synthesizer synthesizer(ocean, options);  // unknown backends name the valid ones
    std::vector<std::byte> frame(synthesizer.frame_bytes());
    const std::size_t field_bytes = samples * item;
    for (int f = 0; f < ocean.frames; ++f) {
      synthesizer.evaluate(ocean.time(f), frame);
      for (const auto& [position, data] : targets) {
        std::memcpy(data + std::size_t(f) * field_bytes, frame.data() + position * field_bytes, field_bytes);
      }
    }
  }
  return out;
}

// A probes case's series, (samples, probes) in metres, float64 as the command's CSV holds them.
py::array synth_probes(const validation::CaseFile& file) {
  const auto probe_case = file.probe_case();
  std::vector<std::vector<double>> series;
  {
    py::gil_scoped_release release;
    const auto lines = reference::probe_wave_lines(probe_case, file.ocean.seed);
    series = impls::synthesize_probe_series(probe_case, lines,
                                            int(std::max(1u, std::thread::hardware_concurrency())));
  }
  const std::size_t probes = series.size();
  const std::size_t samples = probes ? series.front().size() : 0;
  py::array_t<double> out({py::ssize_t(samples), py::ssize_t(probes)});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t p = 0; p < probes; ++p) {
    for (std::size_t n = 0; n < samples; ++n) view(py::ssize_t(n), py::ssize_t(p)) = series[p][n];
  }
  return out;
}

py::object synth(const Case& c, const std::string& impl, const std::string& precision, int frames,
                 const std::vector<std::string>& field_names) {
  const auto& file = *c.file;
  if (file.is_probe_case()) return synth_probes(file);
  if (precision != "float32" && precision != "float64") {
    throw InvalidInput(fmt::format("precision '{}': give \"float32\" or \"float64\" (the command's fp32, fp64)",
                                   precision));
  }
  const auto numbers = precision == "float64" ? impls::Precision::f64 : impls::Precision::f32;
  std::vector<Field> fields;
  for (const auto& name : field_names) fields.push_back(reference::field_from_name(name));
  if (fields.empty()) fields.assign(reference::kAllFields.begin(), reference::kAllFields.end());
  auto with_frames = [&](reference::OceanCase ocean) {
    if (frames > 0) ocean.frames = frames;
    ocean.validate();
    return ocean;
  };
  if (frames < 0) throw InvalidInput(fmt::format("frames = {}: give a count ≥ 1 (or none: the case's)", frames));
  if (!file.is_cascade_set()) return synth_surface(with_frames(file.ocean), impl, numbers, fields);
  // A cascade set, as `swell synth` makes it: a right set only (an additive one shares its bands
  // out); each cascade's fields, and the summed surface where the patches allow one and its grid
  // is at most 2048² (the command's --sum auto).
  if (file.relation == reference::CascadeRelation::additive) {
    try {
      reference::require_bands_share_out(file.ocean, file.members());
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}; swell.synth makes right sets only (swell.gate judges this one)", e.what()));
    }
  }
  py::dict out;
  for (std::size_t k = 0; k < file.cascades.size(); ++k) {
    out[py::str(fmt::format("cascade{}", k))] = synth_surface(with_frames(file.cascade_case(k)), impl, numbers, fields);
  }
  constexpr double kLargestAutomaticSum = 2048.0 * 2048.0;
  auto summed = file.summed_case();
  if (summed && double(summed->grid.nx) * summed->grid.ny <= kLargestAutomaticSum) out["sum"] = synth_surface(with_frames(*summed), impl, numbers, fields);
  return out;
}

}  // namespace

void bind_synth(py::module_& m) { m.def("synth", &synth); }

}  // namespace swell::python
