// swell fft --impl NAME --in X.npy --out Y.npy [--inverse] [--c2r] [--nx N] [--json FILE|-]
// Transforms one .npy array with one backend, unnormalized as FFTW (docs/conventions.md
// §Transforms). A 2-D array (rows, cols) is one transform of nx = cols, ny = rows; a 1-D array of
// length n is nx = n, ny = 1.
//   complex input (c8 → fp32, c16 → fp64): c2c, forward or --inverse; same dtype and shape out
//   real input (f4, f8): r2c forward; out complex (…, nx/2+1)
//   --c2r: complex half spectrum (…, m) → real (…, nx) with nx = 2(m−1) or --nx (nx/2+1 = m)
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/io/npy.hpp"
#include "swell/validation/io/npy_transform.hpp"

namespace swell::cli {
namespace {

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

int run_fft(const FftOptions& o) {
  auto backend = impls::make_backend(o.impl);  // unknown names list the valid ones
  validation::ArrayTransformRequest request;
  request.inverse = o.inverse;
  request.c2r = o.c2r;
  if (o.nx_option->count()) request.nx = o.nx;
  const auto result = validation::transform_array(*backend, validation::read_npy(o.in), o.in, request);
  const auto& spec = result.spec;
  const auto& output = result.output;
  const double seconds = result.seconds;
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
  if (!result.exact) {
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
