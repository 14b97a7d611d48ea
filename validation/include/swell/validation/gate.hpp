// Deprecated path: include "swell/validation/gate/gate.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/gate/gate.hpp"
