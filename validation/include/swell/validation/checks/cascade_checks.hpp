#pragma once
// The checks of a cascade set as a whole (docs/conventions.md §2.2, docs/gate.md §10),
// beside the ordinary checks each cascade passes against its band of the spectrum (w_c² Ψ).
// They consume frames and the case only, and speak the engine's language:
//
//   cascades.bands          exact (additive sets): the declared bands share the spectrum out once
//                           (Σ_c w_c² = 1 wherever the cascades' grids hold it); names every
//                           overlap and gap with its factor and share of m0 ("cascades 0, 1 and 2
//                           all carry 0.101–0.201 rad/m: energy × 3 there, 4.1 % of m0")
//   cascadeC.band.outside   exact: no energy where cascade C's band weight is 0 (beyond rounding);
//                           names the |k| range, the other cascade carrying it ("cascades 0 and 1
//                           both carry 0.063–0.080 rad/m (energy × 2.0 there)") or a square cut
//   cascadeC.band.missing   statistical: no run of wave vectors inside the band, in order of |k|,
//                           all nearly empty (I < 1e-4 μ) beyond chance: "no cascade carries …"
//   cascades.energy         statistical: the energy of the set against the union's band-limited
//                           m0 (exact law of Σ I); names a cascade scaled with another's Δk
//   cascades.independence   statistical: the initial amplitudes recovered from the frames,
//                           normalized, are uncorrelated between cascades at the same (n, m)
//   cascades.patch          exact: each cascade's frames move at the ω of its own patch's k, not
//                           at that of another cascade's patch length
//   cascades.nested         exact: a nested set's coarse band equals the broad band's part at
//                           the same wave vectors, frame by frame
//   sum.band.outside/missing  the same as the band checks, on the summed surface: every wave
//                           vector of the fine grid carries what the cascades whose grids hold it
//                           put there, and nothing elsewhere
#include <complex>
#include <vector>

#include "swell/reference/cascade.hpp"
#include "swell/reference/fields.hpp"
#include "swell/reference/ocean_case.hpp"
#include "swell/validation/io/frame_source.hpp"
#include "swell/validation/results/check_result.hpp"

namespace swell::validation {

// One cascade's frames and case (its grid, band and random-number key). The frames stream
// (io/frame_source.hpp): the set checks keep sums per wave vector, not the frames.
struct CascadeView {
  int index = 0;
  const reference::OceanCase* ocean = nullptr;
  const FrameSource* frames = nullptr;
};

struct CascadeSetOptions {
  reference::CascadeRelation relation = reference::CascadeRelation::additive;
  double alpha_per_check = 1e-3;  // each statistical check's false-alarm rate
  bool free_scale = false;        // the engine's scale is free: no energy check
  int threads = 1;                // the cascades are analysed concurrently
};
// The band checks of every cascade (additive and independent sets), and the set's checks: a
// summed set's energy (unless free_scale), independence and patch; a nested set's nested check.
// The set checks need two cascades; `members` are the whole set's (naming who else carries a
// range). Each cascade's frames stream: once for the two-wave fit's sums (the recovered
// amplitudes, and the patch check's fits at every patch length of the set), once more with
// three frames or more for the patch fits' residuals; the nested check streams the broad band
// and reads each coarse cascade's frame beside it.
struct CascadeSetResults {
  std::vector<std::vector<CheckResult>> bands;  // bands[v]: cascades[v]'s ("cascadeN.band.…")
  std::vector<CheckResult> set;                 // the set's ("cascades.…")
};
CascadeSetResults run_cascade_set_checks(const std::vector<CascadeView>& cascades,
                                         const std::vector<reference::CascadeMember>& members,
                                         const CascadeSetOptions& options);
// cascades.bands: how the declared bands of an additive set share out `sea` (the set's sea,
// reference::band_coverage); fails on every range off Σ w² = 1 holding more than
// reference::kSmallestEnergyFraction of m0. It judges the case, not frames.
CheckResult check_band_sharing(const reference::OceanCase& sea,
                               const std::vector<reference::CascadeMember>& members);
// The band checks on a summed surface (`summed` has members).
std::vector<CheckResult> check_summed_bands(const reference::OceanCase& summed, const FrameSource& frames,
                                            double alpha);

}  // namespace swell::validation
