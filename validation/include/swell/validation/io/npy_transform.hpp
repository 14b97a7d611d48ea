#pragma once
// One array through one transform backend, unnormalized as FFTW (docs/conventions.md
// §Transforms): what `swell fft` does to a .npy file and swell.fft to a NumPy array. A 2-D array
// (rows, cols) is one transform of nx = cols, ny = rows; a 1-D array of length n is nx = n,
// ny = 1.
//   complex input (c8 → fp32, c16 → fp64): c2c, forward or inverse; same dtype and shape out
//   real input (f4, f8): r2c forward; out complex (…, nx/2+1)
//   c2r: complex half spectrum (…, m) → real (…, nx) with nx = 2(m−1) or the nx given
#include <optional>
#include <string>

#include "swell/impls/transform.hpp"
#include "swell/validation/io/npy.hpp"

namespace swell::validation {

struct ArrayTransformRequest {
  bool inverse = false;       // c2c inverse (e^(+i…)) instead of forward
  bool c2r = false;           // complex half spectrum to real
  std::optional<int> nx;      // c2r only: the real length (nx/2+1 must be the columns)
};

struct ArrayTransformResult {
  NpyArray output;
  impls::TransformSpec spec;
  double seconds = 0;  // execution, planning excluded
  bool exact = true;   // false for a backend that only copies (the output is not a spectrum)
};

// Transforms `input` with `backend` (impls::make_backend names an unknown one); `source` names it in messages (the file, or the argument). Bad input —
// a rank other than 1 or 2, float16, a non-finite element (named by its
// index), a request the dtype cannot take, a size the backend does not plan — throws
// InvalidInput with the command's message (its flags spelled --inverse, --c2r, --nx).
ArrayTransformResult transform_array(impls::Backend& backend, const NpyArray& input,
                                     const std::string& source,
                                     const ArrayTransformRequest& request);

}  // namespace swell::validation
