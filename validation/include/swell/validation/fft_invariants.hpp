// Deprecated path: include "swell/validation/testing/fft_invariants.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/testing/fft_invariants.hpp"
