// swell check [reference | all] [--json FILE|-] [--report-dir DIR]
// Runs swell's validations, prints a table and writes <report-dir>/check_<what>.{json,md}.
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/reference_checks.hpp"
#include "swell/validation/report.hpp"

namespace swell::cli {
namespace {

struct CheckOptions {
  std::string what = "all";
  std::string impl = "all";
  std::string json;
  std::string report_dir = "reports/latest";
  std::string data_dir;
};

int run_check(const CheckOptions& o) {
  const std::filesystem::path data =
      o.data_dir.empty() ? validation::default_data_directory() : std::filesystem::path(o.data_dir);
  if (!std::filesystem::exists(data / "external")) {
    throw InvalidInput("data directory '" + data.string() +
                       "' has no external/ reference data (set --data-dir or SWELL_DATA_DIR)");
  }
  std::vector<validation::CheckResult> results;
  // "all" grows as later parts land: transforms, ocean.
  if (o.what == "reference" || o.what == "all") {
    const auto reference = validation::run_reference_checks(data);
    results.insert(results.end(), reference.begin(), reference.end());
  }
  const std::string title = "swell check " + o.what;
  validation::write_report(o.report_dir, "check_" + o.what, results, title);
  if (!o.json.empty()) write_json(o.json, validation::to_json(results));
  if (o.json != "-") {
    std::cout << validation::render_table(results)
              << fmt::format("report: {}/check_{}.{{json,md}}\n", o.report_dir, o.what);
  }
  return validation::all_passed(results) ? 0 : 1;
}

}  // namespace

Action add_check_command(CLI::App& app) {
  auto o = std::make_shared<CheckOptions>();
  app.add_option("what", o->what, "which validations: reference, or all (default)")
      ->check(CLI::IsMember({"reference", "all"}));
  app.add_option("--impl", o->impl, "transform backends to include (all)")
      ->check(CLI::IsMember({"all"}));
  app.add_option("--json", o->json, "also write the results as JSON to FILE, or - for stdout");
  app.add_option("--report-dir", o->report_dir, "where the JSON and Markdown reports go")
      ->capture_default_str();
  app.add_option("--data-dir", o->data_dir, "swell's data/ directory (default: found)");
  return [o] { return run_check(*o); };
}

}  // namespace swell::cli
