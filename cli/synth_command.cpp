// placeholder: being written
#include "commands.hpp"
namespace swell::cli {
Action add_synth_command(CLI::App& app) { return [] { return 2; }; }
}  // namespace swell::cli
