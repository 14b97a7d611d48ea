// One array through one backend (npy_transform.hpp): the spec its dtype and shape ask for, the
// input refused where a transform would only spread garbage, the backend's own buffers.
#include "swell/validation/io/npy_transform.hpp"

#include <fmt/format.h>

#include <cassert>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstring>

#include "swell/reference/errors.hpp"

namespace swell::validation {
namespace {

using impls::Direction;
using impls::Kind;
using impls::Precision;

// "[1, 2]" for element 5 of a (2, 3) array.
std::string index_string(std::size_t flat, const std::vector<std::size_t>& shape) {
  std::vector<std::size_t> index(shape.size());
  for (std::size_t axis = shape.size(); axis-- > 0;) {
    index[axis] = flat % shape[axis];
    flat /= shape[axis];
  }
  std::string out = "[";
  for (std::size_t i = 0; i < index.size(); ++i) out += (i ? ", " : "") + std::to_string(index[i]);
  return out + "]";
}

// A transform spreads one NaN or Inf over the whole output, so it would come back as a wall of
// NaN with no hint of where it came from: refuse it up front and name the first bad element.
template <typename Real>
void require_finite(const NpyArray& array, const std::string& file) {
  const std::size_t per_element = array.is_complex() ? 2 : 1;
  const std::size_t count = array.data.size() / sizeof(Real);
  for (std::size_t i = 0; i < count; ++i) {
    Real x;
    std::memcpy(&x, array.data.data() + i * sizeof(Real), sizeof(Real));
    if (std::isfinite(x)) continue;
    const std::size_t element = i / per_element;
    const std::string part = per_element == 1 ? "" : (i % 2 == 0 ? " (real part)" : " (imaginary part)");
    throw InvalidInput(fmt::format("{}: element {} (flat index {}) is {}{}; swell fft needs finite "
                                   "input", file, index_string(element, array.shape), element,
                                   std::isnan(x) ? "NaN" : (x > 0 ? "+Inf" : "-Inf"), part));
  }
}

int as_size(std::size_t n, const std::string& what) {
  if (n < 1 || n > static_cast<std::size_t>(INT_MAX)) {
    throw InvalidInput(fmt::format("{} must be 1…{} (got {})", what, INT_MAX, n));
  }
  return static_cast<int>(n);
}

// What the request and the input's dtype and shape ask for.
impls::TransformSpec spec_of(const NpyArray& input, const std::string& source,
                             const ArrayTransformRequest& request) {
  const std::string descr = to_descr(input.dtype);
  const std::size_t rank = input.shape.size();
  if (rank != 1 && rank != 2) {
    throw InvalidInput(fmt::format("{}: shape {} has rank {}; swell fft transforms 1-D (n) and "
                                   "2-D (rows, cols) arrays", source, shape_string(input.shape), rank));
  }
  const std::size_t rows = rank == 2 ? input.shape[0] : 1;
  const std::size_t cols = input.shape.back();
  const std::string shape_text = shape_string(input.shape);
  as_size(rows, source + ": rows of " + shape_text);
  as_size(cols, source + ": columns of " + shape_text);

  impls::TransformSpec spec;
  spec.ny = static_cast<int>(rows);
  if (input.dtype == NpyArray::Dtype::f2) {
    throw InvalidInput(fmt::format("{}: '<f2' (float16): swell fft transforms float32 and float64 "
                                   "arrays (convert with a.astype('<f4'))", source));
  }
  spec.precision = input.dtype == NpyArray::Dtype::f4 || input.dtype == NpyArray::Dtype::c8
                       ? Precision::f32
                       : Precision::f64;
  if (request.nx && !request.c2r) {
    throw InvalidInput("--nx applies only to --c2r (c2c and r2c take their size from the input's "
                       "shape)");
  }
  if (!input.is_complex()) {
    if (request.c2r) {
      throw InvalidInput(fmt::format("{}: --c2r needs a complex half spectrum ('<c8' or '<c16'), "
                                     "the file holds real '{}'", source, descr));
    }
    if (request.inverse) {
      throw InvalidInput(fmt::format("{}: --inverse needs complex input ('<c8' or '<c16'), the "
                                     "file holds real '{}' (a real input's transform is r2c, "
                                     "forward only; --c2r inverts a half spectrum)", source, descr));
    }
    spec.kind = Kind::r2c;
    spec.direction = Direction::forward;
    spec.nx = static_cast<int>(cols);
  } else if (request.c2r) {
    // c2r is an inverse by definition, so inverse alongside it is redundant, not a conflict.
    spec.kind = Kind::c2r;
    spec.direction = Direction::inverse;
    const std::size_t m = cols;
    if (request.nx) {
      const int nx = *request.nx;
      if (nx < 1 || static_cast<std::size_t>(nx / 2 + 1) != m) {
        throw InvalidInput(fmt::format("--nx {} does not fit a half spectrum of {} columns: nx/2+1 "
                                       "must equal {} (nx = {} or {})", nx, m, m, 2 * (m - 1),
                                       2 * m - 1));
      }
      spec.nx = nx;
    } else {
      if (m < 2) {
        throw InvalidInput(fmt::format("{}: a half spectrum of 1 column is the spectrum of nx = 1; "
                                       "say --nx 1", source));
      }
      spec.nx = as_size(2 * (m - 1), "nx = 2(m−1)");
    }
  } else {
    spec.kind = Kind::c2c;
    spec.direction = request.inverse ? Direction::inverse : Direction::forward;
    spec.nx = static_cast<int>(cols);
  }
  if (spec.precision == Precision::f32) {
    require_finite<float>(input, source);
  } else {
    require_finite<double>(input, source);
  }
  return spec;
}

}  // namespace

ArrayTransformResult transform_array(impls::Backend& backend, const NpyArray& input,
                                     const std::string& source,
                                     const ArrayTransformRequest& request) {
  ArrayTransformResult result;
  result.spec = spec_of(input, source, request);
  const auto& spec = result.spec;
  // UnsupportedTransform (an InvalidInput) names the backend, the size and the rule.
  const auto plan = backend.plan(spec);
  assert(input.data.size() == spec.input_bytes());  // the spec was derived from the shape
  // Backend buffers, so that a device-resident backend is driven the way it runs for real.
  auto in_buffer = backend.allocate(spec.input_bytes());
  auto out_buffer = backend.allocate(spec.output_bytes());
  in_buffer->upload(input.data.data(), input.data.size());
  const auto start = std::chrono::steady_clock::now();
  plan->execute(*in_buffer, *out_buffer);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  NpyArray& output = result.output;
  output.shape = input.shape;
  switch (spec.kind) {
    case Kind::c2c:
      output.dtype = input.dtype;
      break;
    case Kind::r2c:
      output.dtype = spec.precision == Precision::f32 ? NpyArray::Dtype::c8 : NpyArray::Dtype::c16;
      output.shape.back() = static_cast<std::size_t>(spec.nx / 2 + 1);
      break;
    case Kind::c2r:
      output.dtype = spec.precision == Precision::f32 ? NpyArray::Dtype::f4 : NpyArray::Dtype::f8;
      output.shape.back() = static_cast<std::size_t>(spec.nx);
      break;
  }
  output.data.resize(spec.output_bytes());
  out_buffer->download(output.data.data(), output.data.size());
  result.exact = backend.capabilities().exact;
  return result;
}

}  // namespace swell::validation
