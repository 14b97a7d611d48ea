// swell.spectrum: S(ω), Ψ(k) and the moments of a model or of a case's sea, from the same
// reference spectra as `swell spectrum` (its JSON's moments, sea_state_json).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.hpp"
#include "swell/reference/directional.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/moments.hpp"
#include "swell/validation/results/report.hpp"

namespace swell::python {
namespace {

struct Spectrum {
  std::string description;
  reference::FrequencySpectrumPtr omnidirectional;  // set for a model; else the sea's
  reference::DirectionalSpectrumPtr directional;    // null: no spreading to give Ψ
  std::string why_no_psi;

  const reference::FrequencySpectrum& s() const {
    return omnidirectional ? *omnidirectional : directional->omnidirectional();
  }
};

// NumPy converts any layout and dtype to the contiguous float64 these read (forcecast).
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::array_t<double> s_of(const Spectrum& spectrum, const Doubles& omega) {
  py::array_t<double> out(std::vector<py::ssize_t>(omega.shape(), omega.shape() + omega.ndim()));
  const double* w = omega.data();
  double* values = out.mutable_data();
  const py::ssize_t count = omega.size();
  const auto& s = spectrum.s();
  for (py::ssize_t i = 0; i < count; ++i) {
    if (!(std::isfinite(w[i]) && w[i] >= 0)) {
      throw InvalidInput(fmt::format("omega[{}] = {}: S(ω) takes finite ω ≥ 0 in rad/s", i, w[i]));
    }
  }
  py::gil_scoped_release release;
  for (py::ssize_t i = 0; i < count; ++i) values[i] = s(w[i]);
  return out;
}

// kx and ky of one shape (swell/__init__.py broadcasts them).
py::array_t<double> psi_of(const Spectrum& spectrum, const Doubles& kx, const Doubles& ky) {
  if (!spectrum.directional) throw InvalidInput(spectrum.why_no_psi);
  py::array_t<double> out(std::vector<py::ssize_t>(kx.shape(), kx.shape() + kx.ndim()));
  const double* x = kx.data();
  const double* y = ky.data();
  double* values = out.mutable_data();
  const py::ssize_t count = kx.size();
  for (py::ssize_t i = 0; i < count; ++i) {
    if (!(std::isfinite(x[i]) && std::isfinite(y[i]))) {
      throw InvalidInput(fmt::format("(kx, ky)[{}] = ({}, {}): Ψ(k) takes finite wave vectors in rad/m", i,
                                     x[i], y[i]));
    }
  }
  py::gil_scoped_release release;
  for (py::ssize_t i = 0; i < count; ++i) values[i] = spectrum.directional->psi(x[i], y[i]);
  return out;
}

Spectrum spectrum_of_case(const Case& c) {
  const auto& file = *c.file;
  const auto ocean = file.is_probe_case() ? file.probe_case().synthesized_sea() : file.ocean;
  Spectrum out;
  out.description = ocean.describe_sea();
  out.directional = ocean.sea_spectrum();
  return out;
}

// A model as `swell spectrum --model M` makes it, with Ψ where a spreading is given (or the
// model is Phillips, which carries its own directions) through the case's own assembly.
Spectrum spectrum_of_model(const reference::ModelSpec& spectrum, const reference::ModelSpec& spreading,
                           double wind_dir_deg) {
  Spectrum out;
  out.omnidirectional = reference::make_frequency_spectrum(spectrum);
  out.description = spectrum.model;
  if (spreading.model.empty() && spectrum.model != "phillips") {
    out.why_no_psi = fmt::format("psi: spectrum '{}' gives S(ω) only; Ψ(k) needs a spreading model "
                                 "(spreading=\"cos2s\", s=10, …: {})",
                                 spectrum.model, fmt::join(reference::spreading_model_names(), ", "));
    return out;
  }
  reference::OceanCase ocean;
  ocean.spectrum = spectrum;
  // gravity and depth are the case's, once for all models (ocean_case.hpp).
  for (const char* common : {"gravity", "depth"}) {
    if (auto it = ocean.spectrum.numbers.find(common); it != ocean.spectrum.numbers.end()) {
      (std::string(common) == "gravity" ? ocean.gravity : ocean.depth) = it->second;
      ocean.spectrum.numbers.erase(it);
    }
  }
  ocean.spreading = spreading;
  ocean.wind_dir_deg = wind_dir_deg;
  out.directional = ocean.sea_spectrum();
  if (!spreading.model.empty()) out.description += " + " + spreading.model;
  return out;
}

}  // namespace

void bind_spectrum(py::module_& m) {
  py::class_<Spectrum>(m, "Spectrum")
      .def("S", &s_of)
      .def("psi", &psi_of)
      .def("moments_json", [](const Spectrum& s) {
        const auto state = reference::sea_state(s.s());
        return validation::sea_state_json(state).dump();
      })
      .def_property_readonly("peak_omega", [](const Spectrum& s) { return s.s().peak_omega(); })
      .def_property_readonly("has_psi", [](const Spectrum& s) { return bool(s.directional); })
      .def_property_readonly("description", [](const Spectrum& s) { return s.description; })
      .def_property_readonly("parameters", [](const Spectrum& s) {
        std::map<std::string, double> out;
        for (const auto& p : s.s().parameters()) out[p.name] = p.value;
        return out;
      });
  m.def("spectrum_of_case", &spectrum_of_case);
  m.def("spectrum_of_model",
        [](const std::string& model, const std::map<std::string, double>& numbers,
           const std::map<std::string, std::string>& choices, const std::string& spreading,
           const std::map<std::string, double>& spreading_numbers, double wind_dir_deg) {
          return spectrum_of_model({model, numbers, choices}, {spreading, spreading_numbers, {}},
                                   wind_dir_deg);
        });
  m.def("model_parameters", [](const std::string& model) {
    std::vector<std::pair<std::string, bool>> out;  // name, takes a choice (a string)
    for (const auto& info : reference::model_parameters(model)) {
      out.emplace_back(info.name, info.unit.find('|') != std::string::npos);
    }
    return out;
  });
  m.def("model_names", [] { return reference::frequency_model_names(); });
  m.def("spreading_names", [] { return reference::spreading_model_names(); });
}

}  // namespace swell::python
