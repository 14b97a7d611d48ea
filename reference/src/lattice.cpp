// Rank-1 lattices (lattice.hpp): the lattice made and validated, and its wave-vector table.
// The reduction, the search and the merits are beside it in lattice/.
#include "swell/reference/lattice.hpp"

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

[[noreturn]] void refuse(std::string_view what, std::string_view rule, std::string_view got) {
  throw InvalidInput(fmt::format("{} must be {} (got {})", what, rule, got));
}

[[noreturn]] void bug(std::string_view what) {
  throw InternalError(fmt::format("rank-1 lattice: {} (a bug in swell)", what));
}

void validate_lengths(const std::vector<double>& lengths, std::size_t s) {
  if (lengths.size() != s)
    refuse("lattice lengths", fmt::format("one per generator component ({})", s),
           fmt::format("{} lengths", lengths.size()));
  for (std::size_t d = 0; d < s; ++d) {
    if (!(std::isfinite(lengths[d]) && lengths[d] > 0))
      refuse(fmt::format("lattice length {}", d), "finite and > 0", fmt::format("{}", lengths[d]));
  }
  const auto [lo, hi] = std::minmax_element(lengths.begin(), lengths.end());
  if (*hi / *lo > kMaxLatticeLengthRatio)
    refuse("lattice length ratio max/min", "at most 2^20 = 1048576",
           fmt::format("{:g} / {:g} = {:g}", *hi, *lo, *hi / *lo));
}

void validate_points(std::int64_t points) {
  if (points < 2 || points > kMaxLatticePoints)
    refuse("lattice points N", fmt::format("in [2, 2^30 = {}]", kMaxLatticePoints),
           fmt::format("{}", points));
}

void validate_dimension(std::size_t s, std::string_view what) {
  if (s != 2 && s != 3) refuse(what, "2 or 3", fmt::format("{}", s));
}

void fill_table(std::int64_t n, const std::vector<std::int64_t>& g, const Basis& b,
                const Metric& m, std::vector<std::int32_t>& table) {
  const int s = static_cast<int>(g.size());
  const auto us = static_cast<std::size_t>(s);
  table.assign(static_cast<std::size_t>(n) * us, 0);

  // u with u·g ≡ 1: Bézout over (g, N), which the gcd rule makes 1.
  const BezoutMod bz = bezout_mod(g, n);
  if (bz.gcd != 1) bug("generator passed the gcd rule but has no inverse");
  const Vec u = bz.coef;

  // Fractional coordinates of u in the reduced basis: t(u) = u B⁻¹ = u adj(B) / det(B), and
  // det(B) = ±N, so A = N t(u) = ±Σ_d u_d C[i][d] is an exact integer vector.
  const auto cof = cofactors(b, s);
  Int128 det = 0;
  for (int d = 0; d < s; ++d) det += Int128{b[0][d]} * cof[0][d];
  if (det != n && det != -n) bug("reduced dual basis does not have determinant ±N");
  const int sign = det > 0 ? 1 : -1;
  std::int64_t a[3] = {0, 0, 0};
  Vec shifted = u;  // u − Σ ⌊t_i(u)⌋ b_i = Σ (a_i / N) b_i, inside the parallelepiped
  for (int i = 0; i < s; ++i) {
    Int128 big = 0;
    for (int d = 0; d < s; ++d) big += Int128{u[d]} * cof[i][d];
    big *= sign;
    a[i] = floor_mod(big, n);
    const auto whole = static_cast<std::int64_t>((big - a[i]) / n);
    subtract_multiple(shifted, whole, b[i], s);
  }
  for (int d = 0; d < s; ++d) {
    Int128 check = 0;
    for (int i = 0; i < s; ++i) check += Int128{a[i]} * b[i][d];
    if (check != Int128{shifted[d]} * n) bug("fractional coordinates of u");
  }

  const Gram<double> gram = to_double(gram_schmidt<long double>(b, s, m.wl));
  const double inv_n = 1.0 / static_cast<double>(n);
  Vec p{};                              // representative of class m, Σ (f_i / N) b_i
  std::int64_t f[3] = {0, 0, 0};
  const std::int64_t half = n / 2;
  for (std::int64_t cls = 1; cls <= half; ++cls) {
    for (int d = 0; d < s; ++d) p[d] += shifted[d];
    for (int i = 0; i < s; ++i) {
      f[i] += a[i];
      if (f[i] >= n) {
        f[i] -= n;
        for (int d = 0; d < s; ++d) p[d] -= b[i][d];
      }
    }
    const double t[3] = {static_cast<double>(f[0]) * inv_n, static_cast<double>(f[1]) * inv_n,
                         static_cast<double>(f[2]) * inv_n};
    std::int64_t best[3] = {0, 0, 0};
    bool have = false;
    double best_d2 = std::numeric_limits<double>::infinity();
    enumerate(s, gram, t, best_d2, [&](const std::int64_t* c, double d2) {
      std::int64_t k[3] = {0, 0, 0};
      for (int d = 0; d < s; ++d) {
        std::int64_t x = p[d];
        for (int i = 0; i < s; ++i) x -= c[i] * b[i][d];
        k[d] = x;
      }
      if (!have || compare_vectors(m, k, best) < 0) {
        std::copy(k, k + s, best);
        have = true;
      }
      best_d2 = std::min(best_d2, d2);
      return best_d2 * (1 + kEnumerationSlack);
    });
    std::int32_t* row = table.data() + static_cast<std::size_t>(cls) * us;
    std::int32_t* mirror = table.data() + static_cast<std::size_t>(n - cls) * us;
    for (int d = 0; d < s; ++d) {
      // |k_d| ≤ N/2 for a minimal vector (N e_d ∈ L⊥ bounds the Voronoi cell's slab).
      if (best[d] > n / 2 || best[d] < -(n / 2)) bug("wave vector outside the slab |k_d| ≤ N/2");
      row[d] = static_cast<std::int32_t>(best[d]);
      if (cls != n - cls) mirror[d] = static_cast<std::int32_t>(-best[d]);
    }
  }
  // The invariant everything downstream relies on, checked once in exact integers.
  for (std::int64_t cls = 0; cls < n; ++cls) {
    const std::int32_t* row = table.data() + static_cast<std::size_t>(cls) * us;
    Int128 dot = 0;
    for (int d = 0; d < s; ++d) dot += Int128{row[d]} * g[d];
    if (floor_mod(dot, n) != cls) bug("wave vector in the wrong residue class");
  }
}

std::string join(const std::vector<std::int64_t>& g) {
  std::string out;
  for (std::size_t d = 0; d < g.size(); ++d) out += fmt::format("{}{}", d ? "," : "", g[d]);
  return out;
}

}  // namespace lattice_detail

using namespace lattice_detail;

RankOneLattice RankOneLattice::create(std::int64_t points, std::vector<std::int64_t> generator,
                                      std::vector<double> lengths) {
  validate_points(points);
  validate_dimension(generator.size(), "lattice dimension (generator components)");
  for (std::size_t d = 0; d < generator.size(); ++d) {
    if (generator[d] < 0 || generator[d] >= points)
      refuse(fmt::format("lattice generator component g_{}", d),
             fmt::format("in [0, N) = [0, {})", points), fmt::format("{}", generator[d]));
  }
  std::int64_t common = points;
  for (const std::int64_t gd : generator) common = std::gcd(common, gd);
  if (common != 1)
    refuse(fmt::format("lattice generator ({}) with N = {}", join(generator), points),
           "such that gcd(g_0, …, g_{s−1}, N) = 1 (else the N points repeat)",
           fmt::format("gcd {}", common));
  validate_lengths(lengths, generator.size());

  RankOneLattice out;
  out.points_ = points;
  out.generator_ = std::move(generator);
  out.lengths_ = std::move(lengths);
  const int s = out.dimension();
  const Metric m(out.lengths_);
  Basis b = hermite_dual_basis(points, out.generator_);
  if (s == 2) {
    gauss_reduce(b, m);
  } else {
    lll_reduce<long double>(b, s, m.wl, -1);
  }
  out.basis_ = b;
  fill_table(points, out.generator_, b, m, out.table_);
  return out;
}

std::array<double, 3> RankOneLattice::point(std::int64_t n) const {
  if (n < 0 || n >= points_)
    refuse("lattice point index n", fmt::format("in [0, N) = [0, {})", points_), fmt::format("{}", n));
  std::array<double, 3> x{};
  for (std::size_t d = 0; d < generator_.size(); ++d)
    x[d] = lengths_[d] * (static_cast<double>(mul_mod(n, generator_[d], points_)) / static_cast<double>(points_));
  return x;
}

std::int64_t RankOneLattice::residue(std::span<const std::int64_t> k) const {
  if (k.size() != generator_.size())
    refuse("wave vector for residue()", fmt::format("{} components", generator_.size()),
           fmt::format("{}", k.size()));
  Int128 dot = 0;
  for (std::size_t d = 0; d < k.size(); ++d) dot += Int128{k[d]} * generator_[d];
  return floor_mod(dot, points_);
}

std::int64_t RankOneLattice::residue(std::span<const std::int32_t> k) const {
  if (k.size() != generator_.size())
    refuse("wave vector for residue()", fmt::format("{} components", generator_.size()),
           fmt::format("{}", k.size()));
  std::array<std::int64_t, 3> wide{};
  std::copy(k.begin(), k.end(), wide.begin());
  return residue(std::span<const std::int64_t>(wide.data(), k.size()));
}

std::span<const std::int32_t> RankOneLattice::wave_vector(std::int64_t m) const {
  if (m < 0 || m >= points_)
    refuse("lattice coefficient index m", fmt::format("in [0, N) = [0, {})", points_), fmt::format("{}", m));
  const std::size_t s = generator_.size();
  return std::span<const std::int32_t>(table_).subspan(static_cast<std::size_t>(m) * s, s);
}

std::array<double, 3> RankOneLattice::wave_number(std::int64_t m) const {
  const auto k = wave_vector(m);
  std::array<double, 3> out{};
  for (std::size_t d = 0; d < k.size(); ++d)
    out[d] = static_cast<double>(kTwoPi * k[d] / static_cast<long double>(lengths_[d]));
  return out;
}

bool RankOneLattice::carries_energy(std::int64_t m) const {
  if (m < 0 || m >= points_)
    refuse("lattice coefficient index m", fmt::format("in [0, N) = [0, {})", points_), fmt::format("{}", m));
  return m != 0 && !(points_ % 2 == 0 && m == points_ / 2);
}

std::string RankOneLattice::describe() const {
  std::string box;
  for (std::size_t d = 0; d < lengths_.size(); ++d) box += fmt::format("{}{:g}", d ? "×" : "", lengths_[d]);
  return fmt::format("{} N={} g=({}) over {}{}", family_, points_, join(generator_), box,
                     lengths_.size() == 2 ? " m" : "");
}

double RankOneLattice::patch_norm(std::span<const std::int64_t> k) const {
  if (k.size() != generator_.size())
    refuse("wave vector for patch_norm()", fmt::format("{} components", generator_.size()),
           fmt::format("{}", k.size()));
  long double sum = 0;
  for (std::size_t d = 0; d < k.size(); ++d) {
    const long double x = kTwoPi * static_cast<long double>(k[d]) / static_cast<long double>(lengths_[d]);
    sum += x * x;
  }
  return static_cast<double>(std::sqrt(sum));
}

}  // namespace swell::reference
