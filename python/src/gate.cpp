// swell.gate: frames (or probe series) handed over as arrays, read by frames_from_arrays as the
// command reads .npy files of them — or, with no arrays, the files the case names — then judged
// by the same run_gate; the report is rendered by
// the same functions as the command's text, JSON and JUnit XML.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/gate/power.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/io/probe_series.hpp"

namespace swell::python {
namespace {

validation::GateOptions options_of(double alpha, int threads, bool power) {
  validation::GateOptions options;
  options.alpha = alpha;
  options.threads = threads;
  options.power = power;
  options.validate();
  return options;
}

struct Report {
  validation::GateReport report;
};

// The gate on arrays: `fields` (one surface), or `cascades` and `sum` (a set), or `elevation`
// (a probes case). Each field maps to the list of its frames' arrays.
Report gate(const Case& c, const py::dict& fields, const py::list& cascades, const py::object& sum,
            const py::object& elevation, double alpha, int threads, bool power) {
  const auto& file = *c.file;
  const auto options = options_of(alpha, threads, power);
  validation::GateReport report;
  if (fields.empty() && cascades.empty() && sum.is_none() && elevation.is_none()) {
    // No arrays: the frames (or series) the case's [input] names, read as the command reads them.
    py::gil_scoped_release release;
    report = validation::run_gate(file, options);
  } else if (file.is_probe_case()) {
    if (elevation.is_none()) {
      throw InvalidInput("a probes case is judged on its series: give elevation = an array of (samples, probes)");
    }
    const auto series = validation::probe_series_from_array(npy_of(elevation.cast<py::array>()), "elevation",
                                                            file.probes->layout);
    py::gil_scoped_release release;
    report = validation::run_probe_gate(file, series, options);
  } else if (file.is_cascade_set()) {
    if (py::len(cascades) != file.cascades.size()) {
      throw InvalidInput(fmt::format("the case is a set of {} cascades: give cascades = a list of {} dicts of "
                                     "fields (an empty dict for a cascade not given)",
                                     file.cascades.size(), file.cascades.size()));
    }
    std::vector<reference::FrameSequence> surfaces;
    for (std::size_t k = 0; k < file.cascades.size(); ++k) {
      const auto arrays = field_arrays_of(cascades[k].cast<py::dict>());
      if (arrays.empty()) {
        surfaces.emplace_back();
        continue;
      }
      try {
        surfaces.push_back(validation::frames_from_arrays(file.cascade_case(k), file.cascades[k].input.precision, arrays));
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("cascade {}: {}", k, e.what()));
      }
    }
    std::optional<reference::FrameSequence> summed;
    if (!sum.is_none()) {
      std::string why;
      const auto summed_case = file.summed_case(&why);
      if (!summed_case) throw InvalidInput("sum: the cascades have no summed surface: " + why);
      summed = validation::frames_from_arrays(*summed_case, file.sum.precision, field_arrays_of(sum.cast<py::dict>()));
    }
    py::gil_scoped_release release;
    report = validation::run_cascade_gate(file, surfaces, summed ? &*summed : nullptr, options);
  } else {
    const auto frames = validation::frames_from_arrays(file.ocean, file.input.precision, field_arrays_of(fields));
    py::gil_scoped_release release;
    report = validation::run_gate(file, frames, options);
  }
  report.case_path = file.origin.string();
  return {std::move(report)};
}

}  // namespace

void bind_gate(py::module_& m) {
  py::class_<Report>(m, "GateReport")
      .def_property_readonly("passed", [](const Report& r) { return r.report.passed(); })
      .def("json", [](const Report& r) { return validation::gate_json(r.report).dump(); })
      .def("junit", [](const Report& r) { return validation::gate_junit(r.report); })
      .def("text", [](const Report& r) { return validation::render_gate(r.report); });
  m.def("gate", &gate);
  m.def("gate_power", [](const Case& c, double alpha, int threads) {
    const auto options = options_of(alpha, threads, true);
    py::gil_scoped_release release;
    const auto table = validation::gate_power(*c.file, alpha, options.resolved_threads());
    return std::pair{validation::render_power(table), validation::power_json(table).dump()};
  });
}

}  // namespace swell::python
