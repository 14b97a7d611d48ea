#pragma once
// NumPy .npy files: the exchange format of `swell fft` (and of anything that hands arrays to
// swell from Python). Format spec: numpy.lib.format (NEP 1).
//
//   "\x93NUMPY" major minor  header_len (u16 LE for 1.0, u32 LE for 2.0 and 3.0)
//   header: a Python dict literal {'descr': '<f8', 'fortran_order': False, 'shape': (3,), }
//           padded with spaces and ended by '\n' so that the data starts on a 64-byte boundary
//   data:   the elements in C order, raw little-endian bytes
//
// Supported element types are the four the transforms use, '<f4', '<f8', '<c8', '<c16', and
// '<f2' (float16: half frames, read only).
// Fortran-ordered files (fortran_order: True) are read and rearranged into C order; swell writes
// C order. Anything else — big-endian data, other dtypes, malformed or truncated files —
// throws swell::InvalidInput whose message starts with the file name and names the problem.
// Reading is bounds-checked throughout: a corrupt header never makes the reader allocate or read
// more than the file holds.
#include <bit>
#include <complex>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <iosfwd>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "swell/reference/errors.hpp"

namespace swell::validation {

// The bytes of an .npy file are little-endian; swell keeps them as raw bytes and reinterprets
// them in place, which is only right on a little-endian machine (every platform swell targets).
static_assert(std::endian::native == std::endian::little,
              "npy I/O reinterprets little-endian bytes in place");

struct NpyArray {
  enum class Dtype { f2, f4, f8, c8, c16 };  // float16, float32, float64, complex64, complex128

  Dtype dtype = Dtype::f8;
  std::vector<std::size_t> shape;      // C order; empty for a 0-d (scalar) array
  std::vector<unsigned char> data;     // elements() · itemsize() raw little-endian bytes

  std::size_t elements() const;        // product of shape (1 for rank 0)
  std::size_t itemsize() const;        // bytes per element: 2, 4, 8, 8, 16
  bool is_complex() const { return dtype == Dtype::c8 || dtype == Dtype::c16; }

  // A typed view of the data: T is float, double, std::complex<float> or std::complex<double>
  // and must match dtype (else InvalidInput).
  template <typename T>
  std::vector<T> values() const;
  template <typename T>
  static NpyArray from_values(std::vector<std::size_t> shape, std::span<const T> values);
  template <typename T>
  static NpyArray from_values(std::vector<std::size_t> shape, const std::vector<T>& values) {
    return from_values(std::move(shape), std::span<const T>(values));
  }
};

// The values of a float16 array ('<f2'), decoded exactly (io/half.hpp).
std::vector<double> half_values(const NpyArray& array);
std::size_t itemsize(NpyArray::Dtype dtype);
std::string to_descr(NpyArray::Dtype dtype);  // "<f2", "<f4", "<f8", "<c8", "<c16"
std::string shape_string(const std::vector<std::size_t>& shape);  // "(3,)", "(2, 3)", "()"

template <typename T>
constexpr NpyArray::Dtype npy_dtype_of() {
  if constexpr (std::is_same_v<T, float>) return NpyArray::Dtype::f4;
  else if constexpr (std::is_same_v<T, double>) return NpyArray::Dtype::f8;
  else if constexpr (std::is_same_v<T, std::complex<float>>) return NpyArray::Dtype::c8;
  else {
    static_assert(std::is_same_v<T, std::complex<double>>,
                  "npy element types: float, double, std::complex<float>, std::complex<double>");
    return NpyArray::Dtype::c16;
  }
}

// Reads format versions 1.0, 2.0 and 3.0, any rank. Throws InvalidInput "<path>: <problem>".
NpyArray read_npy(const std::filesystem::path& path);
// The same from a seekable binary stream whose whole content, start to end, is one .npy file (an
// in-memory buffer, a fuzzer's bytes); `name` stands for the file in the messages.
NpyArray read_npy(std::istream& in, const std::filesystem::path& name);

// The header bytes numpy.save writes for this array (magic through the final '\n'), byte for
// byte as numpy ≥ 1.24 does it. version 0 picks the oldest that fits, as numpy: 1.0 unless the
// header exceeds 65535 bytes, then 2.0; 1 or 2 forces that version (InvalidInput if it cannot
// hold the header).
std::vector<unsigned char> npy_header(NpyArray::Dtype dtype, const std::vector<std::size_t>& shape,
                                      int major_version = 0);

// Writes the header and the data. Throws InvalidInput "<path>: …" when data.size() disagrees
// with the shape or the file cannot be written.
void write_npy(const std::filesystem::path& path, const NpyArray& array, int major_version = 0);

// ------------------------------------------------------------------ templates

template <typename T>
std::vector<T> NpyArray::values() const {
  if (dtype != npy_dtype_of<T>()) {
    throw InvalidInput("npy array holds '" + to_descr(dtype) + "', asked for '" +
                       to_descr(npy_dtype_of<T>()) + "'");
  }
  if (data.size() != elements() * sizeof(T)) {
    throw InvalidInput("npy array of shape " + shape_string(shape) + " holds " +
                       std::to_string(data.size()) + " bytes, expected " +
                       std::to_string(elements() * sizeof(T)));
  }
  std::vector<T> out(elements());
  if (!data.empty()) std::memcpy(out.data(), data.data(), data.size());
  return out;
}

template <typename T>
NpyArray NpyArray::from_values(std::vector<std::size_t> shape, std::span<const T> values) {
  NpyArray array;
  array.dtype = npy_dtype_of<T>();
  array.shape = std::move(shape);
  if (values.size() != array.elements()) {
    throw InvalidInput("npy array of shape " + shape_string(array.shape) + " needs " +
                       std::to_string(array.elements()) + " values, got " +
                       std::to_string(values.size()));
  }
  array.data.resize(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(array.data.data(), values.data(), array.data.size());
  return array;
}

}  // namespace swell::validation
