#pragma once
// Internal to the sweep room: what its three parts share — the case keys and points
// (spec.cpp), one run and its row (run.cpp), the outputs over every run (outputs.cpp).
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "swell/reference/ocean_case.hpp"
#include "swell/validation/sweep/sweep.hpp"

namespace swell::validation::sweep::detail {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Shortest text that reads back as the same double ("" for NaN: an empty CSV cell).
inline std::string text(double x) { return std::isfinite(x) ? fmt::format("{}", x) : std::string(); }

// The whole string as a number, or none.
std::optional<double> parse_number(const std::string& s);

// The index of each variation's value at point `point` (the last variation varies fastest).
std::vector<std::size_t> value_indices(const SweepSpec& spec, std::size_t point);

// Frequency moments of a power spectrum over the grid's wave vectors k ≠ 0 (FFT order), each at
// ω(|k|) of the case's dispersion: m_n = Σ P(k) ω^n for n = 0, 1, 2, and the peak band of ω
// (bands 4 % wide, as the moments check) with its P-weighted ω. Used for a run's periodogram and
// for a point's expected μ(k).
struct FrequencyMoments {
  double m[3] = {0, 0, 0};
  double peak_omega = kNaN;  // P-weighted ω of the most energetic band
  double tm01() const { return m[1] > 0 ? 2 * kPi * m[0] / m[1] : kNaN; }
  double tm02() const { return m[2] > 0 ? 2 * kPi * std::sqrt(m[0] / m[2]) : kNaN; }
};
FrequencyMoments frequency_moments(const reference::OceanCase& ocean, const std::vector<double>& power);

}  // namespace swell::validation::sweep::detail
