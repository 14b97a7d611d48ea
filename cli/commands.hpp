#pragma once
// Each subcommand registers its options on the CLI11 app and returns the action to run after a
// successful parse; the action returns the process exit code (0 pass, 1 fail, 2 bad input).
#include <CLI/CLI.hpp>

#include <algorithm>

#include "swell/reference/model_factory.hpp"
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace swell::cli {

using Action = std::function<int()>;

Action add_spectrum_command(CLI::App& app);
Action add_check_command(CLI::App& app);
Action add_fft_command(CLI::App& app);
Action add_synth_command(CLI::App& app);
Action add_fit_command(CLI::App& app);
Action add_gate_command(CLI::App& app);
Action add_lattice_command(CLI::App& app);
Action add_bench_command(CLI::App& app);
Action add_report_command(CLI::App& app);
Action add_sweep_command(CLI::App& app);

// Writes JSON to FILE, or to standard output for "-".
void write_json(const std::string& destination, const nlohmann::json& document);

// The registered transform backends and, where the build has vulkan, the Vulkan device and
// driver it runs on (or why it cannot run): "--help" and `swell check transforms` print it.
std::string backends_summary();
// Where the build has vulkan: "llvmpipe (…), CPU, driver …" or the reason there is none;
// empty otherwise.
std::string vulkan_device_line();

// A CLI11 check for --model (spectra) and --spreading whose refusal teaches: a spreading given
// as a spectrum (or phillips as a spreading) says where it goes, a misspelling names the
// nearest model (reference::unknown_model_message).
inline CLI::Validator model_name_check(reference::ModelKind kind) {
  return CLI::Validator(
      [kind](std::string& name) -> std::string {
        const auto valid = kind == reference::ModelKind::spectrum
                               ? reference::frequency_model_names()
                               : reference::spreading_model_names();
        if (std::find(valid.begin(), valid.end(), name) != valid.end()) return {};
        return reference::unknown_model_message(kind, name);
      },
      "MODEL");
}

}  // namespace swell::cli
