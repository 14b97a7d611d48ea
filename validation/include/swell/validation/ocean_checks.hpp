// Deprecated path: include "swell/validation/checks/ocean_checks.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/checks/ocean_checks.hpp"
