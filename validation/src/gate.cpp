// The gate (docs/gate.md): another engine's frames judged against its case file, with one
// family-wise false-alarm rate α shared by the statistical checks, and the verdict rendered
// for a terminal, as JSON and as JUnit XML for CI systems.
#include "swell/validation/gate.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <thread>

#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/cascade_checks.hpp"
#include "swell/validation/frame_io.hpp"
#include "swell/validation/ocean_checks.hpp"
#include "swell/validation/periodogram.hpp"
#include "swell/validation/report.hpp"

namespace swell::validation {
namespace {

using Clock = std::chrono::steady_clock;
using reference::Field;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

int resolved_threads(int threads) {
  if (threads < 0) throw InvalidInput(fmt::format("threads must be ≥ 0 (got {})", threads));
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

void report_progress(const GateOptions& options, const std::string& message) {
  if (options.progress) options.progress(message);
}

// The statistical checks run_ocean_checks will run on these frames, each at its share of α:
// energy (not with a free scale), spectrum, moments, direction (≥ 2 frames: one frame cannot
// tell k from −k) and statistics (skewness, kurtosis and amplitudes need one frame; its
// hs_steady part splits the check's own α when there are more). A check counted here that
// finds nothing to judge at run time (direction when 2ω dt ≈ 0 mod 2π for every k) only makes
// the gate more conservative.
std::vector<std::string> statistical_checks(SpectrumScale scale, std::size_t frames) {
  std::vector<std::string> checks;
  if (scale != SpectrumScale::free) checks.push_back("energy");
  checks.push_back("spectrum");
  checks.push_back("moments");
  if (frames >= 2) checks.push_back("direction");
  checks.push_back("randomness");
  checks.push_back("statistics");
  return checks;
}

// ------------------------------------------------------------------ text

std::string number(double x) {
  if (std::isnan(x)) return "—";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return fmt::format("{:.4g}", x);
}

// Display width of a UTF-8 string: code points (the symbols used here are one column each).
std::size_t width(const std::string& s) {
  return std::size_t(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

std::string pad(const std::string& s, std::size_t w) {
  return s + std::string(w > width(s) ? w - width(s) : 0, ' ');
}

bool statistical_result(const CheckResult& r) { return !std::isnan(r.alpha); }

// How the measurement is judged, in a few characters: "p 0.41 ≥ α 2.0e-04", "≤ 1.2e-13".
std::string judgement(const CheckResult& r) {
  if (r.check == "scale") return "reported";
  if (statistical_result(r)) {
    if (std::isnan(r.p_value)) {  // a set test (moments.tp): no p-value
      return fmt::format("{} at α {:.1e}", r.passed ? "in set" : "outside set", r.alpha);
    }
    return fmt::format("p {:.2g} {} α {:.1e}", r.p_value, r.p_value >= r.alpha ? "≥" : "<",
                       r.alpha);
  }
  return fmt::format("{} {:.2g}", r.passed ? "≤" : ">", r.tolerance);
}

// "dispersion: needs ≥ 3 frames (…)" → {"dispersion", "needs ≥ 3 frames (…)"}.
std::pair<std::string, std::string> split_skipped(const std::string& entry) {
  const auto colon = entry.find(": ");
  if (colon == std::string::npos) return {entry, ""};
  return {entry.substr(0, colon), entry.substr(colon + 2)};
}

std::string failed_names(const GateReport& report) {
  std::string names;
  for (const auto& r : report.results) {
    if (!r.passed) names += (names.empty() ? "" : ", ") + r.check;
  }
  return names;
}

int failed_count(const GateReport& report) {
  return int(std::count_if(report.results.begin(), report.results.end(),
                           [](const CheckResult& r) { return !r.passed; }));
}

// ------------------------------------------------------------------ XML

// Length of the well-formed UTF-8 sequence at s (1 for ASCII), 0 when malformed: a lead byte
// with its continuation bytes, no overlong form, no surrogate, nothing above U+10FFFF.
std::size_t utf8_length(const unsigned char* s, std::size_t available,
                        char32_t* code_point = nullptr) {
  const unsigned char c = s[0];
  std::size_t length = 0;
  char32_t code = 0;
  if (c < 0x80) {
    length = 1;
    code = c;
  } else if (c >= 0xC2 && c <= 0xDF) {
    length = 2;
    code = c & 0x1F;
  } else if (c >= 0xE0 && c <= 0xEF) {
    length = 3;
    code = c & 0x0F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    length = 4;
    code = c & 0x07;
  }
  if (length == 0 || length > available) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((s[k] & 0xC0) != 0x80) return 0;
    code = (code << 6) | (s[k] & 0x3F);
  }
  const char32_t smallest = length == 1 ? 0 : length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
  if (code < smallest || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  if (code_point) *code_point = code;
  return length;
}

// Valid XML 1.0 character data from any byte string: markup characters escaped, control
// characters other than tab, newline and carriage return dropped (XML 1.0 cannot hold them,
// not even as references), U+FFFE/U+FFFF dropped, and malformed UTF-8 replaced by U+FFFD.
std::string xml_escape(const std::string& text, bool in_attribute = true) {
  std::string out;
  out.reserve(text.size() + 16);
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    char32_t code = 0;
    const std::size_t length = utf8_length(s + i, n - i, &code);
    if (length == 0) {
      out += "\xEF\xBF\xBD";  // U+FFFD for the one bad byte; resynchronize on the next
      ++i;
      continue;
    }
    switch (code) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      // In attribute values as references (a parser would normalize them to spaces).
      case '\t': out += in_attribute ? "&#9;" : "\t"; break;
      case '\n': out += in_attribute ? "&#10;" : "\n"; break;
      case '\r': out += "&#13;"; break;  // else read back as a newline
      default:
        // Other C0 controls, U+FFFE and U+FFFF are not XML 1.0 characters.
        if (code >= 0x20 && code != 0xFFFE && code != 0xFFFF) out.append(text, i, length);
    }
    i += length;
  }
  return out;
}

// Valid UTF-8 of any byte string (malformed bytes → U+FFFD), for JSON, which must be UTF-8.
std::string valid_utf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const std::size_t length = utf8_length(s + i, n - i);
    if (length == 0) {
      out += "\xEF\xBF\xBD";
      ++i;
    } else {
      out.append(text, i, length);
      i += length;
    }
  }
  return out;
}

std::string attribute(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + xml_escape(value) + "\"";
}

// The failure message of a result: measured, expected and the bound (or p against α).
std::string failure_message(const CheckResult& r) {
  std::string bound;
  if (statistical_result(r)) {
    bound = std::isnan(r.p_value) ? fmt::format("set test at α = {:.3g}", r.alpha)
                                  : fmt::format("p = {:.3g} < α = {:.3g}", r.p_value, r.alpha);
  } else {
    bound = fmt::format("bound {:.3g}", r.tolerance);
  }
  return fmt::format("{}: measured {}, expected {}, {}: {}", r.check, number(r.measured),
                     number(r.expected), bound, r.reason);
}

// ------------------------------------------------------------------ reading

// What the gate keeps: the height of every frame (what every check but `derived` uses), and
// every field of the first and the last frame (the two frames `derived` compares). Every field
// of every frame is read and checked (size, finite values); the other fields of the frames
// between are then dropped, which at 512² × 64 frames × 6 fields saves 0.6 GB. `all` holds the
// heights with the other fields on its first and last frames; `ends` the first and last frames
// alone, every field (both frames, in order; one when the case has one frame).
struct GateFrames {
  reference::FrameSequence all, ends;
};

GateFrames read_gate_frames(const CaseFile& case_file, const std::string& pattern_override,
                            int threads) {
  const int count = case_file.ocean.frames;
  const bool has_height = case_file.input.channels.count(Field::height) > 0;
  GateFrames out;
  const auto keep = [&](int frame, Field field) {
    return !has_height || field == Field::height || frame == 0 || frame == count - 1;
  };
  out.all = read_frames(case_file, pattern_override, keep, threads);
  out.ends.grid = out.all.grid;
  out.ends.lattice = out.all.lattice;
  out.ends.unit_roundoff = out.all.unit_roundoff;
  out.ends.frames.push_back(out.all.frames.front());
  if (count > 1) out.ends.frames.push_back(out.all.frames.back());
  return out;
}

// ------------------------------------------------------------------ judging

// The checks run concurrently on one analysis of the frames (run_ocean_check_groups), after the
// wave series and per-wave fits they share were made on every thread; derived needs only the end
// frames. One group per check, the longest first, taken by whichever thread is free (longest
// processing time first keeps two threads within the shortest check of each other). The order
// is what they took at 512² × 64 frames on one thread of the 2-core machine (ms, 2026-12-03):
// statistics 90, derived 85, dispersion 75, moments 75, direction 20, spectrum 17, hermitian 13,
// parseval 10, energy 5, randomness 3. (Results and skipped checks are sorted into
// run_ocean_checks' order afterwards: the grouping does not change the report.)
const std::vector<OceanCheckGroup>& check_groups() {
  static const std::vector<OceanCheckGroup> groups = [] {
    const std::vector<std::string> longest_first = {
        "statistics", "derived",   "dispersion", "moments", "direction",
        "spectrum",   "hermitian", "parseval",   "energy",  "randomness"};
    std::vector<OceanCheckGroup> out;
    for (const auto& name : longest_first) out.push_back({{name}, name == "derived"});
    for (const auto& name : ocean_check_names()) {  // a check added later still runs, last
      if (std::find(longest_first.begin(), longest_first.end(), name) == longest_first.end()) {
        out.push_back({{name}, false});
      }
    }
    return out;
  }();
  return groups;
}

// Position of a result's check ("moments.tp" → moments) in the order run_ocean_checks runs them.
std::size_t check_order(const std::string& name) {
  static const auto names = ocean_check_names();
  const std::string group = name.substr(0, name.find_first_of(".:"));
  const auto it = std::find(names.begin(), names.end(), group);
  return it == names.end() ? names.size() : std::size_t(it - names.begin());
}

// `alpha_per_check`, when given (a cascade set shares α over all its surfaces), replaces
// options.alpha / (the statistical checks of these frames).
GateReport judge(const CaseFile& case_file, const reference::FrameSequence& frames,
                 const reference::FrameSequence& ends, const GateOptions& options,
                 Clock::time_point start,
                 double alpha_per_check = std::numeric_limits<double>::quiet_NaN(),
                 std::vector<double> travelling_power = {}) {
  if (!(options.alpha > 0 && options.alpha < 1)) {
    throw InvalidInput(fmt::format("alpha (the gate's family-wise false-alarm rate) must be in "
                                   "(0, 1) (got {:g})",
                                   options.alpha));
  }
  const int threads = resolved_threads(options.threads);
  GateReport report;
  report.subject = case_file.ocean.describe();
  report.frames = int(frames.frames.size());
  // A lattice's N samples are reported as N×1 (one row of points in n).
  report.nx = frames.lattice ? int(frames.sampling().size()) : frames.grid.nx;
  report.ny = frames.lattice ? 1 : frames.grid.ny;
  report.samples = frames.lattice ? frames.sampling().describe()
                                  : fmt::format("{}×{}", report.nx, report.ny);
  for (Field field : reference::kAllFields) {
    if (ends.has(field)) report.fields.push_back(reference::field_name(field));
  }
  const auto shared = statistical_checks(case_file.scale, frames.frames.size());
  report.alpha = options.alpha;
  report.statistical_checks = int(shared.size());
  report.alpha_per_check = std::isnan(alpha_per_check) ? options.alpha / double(shared.size())
                                                      : alpha_per_check;

  OceanCheckOptions check_options;
  check_options.alpha = report.alpha_per_check;
  check_options.free_scale = case_file.scale == SpectrumScale::free;
  // Parseval through FFTW's estimate planner, as every other analysis transform: a MEASURE plan
  // is chosen by timing, so the measured rounding changed in its last digits from run to run,
  // and its wisdom then changed the estimate plans of later gates in the process (FFTW uses
  // any wisdom it has for an estimate plan). The gate's report is now the same on every run.
  check_options.analysis_backend = kAnalysisBackend;
  report_progress(options, fmt::format("judging {} frame{} of {}×{}…", report.frames,
                                       report.frames == 1 ? "" : "s", report.nx, report.ny));

  // Bad input (a grid that does not match, no height field) is thrown by the analysis.
  auto parts = run_ocean_check_groups(case_file.ocean, frames, ends, check_options, check_groups(),
                                      threads, std::move(travelling_power));
  // Merged in run_ocean_checks' order; with a free scale each group reports the same fitted
  // scale (from frame 0), kept once.
  bool have_scale = false;
  for (auto& part : parts) {
    for (auto& result : part.results) {
      if (result.check == "scale") {
        if (have_scale) continue;
        have_scale = true;
      }
      report.results.push_back(std::move(result));
    }
    for (auto& entry : part.skipped) report.skipped.push_back(std::move(entry));
  }
  report.fitted_scale = parts.front().fitted_scale;
  report.unit_roundoff = frames.unit_roundoff;
  std::stable_sort(report.results.begin(), report.results.end(),
                   [](const CheckResult& x, const CheckResult& y) {
                     const bool x_scale = x.check == "scale", y_scale = y.check == "scale";
                     if (x_scale != y_scale) return x_scale;
                     return check_order(x.check) < check_order(y.check);
                   });
  std::stable_sort(report.skipped.begin(), report.skipped.end(),
                   [](const std::string& x, const std::string& y) {
                     return check_order(x) < check_order(y);
                   });
  report.seconds = seconds_since(start);
  return report;
}

// ------------------------------------------------------------------ cascade sets

// A cascade's (or the sum's) own case file: its case, its frames' input, the set's scale.
CaseFile surface_case_file(const CaseFile& set, const reference::OceanCase& ocean,
                           const InputSpec& input) {
  CaseFile out;
  out.ocean = ocean;
  out.input = input;
  out.scale = set.scale;
  out.directory = set.directory;
  return out;
}

// The surfaces of a set that have frames: each cascade's (an empty sequence when the case gives
// none) and the sum's (null when none).
GateReport judge_cascades(const CaseFile& case_file,
                          const std::vector<reference::FrameSequence>& cascades,
                          const std::vector<reference::FrameSequence>& cascade_ends,
                          const reference::FrameSequence* sum,
                          const reference::FrameSequence* sum_ends, const GateOptions& options,
                          Clock::time_point start) {
  if (!(options.alpha > 0 && options.alpha < 1)) {
    throw InvalidInput(fmt::format("alpha (the gate's family-wise false-alarm rate) must be in "
                                   "(0, 1) (got {:g})",
                                   options.alpha));
  }
  const bool additive = case_file.relation == reference::CascadeRelation::additive;
  std::vector<std::size_t> given;
  for (std::size_t c = 0; c < cascades.size(); ++c) {
    if (!cascades[c].frames.empty()) given.push_back(c);
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
    statistical += int(statistical_checks(case_file.scale, cascades[c].frames.size()).size());
    if (additive) ++statistical;
  }
  const bool set_checks = given.size() >= 2;
  if (set_checks && additive) statistical += free ? 1 : 2;
  if (sum) statistical += int(statistical_checks(case_file.scale, sum->frames.size()).size()) + 1;
  const double alpha_per_check = options.alpha / double(std::max(1, statistical));

  GateReport report;
  report.subject = fmt::format("{} set of {} cascades: {}", to_string(case_file.relation),
                               case_file.cascades.size(), case_file.ocean.describe());
  report.alpha = options.alpha;
  report.alpha_per_check = alpha_per_check;
  report.statistical_checks = statistical;
  std::vector<std::string> samples;
  auto add_surface = [&](const std::string& name, const CaseFile& surface,
                         const reference::FrameSequence& frames,
                         const reference::FrameSequence& ends) {
    report_progress(options, fmt::format("judging {}…", name));
    GateReport part = judge(surface, frames, ends, options, start, alpha_per_check);
    for (auto& result : part.results) {
      result.check = name + "." + result.check;
      report.results.push_back(std::move(result));
    }
    for (auto& entry : part.skipped) report.skipped.push_back(name + "." + entry);
    if (report.frames == 0) {
      report.frames = part.frames;
      report.nx = part.nx;
      report.ny = part.ny;
      report.fields = part.fields;
      report.fitted_scale = part.fitted_scale;
    }
    report.unit_roundoff = std::max(report.unit_roundoff, part.unit_roundoff);
    samples.push_back(fmt::format("{} {}", name, part.samples));
  };
  std::vector<CascadeView> views;
  std::vector<reference::OceanCase> oceans(cascades.size());
  for (auto c : given) oceans[c] = case_file.cascade_case(c);
  for (auto c : given) {
    const std::string name = fmt::format("cascade{}", c);
    add_surface(name, surface_case_file(case_file, oceans[c], case_file.cascades[c].input),
                cascades[c], cascade_ends[c]);
    views.push_back({int(c), &oceans[c], &cascades[c]});
  }
  if (!views.empty()) {
    report_progress(options, "judging the set…");
    CascadeSetOptions set_options;
    set_options.relation = case_file.relation;
    set_options.alpha_per_check = alpha_per_check;
    set_options.free_scale = free;
    set_options.threads = resolved_threads(options.threads);
    for (auto& result : run_cascade_set_checks(views, case_file.members(), set_options)) {
      report.results.push_back(std::move(result));
    }
  }
  if (!set_checks && !given.empty() && case_file.cascades.size() >= 2) {
    report.skipped.push_back("cascades: needs the frames of two or more cascades");
  }
  if (sum) {
    add_surface("sum", surface_case_file(case_file, *summed, case_file.sum), *sum, *sum_ends);
    for (auto& result : check_summed_bands(*summed, *sum, alpha_per_check)) {
      report.results.push_back(std::move(result));
    }
  }
  // Each surface's results together: cascade 0's (its band checks included), cascade 1's, …,
  // the set's, the sum's.
  auto group = [&](const CheckResult& r) -> std::size_t {
    const std::string head = r.check.substr(0, r.check.find('.'));
    if (head == "cascades") return case_file.cascades.size();
    if (head == "sum") return case_file.cascades.size() + 1;
    return std::size_t(std::stoul(head.substr(std::string("cascade").size())));
  };
  std::stable_sort(report.results.begin(), report.results.end(),
                   [&](const CheckResult& x, const CheckResult& y) { return group(x) < group(y); });
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
  return judge_cascades(case_file, cascades, cascades, sum, sum, options, Clock::now());
}

bool GateReport::passed() const {
  return std::all_of(results.begin(), results.end(), [](const CheckResult& r) { return r.passed; });
}

GateReport run_gate(const CaseFile& case_file, const reference::FrameSequence& frames,
                    const GateOptions& options) {
  return judge(case_file, frames, frames, options, Clock::now());
}

GateReport run_gate(const std::filesystem::path& case_path, const GateOptions& options) {
  const auto start = Clock::now();
  const int threads = resolved_threads(options.threads);
  const CaseFile case_file = read_case_file(case_path);
  if (case_file.is_cascade_set()) {
    if (!options.input_pattern.empty()) {
      throw InvalidInput("--input replaces a single surface's [input] files; a cascade set names "
                         "each cascade's frames in its [[cascade]] table and the sum's in [sum]");
    }
    std::vector<reference::FrameSequence> all(case_file.cascades.size()),
        ends(case_file.cascades.size());
    auto read_surface = [&](const reference::OceanCase& ocean, const InputSpec& input,
                            reference::FrameSequence& frames, reference::FrameSequence& end) {
      const CaseFile surface = surface_case_file(case_file, ocean, input);
      const auto sampling = ocean.sampling();
      const double bytes = double(sampling.size()) * (24.0 * ocean.frames + 96 + 64 + 24.0 * threads);
      reference::require_memory(std::uint64_t(std::min(bytes, 1.8e19)), "swell gate",
                                fmt::format("{} frames on a {}", ocean.frames, sampling.describe()));
      reference::require_valid_sampling(ocean, reference::kFloat64);
      report_progress(options, fmt::format("reading {} frame{} on a {}…", ocean.frames,
                                           ocean.frames == 1 ? "" : "s", sampling.describe()));
      GateFrames read = read_gate_frames(surface, "", threads);
      frames = std::move(read.all);
      end = std::move(read.ends);
    };
    for (std::size_t c = 0; c < case_file.cascades.size(); ++c) {
      if (case_file.cascades[c].input.files.empty()) continue;
      read_surface(case_file.cascade_case(c), case_file.cascades[c].input, all[c], ends[c]);
    }
    reference::FrameSequence sum, sum_ends;
    const bool has_sum = !case_file.sum.files.empty();
    if (has_sum) {
      std::string why;
      const auto summed = case_file.summed_case(&why);
      if (!summed) throw InvalidInput("[sum]: the cascades cannot be summed on one grid: " + why);
      read_surface(*summed, case_file.sum, sum, sum_ends);
    }
    const double reading = seconds_since(start);
    GateReport report = judge_cascades(case_file, all, ends, has_sum ? &sum : nullptr,
                                       has_sum ? &sum_ends : nullptr, options, start);
    report.case_path = case_path.string();
    report.read_seconds = reading;
    return report;
  }
  // Memory first, before anything of the grid's size is read: per sample, every frame's height
  // (8 bytes) and its two complex waves in the dispersion fit (16), the two end frames' six
  // fields (96), the analysis' spectra and expected powers (64), and one frame of float
  // channels being decoded per reading thread (24).
  const auto sampling = case_file.ocean.sampling();
  const double per_sample = 24.0 * case_file.ocean.frames + 96 + 64 + 24.0 * threads;
  const double bytes = double(sampling.size()) * per_sample;
  reference::require_memory(std::uint64_t(std::min(bytes, 1.8e19)), "swell gate",
                            fmt::format("{} frame{} on a {}", case_file.ocean.frames,
                                        case_file.ocean.frames == 1 ? "" : "s",
                                        sampling.describe()));
  // The rest of the rule before any frame is read (a case no frames can satisfy is refused as
  // such, not as a missing file); the analysis applies it again in the frames' stored format.
  // Ψ over the samples once, on every thread, for this rule and the analysis (on one thread here
  // and again in the analysis it was 5 % of the gate's CPU at 512², all of it before reading).
  std::vector<double> travelling =
      expected_travelling_power(*case_file.ocean.directional_spectrum(), sampling, threads);
  reference::require_valid_sampling(case_file.ocean, reference::kFloat64, 0, "", &travelling);
  report_progress(options,
                  fmt::format("reading {} frame{} on a {}…", case_file.ocean.frames,
                              case_file.ocean.frames == 1 ? "" : "s", sampling.describe()));
  const GateFrames frames = read_gate_frames(case_file, options.input_pattern, threads);
  const double reading = seconds_since(start);
  GateReport report = judge(case_file, frames.all, frames.ends, options, start,
                            std::numeric_limits<double>::quiet_NaN(), std::move(travelling));
  report.case_path = case_path.string();
  report.read_seconds = reading;
  return report;
}

std::string render_gate(const GateReport& report) {
  std::string out = fmt::format("swell gate: {}\n", report.subject);
  std::string fields;
  for (const auto& f : report.fields) fields += (fields.empty() ? "" : ", ") + f;
  out += fmt::format("{}{} frame{} of {}; fields: {}; unit roundoff {:.2g}\n",
                     report.case_path.empty() ? "" : "case " + report.case_path + "; ",
                     report.frames, report.frames == 1 ? "" : "s",
                     report.samples.empty() ? fmt::format("{}×{}", report.nx, report.ny)
                                            : report.samples,
                     fields.empty() ? "none" : fields, report.unit_roundoff);
  out += fmt::format("family-wise α = {:.3g}, shared by {} statistical checks: each at α = {:.3g}\n\n",
                     report.alpha, report.statistical_checks, report.alpha_per_check);

  struct Row {
    std::string verdict, check, measured, expected, judged, reason;
  };
  std::vector<Row> rows;
  for (const auto& r : report.results) {
    rows.push_back({r.passed ? "PASS" : "FAIL", r.check, number(r.measured), number(r.expected),
                    judgement(r), r.reason});
  }
  for (const auto& entry : report.skipped) {
    const auto [check, why] = split_skipped(entry);
    rows.push_back({"SKIP", check, "", "", "", why});
  }
  std::size_t w_check = 5, w_measured = 8, w_expected = 8, w_judged = 6;
  for (const auto& row : rows) {
    w_check = std::max(w_check, width(row.check));
    w_measured = std::max(w_measured, width(row.measured));
    w_expected = std::max(w_expected, width(row.expected));
    w_judged = std::max(w_judged, width(row.judged));
  }
  out += fmt::format("{}  {}  {}  {}  {}  {}\n", pad("", 4), pad("check", w_check),
                     pad("measured", w_measured), pad("expected", w_expected),
                     pad("judged", w_judged), "reason");
  for (const auto& row : rows) {
    out += fmt::format("{}  {}  {}  {}  {}  {}\n", row.verdict, pad(row.check, w_check),
                       pad(row.measured, w_measured), pad(row.expected, w_expected),
                       pad(row.judged, w_judged), row.reason);
  }
  const int failed = failed_count(report);
  const int total = int(report.results.size());
  std::string skipped = report.skipped.empty()
                            ? std::string()
                            : fmt::format(", {} skipped", report.skipped.size());
  if (failed == 0) {
    out += fmt::format("\nverdict: PASS — {} check{} passed{}; family-wise α = {:.3g} ({:.2f} s)\n",
                       total, total == 1 ? "" : "s", skipped, report.alpha, report.seconds);
  } else {
    out += fmt::format("\nverdict: FAIL — {} of {} checks failed ({}){}; family-wise α = {:.3g} "
                       "({:.2f} s)\n",
                       failed, total, failed_names(report), skipped, report.alpha, report.seconds);
  }
  return out;
}

nlohmann::json gate_json(const GateReport& report) {
  // Strings as valid UTF-8: a case path may hold any bytes, and JSON cannot.
  auto checks = to_json(report.results);
  for (auto& check : checks["checks"]) {
    for (auto& [key, value] : check.items()) {
      if (value.is_string()) value = valid_utf8(value.get<std::string>());
    }
  }
  auto skipped = nlohmann::json::array();
  for (const auto& entry : report.skipped) {
    const auto [check, why] = split_skipped(entry);
    skipped.push_back({{"check", valid_utf8(check)}, {"reason", valid_utf8(why)}});
  }
  return {{"case", valid_utf8(report.case_path)},
          {"subject", valid_utf8(report.subject)},
          {"frames", report.frames},
          {"nx", report.nx},
          {"ny", report.ny},
          {"samples", report.samples},
          {"fields", report.fields},
          {"alpha", json_number(report.alpha)},
          {"alpha_per_check", json_number(report.alpha_per_check)},
          {"statistical_checks", report.statistical_checks},
          {"fitted_scale", json_number(report.fitted_scale)},
          {"unit_roundoff", json_number(report.unit_roundoff)},
          {"checks", checks["checks"]},
          {"skipped", skipped},
          {"passed", checks["passed"]},
          {"failed", checks["failed"]},
          {"seconds", json_number(report.seconds)},
          {"pass", report.passed()}};
}

std::string gate_junit(const GateReport& report) {
  const int failed = failed_count(report);
  const int tests = int(report.results.size() + report.skipped.size());
  const std::string time = fmt::format("{:.3f}", report.seconds);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites" + attribute("name", "swell gate") + attribute("tests", std::to_string(tests)) +
         attribute("failures", std::to_string(failed)) + attribute("errors", "0") +
         attribute("skipped", std::to_string(report.skipped.size())) + attribute("time", time) +
         ">\n";
  out += "  <testsuite" + attribute("name", "swell gate") +
         attribute("tests", std::to_string(tests)) + attribute("failures", std::to_string(failed)) +
         attribute("errors", "0") + attribute("skipped", std::to_string(report.skipped.size())) +
         attribute("time", time) + ">\n";
  out += "    <properties>\n";
  auto property = [&](const std::string& name, const std::string& value) {
    out += "      <property" + attribute("name", name) + attribute("value", value) + "/>\n";
  };
  property("case", report.case_path);
  property("subject", report.subject);
  property("frames", fmt::format("{} of {}x{}", report.frames, report.nx, report.ny));
  property("alpha", fmt::format("{:g}", report.alpha));
  property("alpha_per_check", fmt::format("{:g}", report.alpha_per_check));
  property("statistical_checks", std::to_string(report.statistical_checks));
  out += "    </properties>\n";
  for (const auto& r : report.results) {
    const std::string group = r.check.substr(0, r.check.find('.'));
    out += "    <testcase" + attribute("classname", "swell.gate." + group) +
           attribute("name", r.check) + attribute("time", "0");
    if (r.passed) {
      out += ">\n      <system-out>" + xml_escape(r.reason + " (" + r.criterion + ")", false) +
             "</system-out>\n    </testcase>\n";
      continue;
    }
    const std::string message = failure_message(r);
    out += ">\n      <failure" + attribute("message", message) + attribute("type", r.check) + ">" +
           xml_escape(fmt::format("{}\nsubject: {}\nmeasured: {}\nexpected: {}\ncriterion: {}\n"
                                  "p-value: {}\nalpha: {}\nreason: {}",
                                  r.check, r.subject, number(r.measured), number(r.expected),
                                  r.criterion, number(r.p_value), number(r.alpha), r.reason),
                      false) +
           "</failure>\n    </testcase>\n";
  }
  for (const auto& entry : report.skipped) {
    const auto [check, why] = split_skipped(entry);
    const std::string group = check.substr(0, check.find('.'));
    out += "    <testcase" + attribute("classname", "swell.gate." + group) +
           attribute("name", check) + attribute("time", "0") + ">\n      <skipped" +
           attribute("message", why) + "/>\n    </testcase>\n";
  }
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

std::string gate_junit_error(const std::string& case_path, const std::string& message) {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  const std::string counts = attribute("tests", "1") + attribute("failures", "0") +
                             attribute("errors", "1") + attribute("skipped", "0") +
                             attribute("time", "0");
  out += "<testsuites" + attribute("name", "swell gate") + counts + ">\n";
  out += "  <testsuite" + attribute("name", "swell gate") + counts + ">\n";
  out += "    <properties>\n      <property" + attribute("name", "case") +
         attribute("value", case_path) + "/>\n    </properties>\n";
  out += "    <testcase" + attribute("classname", "swell.gate") + attribute("name", "input") +
         attribute("time", "0") + ">\n      <error" + attribute("message", message) +
         attribute("type", "bad input") + ">" + xml_escape(message, false) +
         "</error>\n    </testcase>\n";
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

}  // namespace swell::validation
