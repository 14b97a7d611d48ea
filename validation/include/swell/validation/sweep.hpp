// Deprecated path: include "swell/validation/sweep/sweep.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/sweep/sweep.hpp"
