#pragma once
// Seas made of parts (docs/case_files.md §Composite seas): a component's Ψ with its declared
// energy factor and short-wave fade, and the sum of several components' Ψ.
#include <vector>

#include "swell/reference/directional.hpp"

namespace swell::reference {

// F · Ψ(k) · e^(−k² l²): a component whose engine knowingly makes F times the declared energy
// (energy_factor), faded below the length l in m (short_wave_fade; 0: no fade). Its
// omnidirectional spectrum is F · S(ω) · e^(−k(ω)² l²). Returns `psi` itself when F = 1, l = 0.
DirectionalSpectrumPtr adjusted_spectrum(DirectionalSpectrumPtr psi, double energy_factor,
                                         double fade_length);

// Ψ = Σ Ψ_i over components that share one dispersion relation; S(ω) = Σ S_i(ω), its peak the
// highest of the sum, its tail the slowest of the parts, its mean direction the m0-weighted
// circular mean of the parts'. Returns the single part itself for one part.
DirectionalSpectrumPtr summed_spectrum(std::vector<DirectionalSpectrumPtr> parts);

}  // namespace swell::reference
