// swell — numerical validation and benchmarking harness for ocean-wave spectra and FFTs.
// Exit codes: 0 success or pass, 1 a check failed (or a computation missed its accuracy),
// 2 bad input (the message names what was wrong).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <glog/logging.h>
#include <fstream>
#include <iostream>
#include <new>

#include "commands.hpp"
#include "swell/impls/transform.hpp"
#include "swell/reference/errors.hpp"
#ifdef SWELL_HAVE_VULKAN
#include "swell/impls/vulkan.hpp"
#endif

namespace swell::cli {

void write_json(const std::string& destination, const nlohmann::json& document) {
  if (destination == "-") {
    std::cout << document.dump(2) << "\n";
    return;
  }
  std::ofstream file(destination);
  file << document.dump(2) << "\n";
  if (!file) throw InvalidInput("cannot write JSON to '" + destination + "'");
}

std::string vulkan_device_line() {
#ifdef SWELL_HAVE_VULKAN
  try {
    impls::make_backend("vulkan");
  } catch (const std::exception& e) {
    return std::string("no device (") + e.what() + ")";
  }
  return impls::vulkan_device_description("vulkan");
#else
  return "";
#endif
}

std::string backends_summary() {
  std::string names;
  for (const auto& name : impls::backend_names()) names += (names.empty() ? "" : ", ") + name;
  std::string text = "Transform backends (--impl): " + names + ".";
  const std::string device = vulkan_device_line();
  if (!device.empty()) text += "\nvulkan runs on: " + device;
  return text;
}

}  // namespace swell::cli

int main(int argc, char** argv) {
  // Ceres logs each BFGS restart of its line search as a glog warning ("Numerical failure in
  // BFGS update…": hundreds over a buoy record); the fits report their own convergence
  // (docs/fit.md §3), so only Ceres's errors reach standard error.
  FLAGS_minloglevel = google::GLOG_ERROR;
  CLI::App app{"swell: checks ocean-wave spectra, surfaces and FFTs against physics and each other"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "swell 0.1.0");
  // Opens the Vulkan device only when help is printed.
  app.footer([] { return swell::cli::backends_summary(); });
  std::map<std::string, swell::cli::Action> actions;
  auto* spectrum = app.add_subcommand("spectrum", "evaluate a wave spectrum and its moments");
  actions["spectrum"] = swell::cli::add_spectrum_command(*spectrum);
  auto* check = app.add_subcommand("check", "run swell's validations and write a report");
  actions["check"] = swell::cli::add_check_command(*check);
  auto* fft = app.add_subcommand("fft", "transform one .npy array with one backend");
  actions["fft"] = swell::cli::add_fft_command(*fft);
  auto* synth = app.add_subcommand("synth", "synthesize ocean frames and write them with their case");
  actions["synth"] = swell::cli::add_synth_command(*synth);
  auto* fit = app.add_subcommand("fit", "fit JONSWAP parameters, with 95 % intervals, to frames");
  actions["fit"] = swell::cli::add_fit_command(*fit);
  auto* gate = app.add_subcommand("gate", "judge another engine's frames against its case file");
  actions["gate"] = swell::cli::add_gate_command(*gate);
  auto* lattice = app.add_subcommand("lattice", "a rank-1 lattice: generator, merits, band and wave vectors");
  actions["lattice"] = swell::cli::add_lattice_command(*lattice);
  auto* bench = app.add_subcommand("bench", "run the benchmark suites and keep their results with the machine context");
  actions["bench"] = swell::cli::add_bench_command(*bench);
  auto* sweep = app.add_subcommand("sweep", "tuning experiments: varied case keys × seeds, their statistics and fits (mpirun for many machines)");
  actions["sweep"] = swell::cli::add_sweep_command(*sweep);
  auto* report = app.add_subcommand("report", "turn swell bench results into a report with figures, or compare two runs");
  actions["report"] = swell::cli::add_report_command(*report);

  // CLI11 says only "A subcommand is required" for a misspelt one; name it instead.
  if (argc > 1 && argv[1][0] != '-' && !actions.count(argv[1])) {
    std::string valid;
    for (auto* sub : app.get_subcommands({})) valid += (valid.empty() ? "" : ", ") + sub->get_name();
    std::cerr << "swell: error: unknown subcommand '" << argv[1] << "'; valid: " << valid
              << " (run 'swell --help' for usage)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "swell: error: " << e.what() << "\n(run 'swell --help' for usage)\n";
    return 2;
  }

  try {
    for (auto* sub : app.get_subcommands()) return actions.at(sub->get_name())();
  } catch (const swell::InvalidInput& e) {
    std::cerr << "swell: error: " << e.what() << "\n";
    return 2;
  } catch (const swell::NumericalError& e) {
    std::cerr << "swell: numerical failure: " << e.what() << "\n";
    return 1;
  } catch (const swell::InternalError& e) {
    std::cerr << "swell: internal error (a bug in swell; please report it with this command "
                 "line): " << e.what() << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "swell: error: out of memory: the machine could not give swell the memory this "
                 "command needs (a smaller grid, fewer frames or fewer threads need less)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "swell: error: " << e.what() << "\n";
    return 2;
  }
  return 2;
}
