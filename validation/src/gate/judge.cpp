// One surface judged: the checks run on one analysis of its frames, at their share of α, and
// their results merged into a report in the checks' order.
#include "gate/judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/checks/ocean_check_table.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "swell/validation/gate/power.hpp"
#include "swell/validation/stats/periodogram.hpp"

namespace swell::validation::gate_path {

using reference::Field;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

int statistical_check_count(SpectrumScale scale, std::size_t frames) {
  return int(statistical_ocean_checks(scale == SpectrumScale::free, frames).size());
}

GateReport judge(const CaseFile& case_file, const reference::FrameSequence& frames,
                 std::vector<double> travelling_power,
                 const GateOptions& options, Clock::time_point start, double alpha_per_check) {
  const MemoryFrameSource source(frames);
  return judge(case_file, source, std::move(travelling_power), options, start, alpha_per_check);
}

GateReport judge(const CaseFile& case_file, const FrameSource& frames,
                 std::vector<double> travelling_power,
                 const GateOptions& options, Clock::time_point start, double alpha_per_check) {
  options.validate();
  const int threads = options.resolved_threads();
  GateReport report;
  report.subject = case_file.ocean.describe();
  report.frames = int(frames.size());
  // A lattice's N samples are reported as N×1 (one row of points in n).
  const reference::Sampling sampling = frames.sampling();
  report.nx = sampling.is_lattice() ? int(sampling.size()) : sampling.grid().nx;
  report.ny = sampling.is_lattice() ? 1 : sampling.grid().ny;
  report.samples = sampling.is_lattice() ? sampling.describe() : fmt::format("{}×{}", report.nx, report.ny);
  for (Field field : frames.fields()) report.fields.push_back(reference::field_name(field));
  report.alpha = options.alpha;
  report.statistical_checks = statistical_check_count(case_file.scale, frames.size());
  report.alpha_per_check = std::isnan(alpha_per_check)
                               ? options.alpha / double(report.statistical_checks)
                               : alpha_per_check;

  OceanCheckOptions check_options;
  check_options.alpha = report.alpha_per_check;
  check_options.free_scale = case_file.scale == SpectrumScale::free;
  // Parseval through FFTW's estimate planner, as every other analysis transform: a MEASURE plan
  // is chosen by timing, so the measured rounding changed in its last digits from run to run,
  // and its wisdom then changed the estimate plans of later gates in the process (FFTW uses
  // any wisdom it has for an estimate plan). So the gate's report is the same on every run.
  check_options.analysis_backend = kAnalysisBackend;
  check_options.progress = options.progress;
  options.report_progress(fmt::format("judging {} frame{} of {}×{}…", report.frames,
                                       report.frames == 1 ? "" : "s", report.nx, report.ny));

  // A tabulated sea: what its reader did, and how much of the table the sampling carries (the
  // rest, beyond the grid's band of |k|, is judged as absent).
  bool tabulated = false;
  const auto components = case_file.ocean.components();
  for (std::size_t i = 0; i < components.size(); ++i) {
    if (!components[i].table) continue;
    tabulated = true;
    const std::string who = components.size() > 1
                                ? fmt::format("component {} ({}): ", i, components[i].spectrum.model)
                                : components[i].spectrum.model + ": ";
    for (const auto& note : components[i].table->notes) report.notes.push_back(who + note);
  }
  if (tabulated) {
    // Σ Ψ Δk² over the samples' wave vectors (a grid's, or a lattice's N) against ∫∫ Ψ dk:
    // below 100 % where the table reaches beyond their band of |k|; a band-averaged table's
    // steps can put it a little above.
    const auto summary = reference::summarize_sampling(case_file.ocean, &travelling_power);
    const char* samples = case_file.ocean.is_lattice() ? "lattice" : "grid";
    report.notes.push_back(fmt::format(
        "the {}'s wave vectors carry {:.2f} % of the sea's m0 (Σ Ψ Δk² = {:.4g} m², ∫∫ Ψ dk = "
        "{:.4g} m²; the {}'s band of |k| is {:.3g} to {:.3g} rad/m, and what lies beyond it is "
        "judged as absent)",
        samples, 100 * summary.fraction, summary.m0_on_grid, summary.m0, samples, summary.k_min,
        summary.k_max));
  }

  // The gate's power on this case (a single surface: a cascade set shares α otherwise), in the
  // precision the frames show, on a thread of its own through the passes (ocean_checks.hpp's
  // BesideChecks).
  const bool with_power = options.power && std::isnan(alpha_per_check);
  std::string no_power;
  BesideChecks make_power;
  if (with_power) {
    make_power = [&](const FramePrecision& precision, const CaseSamples* samples) {
      // A table the case's sampling cannot support (no resolved wave) is a note, never bad
      // input: the frames are still judged. A free-scale analysis holds τ scaled: the case's
      // own is evaluated again.
      try {
        if (samples) {
          report.power = gate_power(case_file, options.alpha, precision.unit_roundoff, precision.storage_roundoff,
                                    *samples, threads);
        } else {
          report.power = gate_power(case_file, options.alpha, precision.unit_roundoff, precision.storage_roundoff,
                                    expected_travelling_power(case_file.ocean, threads), threads);
        }
      } catch (const InvalidInput& e) {
        report.power.reset();
        no_power = std::string("no power table: ") + e.what();
      }
    };
  }
  // Bad input (a grid that does not match, no height field) is thrown by the analysis.
  auto parts = run_ocean_check_groups(case_file.ocean, frames, check_options,
                                      ocean_check_groups_longest_first(),
                                      std::move(travelling_power), threads, make_power);
  // The stored precision as every frame showed it (a file source knows it once all are read).
  const FramePrecision precision = frames.precision();
  if (precision.storage_roundoff > 0) {
    report.notes.push_back(fmt::format(
        "frames stored in half precision ({}): the exact checks allow each stored value an error "
        "of one ulp ({:.3g} of itself, rounding toward zero included) on top of float32 arithmetic, "
        "and no more",
        case_file.input.precision == "half" ? "declared by [input] precision"
                                            : "their every value is a half",
        precision.storage_roundoff));
  }
  if (!no_power.empty()) report.notes.push_back(no_power);
  // Merged in the table's order, the fitted scale of a free-scale case first.
  for (auto& part : parts) {
    for (auto& result : part.results) report.results.push_back(std::move(result));
    for (auto& entry : part.skipped) report.skipped.push_back(std::move(entry));
  }
  report.fitted_scale = parts.front().fitted_scale;
  report.unit_roundoff = precision.unit_roundoff;
  report.storage_roundoff = precision.storage_roundoff;
  auto position = [](const std::string& check) {
    return check == kFittedScaleCheck ? 0 : ocean_check_position(check) + 1;
  };
  std::stable_sort(report.results.begin(), report.results.end(),
                   [&](const CheckResult& x, const CheckResult& y) {
                     return position(x.check) < position(y.check);
                   });
  std::stable_sort(report.skipped.begin(), report.skipped.end(),
                   [&](const Skipped& x, const Skipped& y) {
                     return position(x.check) < position(y.check);
                   });
  report.seconds = seconds_since(start);
  return report;
}

}  // namespace swell::validation::gate_path
