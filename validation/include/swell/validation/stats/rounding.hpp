#pragma once
// The rounding budgets of swell's exact checks (docs/checks.md §3). A transform of N points moves
// a value by a few u log₂N of the field's scale (u the unit roundoff of the numbers: the stored
// type's for frames, fp64's for the analysis); each budget is c · u · log₂N with a multiple c
// that covers the constants of its path, named here once.
namespace swell::validation {

// Sums and products in fp64 around one transform (parseval's Σ h² against N Σ |ĥ|²).
inline constexpr double kSumRounding = 8;
// A value after one transform of a stored field: the imaginary residue, Hermitian symmetry, a
// spectrum's rounding noise, the amplitudes the fits recover.
inline constexpr double kTransformRounding = 16;
// A quantity built from several transforms and products: a fitted frequency or residual, a
// spectral moment, the derived fields' own rounding.
inline constexpr double kCompoundRounding = 64;

// c · u · log₂N (evaluated in that order, so every check's bound is the same double wherever it
// is computed).
constexpr double rounding_budget(double multiple, double unit_roundoff, double log2n) {
  return multiple * unit_roundoff * log2n;
}

}  // namespace swell::validation
