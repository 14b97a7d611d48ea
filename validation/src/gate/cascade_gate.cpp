// A cascade set judged (docs/gate.md §10): every cascade and the sum as surfaces of their own,
// the set's checks across cascades, one family-wise α over all.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <memory>
#include <optional>

#include "gate/judge.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/checks/cascade_checks.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "swell/validation/gate/gate.hpp"

namespace swell::validation {

using namespace gate_path;

namespace {

// The surfaces of a set that have frames: each cascade's (null when the case gives none) and
// the sum's (null when none). Every surface streams its frames (io/frame_source.hpp).
GateReport judge_cascades(const CaseFile& case_file,
                          const std::vector<const FrameSource*>& cascades,
                          const FrameSource* sum,
                          const GateOptions& options,
                          Clock::time_point start) {
  options.validate();
  const bool summed_set = reference::is_summed(case_file.relation);
  std::vector<std::size_t> given;
  for (std::size_t c = 0; c < cascades.size(); ++c) {
    if (cascades[c]) given.push_back(c);
  }
  std::optional<reference::OceanCase> summed;
  if (sum) {
    std::string why;
    summed = case_file.summed_case(&why);
    if (!summed) throw InvalidInput("[sum]: the cascades cannot be summed on one grid: " + why);
  }
  if (given.empty() && !sum) {
    throw InvalidInput("the cascade set names no frames: give files and channels in each "
                       "[[cascade]] table, or the summed surface's in [sum]");
  }
  // One family-wise α over every statistical check of every surface (Bonferroni): each
  // cascade's ordinary ones and its band.missing, the set's energy and independence, and the
  // sum's.
  const bool free = case_file.scale == SpectrumScale::free;
  int statistical = 0;
  for (auto c : given) {
    statistical += statistical_check_count(case_file.scale, cascades[c]->size());
    if (summed_set) ++statistical;
  }
  const bool set_checks = given.size() >= 2;
  if (set_checks && summed_set) statistical += free ? 1 : 2;
  if (sum) statistical += statistical_check_count(case_file.scale, sum->size()) + 1;
  const double alpha_per_check = options.alpha / double(std::max(1, statistical));

  GateReport report;
  report.subject = fmt::format("{} set of {} cascades: {}", to_string(case_file.relation),
                               case_file.cascades.size(), case_file.ocean.describe());
  report.alpha = options.alpha;
  report.alpha_per_check = alpha_per_check;
  report.statistical_checks = statistical;
  std::vector<std::string> samples;
  // Judges one surface; its results, named "<name>.<check>", are returned for the caller to
  // place, its skipped checks go to the report.
  auto judge_surface = [&](const std::string& name, const CaseFile& surface,
                           const FrameSource& frames) {
    options.report_progress(fmt::format("judging {}…", name));
    GateReport part = judge(surface, frames,
                            expected_travelling_power(surface.ocean, options.resolved_threads()),
                            options, start, alpha_per_check);
    for (auto& result : part.results) result.check = name + "." + result.check;
    for (const auto& note : part.notes) report.notes.push_back(name + ": " + note);
    for (auto& entry : part.skipped) {
      entry.check = name + "." + entry.check;
      report.skipped.push_back(std::move(entry));
    }
    if (report.frames == 0) {
      report.frames = part.frames;
      report.nx = part.nx;
      report.ny = part.ny;
      report.fields = part.fields;
      report.fitted_scale = part.fitted_scale;
    }
    report.unit_roundoff = std::max(report.unit_roundoff, part.unit_roundoff);
    report.storage_roundoff = std::max(report.storage_roundoff, part.storage_roundoff);
    samples.push_back(fmt::format("{} {}", name, part.samples));
    return std::move(part.results);
  };
  // Each surface's results together: cascade 0's (its band checks after its ordinary ones),
  // cascade 1's, …, the set's, the sum's.
  auto append = [&](std::vector<CheckResult>& results) {
    for (auto& result : results) report.results.push_back(std::move(result));
  };
  std::vector<CascadeView> views;
  std::vector<reference::OceanCase> oceans(cascades.size());
  for (auto c : given) oceans[c] = case_file.cascade_case(c);
  std::vector<std::vector<CheckResult>> ordinary(cascades.size());
  for (auto c : given) {
    const std::string name = fmt::format("cascade{}", c);
    ordinary[c] = judge_surface(name, surface_case_file(case_file, oceans[c], case_file.cascades[c].input),
                                *cascades[c]);
    views.push_back({int(c), &oceans[c], cascades[c]});
  }
  CascadeSetResults set_results;
  if (!views.empty()) {
    options.report_progress("judging the set…");
    CascadeSetOptions set_options;
    set_options.relation = case_file.relation;
    set_options.alpha_per_check = alpha_per_check;
    set_options.free_scale = free;
    set_options.threads = options.resolved_threads();
    set_results = run_cascade_set_checks(views, case_file.members(), set_options);
  }
  for (std::size_t v = 0; v < views.size(); ++v) {
    append(ordinary[std::size_t(views[v].index)]);
    if (v < set_results.bands.size()) append(set_results.bands[v]);
  }
  // An additive set's bands are judged from the case alone, whichever frames are given: a set
  // whose bands overlap or leave a gap is judged, and fails here naming every range.
  if (case_file.relation == reference::CascadeRelation::additive &&
      case_file.cascades.size() >= 2) {
    report.results.push_back(check_band_sharing(case_file.ocean, case_file.members()));
  }
  append(set_results.set);
  if (!set_checks && !given.empty() && case_file.cascades.size() >= 2) {
    report.skipped.push_back(
        {"cascades", SkipReason::too_few_cascades, "needs the frames of two or more cascades"});
  }
  if (sum) {
    auto results = judge_surface("sum", surface_case_file(case_file, *summed, case_file.sum), *sum);
    append(results);
    auto bands = check_summed_bands(*summed, *sum, alpha_per_check);
    append(bands);
  }
  report.samples = fmt::format("{}", fmt::join(samples, ", "));
  report.seconds = seconds_since(start);
  return report;
}

}  // namespace

GateReport run_cascade_gate(const CaseFile& case_file,
                            const std::vector<reference::FrameSequence>& cascades,
                            const reference::FrameSequence* sum, const GateOptions& options) {
  if (cascades.size() != case_file.cascades.size()) {
    throw InvalidInput(fmt::format("the set has {} cascades; frames were given for {}",
                                   case_file.cascades.size(), cascades.size()));
  }
  std::vector<std::unique_ptr<MemoryFrameSource>> sources;
  std::vector<const FrameSource*> given(cascades.size(), nullptr);
  for (std::size_t c = 0; c < cascades.size(); ++c) {
    if (cascades[c].frames.empty()) continue;
    sources.push_back(std::make_unique<MemoryFrameSource>(cascades[c]));
    given[c] = sources.back().get();
  }
  std::optional<MemoryFrameSource> summed;
  if (sum) summed.emplace(*sum);
  return judge_cascades(case_file, given, summed ? &*summed : nullptr, options, Clock::now());
}

namespace gate_path {

GateReport read_and_judge_cascades(const CaseFile& case_file, const GateOptions& options,
                                   Clock::time_point start) {
  const int threads = options.resolved_threads();
  if (!options.input_pattern.empty()) {
    throw InvalidInput("--input replaces a single surface's [input] files; a cascade set names "
                       "each cascade's frames in its [[cascade]] table and the sum's in [sum]");
  }
  // Each surface's memory (its analysis, judged one surface at a time) and the set checks'
  // sums over every cascade's wave vectors, whatever the frame counts; then each surface's
  // files, opened to stream (frame 0 read now, the rest as they are judged).
  require_cascade_set_memory(case_file, threads);
  std::vector<std::unique_ptr<FileFrameSource>> sources;
  std::vector<const FrameSource*> all(case_file.cascades.size(), nullptr);
  auto open_surface = [&](const reference::OceanCase& ocean, const InputSpec& input) {
    const CaseFile surface = surface_case_file(case_file, ocean, input);
    require_streamed_gate_memory(ocean, input.channels.size(), threads);
    reference::require_valid_sampling(ocean, reference::kFloat64);
    sources.push_back(std::make_unique<FileFrameSource>(surface, ""));
    return sources.back().get();
  };
  for (std::size_t c = 0; c < case_file.cascades.size(); ++c) {
    if (case_file.cascades[c].input.files.empty()) continue;
    all[c] = open_surface(case_file.cascade_case(c), case_file.cascades[c].input);
  }
  const FrameSource* sum = nullptr;
  if (!case_file.sum.files.empty()) {
    std::string why;
    const auto summed = case_file.summed_case(&why);
    if (!summed) throw InvalidInput("[sum]: the cascades cannot be summed on one grid: " + why);
    sum = open_surface(*summed, case_file.sum);
  }
  options.report_progress(fmt::format("reading and judging {} surface{}, one frame at a time…",
                                      sources.size(), sources.size() == 1 ? "" : "s"));
  GateReport report = judge_cascades(case_file, all, sum, options, start);
  report.case_path = case_file.origin.string();
  double reading = 0;
  for (const auto& source : sources) reading += source->reading_seconds();
  report.read_seconds = reading;
  return report;
}

}  // namespace gate_path
}  // namespace swell::validation
