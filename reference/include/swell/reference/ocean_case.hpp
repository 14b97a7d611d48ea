#pragma once
// An ocean case: everything that fixes a synthesized surface and everything a check needs to
// judge one (docs/conventions.md, docs/case_files.md). It is what a case file (case.toml)
// holds: grid, frame times, physics, spectrum, spreading, synthesis settings and seed.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "swell/reference/cascade.hpp"
#include "swell/reference/directional.hpp"
#include "swell/reference/dispersion.hpp"
#include "swell/reference/grid.hpp"
#include "swell/reference/sampling.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/spectrum_table.hpp"

namespace swell::reference {

// One component of a sea (docs/case_files.md §Composite seas): its frequency spectrum, its
// spreading about its own mean direction, the energy factor its engine declares, and its
// short-wave fade.
struct SeaComponent {
  ModelSpec spectrum;
  ModelSpec spreading;      // empty model for phillips, which carries its own directionality
  double wind_dir_deg = 0;  // θw, degrees counter-clockwise from +x, direction of travel
  // F: the engine knowingly makes F times the declared energy (its own convention, e.g. 8 for
  // unit-variance real and imaginary parts with a √2 on the amplitude and both halves of each
  // ±k pair at full variance); Ψ is F times the model's.
  double energy_factor = 1;
  double short_wave_fade = 0;  // l, m: Ψ·e^(−k²l²) (0: none)
  // A tabulated spectrum (spectrum.model "table" or "ndbc"), read from its files once: a 2-D
  // E(ω, θ) is the component's Ψ itself (no spreading); a 1-D S(ω) takes the spreading above.
  std::shared_ptr<const SpectrumTable> table;
};

struct OceanCase {
  // The samples: a grid, or (lattice set) a 2-D rank-1 lattice over grid.lx × grid.ly, when
  // grid.nx = grid.ny = 0 (set_lattice). Code that handles only grids asks is_lattice() and
  // refuses a lattice by name.
  Grid grid;
  std::shared_ptr<const RankOneLattice> lattice;
  Sampling sampling() const { return lattice ? Sampling(lattice) : Sampling(grid); }
  bool is_lattice() const { return lattice != nullptr; }
  // Samples the patch with `lattice` (2-D): grid becomes its lengths, with nx = ny = 0.
  void set_lattice(std::shared_ptr<const RankOneLattice> lattice);

  // Frame f is at time t0 + f·dt (s).
  double t0 = 0;
  double dt = 0;
  int frames = 1;

  double gravity = kStandardGravity;  // m/s²
  double depth = kInfiniteDepth;      // m

  // The sea: component 0 in the five fields below (what a one-component case is), and the
  // further components of a composite sea in more_components; their Ψ add.
  // Frequency spectrum by name and parameters (model_factory.hpp vocabulary), without the
  // common parameters gravity, depth and wind_dir, which the case holds once for all models.
  ModelSpec spectrum;
  // Spreading model; empty model name for phillips, which carries its own directionality.
  ModelSpec spreading;
  double wind_dir_deg = 0;  // θw, degrees counter-clockwise from +x, direction of travel
  double energy_factor = 1;    // SeaComponent::energy_factor
  double short_wave_fade = 0;  // SeaComponent::short_wave_fade, m
  std::shared_ptr<const SpectrumTable> table;  // SeaComponent::table
  std::vector<SeaComponent> more_components;
  // Every component, component 0 first.
  std::vector<SeaComponent> components() const;
  bool is_composite() const { return !more_components.empty(); }
  // Replaces the sea by `components` (at least one).
  void set_components(const std::vector<SeaComponent>& components);

  double choppiness = 1;   // λ: stored displacement is λD (conventions §Derived fields)
  double loop_period = 0;  // s; 0 = none, else ω is quantized down to multiples of 2π/T
  std::uint64_t seed = 0;

  // Cascades (reference/cascade.hpp, docs/conventions.md §2.2): this surface is cascade `cascade` of a set
  // (its random numbers keyed by it), its amplitudes weighted by `band`; or, when `members` is
  // not empty, it is the summed surface of an additive set on the fine grid `grid`, where
  // cascade c's wave vectors carry w_c² Ψ Δk_c² (its own Δk) with its own random numbers.
  int cascade = 0;
  BandWeight band;
  std::vector<CascadeMember> members;
  bool is_summed_cascades() const { return !members.empty(); }

  // Checks it and throws InvalidInput naming the first thing wrong.
  void validate() const;
  // The rules of the sea alone — time origin and step, physics, components, choppiness, loop
  // period — without its samples (a probes case has none on a grid).
  void validate_sea() const;

  double time(int frame) const { return t0 + frame * dt; }
  // ω(|k|) of the case: its dispersion relation, quantized by the loop period if one is set.
  double omega(double k) const;
  Dispersion dispersion() const;
  // Ψ(k) of the case (with gravity, depth and wind direction applied), times the band weight
  // w² of a cascade; for a summed set, Σ_c [k on cascade c's grid] w_c² Ψ Δk_c²/Δk², meaningful
  // at the fine grid's wave vectors only.
  DirectionalSpectrumPtr directional_spectrum() const;
  // Ψ(k) of the whole sea, without band weights.
  DirectionalSpectrumPtr sea_spectrum() const;
  // Component 0's spectrum spec with gravity, depth and wind_dir filled in, as model_factory
  // takes it; full_spectrum_spec(c) for any component.
  ModelSpec full_spectrum_spec() const;
  ModelSpec full_spectrum_spec(const SeaComponent& component) const;
  // Ψ(k) of one component, its energy factor and fade applied.
  DirectionalSpectrumPtr component_spectrum(const SeaComponent& component) const;
  std::string describe_sea() const;  // "jonswap hs=3 tp=8 gamma=3.3 + cos2s s=10"
  std::string describe() const;  // "jonswap hs=3 tp=8 gamma=3.3 + cos2s s=10, 256×256 over 200×200 m"
};

}  // namespace swell::reference
