// NumPy arrays to the readers' NpyArray and back (bindings.hpp). The Python layer has already
// made each array C-contiguous and little-endian with NumPy's own conversion; this side checks
// that it did, so that no layout is ever misread.
#include <fmt/format.h>

#include <cstring>

#include "bindings.hpp"
#include "swell/reference/errors.hpp"

namespace swell::python {

using validation::NpyArray;

namespace {

NpyArray::Dtype dtype_of(const py::dtype& dtype) {
  const char kind = dtype.kind();
  const auto size = dtype.itemsize();
  if (kind == 'f' && size == 2) return NpyArray::Dtype::f2;
  if (kind == 'f' && size == 4) return NpyArray::Dtype::f4;
  if (kind == 'f' && size == 8) return NpyArray::Dtype::f8;
  if (kind == 'c' && size == 8) return NpyArray::Dtype::c8;
  if (kind == 'c' && size == 16) return NpyArray::Dtype::c16;
  throw InvalidInput(fmt::format("dtype '{}': swell reads float16, float32, float64, complex64 and "
                                 "complex128 arrays",
                                 py::str(py::handle(dtype)).cast<std::string>()));
}

py::dtype numpy_dtype(NpyArray::Dtype dtype) { return py::dtype(validation::to_descr(dtype)); }

}  // namespace

NpyArray npy_of(const py::array& array) {
  const py::dtype dtype = array.dtype();
  const char order = dtype.attr("byteorder").cast<std::string>().front();
  if (!(array.flags() & py::array::c_style) || order == '>') {
    throw InternalError("swell.python: an array reached the extension that is not C-contiguous "
                        "little-endian; swell/__init__.py converts every array first");
  }
  NpyArray out;
  out.dtype = dtype_of(dtype);
  for (py::ssize_t axis = 0; axis < array.ndim(); ++axis) out.shape.push_back(std::size_t(array.shape(axis)));
  out.data.resize(std::size_t(array.nbytes()));
  if (!out.data.empty()) std::memcpy(out.data.data(), array.data(), out.data.size());
  return out;
}

py::array numpy_of(NpyArray&& array) {
  auto* bytes = new std::vector<unsigned char>(std::move(array.data));
  py::capsule owner(bytes, [](void* p) { delete static_cast<std::vector<unsigned char>*>(p); });
  std::vector<py::ssize_t> shape(array.shape.begin(), array.shape.end());
  return py::array(numpy_dtype(array.dtype), shape, bytes->data(), owner);
}

FieldArrays field_arrays_of(const py::dict& fields) {
  FieldArrays out;
  for (const auto& [key, value] : fields) {
    const auto name = key.cast<std::string>();
    const reference::Field field = reference::field_from_name(name);
    auto& frames = out[field];
    for (const auto& frame : value.cast<py::list>()) frames.push_back(npy_of(frame.cast<py::array>()));
  }
  return out;
}

}  // namespace swell::python
