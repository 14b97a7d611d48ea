#pragma once
// One validity rule for a case on its sampling (docs/case_files.md "Validity of a case on its grid"), shared by every command that
// takes a case — synth, gate, fit, check — so that no command accepts what another refuses.
// A case passes when, on its grid and in the number format its frames are made or stored in:
//
//   energy    the grid carries at least kSmallestEnergyFraction of the spectrum's m0; otherwise
//             the grid's band of |k| misses where the spectrum's energy is, and a surface is
//             zeros (or rounding) that no check can judge;
//   range     the rms of every field (height, slopes, displacements λD, the λ∂D terms of J) lies
//             between smallest normal / u (below it values lose bits to gradual underflow) and
//             the largest finite / 64 (√ of it for the λ∂D terms, which J multiplies): a
//             Gaussian field's largest sample over 2⁴⁰ points is 7.4σ, so 64σ is a wide margin;
//   times     the fastest wave's phase ω t stays within kLargestPhase at every frame time
//             (reference/phase.hpp: beyond it a phase carries fewer than 53 bits);
//   memory    the command's working set fits in the memory the machine has available.
//
// Each failure is InvalidInput naming the parameter, the limit and the value.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "swell/reference/ocean_case.hpp"

namespace swell::reference {

// The number format a case's fields are computed or stored in.
struct NumberFormat {
  std::string_view name;   // "fp32", "fp64"
  double unit_roundoff;    // 2⁻²⁴, 2⁻⁵³
  double smallest_normal;  // FLT_MIN, DBL_MIN
  double largest;          // FLT_MAX, DBL_MAX
};
inline constexpr NumberFormat kFloat32{"fp32", 0x1p-24, 0x1p-126, 0x1.fffffep127};
inline constexpr NumberFormat kFloat64{"fp64", 0x1p-53, 0x1p-1022, 0x1.fffffffffffffp1023};

// The grid must carry at least this fraction of m0. A grid that holds less samples the far tail
// of the spectrum only (10⁻⁶ of m0 is an rms height 10⁻³ of the sea's); a cascade of bands
// adds its patches up and is judged as a whole.
inline constexpr double kSmallestEnergyFraction = 1e-6;

// What a case puts on its grid: the sums the rule judges, each over the wave vectors that carry
// energy (not k = 0, not the Nyquist row and column), with Δk² = Δkx Δky.
struct SamplingSummary {
  double m0 = 0;              // the spectrum's m0 = ∫∫ Ψ dk, m²
  double m0_on_grid = 0;      // Σ Ψ Δk² = E[mean h²], m²
  double fraction = 0;        // m0_on_grid / m0
  double k_min = 0, k_max = 0;        // the grid's band: min(Δkx, Δky) and the largest |k|, rad/m
  double slope_variance = 0;          // max over x, y of Σ k_a² Ψ Δk² (1)
  double displacement_variance = 0;   // max over x, y of Σ (k_a/|k|)² Ψ Δk² (m², before λ)
  double strain_variance = 0;         // max over the ∂D terms of Σ (k_a k_b/|k|)² Ψ Δk² (before λ)
};

// Evaluates Ψ once per wave vector of the case's grid (0.12 µs each: 0.03 s at 512², 0.5 s at
// 2048²), or takes `travelling` = ½ Ψ(k) Δkx Δky per grid entry in FFT order (what the checks
// compute anyway, validation/periodogram.hpp) when given. Throws InvalidInput when Ψ Δk² is
// not finite somewhere on the grid.
SamplingSummary summarize_sampling(const OceanCase& ocean_case,
                                   const std::vector<double>* travelling = nullptr);

// The bytes the machine has available to a new process (Linux: MemAvailable), or 0 when unknown.
std::uint64_t available_memory_bytes();
// "1.5 GiB": bytes in binary units, three significant digits.
std::string human_bytes(double bytes);

// Applies the rule for frames made or stored in `numbers`. `bytes_needed` is the command's
// working set (0: not checked); it is checked first, before anything of the grid's size is
// allocated or evaluated. `command` names who asks ("swell synth") in the memory message.
void require_valid_sampling(const OceanCase& ocean_case, const NumberFormat& numbers,
                            std::uint64_t bytes_needed = 0, std::string_view command = "",
                            const std::vector<double>* travelling = nullptr);

// Only the memory part: InvalidInput "<command> needs N bytes … the machine has M available".
void require_memory(std::uint64_t bytes_needed, std::string_view command,
                    std::string_view what);

}  // namespace swell::reference
