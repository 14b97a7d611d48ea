// Deprecated path: include "swell/validation/results/check_result.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/results/check_result.hpp"
