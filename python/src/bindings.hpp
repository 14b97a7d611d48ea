#pragma once
// The pieces of the _swell extension module (module.cpp puts them together); each binds one
// of the public functions of python/swell/__init__.py on the same library calls as the command
// that does the same job.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/npy.hpp"

namespace swell::python {

namespace py = pybind11;

// A case as the Python module holds it: read once, shared by every call that takes it.
struct Case {
  std::shared_ptr<const validation::CaseFile> file;
};

// An array the Python layer made C-contiguous and little-endian, as an .npy file holds it
// (float16, float32, float64, complex64, complex128); copied, since the readers take NpyArray.
validation::NpyArray npy_of(const py::array& array);
// An NpyArray as a NumPy array that owns its bytes (no copy: the vector moves into a capsule).
py::array numpy_of(validation::NpyArray&& array);

// Per field name, the arrays of its frames.
using FieldArrays = std::map<reference::Field, std::vector<validation::NpyArray>>;
FieldArrays field_arrays_of(const py::dict& fields);

void bind_case(py::module_& m);
void bind_spectrum(py::module_& m);
void bind_synth(py::module_& m);
void bind_gate(py::module_& m);
void bind_fit(py::module_& m);
void bind_fft(py::module_& m);

}  // namespace swell::python
