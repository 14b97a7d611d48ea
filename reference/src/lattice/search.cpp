// The search for rank-1 lattices: Korobov multipliers by their spectral test, Fibonacci
// lattices (lattice.hpp, docs/lattice.md "Generators").
#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <string_view>
#include <utility>

#include "integer_arithmetic.hpp"
#include "lattice/lattice_internal.hpp"
#include "swell/reference/errors.hpp"

namespace swell::reference {
namespace lattice_detail {

double korobov_lambda1_sq_2d(std::int64_t n, std::int64_t a, const double* w, double reject_below) {
  // L⊥ for g = (1, a): h_0 ≡ −a h_1, basis (N, 0), (−a, 1).
  std::int64_t ux = n, uy = 0, vx = -a, vy = 1;
  auto q = [w](std::int64_t x, std::int64_t y) {
    const auto fx = static_cast<double>(x), fy = static_cast<double>(y);
    return fx * fx * w[0] + fy * fy * w[1];
  };
  double qu = q(ux, uy), qv = q(vx, vy);
  if (qv < reject_below) return -1;
  if (qv < qu) {
    std::swap(ux, vx);
    std::swap(uy, vy);
    std::swap(qu, qv);
  }
  for (int iteration = 0; iteration < 400; ++iteration) {
    const double dot = static_cast<double>(ux) * static_cast<double>(vx) * w[0] +
                       static_cast<double>(uy) * static_cast<double>(vy) * w[1];
    if (2 * std::fabs(dot) > qu) {
      const std::int64_t k = std::llround(dot / qu);
      vx -= k * ux;
      vy -= k * uy;
      qv = q(vx, vy);
      if (qv < reject_below) return -1;
    }
    if (qv < qu) {
      std::swap(ux, vx);
      std::swap(uy, vy);
      std::swap(qu, qv);
    } else {
      return qu;
    }
  }
  bug("Lagrange-Gauss reduction did not converge in the spectral search");
}

double korobov_lambda1_sq_3d(std::int64_t n, std::int64_t a, const double* w, double reject_below) {
  const std::int64_t a2 = mul_mod(a, a, n);
  Basis b{};
  b[0] = {n, 0, 0};
  b[1] = {centered(-a, n), 1, 0};
  b[2] = {centered(-a2, n), 0, 1};
  for (int i = 1; i < 3; ++i)
    if (weighted_q<double>(b[i], 3, w) < reject_below) return -1;
  if (!lll_reduce<double>(b, 3, w, reject_below)) return -1;
  const Gram<double> g = gram_schmidt<double>(b, 3, w);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) best = std::min(best, weighted_q<double>(b[i], 3, w));
  if (best < reject_below) return -1;
  bool rejected = false;
  const double zero[3] = {0, 0, 0};
  enumerate(3, g, zero, best * (1 + kEnumerationSlack), [&](const std::int64_t* c, double) {
    if (c[0] == 0 && c[1] == 0 && c[2] == 0) return best * (1 + kEnumerationSlack);
    const Vec h = combination(b, c, 3);
    const double qh = weighted_q<double>(h, 3, w);
    if (qh < reject_below) {
      rejected = true;
      return -1.0;
    }
    best = std::min(best, qh);
    return best * (1 + kEnumerationSlack);
  });
  return rejected ? -1 : best;
}

}  // namespace lattice_detail

using namespace lattice_detail;

std::int64_t fibonacci_number(int j) {
  if (j < 1 || j > 92)
    refuse("Fibonacci index j", "in [1, 92] (F_93 exceeds 2^63)", fmt::format("{}", j));
  std::int64_t previous = 0, current = 1;  // F_0, F_1
  for (int i = 1; i < j; ++i) previous = std::exchange(current, current + previous);
  return current;
}

RankOneLattice fibonacci_lattice(int j, double lx, double ly) {
  if (j < 3 || j > 92)
    refuse("Fibonacci lattice index j", "in [3, 92] (F_3 = 2 points; F_93 exceeds 2^63)", fmt::format("{}", j));
  RankOneLattice out =
      RankOneLattice::create(fibonacci_number(j), {1, fibonacci_number(j - 1)}, {lx, ly});
  out.family_ = "fibonacci";
  return out;
}

int fibonacci_index(std::int64_t points) {
  std::int64_t below = 0, above = 0;
  int below_j = 0;
  for (int j = 3; j <= 92; ++j) {
    const std::int64_t f = fibonacci_number(j);
    if (f == points) return j;
    if (f < points) {
      below = f;
      below_j = j;
    } else {
      above = f;
      break;
    }
  }
  std::string nearest;
  if (below_j == 0) {
    nearest = fmt::format("the smallest is F_3 = 2");
  } else if (above == 0) {
    nearest = fmt::format("the largest in int64 is F_92 = {}", below);
  } else {
    nearest = fmt::format("the nearest are F_{} = {} and F_{} = {}", below_j, below, below_j + 1, above);
  }
  refuse("lattice points", "a Fibonacci number F_j, j ≥ 3", fmt::format("{}; {}", points, nearest));
}

RankOneLattice korobov_lattice(std::int64_t points, std::int64_t a, std::vector<double> lengths) {
  validate_points(points);
  validate_dimension(lengths.size(), "Korobov lattice dimension (number of lengths)");
  if (a < 1 || a >= points)
    refuse("Korobov multiplier a", fmt::format("in [1, N) = [1, {})", points), fmt::format("{}", a));
  std::vector<std::int64_t> g = {1, a};
  if (lengths.size() == 3) g.push_back(mul_mod(a, a, points));
  RankOneLattice out = RankOneLattice::create(points, std::move(g), std::move(lengths));
  out.family_ = "korobov";
  return out;
}

std::int64_t korobov_spectral_choice(std::int64_t points, int dimension, std::vector<double> lengths) {
  validate_points(points);
  validate_dimension(static_cast<std::size_t>(std::max(dimension, 0)), "Korobov lattice dimension");
  validate_lengths(lengths, static_cast<std::size_t>(dimension));
  const Metric m(lengths);
  const bool inverse_is_isometry =
      dimension == 2 ? lengths[0] == lengths[1] : lengths[0] == lengths[2];
  double best_q = -1;
  std::int64_t best_a = 0;
  for (std::int64_t a = 1; a <= points / 2; ++a) {
    if (std::gcd(a, points) != 1) continue;
    if (inverse_is_isometry) {
      const std::int64_t inv = inverse_mod(a, points);
      if (std::min(inv, points - inv) < a) continue;  // its orbit's smallest member came first
    }
    const double reject_below = best_q < 0 ? -1 : best_q * (1 - kSearchTie);
    const double q = dimension == 2 ? korobov_lambda1_sq_2d(points, a, m.w, reject_below)
                                    : korobov_lambda1_sq_3d(points, a, m.w, reject_below);
    if (q > best_q * (1 + kSearchTie) || best_q < 0) {
      best_q = q;
      best_a = a;
    }
  }
  if (best_a == 0) bug("no admissible Korobov multiplier");
  return best_a;
}

RankOneLattice korobov_lattice(std::int64_t points, std::vector<double> lengths) {
  validate_dimension(lengths.size(), "Korobov lattice dimension (number of lengths)");
  const std::int64_t a = korobov_spectral_choice(points, static_cast<int>(lengths.size()), lengths);
  return korobov_lattice(points, a, std::move(lengths));
}

}  // namespace swell::reference
