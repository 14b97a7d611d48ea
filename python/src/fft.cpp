// swell.fft and swell.backends: one array through one registered backend, as `swell fft`
// transforms one .npy file (transform_array), unnormalized in both directions.
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "swell/impls/transform.hpp"
#include "swell/validation/io/npy_transform.hpp"

namespace swell::python {
namespace {

py::array fft(const py::array& x, const std::string& impl, bool inverse, bool c2r, std::optional<int> nx) {
  auto backend = impls::make_backend(impl);  // unknown names list the valid ones
  const auto input = npy_of(x);
  validation::ArrayTransformRequest request;
  request.inverse = inverse;
  request.c2r = c2r;
  request.nx = nx;
  validation::ArrayTransformResult result;
  {
    py::gil_scoped_release release;
    result = validation::transform_array(*backend, input, "x", request);
  }
  return numpy_of(std::move(result.output));
}

}  // namespace

void bind_fft(py::module_& m) {
  m.def("fft", &fft);
  m.def("backends", [] { return impls::backend_names(); });
}

}  // namespace swell::python
