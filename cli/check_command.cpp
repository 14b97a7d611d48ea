// swell check [reference | transforms | ocean | all] [--impl NAME|all] [--alpha A] [--json FILE|-]
//             [--report-dir DIR]
// Runs swell's validations, prints tables and writes <report-dir>/check_<what>.{json,md}.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/checks/ocean_matrix.hpp"
#include "swell/validation/checks/reference_checks.hpp"
#include "swell/validation/results/report.hpp"
#include "swell/validation/checks/transform_checks.hpp"

namespace swell::cli {
namespace {

struct CheckOptions {
  std::string what = "all";
  std::string impl = "all";
  std::string json;
  std::string report_dir = "reports/latest";
  std::string data_dir;
  double alpha = 1e-3;
  int n = 128;
};

int run_check(const CheckOptions& o) {
  const bool all = o.what == "all";
  // Unknown names exit 2 up front. Of "all", a backend that cannot start here (vulkan without
  // a device) is left out, saying why; asked for by name, it is an error (exit 2).
  std::vector<std::string> impls;
  nlohmann::json unavailable = nlohmann::json::object();
  // lattice[:fft=NAME]: rank-1 lattice synthesis through NAME's 1-D transforms (default fftw);
  // with "all", the lattice rows run through fftw. Lattices have ocean rows only (their
  // transforms are the backends' own, checked under those names).
  std::string lattice_fft = o.impl == "all" ? "fftw" : "";
  if (o.impl.rfind("lattice", 0) == 0) {
    if (o.impl == "lattice") {
      lattice_fft = "fftw";
    } else if (o.impl.rfind("lattice:fft=", 0) == 0 && o.impl.size() > 12) {
      lattice_fft = o.impl.substr(12);
    } else {
      throw InvalidInput("--impl " + o.impl + ": a lattice takes one option, fft=NAME, as "
                         "lattice:fft=radix2");
    }
    impls::make_backend(lattice_fft);  // an unknown backend names the valid ones (exit 2)
  }
  const bool lattice_only = o.impl.rfind("lattice", 0) == 0;
  for (const auto& name : o.impl == "all" ? impls::backend_names()
                          : lattice_only  ? std::vector<std::string>{}
                                          : std::vector<std::string>{o.impl}) {
    try {
      impls::make_backend(name);
      impls.push_back(name);
    } catch (const impls::UnsupportedTransform& e) {
      if (o.impl != "all") throw;
      std::cerr << "skipping " << name << ": " << e.what() << "\n";
      unavailable[name] = e.what();
    }
  }
  const bool with_vulkan = std::find(impls.begin(), impls.end(), "vulkan") != impls.end();
  const std::string vulkan_device = with_vulkan ? vulkan_device_line() : "";
  if (with_vulkan) std::cerr << "vulkan runs on: " << vulkan_device << "\n";

  std::vector<validation::CheckResult> checks;
  if (o.what == "reference" || all) {
    const std::filesystem::path data =
        o.data_dir.empty() ? validation::default_data_directory() : std::filesystem::path(o.data_dir);
    if (!std::filesystem::exists(data / "external")) {
      throw InvalidInput("data directory '" + data.string() +
                         "' has no external/ reference data (set --data-dir or SWELL_DATA_DIR)");
    }
    checks = validation::run_reference_checks(data);
  }
  std::vector<validation::OceanMatrixRow> ocean;
  if (o.what == "ocean" || all) {
    validation::OceanCheckOptions options;
    options.alpha = o.alpha;
    for (const auto& name : impls) {
      // `null` copies instead of transforming: there is no surface to judge.
      if (o.impl == "all" && !impls::make_backend(name)->capabilities().exact) continue;
      std::cerr << "checking ocean surfaces synthesized with " << name << "…\n";
      const auto rows = validation::run_ocean_matrix(name, options, o.n);
      ocean.insert(ocean.end(), rows.begin(), rows.end());
    }
    if (!lattice_fft.empty()) {
      std::cerr << "checking ocean surfaces synthesized on rank-1 lattices with lattice:fft="
                << lattice_fft << "…\n";
      const auto rows = validation::run_lattice_ocean_matrix(lattice_fft, options, o.n);
      ocean.insert(ocean.end(), rows.begin(), rows.end());
    }
  }
  std::vector<validation::TransformAccuracy> transforms;
  if (o.what == "transforms" || all) {
    for (const auto& name : impls) {
      std::cerr << "checking transforms of " << name << "…\n";
      const auto rows = validation::run_transform_checks(name);
      transforms.insert(transforms.end(), rows.begin(), rows.end());
    }
  }

  nlohmann::json document = validation::to_json(checks);
  document["transforms"] = validation::transforms_to_json(transforms)["transforms"];
  if (!ocean.empty()) document["ocean"] = validation::ocean_matrix_to_json(ocean);
  const bool passed = validation::all_passed(checks) &&
                      std::all_of(transforms.begin(), transforms.end(),
                                  [](const auto& t) { return t.pass; }) &&
                      std::all_of(ocean.begin(), ocean.end(), [](const auto& r) { return r.passed(); });
  document["pass"] = passed;
  if (with_vulkan) document["vulkan_device"] = vulkan_device;
  if (!unavailable.empty()) document["unavailable_backends"] = unavailable;

  const std::string title = "swell check " + o.what;
  std::string markdown = validation::render_markdown(checks, title);
  if (!transforms.empty()) {
    markdown += "\n## Transform accuracy against the long-double oracle\n\n" +
                (with_vulkan ? "vulkan runs on: " + vulkan_device + "\n\n" : std::string()) +
                "```\n" + validation::render_transform_table(transforms) + "```\n";
  }
  if (!ocean.empty()) {
    markdown += fmt::format("\n## Ocean surfaces: every check on the built-in cases ({}², α = {:g} per "
                            "check)\n\n```\n{}```\n",
                            o.n, o.alpha, validation::render_ocean_matrix(ocean));
  }
  validation::write_report(o.report_dir, "check_" + o.what, document, markdown);
  const std::string stem = (std::filesystem::path(o.report_dir) / ("check_" + o.what)).string();
  if (!o.json.empty()) write_json(o.json, document);
  if (o.json != "-") {
    if (!checks.empty()) std::cout << validation::render_table(checks);
    if (!transforms.empty()) {
      if (with_vulkan) std::cout << "\nvulkan runs on: " << vulkan_device;
      std::cout << "\n" << validation::render_transform_table(transforms);
    }
    for (const auto& [name, why] : unavailable.items()) {
      std::cout << "not checked: " << name << " (" << why.get<std::string>() << ")\n";
    }
    if (!ocean.empty()) std::cout << "\n" << validation::render_ocean_matrix(ocean);
    std::cout << fmt::format("{}\nreport: {}.{{json,md}}\n", passed ? "PASS" : "FAIL", stem);
  }
  return passed ? 0 : 1;
}

}  // namespace

Action add_check_command(CLI::App& app) {
  auto o = std::make_shared<CheckOptions>();
  app.add_option("what", o->what,
                 "which validations: reference, transforms, ocean, or all (default)")
      ->check(CLI::IsMember({"reference", "transforms", "ocean", "all"}));
  app.add_option("--impl", o->impl,
                 "transform backend to check, lattice[:fft=NAME] (ocean rows on rank-1 "
                 "lattices), or all (default; lattice rows through fftw)");
  app.footer([] { return backends_summary(); });
  app.add_option("--json", o->json, "also write the results as JSON to FILE, or - for stdout");
  app.add_option("--report-dir", o->report_dir, "where the JSON and Markdown reports go")
      ->capture_default_str();
  app.add_option("--data-dir", o->data_dir, "swell's data/ directory (default: found)");
  app.add_option("--alpha", o->alpha, "ocean: false-alarm rate of each statistical check")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 0.5));
  app.add_option("--n", o->n, "ocean: samples per side of the built-in cases")
      ->capture_default_str()
      ->check(CLI::Range(16, 1024));
  return [o] { return run_check(*o); };
}

}  // namespace swell::cli
