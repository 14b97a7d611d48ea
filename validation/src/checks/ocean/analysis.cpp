#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/statistics.hpp"

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

RingShape ring_shape(std::vector<NormalizedOrdinate> ordinates) {
  std::sort(ordinates.begin(), ordinates.end(),
            [](const NormalizedOrdinate& x, const NormalizedOrdinate& y) { return x.k < y.k; });
  RingShape out;
  const int n = int(ordinates.size());
  if (n == 0) return out;
  out.rings = std::clamp(n / 64, 1, 24);
  std::vector<double> p_values;
  out.low_ratio = 1e300, out.high_ratio = 0;
  for (int r = 0; r < out.rings; ++r) {
    const int begin = r * n / out.rings, end = (r + 1) * n / out.rings;
    double sum = 0;
    for (int i = begin; i < end; ++i) sum += ordinates[i].u;
    const double count = end - begin;
    const double p = std::min(1.0, 2 * std::min(stats::gamma_lower_p(count, sum),
                                                stats::gamma_upper_p(count, sum)));
    p_values.push_back(p);
    const double ratio = sum / count;
    out.ratios.push_back(ratio);
    out.counts.push_back(int(count));
    out.low_ratio = std::min(out.low_ratio, ratio);
    out.high_ratio = std::max(out.high_ratio, ratio);
    if (p <= out.worst_p) {
      out.worst_p = p;
      out.worst_ratio = ratio;
      out.worst_k = 0.5 * (ordinates[begin].k + ordinates[end - 1].k);
    }
  }
  out.p = stats::fisher_combined_p(p_values);
  return out;
}

std::string verdict(bool passed) { return passed ? "" : " — FAILED"; }

}  // namespace swell::validation::ocean_analysis
