#include "swell/validation/stats/rounding.hpp"
#include "swell/validation/checks/space_time_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "swell/reference/dispersion.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/stats/periodogram.hpp"

namespace swell::validation {
namespace {

// (h·g) mod N, exact: each component reduced mod N first, so products stay below N² ≤ 2^60.
std::int64_t residue(std::int64_t n, std::int64_t m, std::int64_t s,
                     const std::vector<std::int64_t>& g, std::int64_t points) {
  std::int64_t r = 0;
  const std::int64_t h[3] = {n, m, s};
  for (int d = 0; d < 3; ++d) {
    std::int64_t c = h[d] % points;
    if (c < 0) c += points;
    r = (r + c * g[static_cast<std::size_t>(d)]) % points;
  }
  return r;
}

struct Image {
  std::vector<char> on;  // per class: the image of a vector on the surface
  std::int64_t vectors = 0, classes = 0;
};

// The classes of the vectors (n, m, ±q(k)) of the band, with q(k) from a dispersion ω(k) (rad/s).
Image image(const reference::RankOneLattice& lattice,
            std::span<const std::array<std::int32_t, 2>> wave_vectors, double dkx, double dky,
            const std::function<std::int64_t(double)>& q_of_k) {
  const std::int64_t points = lattice.points();
  Image out;
  out.on.assign(static_cast<std::size_t>(points), 0);
  auto mark = [&](std::int64_t n, std::int64_t m, std::int64_t s) {
    char& on = out.on[static_cast<std::size_t>(residue(n, m, s, lattice.generator(), points))];
    ++out.vectors;
    if (!on) ++out.classes;
    on = 1;
  };
  for (const auto& [n, m] : wave_vectors) {
    const std::int64_t q = q_of_k(std::hypot(n * dkx, m * dky));
    mark(n, m, -q);
    if (q != 0) mark(n, m, q);
  }
  return out;
}

double off_fraction(const std::vector<double>& energy, const Image& img, double total) {
  long double off = 0;
  for (std::size_t r = 0; r < energy.size(); ++r) {
    if (!img.on[r]) off += energy[r];
  }
  return static_cast<double>(off / total);
}

}  // namespace

CheckResult space_time_dispersion(std::span<const double> samples,
                                  const reference::RankOneLattice& lattice,
                                  const reference::OceanCase& ocean_case,
                                  std::span<const std::array<std::int32_t, 2>> wave_vectors,
                                  double unit_roundoff) {
  const double period = ocean_case.loop_period;
  require(std::isfinite(period) && period > 0, "loop_period",
          "finite and > 0 s for a space-time surface", period);
  require(unit_roundoff > 0 && unit_roundoff < 1, "unit_roundoff", "in (0, 1)", unit_roundoff);
  if (lattice.dimension() != 3) {
    throw InvalidInput(fmt::format("space-time samples need a 3-D lattice over (Lx, Ly, T); {} is "
                                   "{}-D",
                                   lattice.describe(), lattice.dimension()));
  }
  const std::int64_t points = lattice.points();
  if (samples.size() != static_cast<std::size_t>(points)) {
    throw InvalidInput(fmt::format("{} space-time samples for a lattice of N = {} points",
                                   samples.size(), points));
  }
  require(points <= std::numeric_limits<int>::max(), "space-time lattice points N",
          "≤ 2^31 − 1 (a transform's size is an int)", double(points));
  const std::array<double, 3> want = {ocean_case.grid.lx, ocean_case.grid.ly, period};
  for (std::size_t d = 0; d < 3; ++d) {
    if (std::abs(lattice.lengths()[d] - want[d]) > 1e-12 * want[d]) {
      throw InvalidInput(fmt::format(
          "space-time lattice {} spans {:g} × {:g} × {:g}; the case's patch and loop period are "
          "{:g} m × {:g} m × {:g} s",
          lattice.describe(), lattice.lengths()[0], lattice.lengths()[1], lattice.lengths()[2],
          want[0], want[1], want[2]));
    }
  }
  if (wave_vectors.empty()) throw InvalidInput("space-time dispersion check: the band is empty");

  // The analysis: forward 1-D FFT of the N samples / N (fp64 FFTW), one coefficient per class.
  const std::vector<double> field(samples.begin(), samples.end());
  const auto spectrum = field_spectrum(field, reference::Grid{static_cast<int>(points), 1,
                                                              ocean_case.grid.lx, ocean_case.grid.ly});
  std::vector<double> energy(spectrum.size());
  long double total_sum = 0;
  for (std::size_t r = 0; r < spectrum.size(); ++r) {
    energy[r] = std::norm(spectrum[r]);
    total_sum += energy[r];
  }
  const double total = static_cast<double>(total_sum);

  const double omega0 = 2 * std::numbers::pi / period;
  const double dkx = ocean_case.grid.dkx(), dky = ocean_case.grid.dky();
  auto quantized_down = [&](double omega) { return std::int64_t(std::floor(omega / omega0)); };
  const Image right = image(lattice, wave_vectors, dkx, dky, [&](double k) {
    return std::int64_t(std::llround(ocean_case.omega(k) / omega0));
  });

  const double log2n = std::log2(double(points));
  const double bound = std::pow(rounding_budget(kTransformRounding, unit_roundoff, log2n), 2);
  const std::string subject =
      fmt::format("{}, loop period T = {:g} s, {}", ocean_case.describe(), period, lattice.describe());
  const std::string criterion =
      fmt::format("off-surface energy fraction ≤ (16 u log2 N)² = {:.1e} (rounding)", bound);
  CheckResult result;
  result.check = "space_time.dispersion";
  result.subject = subject;
  result.expected = 0;
  result.tolerance = bound;
  result.criterion = criterion;
  if (!(total > 0)) {
    result.measured = std::nan("");
    result.passed = false;
    result.reason = "the samples carry no energy (all zero): nothing to judge";
    return result;
  }
  const double fraction = off_fraction(energy, right, total);
  result.measured = fraction;
  result.passed = fraction <= bound;  // false for NaN
  const std::string merged =
      right.classes < right.vectors
          ? fmt::format("; the lattice merges the surface's {} vectors into {} classes (not "
                        "injective on them)",
                        right.vectors, right.classes)
          : "";
  if (result.passed) {
    result.reason = fmt::format(
        "{:.2e} of the energy lies off the case's dispersion surface ({} vectors of the band in "
        "{} of the N = {} classes){}",
        fraction, right.vectors, right.classes, points, merged);
    return result;
  }
  // What the samples follow instead, when another relation explains them to rounding.
  struct Candidate {
    std::string name;
    std::function<std::int64_t(double)> q;
  };
  std::vector<Candidate> candidates;
  const double g = ocean_case.gravity;
  if (!std::isinf(ocean_case.depth)) {
    const auto deep = reference::Dispersion::deep(g);
    candidates.push_back({fmt::format("deep-water dispersion ω² = g k (the case's depth is {:g} m)",
                                      ocean_case.depth),
                          [&, deep](double k) { return quantized_down(deep.omega(k)); }});
  }
  candidates.push_back({"ω = g k (ω² used where ω is meant: a missing square root)",
                        [&](double k) { return quantized_down(g * k); }});
  const auto unquantized = reference::Dispersion::finite_depth(ocean_case.depth, g);
  candidates.push_back({"ω rounded to the nearest multiple of 2π/T instead of down",
                        [&](double k) { return std::int64_t(std::llround(unquantized.omega(k) / omega0)); }});
  std::string explanation = "no candidate relation (deep water, ω = g k, ω rounded to the nearest "
                            "2π/T) explains them";
  for (const auto& c : candidates) {
    const Image other = image(lattice, wave_vectors, dkx, dky, c.q);
    if (off_fraction(energy, other, total) <= bound) {
      explanation = "they follow " + c.name;
      break;
    }
  }
  result.reason = fmt::format(
      "{:.3g} of the energy lies in classes off the case's dispersion surface ω(k) = {} quantized "
      "down to multiples of 2π/T ({} vectors of the band in {} of N = {} classes){} — the samples "
      "do not evolve as the case's dispersion says; {}",
      fraction, unquantized.describe(), right.vectors, right.classes, points, merged, explanation);
  return result;
}

}  // namespace swell::validation
