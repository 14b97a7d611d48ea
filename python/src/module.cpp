// The _swell extension module: swell's libraries for python/swell/__init__.py, which gives
// them their Python signatures (docs/python.md). swell::InvalidInput — what the command
// answers with exit code 2 — is raised as swell.InvalidInput, a ValueError, with the same
// message; a failed check is a result, never an exception.
#include "bindings.hpp"
#include "swell/reference/errors.hpp"

PYBIND11_MODULE(_swell, m) {
  namespace py = pybind11;
  m.doc() = "swell's C++ libraries; use the swell package, not this module";
  py::register_exception<swell::InvalidInput>(m, "InvalidInput", PyExc_ValueError);
  py::register_exception<swell::NumericalError>(m, "NumericalError", PyExc_ArithmeticError);
  swell::python::bind_case(m);
  swell::python::bind_spectrum(m);
  swell::python::bind_synth(m);
  swell::python::bind_gate(m);
  swell::python::bind_fit(m);
  swell::python::bind_fft(m);
}
