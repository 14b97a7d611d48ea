// Deprecated path: include "swell/validation/fit/buoy_spectrum.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/fit/buoy_spectrum.hpp"
