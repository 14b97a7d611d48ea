#pragma once
// What a performance result depends on besides the code: the machine, the build and the
// libraries, collected when `swell bench` runs and kept beside its results (context.json).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace swell::reports {

// Keys (each always present; a value that cannot be read is the string "unknown" with the
// reason where there is one):
//   cpu        {model, logical_cores, flags (every flag of /proc/cpuinfo), simd (the vector
//               extensions among them), caches [{level, type, size}], mhz, frequency_scaling
//               {governor, driver, min_khz, max_khz}}
//   memory     {total_bytes, available_bytes}
//   os         {name, kernel, machine}
//   load_average [1, 5, 15 min]
//   build      {compiler, flags, build_type, git_commit, git_dirty}
//   libraries  {fftw, openimageio, ceres, google_benchmark, vulkan_loader, vulkan_device}
//   date       ISO 8601, UTC
// `vulkan` fills libraries.vulkan_loader and vulkan_device (the CLI knows them; "not built"
// elsewhere).
nlohmann::json machine_context(const std::string& vulkan_loader, const std::string& vulkan_device);

// The keys above, for the tests and the report: every one must be present.
const std::vector<std::string>& machine_context_keys();

}  // namespace swell::reports
