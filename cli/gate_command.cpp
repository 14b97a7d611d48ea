// swell gate --case FILE [--input PATTERN] [--json FILE|-] [--junit FILE] [--alpha A]
//            [--threads N] [--quiet]
// swell gate --power --case FILE [--alpha A] [--json FILE|-]
//
// Judges another engine's frames against its case file (docs/gate.md): reads the frames the
// case's [input] names (or --input), runs every check the given fields and frame count allow,
// with one family-wise false-alarm rate α shared by the statistical checks, and prints one
// line per check and a verdict. --junit writes JUnit XML for CI systems (one testcase per
// check), --json the same as JSON.
//
// Exit 0 when every check passes, 1 when one fails, 2 for bad input (a malformed case, a
// missing or unreadable frame: the message names it). --power prints the gate's power table for
// the case without reading frames (docs/gate.md §11), exit 0.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "commands.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/gate/power.hpp"

namespace swell::cli {
namespace {

struct GateCommandOptions {
  std::string case_file;
  std::string input;
  std::string json;
  std::string junit;
  double alpha = 1e-3;
  int threads = 0;
  bool quiet = false;
  bool power = false;
};

void write_text(const std::string& path, const std::string& text, const char* what) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw InvalidInput(fmt::format("cannot write {} to '{}'", what, path));
}

// An existing file that may be written, or a new one in a writable directory.
bool writable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(path, error)) {
    return !fs::is_directory(path, error) && access(path.c_str(), W_OK) == 0;
  }
  fs::path directory = fs::path(path).parent_path();
  if (directory.empty()) directory = ".";
  return fs::is_directory(directory, error) && access(directory.c_str(), W_OK) == 0;
}

int run_gate_command(const GateCommandOptions& o) {
  // Bad output paths are bad input: found before anything is read.
  for (const auto& [path, what] : {std::pair{o.junit, "JUnit XML"}, std::pair{o.json, "JSON"}}) {
    if (path.empty() || path == "-") continue;
    if (!writable(path)) throw InvalidInput(fmt::format("cannot write {} to '{}'", what, path));
  }
  if (o.power) {
    if (!o.junit.empty() || !o.input.empty()) {
      throw InvalidInput("--power reads no frames: it takes --case, --alpha, --threads and --json only");
    }
    validation::GateOptions options;
    options.alpha = o.alpha;
    options.threads = o.threads;
    options.validate();
    const auto case_file = validation::read_case_file(o.case_file);
    const auto table = validation::gate_power(case_file, o.alpha, options.resolved_threads());
    if (!o.json.empty()) write_json(o.json, validation::power_json(table));
    if (o.json != "-") fmt::print("{}", validation::render_power(table));
    return 0;
  }
  validation::GateReport report;
  try {
    validation::GateOptions options;
    options.alpha = o.alpha;
    options.input_pattern = o.input;
    options.threads = o.threads;
    options.validate();
    const auto case_file = validation::read_case_file(o.case_file);
    if (!o.quiet) {
      // Progress for long runs, on standard error: always on a terminal; in a CI log only when
      // the input is large (≥ 2²⁴ values, e.g. 64 frames of 512² heights), so that small runs
      // print nothing but their report.
      const auto& grid = case_file.ocean.grid;
      const double fields = double(std::max<std::size_t>(1, case_file.input.channels.size()));
      const double values = double(case_file.ocean.frames) * grid.nx * grid.ny * fields;
      if (isatty(fileno(stderr)) != 0 || values >= 0x1p24) {
        options.progress = [](const std::string& message) {
          fmt::print(stderr, "swell gate: {}\n", message);
        };
      }
    }
    report = validation::run_gate(case_file, options);
  } catch (const InvalidInput& e) {
    // The CI job's test report then shows why the gate could not judge (exit code 2), in JUnit
    // and in JSON alike.
    if (!o.junit.empty()) {
      write_text(o.junit, validation::gate_junit_error(o.case_file, e.what()), "JUnit XML");
    }
    if (!o.json.empty()) {
      write_json(o.json, nlohmann::json{{"case", o.case_file}, {"pass", false}, {"exit_code", 2}, {"error", e.what()}});
    }
    throw;
  }
  if (!o.junit.empty()) write_text(o.junit, validation::gate_junit(report), "JUnit XML");
  if (!o.json.empty()) write_json(o.json, validation::gate_json(report));
  if (o.json != "-") fmt::print("{}", validation::render_gate(report));
  return report.passed() ? 0 : 1;
}

}  // namespace

Action add_gate_command(CLI::App& app) {
  auto o = std::make_shared<GateCommandOptions>();
  app.add_option("--case", o->case_file,
                 "case file (docs/case_files.md): grid, times, spectrum, spreading and [input], "
                 "where the frames are and which channel holds which field")
      ->required();
  app.add_option("--input", o->input,
                 "frame file pattern replacing the case's [input] files, relative to the current "
                 "directory (frames/frame_%04d.exr); the channels still come from [input]");
  app.add_option("--json", o->json, "write the report as JSON to FILE, or - for standard output");
  app.add_option("--junit", o->junit,
                 "write JUnit XML to FILE: one testcase per check, failures with measured, "
                 "expected and bound");
  app.add_option("--alpha", o->alpha,
                 "family-wise false-alarm rate shared by all statistical checks (default 1e-3)");
  app.add_option("--threads", o->threads,
                 "threads for decoding and transforms (default 0: every hardware thread)");
  app.add_flag("--quiet", o->quiet, "no progress messages on standard error");
  app.add_flag("--power", o->power,
               "print the gate's power for the case without reading frames: the smallest error "
               "of each kind it detects with 90 % power, and the check that does");
  app.footer(
      "Reads the frames (EXR, TIFF, PNG, .npy, .raw) and runs every check the fields allow: "
      "hermitian, parseval, energy (not with scale = \"free\"), spectrum, moments, dispersion "
      "(≥ 3 frames), direction (≥ 2 frames), statistics, derived fields (when slopes, "
      "displacements or the Jacobian are given). A right engine fails with probability ≤ α: "
      "the statistical checks each run at α / (their number); the exact ones are judged "
      "against rounding bounds. Exit 0 pass, 1 fail, 2 bad input. See docs/gate.md.");
  return [o] { return run_gate_command(*o); };
}

}  // namespace swell::cli
