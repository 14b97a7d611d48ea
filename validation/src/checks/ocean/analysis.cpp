#include "checks/ocean/analysis.hpp"

namespace swell::validation::ocean_analysis {

double mean_square(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x * x;
  return sum / double(v.size());
}

std::vector<const std::vector<double>*> heights(const FrameSequence& frames) {
  std::vector<const std::vector<double>*> out;
  for (std::size_t f = 0; f < frames.frames.size(); ++f) out.push_back(&frames.field(int(f), Field::height));
  return out;
}

[[noreturn]] void throw_rounding_hides_every_wave(double u, const OceanCase& c) {
  throw InvalidInput(fmt::format(
      "the stored values' rounding (unit roundoff {:.2g} relative to the height's rms) hides "
      "every wave vector: none carries 10⁶ times the rounding noise, so no check can judge these "
      "frames ({}); store floats, or 16-bit integers with a value_range close to the values' "
      "extent",
      u, c.describe()));
}

double resolution_floor(double u, double mean_square_height, std::size_t count) {
  return 1e6 * u * u * mean_square_height / double(count);
}

std::string verdict(bool passed) { return passed ? "" : " — FAILED"; }

}  // namespace swell::validation::ocean_analysis
