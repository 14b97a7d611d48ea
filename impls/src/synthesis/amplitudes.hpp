#pragma once
// The initial amplitudes h̃0(k) of a case (docs/conventions.md §5.1): a single grid's, a
// cascade's in its band, a summed cascade set's.
#include <complex>

#include "swell/reference/ocean_case.hpp"

namespace swell::impls::synthesis {

// h̃0 at signed wave index (n, m) of the case's sampling, from the sea's (unweighted) Ψ.
std::complex<double> amplitude(const reference::DirectionalSpectrum& sea,
                               const reference::OceanCase& c, int n, int m);

}  // namespace swell::impls::synthesis
