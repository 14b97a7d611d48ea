#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"

namespace swell::validation::ocean_analysis {

// A real field's spectrum is Hermitian to rounding whatever the engine did; what an engine can
// get wrong shows in the imaginary part of a complex synthesis, when it hands that over. The
// imaginary residue of a right synthesis is the transform's rounding, ≲ u log2 N of the field.
void HermitianFold::add(const Analysis& a, std::size_t f, const reference::FieldFrame& frame,
                        std::span<const Complex> spectrum) {
  for (const auto& [field, values] : frame.fields) {
    const auto imaginary = frame.imaginary.find(field);
    if (imaginary != frame.imaginary.end()) {
      any_imaginary = true;
      const double residue =
          std::sqrt(mean_square(imaginary->second) / std::max(mean_square(values), 1e-300));
      if (residue >= worst_residue) {
        worst_residue = residue;
        residue_where = fmt::format("{} frame {}", reference::field_name(field), f);
      }
    }
  }
  // The first frame and the last: the engine's sign conventions do not change between them.
  if (f == 0 || f + 1 == a.frame_count()) {
    double largest = 0, asymmetry = 0;
    for (const Wave& w : a.half_plane()) {
      largest = std::max(largest, std::abs(spectrum[w.index]));
      asymmetry = std::max(asymmetry, std::abs(spectrum[w.index] - std::conj(spectrum[w.minus_index])));
    }
    const double relative = asymmetry / std::max(largest, 1e-300);
    if (relative >= worst_symmetry) {
      worst_symmetry = relative;
      symmetry_where = fmt::format("height frame {}", f);
    }
  }
}

Results check_hermitian(const Analysis& a, OceanCheckReport&) {
  Results out;
  const HermitianFold& fold = a.pass().hermitian;
  const double worst_residue = fold.worst_residue, worst_symmetry = fold.worst_symmetry;
  const std::string& residue_where = fold.residue_where;
  const std::string& symmetry_where = fold.symmetry_where;
  const bool any_imaginary = fold.any_imaginary;
  const double symmetry_bound = rounding_budget(kTransformRounding, kFp64Roundoff, a.log2n());
  out.push_back(bounded_check("hermitian.symmetry", a.subject(), worst_symmetry, symmetry_bound,
                        fmt::format("max|ĥ(k) − conj ĥ(−k)| / max|ĥ| ≤ {:.1e}", symmetry_bound),
                        fmt::format("height spectrum Hermitian to {:.1e} ({}){}", worst_symmetry,
                                    symmetry_where, verdict(worst_symmetry <= symmetry_bound))));
  if (any_imaginary) {
    const double bound = rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n());
    const bool ok = worst_residue <= bound;
    out.push_back(bounded_check(
        "hermitian.imaginary_residue", a.subject(), worst_residue, bound,
        fmt::format("rms(Im) / rms(Re) ≤ {:.1e}", bound),
        ok ? fmt::format("imaginary residue {:.1e} of the field ({})", worst_residue, residue_where)
           : fmt::format("imaginary residue {:.2g} of the field ({}): h̃(−k) is not conj(h̃(k)) — "
                         "missing conjugate pairing",
                         worst_residue, residue_where)));
  }
  return out;
}

}  // namespace swell::validation::ocean_analysis
