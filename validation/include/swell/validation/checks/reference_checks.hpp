#pragma once
// The checks of reference/ that `swell check all` runs: normalizations, dispersion round trips
// and published values, moment identities. Each compares swell's reference implementation with
// something independent of it (a closed form, a second quadrature, data under data/external).
#include <filesystem>
#include <vector>

#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

// data_dir holds external/mhkit/ValData1.json and ValData2_CDiP.json.
std::vector<CheckResult> run_reference_checks(const std::filesystem::path& data_dir);

// Where swell's shipped data lives: $SWELL_DATA_DIR if set, else the source tree's data/ when
// it exists, else the installed share/swell.
std::filesystem::path default_data_directory();

}  // namespace swell::validation
