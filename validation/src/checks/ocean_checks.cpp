// The ocean checks' table and runner (ocean_checks.hpp, ocean_check_table.hpp); the analysis
// they share and one file per check are in checks/ocean/.
#include "swell/validation/checks/ocean_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <thread>
#include <optional>

#include "checks/ocean/analysis.hpp"
#include "common/parallel_tasks.hpp"
#include "swell/validation/checks/ocean_check_table.hpp"

namespace swell::validation {

using namespace ocean_analysis;

namespace {

using CheckFunction = Results (*)(const Analysis&, OceanCheckReport&);

struct TableEntry {
  OceanCheckRow row;
  CheckFunction run;
};

// Cost ranks: what each took at 512² × 64 frames on one thread of a 2-core machine (ms):
// statistics 90, derived 85, dispersion 75, moments 75, direction 20, spectrum 17, hermitian 13,
// parseval 10, energy 5, randomness 3.
const std::vector<TableEntry>& table() {
  using enum SkipReason;
  static const std::vector<TableEntry> entries = {
      {{"hermitian", false, false, 1, "height (and imaginary parts when given)", 7, {}},
       check_hermitian},
      {{"parseval", false, false, 1, "every frame's height", 8, {}},
       check_parseval},
      {{"energy", true, true, 1, "frame 0's height", 9, {free_scale}}, check_energy},
      {{"spectrum", true, false, 1, "frame 0's height; every frame's for unexpected energy", 6, {}},
       check_spectrum},
      {{"moments", true, false, 1, "frame 0's height", 4, {free_scale, no_wave_motion}},
       check_moments},
      {{"dispersion", false, false, 1, "the heights of ≥ 3 frames at identifiable times", 3,
        {too_few_frames, unidentifiable_times, above_nyquist}},
       check_dispersion},
      {{"direction", true, false, 2, "the heights of ≥ 2 frames at identifiable times", 5,
        {too_few_frames, unidentifiable_times, too_few_wave_vectors}},
       check_direction},
      {{"randomness", true, false, 1, "the heights of ≥ 2 frames, or of one at t = 0", 10,
        {unidentifiable_times, ambiguous_phase}},
       check_randomness},
      {{"statistics", true, false, 1, "frame 0's height; every frame's for hs_steady", 1,
        {too_few_frames}},
       check_statistics},
      {{"derived", false, false, 1, "slopes, displacements or Jacobian of every frame", 2,
        {no_field}},
       check_derived},
  };
  return entries;
}

const TableEntry& entry(const std::string& name) {
  for (const auto& e : table()) {
    if (e.row.name == name) return e;
  }
  std::string valid;
  for (const auto& e : table()) valid += fmt::format("{}{}", valid.empty() ? "" : ", ", e.row.name);
  throw InvalidInput("unknown ocean check '" + name + "'; valid: " + valid);
}

bool selected(const std::vector<std::string>& checks, std::string_view name) {
  return checks.empty() || std::find(checks.begin(), checks.end(), name) != checks.end();
}

// The checks named (all when empty) on one analysis, in the table's order; with a free scale the
// fitted scale is reported first when `report_scale`.
OceanCheckReport run_on(const Analysis& analysis, const std::vector<std::string>& checks,
                        bool report_scale) {
  OceanCheckReport report;
  report.fitted_scale = analysis.scale();
  for (const auto& e : table()) {
    if (!selected(checks, e.row.name)) continue;
    for (auto& result : e.run(analysis, report)) report.results.push_back(std::move(result));
  }
  if (analysis.options().free_scale && report_scale) {
    CheckResult scale;
    scale.check = std::string(kFittedScaleCheck);
    scale.subject = analysis.subject();
    scale.measured = analysis.scale();
    scale.expected = 1;
    scale.criterion = "reported, not judged (free scale)";
    scale.passed = true;
    scale.reason = fmt::format("the engine's spectrum is {:.4g}× the case's (Hs × {:.4g})",
                               analysis.scale(), std::sqrt(analysis.scale()));
    report.results.insert(report.results.begin(), scale);
  }
  return report;
}

}  // namespace

const std::vector<OceanCheckRow>& ocean_check_table() {
  static const std::vector<OceanCheckRow> rows = [] {
    std::vector<OceanCheckRow> out;
    for (const auto& e : table()) out.push_back(e.row);
    return out;
  }();
  return rows;
}

std::vector<std::string_view> statistical_ocean_checks(bool free_scale, std::size_t frames) {
  std::vector<std::string_view> out;
  for (const auto& row : ocean_check_table()) {
    if (!row.statistical || (row.needs_absolute_scale && free_scale)) continue;
    if (frames < row.statistical_frames) continue;
    out.push_back(row.name);
  }
  return out;
}

std::vector<std::string> ocean_check_names() {
  std::vector<std::string> names;
  for (const auto& row : ocean_check_table()) names.emplace_back(row.name);
  return names;
}

std::vector<OceanCheckGroup> ocean_check_groups_longest_first() {
  std::vector<const OceanCheckRow*> rows;
  for (const auto& row : ocean_check_table()) rows.push_back(&row);
  std::stable_sort(rows.begin(), rows.end(), [](const OceanCheckRow* x, const OceanCheckRow* y) {
    return x->cost_rank < y->cost_rank;
  });
  std::vector<OceanCheckGroup> groups;
  for (const auto* row : rows) groups.push_back({{std::string(row->name)}});
  return groups;
}

std::size_t ocean_check_position(const std::string& check) {
  const std::string head = check.substr(0, check.find_first_of(".:"));
  const auto& rows = ocean_check_table();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].name == head) return i;
  }
  return rows.size();
}

void require_judgeable_rounding(const OceanCase& ocean_case, double unit_roundoff,
                                double mean_square_height) {
  const auto mu = expected_periodogram(*ocean_case.directional_spectrum(), ocean_case.sampling());
  const double floor = resolution_floor(unit_roundoff, mean_square_height, mu.size());
  if (std::none_of(mu.begin(), mu.end(), [&](double m) { return m > 0 && m >= floor; })) {
    throw_rounding_hides_every_wave(unit_roundoff, ocean_case);
  }
}

std::vector<double> expected_travelling_power(const OceanCase& ocean_case, int threads) {
  return expected_travelling_power(*ocean_case.directional_spectrum(), ocean_case.sampling(),
                                   threads);
}

OceanCheckReport run_ocean_checks(const OceanCase& ocean_case, const FrameSequence& frames,
                                  const OceanCheckOptions& options,
                                  const std::vector<std::string>& checks) {
  for (const auto& name : checks) entry(name);
  const MemoryFrameSource source(frames);
  return run_on(Analysis(ocean_case, source, options, expected_travelling_power(ocean_case)), checks, true);
}

std::vector<OceanCheckReport> run_ocean_check_groups(const OceanCase& ocean_case,
                                                     const FrameSequence& frames,
                                                     const OceanCheckOptions& options,
                                                     const std::vector<OceanCheckGroup>& groups,
                                                     std::vector<double> travelling_power,
                                                     int threads) {
  const MemoryFrameSource source(frames);
  return run_ocean_check_groups(ocean_case, source, options, groups, std::move(travelling_power), threads);
}

std::vector<OceanCheckReport> run_ocean_check_groups(const OceanCase& ocean_case,
                                                     const FrameSource& frames,
                                                     const OceanCheckOptions& options,
                                                     const std::vector<OceanCheckGroup>& groups,
                                                     std::vector<double> travelling_power,
                                                     int threads, const BesideChecks& beside) {
  for (const auto& group : groups) {
    for (const auto& name : group.checks) entry(name);
  }
  auto any_group_reads = [&](const char* name) {
    return std::any_of(groups.begin(), groups.end(),
                       [&](const OceanCheckGroup& g) { return selected(g.checks, name); });
  };
  // One analysis of the surface for every group. Its passes over the frames run first, on every
  // thread: the checks then only read what they gathered. Frames whose files turn out, once
  // all are read, to be stored in another precision than frame 0 said (a float frame among
  // halves) are analysed again in the precision of them all.
  std::optional<Analysis> analysis;
  // `beside` runs on a thread of its own through the passes (which leave the cores idle while
  // frames are decoded) once the analysis has taken the frames; with one thread, before the
  // checks. It reads the analysis' τ, μ and half plane, so it ends before the analysis does,
  // whatever is thrown.
  std::thread beside_thread;
  std::exception_ptr beside_error;
  struct JoinBeside {
    std::thread& thread;
    ~JoinBeside() {
      if (thread.joinable()) thread.join();
    }
  } join_beside_on_exit{beside_thread};
  auto run_beside = [&] {
    try {
      if (options.free_scale) {
        beside(analysis->precision(), nullptr);
      } else {
        const CaseSamples samples{analysis->travelling_power(), analysis->mu(), analysis->half_plane()};
        beside(analysis->precision(), &samples);
      }
    } catch (...) {
      beside_error = std::current_exception();
    }
  };
  for (;;) {
    const bool settled = frames.precision_final();
    // τ is the case's (the caller's contract), so a second analysis evaluates it again rather
    // than keep a copy of it through the first's pass.
    if (travelling_power.empty()) travelling_power = expected_travelling_power(ocean_case, threads);
    analysis.emplace(ocean_case, frames, options, std::move(travelling_power), threads);
    travelling_power.clear();
    if (beside && threads > 1) beside_thread = std::thread(run_beside);
    analysis->pass();
    if (beside_thread.joinable() && !(settled || frames.precision() == analysis->precision())) {
      beside_thread.join();  // made again with the next analysis, in the precision of every frame
      beside_error = nullptr;
    }
    if (settled || frames.precision() == analysis->precision()) break;
  }
  if (beside && threads <= 1) run_beside();
  if (any_group_reads("dispersion") && analysis->frame_count() >= 3) analysis->dispersion_pass();
  std::vector<OceanCheckReport> parts(groups.size());
  std::exception_ptr groups_error;
  try {
    detail::run_tasks(groups.size(), threads, [&](std::size_t g) {
      parts[g] = run_on(*analysis, groups[g].checks, g == 0);
    });
  } catch (...) {
    groups_error = std::current_exception();
  }
  if (beside_thread.joinable()) beside_thread.join();
  if (beside_error) std::rethrow_exception(beside_error);
  if (groups_error) std::rethrow_exception(groups_error);
  return parts;
}

}  // namespace swell::validation
