#pragma once
// Spectra given as tables (SpectrumTable, docs/conventions.md §3.6): between table points the
// density is interpolated linearly in ω and, for a 2-D table, periodically and linearly in θ;
// a band-averaged table (NDBC) is constant over each band; beyond the table it is zero.
#include <memory>

#include "swell/reference/directional.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/spectrum_table.hpp"

namespace swell::reference {

// Throws InvalidInput naming the row (and column) of the first value that breaks the table's
// rules: ω > 0 and strictly increasing, θ in [0, 2π) and strictly increasing, densities finite
// and ≥ 0, band widths > 0 and bands that do not overlap, and the sizes consistent.
void validate_table(const SpectrumTable& table);

// S(ω) of a 1-D table, or the omnidirectional S(ω) = ∫ E(ω, θ) dθ of a 2-D one (exact for the
// interpolant: the periodic trapezoid rule in θ).
FrequencySpectrumPtr table_frequency_spectrum(std::shared_ptr<const SpectrumTable> table);

// Ψ(k) = E(ω(k), θ_k) (dω/dk)/k of a 2-D table under `dispersion`; its mean direction is the
// direction of ∫∫ E (cos θ, sin θ) dω dθ.
DirectionalSpectrumPtr table_directional_spectrum(std::shared_ptr<const SpectrumTable> table,
                                                  Dispersion dispersion);

}  // namespace swell::reference
