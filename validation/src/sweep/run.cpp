// One run of a sweep: a point's case synthesized at the run's seed, the statistics of its
// frames and, with --fit, the JONSWAP fit; and its row, as JSON and back.
#include "swell/validation/sweep/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "sweep/sweep_internal.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"
#include "swell/validation/results/report.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "swell/validation/stats/sample_moments.hpp"

namespace swell::validation::sweep {

using namespace detail;

namespace {

using nlohmann::json;

double number_or_nan(const json& x) { return x.is_number() ? x.get<double>() : kNaN; }

}  // namespace

namespace detail {

FrequencyMoments frequency_moments(const reference::OceanCase& ocean, const std::vector<double>& power) {
  const auto& grid = ocean.grid;
  FrequencyMoments out;
  std::map<int, std::pair<double, double>> bands;  // band → (Σ P, Σ P ω)
  const double dkx = 2 * kPi / grid.lx, dky = 2 * kPi / grid.ly;
  for (int row = 0; row < grid.ny; ++row) {
    const int wy = row <= grid.ny / 2 ? row : row - grid.ny;
    for (int i = 0; i < grid.nx; ++i) {
      const int wx = i <= grid.nx / 2 ? i : i - grid.nx;
      if (wx == 0 && wy == 0) continue;
      const double p = power[std::size_t(row) * grid.nx + i];
      const double omega = ocean.omega(std::hypot(wx * dkx, wy * dky));
      out.m[0] += p;
      out.m[1] += p * omega;
      out.m[2] += p * omega * omega;
      auto& band = bands[int(std::floor(std::log(omega) / std::log(1.04)))];
      band.first += p;
      band.second += p * omega;
    }
  }
  double peak = 0;
  for (const auto& [key, band] : bands) {
    if (band.first > peak) {
      peak = band.first;
      out.peak_omega = band.second / band.first;
    }
  }
  return out;
}

}  // namespace detail

const std::vector<std::string>& statistic_names() {
  static const std::vector<std::string> names = {"hs",       "tp",           "tm01",
                                                 "tm02",     "skewness",     "excess_kurtosis",
                                                 "foam_fraction", "min_jacobian"};
  return names;
}

RunRow run(const SweepSpec& spec, const Point& point, int replicate) {
  const auto start = std::chrono::steady_clock::now();
  RunRow row;
  row.point = point.index;
  row.replicate = replicate;
  row.seed = run_seed(spec.sweep_seed, point.index, replicate);
  reference::OceanCase ocean = point.case_file.ocean;
  ocean.seed = row.seed;
  impls::SynthesizerOptions options;
  options.backend = spec.impl;
  options.precision = spec.precision;
  const impls::Synthesizer synthesizer(ocean, options);
  const reference::FrameSequence frames = synthesizer.frames();
  const auto& grid = ocean.grid;
  const std::size_t n = std::size_t(grid.nx) * std::size_t(grid.ny);

  // Central moments of h and the Jacobian's extremes over all samples of all frames.
  long double sum = 0;
  std::size_t count = 0, folded = 0;
  double min_j = std::numeric_limits<double>::infinity();
  for (const auto& frame : frames.frames) {
    for (const double h : frame.fields.at(reference::Field::height)) sum += h;
    for (const double j : frame.fields.at(reference::Field::jacobian)) {
      min_j = std::min(min_j, j);
      folded += j < 0;
    }
    count += n;
  }
  const double mean = double(sum / (long double)count);
  stats::SampleMoments<long double> height;
  for (const auto& frame : frames.frames) {
    height.add(frame.fields.at(reference::Field::height), mean);
  }
  const long double m2 = height.variance();
  auto& s = row.statistics;
  s["hs"] = 4 * std::sqrt(double(m2));
  s["skewness"] = m2 > 0 ? double(height.skewness()) : kNaN;
  s["excess_kurtosis"] = m2 > 0 ? double(height.excess_kurtosis()) : kNaN;
  s["foam_fraction"] = double(folded) / double(count);
  s["min_jacobian"] = min_j;

  // Periods from the periodogram averaged over frames, each wave vector at ω(|k|) of the case's
  // dispersion: m_n = Σ ω^n I(k) over k ≠ 0; Tm01 = 2π m0/m1, Tm02 = 2π √(m0/m2); Tp = 2π over
  // the energy-weighted ω of the most energetic 4 % band of ω (the moments check's bins).
  std::vector<double> periodogram(n, 0.0);
  for (std::size_t f = 0; f < frames.frames.size(); ++f) {
    const auto spectrum = field_spectrum(frames.field(int(f), reference::Field::height), grid);
    for (std::size_t i = 0; i < n; ++i) periodogram[i] += std::norm(spectrum[i]);
  }
  for (double& p : periodogram) p /= double(frames.frames.size());
  const FrequencyMoments moments = frequency_moments(ocean, periodogram);
  s["tm01"] = moments.tm01();
  s["tm02"] = moments.tm02();
  s["tp"] = 2 * kPi / moments.peak_omega;

  if (spec.fit) {
    const JonswapFit fit = fit_jonswap(ocean, {frames});
    row.fitted = true;
    row.fit_converged = fit.converged;
    auto keep = [&](const char* name, const Estimate& e) {
      row.fit[name] = {e.value, e.ci95_low, e.ci95_high, e.calibrated};
    };
    keep("hs", fit.hs);
    keep("tp", fit.tp);
    keep("gamma", fit.gamma);
  }
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

json row_json(const SweepSpec& spec, const RunRow& row) {
  json parameters = json::object();
  const auto value_index = value_indices(spec, row.point);
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    const auto& variation = spec.variations[v];
    const double x = variation.numbers[value_index[v]];
    parameters[variation.name] = std::isfinite(x) ? json(x) : json(variation.labels[value_index[v]]);
  }
  json statistics = json::object();
  for (const auto& name : statistic_names()) statistics[name] = json_number(row.statistics.at(name));
  json out = {{"point", row.point}, {"replicate", row.replicate}, {"seed", row.seed},
              {"parameters", parameters}, {"statistics", statistics}};
  if (row.fitted) {
    json fit = {{"converged", row.fit_converged}};
    for (const auto& [name, value] : row.fit) {
      fit[name] = {{"value", json_number(value.value)},
                   {"ci95", {json_number(value.ci95_low), json_number(value.ci95_high)}},
                   {"calibrated", value.calibrated}};
    }
    out["fit"] = fit;
  }
  out["seconds"] = row.seconds;
  return out;
}

RunRow row_from_json(const json& o) {
  RunRow row;
  try {
    row.point = o.at("point").get<std::size_t>();
    row.replicate = o.at("replicate").get<int>();
    row.seed = o.at("seed").get<std::uint64_t>();
    for (const auto& name : statistic_names()) row.statistics[name] = number_or_nan(o.at("statistics").at(name));
    if (o.contains("fit")) {
      row.fitted = true;
      row.fit_converged = o["fit"].at("converged").get<bool>();
      for (const char* name : {"hs", "tp", "gamma"}) {
        const auto& f = o["fit"].at(name);
        row.fit[name] = {number_or_nan(f.at("value")), number_or_nan(f.at("ci95")[0]),
                         number_or_nan(f.at("ci95")[1]), f.at("calibrated").get<bool>()};
      }
    }
    row.seconds = o.at("seconds").get<double>();
  } catch (const json::exception& e) {
    throw InvalidInput(std::string("not a sweep row: ") + e.what());
  }
  return row;
}

}  // namespace swell::validation::sweep
