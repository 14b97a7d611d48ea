// placeholder: being written
#include "commands.hpp"
namespace swell::cli {
Action add_gate_command(CLI::App& app) { return [] { return 2; }; }
}  // namespace swell::cli
