// Backend names → factories. One name serves --impl, test names and benchmark names.
#include <functional>
#include <map>

#include "backends.hpp"

namespace swell::impls {
namespace {

using Factory = std::function<std::unique_ptr<Backend>(const BackendOptions&)>;

const std::vector<std::pair<std::string, Factory>>& factories() {
  static const std::vector<std::pair<std::string, Factory>> table = {
      {"naive", make_naive_backend},
      {"radix2", make_radix2_backend},
      {"fftw", make_fftw_backend},
      {"null", make_null_backend},
#ifdef SWELL_HAVE_VULKAN
      {"vulkan", make_vulkan_backend},
#endif
  };
  return table;
}

std::string joined_names() {
  std::string out;
  for (const auto& [name, factory] : factories()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : factories()) names.push_back(name);
  return names;
}

std::unique_ptr<Backend> make_backend(const std::string& name_and_options) {
  const auto colon = name_and_options.find(':');
  const std::string name = name_and_options.substr(0, colon);
  BackendOptions options;
  if (colon != std::string::npos) {
    std::string rest = name_and_options.substr(colon + 1);
    std::size_t start = 0;
    while (start <= rest.size()) {
      const auto comma = rest.find(',', start);
      const std::string item = rest.substr(start, comma - start);
      const auto equals = item.find('=');
      const std::string key = item.substr(0, equals);
      const std::string value = equals == std::string::npos ? "" : item.substr(equals + 1);
      if ((key == "device" || key == "subgroups") && name != "vulkan") {
        throw InvalidInput("backend option " + key + " is for vulkan, not " + name);
      }
      if (key == "planner" && !value.empty()) {
        options.planner = value;
      } else if (key == "threads") {
        std::size_t used = 0;
        int threads = 0;
        try {
          threads = std::stoi(value, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != value.size() || value.empty() || threads < 1 || threads > 256) {
          throw InvalidInput("backend option threads='" + value + "' must be a whole number 1…256");
        }
        options.threads = threads;
      } else if (key == "device") {
        std::size_t used = 0;
        int device = -1;
        try {
          device = std::stoi(value, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != value.size() || value.empty() || device < 0 || device > 255) {
          throw InvalidInput("backend option device='" + value +
                             "' must be a Vulkan device index 0…255 (see `vulkaninfo --summary`)");
        }
        options.device = device;
      } else if (key == "subgroups") {
        if (value != "on" && value != "off") {
          throw InvalidInput("backend option subgroups='" + value + "' must be on or off");
        }
        options.subgroups = value == "on";
      } else {
        throw InvalidInput("unknown backend option '" + item + "' in '" + name_and_options +
                           "'; valid: planner=estimate|measure|patient|exhaustive (fftw), "
                           "threads=N (fftw, radix2), device=N and subgroups=on|off (vulkan)");
      }
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  for (const auto& [known, factory] : factories()) {
    if (known == name) return factory(options);
  }
  throw InvalidInput("unknown transform backend '" + name + "'; valid: " + joined_names());
}

}  // namespace swell::impls
