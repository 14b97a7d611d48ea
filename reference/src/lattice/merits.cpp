// A lattice's merits: its P2 discrepancy, its shortest dual vectors and its covering radius
// (lattice.hpp, docs/lattice.md).
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

// An obtuse superbase v_0 … v_s (Σ v_i = 0, ⟨v_i, v_j⟩ ≤ 0 for i ≠ j) of the lattice.
std::vector<Vec> obtuse_superbase(const Basis& b, int s, const Metric& m) {
  auto sum = [s](const Vec& x, const Vec& y, std::int64_t sy) {
    Vec r{};
    for (int d = 0; d < s; ++d) r[d] = x[d] + sy * y[d];
    return r;
  };
  Vec zero{};
  if (s == 2) {
    // Gauss-reduced: if ⟨b_0, b_1⟩ ≤ 0, (b_0, b_1, −b_0 − b_1) is obtuse; otherwise
    // (b_0, −b_1, b_1 − b_0), since ⟨b_0, b_1⟩ ≤ ‖b_0‖²/2 ≤ ‖b_1‖²/2.
    if (m.dotl(b[0].data(), b[1].data()) <= 0)
      return {b[0], b[1], sum(sum(zero, b[0], -1), b[1], -1)};
    return {b[0], sum(zero, b[1], -1), sum(b[1], b[0], -1)};
  }
  // Selling's reduction: while some ⟨v_i, v_j⟩ > 0, v_i → −v_i and v_k → v_k + v_i for the
  // other two; Σ ‖v‖² drops by 2⟨v_i, v_j⟩ each time, so it ends (quickly from an LLL basis).
  std::vector<Vec> v = {sum(sum(sum(zero, b[0], -1), b[1], -1), b[2], -1), b[0], b[1], b[2]};
  for (int iteration = 0;; ++iteration) {
    if (iteration > 10000) bug("Selling reduction did not converge");
    bool changed = false;
    for (int i = 0; i < 4 && !changed; ++i) {
      for (int j = i + 1; j < 4 && !changed; ++j) {
        const long double p = m.dotl(v[i].data(), v[j].data());
        const long double scale = std::sqrt(m.ql(v[i].data()) * m.ql(v[j].data()));
        if (p <= 1e-15L * scale) continue;
        for (int k = 0; k < 4; ++k)
          if (k != i && k != j) v[k] = sum(v[k], v[i], 1);
        v[i] = sum(zero, v[i], -1);
        changed = true;
      }
    }
    if (!changed) return v;
  }
}

VoronoiCell voronoi_cell(const Basis& b, int s, const Metric& m) {
  const std::vector<Vec> v = obtuse_superbase(b, s, m);
  // The 2^{s+1} − 2 partial sums, in Euclidean K coordinates (rad/m).
  std::vector<std::array<long double, 3>> rel;
  const int parts = s + 1;
  for (int mask = 1; mask < (1 << parts) - 1; ++mask) {
    std::array<long double, 3> y{};
    for (int i = 0; i < parts; ++i) {
      if (!(mask & (1 << i))) continue;
      for (int d = 0; d < s; ++d)
        y[d] += static_cast<long double>(v[i][d]) * m.root_w[d] * m.unit;
    }
    rel.push_back(y);
  }
  auto dot = [s](const std::array<long double, 3>& x, const std::array<long double, 3>& y) {
    long double r = 0;
    for (int d = 0; d < s; ++d) r += x[d] * y[d];
    return r;
  };
  VoronoiCell out;
  out.shortest_relevant = std::numeric_limits<long double>::infinity();
  for (const auto& y : rel) out.shortest_relevant = std::min(out.shortest_relevant, std::sqrt(dot(y, y)));
  // Vertices: x with ⟨x, y⟩ = ‖y‖²/2 for s of the relevant vectors, inside all the others'
  // half-spaces. Cramer's rule on s×s systems (long double); parallel planes are skipped.
  const std::size_t r = rel.size();
  long double best2 = 0;
  auto feasible = [&](const std::array<long double, 3>& x) {
    for (const auto& y : rel)
      if (dot(x, y) > dot(y, y) / 2 * (1 + 1e-12L)) return false;
    return true;
  };
  if (s == 2) {
    for (std::size_t i = 0; i < r; ++i) {
      for (std::size_t j = i + 1; j < r; ++j) {
        const auto& p = rel[i];
        const auto& q = rel[j];
        const long double det = p[0] * q[1] - p[1] * q[0];
        if (std::fabs(det) <= 1e-12L * std::sqrt(dot(p, p) * dot(q, q))) continue;
        const long double cp = dot(p, p) / 2, cq = dot(q, q) / 2;
        const std::array<long double, 3> x = {(cp * q[1] - cq * p[1]) / det, (p[0] * cq - q[0] * cp) / det, 0};
        if (feasible(x)) best2 = std::max(best2, dot(x, x));
      }
    }
  } else {
    for (std::size_t i = 0; i < r; ++i) {
      for (std::size_t j = i + 1; j < r; ++j) {
        for (std::size_t k = j + 1; k < r; ++k) {
          const auto& p = rel[i];
          const auto& q = rel[j];
          const auto& t = rel[k];
          // x = (c_p (q × t) + c_q (t × p) + c_t (p × q)) / det, det = p · (q × t).
          auto cross = [](const std::array<long double, 3>& x, const std::array<long double, 3>& y) {
            return std::array<long double, 3>{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                                              x[0] * y[1] - x[1] * y[0]};
          };
          const auto qt = cross(q, t), tp = cross(t, p), pq = cross(p, q);
          const long double det = dot(p, qt);
          if (std::fabs(det) <= 1e-12L * std::sqrt(dot(p, p) * dot(q, q) * dot(t, t))) continue;
          const long double cp = dot(p, p) / 2, cq = dot(q, q) / 2, ct = dot(t, t) / 2;
          std::array<long double, 3> x{};
          for (int d = 0; d < 3; ++d)
            x[d] = (cp * qt[d] + cq * tp[d] + ct * pq[d]) / det;
          if (feasible(x)) best2 = std::max(best2, dot(x, x));
        }
      }
    }
  }
  if (!(best2 > 0)) bug("Voronoi cell has no vertex");
  out.covering_radius = std::sqrt(best2);
  return out;
}

}  // namespace lattice_detail

using namespace lattice_detail;

double rank_one_p2(std::int64_t points, std::span<const std::int64_t> generator) {
  if (points < 2) refuse("lattice points N for P2", "at least 2", fmt::format("{}", points));
  if (generator.empty() || generator.size() > 3)
    refuse("generator for P2", "1 to 3 components", fmt::format("{}", generator.size()));
  for (std::size_t d = 0; d < generator.size(); ++d) {
    if (generator[d] < 0 || generator[d] >= points)
      refuse(fmt::format("generator component g_{} for P2", d), fmt::format("in [0, N) = [0, {})", points),
             fmt::format("{}", generator[d]));
  }
  // Π_d (1 + 2π² B₂(r_d/N)) − 1 summed in long double with Neumaier's compensation: the terms
  // are O(1) and cancel to N·P₂ (1e-4 at N = 2^22), so a plain double sum would lose the
  // answer's leading digits and even a plain long-double one some of its last.
  const long double two_pi2 = 2 * std::numbers::pi_v<long double> * std::numbers::pi_v<long double>;
  const auto nl = static_cast<long double>(points);
  std::int64_t r[3] = {0, 0, 0};
  long double sum = 0, compensation = 0;
  for (std::int64_t n = 0; n < points; ++n) {
    long double prod = 1;
    for (std::size_t d = 0; d < generator.size(); ++d) {
      const long double x = static_cast<long double>(r[d]) / nl;
      prod *= 1 + two_pi2 * (x * x - x + 1.0L / 6);
      r[d] += generator[d];
      if (r[d] >= points) r[d] -= points;
    }
    const long double term = prod - 1;
    const long double next = sum + term;
    compensation += std::fabs(sum) >= std::fabs(term) ? (sum - next) + term : (term - next) + sum;
    sum = next;
  }
  return static_cast<double>((sum + compensation) / nl);
}

LatticeMerits lattice_merits(const RankOneLattice& lattice) {
  const int s = lattice.dimension();
  const Metric m(lattice.lengths());
  const Basis& b = lattice.dual_basis();
  const std::int64_t n = lattice.points();
  const auto& g = lattice.generator();
  LatticeMerits out;

  // Spectral test: every shortest vector by exact enumeration, then the canonical one.
  std::vector<Vec> ties = shortest_vectors(b, s, m);
  for (Vec& v : ties) {
    const auto first = std::find_if(v.begin(), v.begin() + s, [](std::int64_t x) { return x != 0; });
    if (*first < 0)
      for (int d = 0; d < s; ++d) v[d] = -v[d];
  }
  const Vec h = *std::min_element(ties.begin(), ties.end(), [s](const Vec& x, const Vec& y) {
    return std::lexicographical_compare(x.begin(), x.begin() + s, y.begin(), y.begin() + s);
  });
  out.shortest_dual_vector.assign(h.begin(), h.begin() + s);
  out.lambda1 = static_cast<double>(m.norm(h.data()));

  // Zaremba ρ, exactly: enumerate the prefixes (h_0, …, h_{s−2}) with Π max(1, |h_d|) below
  // the best ρ so far (first nonzero positive: ±h have the same ρ) and solve for the last
  // coordinate: h_{s−1} g_{s−1} ≡ −c (mod N) has solutions iff G = gcd(g_{s−1}, N) divides c,
  // and then they are one class mod N/G, whose smallest |h_{s−1}| is taken. Cost O(ρ) prefixes
  // in 2-D, O(ρ log ρ) in 3-D (ρ ≤ N): 30 ms for the Korobov lattice of 2^22 points.
  const std::int64_t gl = g[s - 1];
  const std::int64_t big_g = std::gcd(gl, n);
  const std::int64_t mod_m = n / big_g;
  const std::int64_t inv = mod_m == 1 ? 0 : inverse_mod(gl / big_g, mod_m);
  auto rho_of = [](std::int64_t prefix_product, std::int64_t last) {
    return prefix_product * std::max<std::int64_t>(1, last < 0 ? -last : last);
  };
  // Start from N (h = N e_0 is dual) and the reduced basis vectors (products in 128 bits: a
  // basis vector of an extreme patch can have components near 2^51).
  std::int64_t best = n;
  for (int i = 0; i < s; ++i) {
    Int128 rho = 1;
    for (int d = 0; d < s; ++d) rho *= std::max<std::int64_t>(1, std::abs(b[i][d]));
    if (rho < best) best = static_cast<std::int64_t>(rho);
  }
  auto try_prefix = [&](std::int64_t c_mod_n, std::int64_t prefix_product, bool prefix_zero) {
    if (c_mod_n % big_g != 0) return;
    std::int64_t last = mul_mod(floor_mod(-c_mod_n / big_g, mod_m), inv, mod_m);  // in [0, M)
    if (prefix_zero) {
      best = std::min(best, mod_m);  // h = (0, …, 0, ±M)
      return;
    }
    const std::int64_t alt = last - mod_m;
    best = std::min({best, rho_of(prefix_product, last), rho_of(prefix_product, alt)});
  };
  if (s == 2) {
    for (std::int64_t h0 = 0; h0 < best; ++h0)
      try_prefix(mul_mod(h0, g[0], n), std::max<std::int64_t>(1, h0), h0 == 0);
  } else {
    for (std::int64_t h0 = 0; h0 < best; ++h0) {
      const std::int64_t p0 = std::max<std::int64_t>(1, h0);
      const std::int64_t c0 = mul_mod(h0, g[0], n);
      const std::int64_t reach = (best - 1) / p0;  // |h_1| ≤ reach keeps p0·max(1,|h1|) < best
      for (std::int64_t h1 = h0 == 0 ? 0 : -reach; h1 <= reach; ++h1) {
        const std::int64_t product = p0 * std::max<std::int64_t>(1, std::abs(h1));
        if (product >= best) continue;  // best may have dropped since reach was set
        const std::int64_t c = floor_mod(Int128{c0} + Int128{h1} * g[1], n);
        try_prefix(c, product, h0 == 0 && h1 == 0);
      }
    }
  }
  out.zaremba_rho = static_cast<double>(best);
  out.p2 = rank_one_p2(n, g);
  return out;
}

LatticeBand lattice_band(const RankOneLattice& lattice) {
  const int s = lattice.dimension();
  const Metric m(lattice.lengths());
  const std::vector<Vec> shortest = shortest_vectors(lattice.dual_basis(), s, m);
  const long double lambda1 = m.norm(shortest.front().data());
  const VoronoiCell cell = voronoi_cell(lattice.dual_basis(), s, m);
  // The shortest vector is always a strict Voronoi-relevant vector, so the superbase's partial
  // sums must contain it: two independent routes to λ₁ that have to agree.
  if (std::fabs(cell.shortest_relevant - lambda1) > 1e-12L * lambda1)
    bug(fmt::format("Voronoi vectors miss the shortest vector ({} vs {} rad/m)",
                    static_cast<double>(cell.shortest_relevant), static_cast<double>(lambda1)));
  LatticeBand out;
  out.inscribed_radius = static_cast<double>(lambda1 / 2);
  out.covering_radius = static_cast<double>(cell.covering_radius);
  long double cell_volume = static_cast<long double>(lattice.points());
  for (const double l : lattice.lengths()) cell_volume *= kTwoPi / static_cast<long double>(l);
  const long double r = lambda1 / 2;
  const long double pi = std::numbers::pi_v<long double>;
  const long double ball = s == 2 ? pi * r * r : 4 * pi * r * r * r / 3;
  out.alias_free_fraction = static_cast<double>(ball / cell_volume);
  return out;
}

}  // namespace swell::reference
