// Finds and loads libswell_openimageio.so (image_module.hpp) the first time an image needs it.
#include "image_module.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "swell/reference/errors.hpp"

namespace swell::validation::detail {
namespace {

namespace fs = std::filesystem;

struct Loaded {
  const ImageModule* module = nullptr;
  std::string why;  // what was tried, when nothing loaded
};

// One file: its module, or why not (appended to `why`).
const ImageModule* try_load(const fs::path& file, std::string& why) {
  std::error_code error;
  if (!fs::exists(file, error)) {
    why += fmt::format("\n  {}: no such file", file.string());
    return nullptr;
  }
  // RTLD_LOCAL: OpenImageIO's symbols stay the module's. It is never unloaded (OpenImageIO
  // keeps threads and caches until the process ends).
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* text = dlerror();
    why += fmt::format("\n  {}: {}", file.string(), text ? text : "cannot be loaded");
    return nullptr;
  }
  using Entry = const ImageModule* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, "swell_openimageio_module"));
  const ImageModule* module = entry ? entry() : nullptr;
  if (!module || module->interface_version != kImageModuleInterfaceVersion) {
    why += fmt::format("\n  {}: not a module of this swell (interface {}, this swell needs {})",
                       file.string(), module ? module->interface_version : 0,
                       kImageModuleInterfaceVersion);
    return nullptr;
  }
  return module;
}

// In order: $SWELL_OPENIMAGEIO_MODULE alone when set; beside an installed program
// (BINDIR/../LIBDIR/swell); the build tree's; the install prefix's (for another project's
// program linking an installed swell::io).
Loaded load() {
  Loaded out;
  if (const char* chosen = std::getenv("SWELL_OPENIMAGEIO_MODULE"); chosen && *chosen) {
    out.module = try_load(chosen, out.why);
    return out;
  }
  std::vector<fs::path> files;
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error) files.push_back(program.parent_path() / SWELL_OPENIMAGEIO_MODULE_FROM_BINDIR);
  files.emplace_back(SWELL_OPENIMAGEIO_MODULE_BUILD_PATH);
  files.emplace_back(SWELL_OPENIMAGEIO_MODULE_INSTALL_PATH);
  for (const auto& file : files) {
    if ((out.module = try_load(file, out.why))) return out;
  }
  return out;
}

}  // namespace

const ImageModule& image_module(const std::string& purpose) {
  static const Loaded loaded = load();  // thread-safe: C++11 static initialization
  if (!loaded.module) {
    throw InvalidInput(fmt::format("{} needs OpenImageIO, which swell loads from its module "
                                   "libswell_openimageio.so; none could be loaded (set "
                                   "SWELL_OPENIMAGEIO_MODULE to its path):{}",
                                   purpose, loaded.why));
  }
  return *loaded.module;
}

}  // namespace swell::validation::detail
