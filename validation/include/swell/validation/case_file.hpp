// Deprecated path: include "swell/validation/io/case_file.hpp";
// this header forwards there for one release (docs/library.md).
#pragma once
#include "swell/validation/io/case_file.hpp"
