#pragma once
// `swell check all`'s rows for the seas a case reads from files or builds from parts
// (sea_file_checks.cpp): tabulated spectra against the moments a file states, a tabulated
// parametric spectrum against the interpolation's error bound, and a composite sea's m0
// against its components' Hs.
#include <filesystem>
#include <vector>

#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

// data_dir holds external/twopeak/twopeak_ochi_hubble.{nc,json}.
void sea_file_checks(const std::filesystem::path& data_dir, std::vector<CheckResult>& out);

}  // namespace swell::validation
