#include "swell/validation/checks/transform_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <random>

namespace swell::validation {
namespace {

using impls::Direction;
using impls::Kind;
using impls::Precision;
using impls::TransformSpec;

double epsilon(Precision p) {
  switch (p) {
    case Precision::f32: return std::numeric_limits<float>::epsilon();
    case Precision::f64: return std::numeric_limits<double>::epsilon();
    case Precision::f80: return std::numeric_limits<long double>::epsilon();
  }
  return 0;
}

std::size_t reals_in(const TransformSpec& s) {
  return s.howmany * s.input_elements() * (s.input_is_complex() ? 2 : 1);
}
std::size_t reals_out(const TransformSpec& s) {
  return s.howmany * s.output_elements() * (s.output_is_complex() ? 2 : 1);
}

// Uniform in [−1, 1) from the top 53 bits of a 64-bit Mersenne twister: reproducible on every
// platform (std::uniform_real_distribution's algorithm is not fixed by the standard).
class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : engine_(seed) {}
  double operator()() { return 2.0 * ((engine_() >> 11) * 0x1.0p-53) - 1.0; }

 private:
  std::mt19937_64 engine_;
};

template <typename T>
std::vector<T> to(const std::vector<long double>& v) {
  return std::vector<T>(v.begin(), v.end());
}

template <typename T>
std::vector<long double> run_backend(const impls::Backend& backend, const TransformSpec& spec,
                                     const std::vector<long double>& input) {
  const auto plan = backend.plan(spec);
  std::vector<T> in = to<T>(input);
  std::vector<T> out(std::max(reals_out(spec), spec.placement == impls::Placement::in_place ? in.size() : 0));
  if (spec.placement == impls::Placement::in_place) {
    plan->execute(static_cast<const void*>(in.data()), static_cast<void*>(in.data()));
    out = in;
  } else {
    plan->execute(static_cast<const void*>(in.data()), static_cast<void*>(out.data()));
  }
  out.resize(reals_out(spec));
  return std::vector<long double>(out.begin(), out.end());
}

}  // namespace

double transform_error_bound(const TransformSpec& spec) {
  const double log2n = std::log2(double(spec.nx) * spec.ny);
  return 4.0 * epsilon(spec.precision) * std::max(1.0, log2n);
}

std::vector<long double> oracle_transform(TransformSpec spec, const std::vector<long double>& input,
                                          std::string* oracle_name) {
  spec.precision = Precision::f80;
  // The naive DFT costs N·(nx + ny) long-double products: affordable to about 256².
  const double cost = double(spec.nx) * spec.ny * (spec.nx + spec.ny) * spec.howmany;
  const bool naive = cost <= 256.0 * 256.0 * 512.0;
  const auto backend = impls::make_backend(naive ? "naive" : "fftw:planner=estimate");
  if (oracle_name) *oracle_name = naive ? "naive fp80" : "fftw fp80";
  return run_backend<long double>(*backend, spec, input);
}

TransformAccuracy measure_transform_accuracy(const impls::Backend& backend, TransformSpec spec,
                                             std::uint64_t seed) {
  Uniform uniform(seed);
  std::vector<long double> input(reals_in(spec));
  // Input is drawn, then rounded to the precision under test, so backend and oracle see the
  // same numbers.
  auto round = [&](long double x) -> long double {
    switch (spec.precision) {
      case Precision::f32: return static_cast<float>(x);
      case Precision::f64: return static_cast<double>(x);
      case Precision::f80: return x;
    }
    return x;
  };
  if (spec.kind == Kind::c2r) {
    // A half spectrum that really is one: the r2c of a random real field.
    TransformSpec r2c = spec;
    r2c.kind = Kind::r2c;
    r2c.direction = Direction::forward;
    r2c.placement = impls::Placement::out_of_place;
    std::vector<long double> field(reals_in(r2c));
    for (auto& x : field) x = uniform();
    input = oracle_transform(r2c, field);
  } else {
    for (auto& x : input) x = uniform();
  }
  for (auto& x : input) x = round(x);

  TransformAccuracy result;
  result.impl = backend.name();
  result.spec = spec;
  const auto reference = oracle_transform(spec, input, &result.oracle);
  std::vector<long double> got;
  switch (spec.precision) {
    case Precision::f32: got = run_backend<float>(backend, spec, input); break;
    case Precision::f64: got = run_backend<double>(backend, spec, input); break;
    case Precision::f80: got = run_backend<long double>(backend, spec, input); break;
  }
  long double err2 = 0, ref2 = 0, err_max = 0, ref_max = 0;
  const std::size_t step = spec.output_is_complex() ? 2 : 1;
  for (std::size_t i = 0; i < got.size(); i += step) {
    const long double er = got[i] - reference[i];
    const long double ei = step == 2 ? got[i + 1] - reference[i + 1] : 0;
    const long double rr = reference[i], ri = step == 2 ? reference[i + 1] : 0;
    err2 += er * er + ei * ei;
    ref2 += rr * rr + ri * ri;
    err_max = std::max(err_max, std::sqrt(er * er + ei * ei));
    ref_max = std::max(ref_max, std::sqrt(rr * rr + ri * ri));
  }
  result.rel_l2 = double(std::sqrt(err2 / ref2));
  result.rel_linf = double(err_max / ref_max);
  result.bound = transform_error_bound(spec);
  result.pass = result.rel_l2 <= result.bound && result.rel_linf <= result.bound;
  return result;
}

std::vector<TransformAccuracy> run_transform_checks(const std::string& backend_name) {
  const auto backend = impls::make_backend(backend_name);
  const auto caps = backend->capabilities();
  std::vector<TransformAccuracy> results;
  if (!caps.exact) return results;  // `null` copies; there is no accuracy to judge
  std::vector<std::pair<int, int>> sizes = {{16, 16}, {64, 64}, {256, 256}};
  if (backend->name() != "naive") sizes.push_back({1024, 1024});  // naive is the oracle there
  if (caps.any_size) sizes.push_back({15, 9});
  for (Precision precision : caps.precisions) {
    if (precision == Precision::f80) continue;
    for (auto [nx, ny] : sizes) {
      for (auto [kind, direction] : {std::pair{Kind::c2c, Direction::forward},
                                     std::pair{Kind::c2c, Direction::inverse},
                                     std::pair{Kind::r2c, Direction::forward},
                                     std::pair{Kind::c2r, Direction::inverse}}) {
        TransformSpec spec;
        spec.nx = nx;
        spec.ny = ny;
        spec.kind = kind;
        spec.direction = direction;
        spec.precision = precision;
        results.push_back(measure_transform_accuracy(*backend, spec));
      }
    }
    if (backend->name() != "naive") {
      // The size the accuracy targets are quoted at: 2048², c2c inverse (the ocean's transform).
      TransformSpec spec;
      spec.nx = spec.ny = 2048;
      spec.direction = Direction::inverse;
      spec.precision = precision;
      results.push_back(measure_transform_accuracy(*backend, spec));
    }
  }
  return results;
}

std::string render_transform_table(const std::vector<TransformAccuracy>& results) {
  std::string out = fmt::format("{:<8} {:<9} {:<12} {:<11} {:>10} {:>10} {:>10}  {}\n", "backend",
                                "precision", "kind", "size", "rel_l2", "rel_linf", "bound", "verdict");
  int failed = 0;
  for (const auto& r : results) {
    failed += !r.pass;
    out += fmt::format("{:<8} {:<9} {:<12} {:<11} {:>10.2e} {:>10.2e} {:>10.2e}  {}\n", r.impl,
                       impls::to_string(r.spec.precision),
                       impls::to_string(r.spec.kind) +
                           (r.spec.kind == Kind::c2c ? (r.spec.direction == Direction::forward ? " fwd" : " inv") : ""),
                       fmt::format("{}×{}", r.spec.nx, r.spec.ny), r.rel_l2, r.rel_linf, r.bound,
                       r.pass ? "pass" : "FAIL");
  }
  out += fmt::format("{} passed, {} failed\n", results.size() - failed, failed);
  return out;
}

nlohmann::json transforms_to_json(const std::vector<TransformAccuracy>& results) {
  auto rows = nlohmann::json::array();
  for (const auto& r : results) {
    rows.push_back({{"impl", r.impl},
                    {"precision", impls::to_string(r.spec.precision)},
                    {"kind", impls::to_string(r.spec.kind)},
                    {"direction", impls::to_string(r.spec.direction)},
                    {"n", {r.spec.nx, r.spec.ny}},
                    {"rel_l2", r.rel_l2},
                    {"rel_linf", r.rel_linf},
                    {"bound", r.bound},
                    {"oracle", r.oracle},
                    {"pass", r.pass}});
  }
  return {{"transforms", rows}};
}

}  // namespace swell::validation
