// Deprecated path: include "swell/validation/stats/wave_fit.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/stats/wave_fit.hpp"
