#pragma once
// Each subcommand registers its options on the CLI11 app and returns the action to run after a
// successful parse; the action returns the process exit code (0 pass, 1 fail, 2 bad input).
#include <CLI/CLI.hpp>
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

// Writes JSON to FILE, or to standard output for "-".
void write_json(const std::string& destination, const nlohmann::json& document);

}  // namespace swell::cli
