// swell fft --impl NAME --in X.npy --out Y.npy [--inverse] [--c2r] [--nx N] [--json FILE|-]
// Transforms one .npy array with one backend, unnormalized as FFTW (docs/conventions.md
// §Transforms). A 2-D array (rows, cols) is one transform of nx = cols, ny = rows; a 1-D array of
// length n is nx = n, ny = 1.
//   complex input (c8 → fp32, c16 → fp64): c2c, forward or --inverse; same dtype and shape out
//   real input (f4, f8): r2c forward; out complex (…, nx/2+1)
//   --c2r: complex half spectrum (…, m) → real (…, nx) with nx = 2(m−1) or --nx (nx/2+1 = m)
#include <fmt/format.h>

#include <cassert>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/io/npy.hpp"

namespace swell::cli {
namespace {

using impls::Direction;
using impls::Kind;
using impls::Precision;
using validation::NpyArray;

struct FftOptions {
  std::string impl;
  std::string in;
  std::string out;
  bool inverse = false;
  bool c2r = false;
  int nx = 0;
  CLI::Option* nx_option = nullptr;
  std::string json;
};

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

int run_fft(const FftOptions& o) {
  auto backend = impls::make_backend(o.impl);  // unknown names list the valid ones
  const NpyArray input = validation::read_npy(o.in);
  const std::string descr = validation::to_descr(input.dtype);
  const std::size_t rank = input.shape.size();
  if (rank != 1 && rank != 2) {
    throw InvalidInput(fmt::format("{}: shape {} has rank {}; swell fft transforms 1-D (n) and "
                                   "2-D (rows, cols) arrays", o.in,
                                   validation::shape_string(input.shape), rank));
  }
  const std::size_t rows = rank == 2 ? input.shape[0] : 1;
  const std::size_t cols = input.shape.back();
  const std::string shape_text = validation::shape_string(input.shape);
  as_size(rows, o.in + ": rows of " + shape_text);
  as_size(cols, o.in + ": columns of " + shape_text);

  // What the flags and the input's dtype ask for.
  impls::TransformSpec spec;
  spec.ny = static_cast<int>(rows);
  if (input.dtype == NpyArray::Dtype::f2) {
    throw InvalidInput(fmt::format("{}: '<f2' (float16): swell fft transforms float32 and float64 "
                                   "arrays (convert with a.astype('<f4'))",
                                   o.in));
  }
  spec.precision = input.dtype == NpyArray::Dtype::f4 || input.dtype == NpyArray::Dtype::c8
                       ? Precision::f32
                       : Precision::f64;
  if (o.nx_option->count() && !o.c2r) {
    throw InvalidInput("--nx applies only to --c2r (c2c and r2c take their size from the input's "
                       "shape)");
  }
  if (!input.is_complex()) {
    if (o.c2r) {
      throw InvalidInput(fmt::format("{}: --c2r needs a complex half spectrum ('<c8' or '<c16'), "
                                     "the file holds real '{}'", o.in, descr));
    }
    if (o.inverse) {
      throw InvalidInput(fmt::format("{}: --inverse needs complex input ('<c8' or '<c16'), the "
                                     "file holds real '{}' (a real input's transform is r2c, "
                                     "forward only; --c2r inverts a half spectrum)", o.in, descr));
    }
    spec.kind = Kind::r2c;
    spec.direction = Direction::forward;
    spec.nx = static_cast<int>(cols);
  } else if (o.c2r) {
    // c2r is an inverse by definition, so --inverse alongside it is redundant, not a conflict.
    spec.kind = Kind::c2r;
    spec.direction = Direction::inverse;
    const std::size_t m = cols;
    if (o.nx_option->count()) {
      if (o.nx < 1 || static_cast<std::size_t>(o.nx / 2 + 1) != m) {
        throw InvalidInput(fmt::format("--nx {} does not fit a half spectrum of {} columns: nx/2+1 "
                                       "must equal {} (nx = {} or {})", o.nx, m, m, 2 * (m - 1),
                                       2 * m - 1));
      }
      spec.nx = o.nx;
    } else {
      if (m < 2) {
        throw InvalidInput(fmt::format("{}: a half spectrum of 1 column is the spectrum of nx = 1; "
                                       "say --nx 1", o.in));
      }
      spec.nx = as_size(2 * (m - 1), "nx = 2(m−1)");
    }
  } else {
    spec.kind = Kind::c2c;
    spec.direction = o.inverse ? Direction::inverse : Direction::forward;
    spec.nx = static_cast<int>(cols);
  }

  if (spec.precision == Precision::f32) {
    require_finite<float>(input, o.in);
  } else {
    require_finite<double>(input, o.in);
  }

  // UnsupportedTransform (an InvalidInput) names the backend, the size and the rule: exit 2.
  const auto plan = backend->plan(spec);
  assert(input.data.size() == spec.input_bytes());  // the spec was derived from the shape
  // Backend buffers, so that a device-resident backend is driven the way it runs for real.
  auto in_buffer = backend->allocate(spec.input_bytes());
  auto out_buffer = backend->allocate(spec.output_bytes());
  in_buffer->upload(input.data.data(), input.data.size());
  const auto start = std::chrono::steady_clock::now();
  plan->execute(*in_buffer, *out_buffer);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  NpyArray output;
  switch (spec.kind) {
    case Kind::c2c:
      output.dtype = input.dtype;
      output.shape = input.shape;
      break;
    case Kind::r2c:
      output.dtype = spec.precision == Precision::f32 ? NpyArray::Dtype::c8 : NpyArray::Dtype::c16;
      output.shape = input.shape;
      output.shape.back() = static_cast<std::size_t>(spec.nx / 2 + 1);
      break;
    case Kind::c2r:
      output.dtype = spec.precision == Precision::f32 ? NpyArray::Dtype::f4 : NpyArray::Dtype::f8;
      output.shape = input.shape;
      output.shape.back() = static_cast<std::size_t>(spec.nx);
      break;
  }
  output.data.resize(spec.output_bytes());
  out_buffer->download(output.data.data(), output.data.size());
  validation::write_npy(o.out, output);

  if (!o.json.empty()) {
    const nlohmann::json document = {{"impl", o.impl},
                                     {"kind", impls::to_string(spec.kind)},
                                     {"direction", impls::to_string(spec.direction)},
                                     {"precision", impls::to_string(spec.precision)},
                                     {"n", {spec.nx, spec.ny}},
                                     {"in", o.in},
                                     {"out", o.out},
                                     {"seconds", seconds}};
    write_json(o.json, document);
    if (o.json == "-") return 0;
  }
  fmt::print("{}: {} {} → {} {} in {:.3g} s\n", o.impl, spec.describe(), o.in, o.out,
             validation::shape_string(output.shape), seconds);
  if (!backend->capabilities().exact) {
    fmt::print("note: {} does not transform (it copies); the output is not a spectrum\n", o.impl);
  }
  return 0;
}

}  // namespace

Action add_fft_command(CLI::App& app) {
  auto o = std::make_shared<FftOptions>();
  std::string names;
  for (const auto& name : impls::backend_names()) names += (names.empty() ? "" : ", ") + name;
  app.add_option("--impl", o->impl, "transform backend (" + names + "), with options as in "
                 "fftw:planner=estimate,threads=2")->required();
  app.add_option("--in", o->in, "input .npy: '<c8'/'<c16' (c2c, --c2r) or '<f4'/'<f8' (r2c)")
      ->required();
  app.add_option("--out", o->out, "output .npy")->required();
  app.add_flag("--inverse", o->inverse, "c2c inverse (e^(+i…)) instead of forward");
  app.add_flag("--c2r", o->c2r, "complex half spectrum (…, nx/2+1) to real (…, nx)");
  o->nx_option = app.add_option("--nx", o->nx, "with --c2r: the real length nx (default 2(m−1) "
                                "for m columns; nx/2+1 must equal m)");
  app.add_option("--json", o->json, "write JSON to FILE, or - for standard output");
  app.footer("2-D arrays (rows, cols) are one nx = cols × ny = rows transform; transforms are "
             "unnormalized (inverse(forward(x)) = nx·ny·x). c8/f4 run in fp32, c16/f8 in fp64. "
             "JSON: {impl, kind, direction, precision, n: [nx, ny], in, out, seconds} with "
             "seconds the execution time (planning excluded).");
  return [o] { return run_fft(*o); };
}

}  // namespace swell::cli
