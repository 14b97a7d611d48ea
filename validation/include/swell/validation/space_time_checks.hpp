// Deprecated path: include "swell/validation/checks/space_time_checks.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/checks/space_time_checks.hpp"
