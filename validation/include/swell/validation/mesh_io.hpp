// Deprecated path: include "swell/validation/io/mesh_io.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/io/mesh_io.hpp"
