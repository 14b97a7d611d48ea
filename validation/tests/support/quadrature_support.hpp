#pragma once
// The tests' own quadrature, independent of reference/'s Gauss–Kronrod: Boost's double-
// exponential rules (tanh-sinh on finite pieces, exp-sinh on [a, ∞)).
#include <algorithm>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <functional>
#include <vector>

namespace swell::test {

// ∫_a^b f, requested to `tolerance` relative. On [a, ∞) the integrand is cut at 1e12 a:
// exp-sinh samples out to ~1e300, and the slowest tail integrated by these tests, an ω⁻² (m2 of
// an ω⁻⁴ spectrum), leaves 1e-12 of its piece beyond that.
inline double integrate(const std::function<double(double)>& f, double a, double b,
                        double tolerance = 1e-13) {
  static boost::math::quadrature::tanh_sinh<double> tanh_sinh;
  static boost::math::quadrature::exp_sinh<double> exp_sinh;
  double error = 0, l1 = 0;
  if (std::isinf(b)) {
    auto cut = [&](double x) { return x > 1e12 * a ? 0.0 : f(x); };
    return exp_sinh.integrate(cut, a, b, tolerance, &error, &l1);
  }
  return tanh_sinh.integrate(f, a, b, tolerance, &error, &l1);
}

// ∫ over [min cut, ∞) in the pieces between consecutive cuts (in any order), so each piece is
// smooth: a peak, a kink or a branch of a piecewise law sits at a cut.
inline double integrate_pieces(const std::function<double(double)>& f, std::vector<double> cuts,
                               double tolerance = 1e-13) {
  std::sort(cuts.begin(), cuts.end());
  double sum = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (cuts[i + 1] > cuts[i]) sum += integrate(f, cuts[i], cuts[i + 1], tolerance);
  }
  return sum + integrate(f, cuts.back(), INFINITY, tolerance);
}

// ∫ f dθ over (−π, π], split at −π/2, 0, π/2 (the peak of every spreading model and the kinks
// of the one-sided and non-integer |cos θ|^p laws), each piece by tanh-sinh to 1e-14.
inline double circle_integral(const std::function<double(double)>& f) {
  static boost::math::quadrature::tanh_sinh<double> ts;
  constexpr double pi = 3.141592653589793238462643383279502884;
  double sum = 0;
  const double cuts[] = {-pi, -pi / 2, 0.0, pi / 2, pi};
  for (int i = 0; i < 4; ++i) {
    double error = 0, l1 = 0;
    sum += ts.integrate(f, cuts[i], cuts[i + 1], 1e-14, &error, &l1);
  }
  return sum;
}

// Golden-section search for the maximum of f on [a, b] (unimodal there), to ~√ε relative.
template <class F>
double golden_section_maximum(F f, double a, double b) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double c = b - r * (b - a), d = a + r * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < 200 && (b - a) > 1e-15 * b; ++i) {
    if (fc > fd) {
      b = d, d = c, fd = fc, c = b - r * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd, d = a + r * (b - a), fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace swell::test
