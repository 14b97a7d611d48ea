// swell lattice --points N [--kind korobov|fibonacci] [--dim 2|3] [--length LX[,LY[,LZ]]]
// [--json F]: a rank-1 lattice (docs/conventions.md §2.1, docs/lattice.md) — its generator, its
// merits (the spectral test's shortest dual vector and λ₁, Zaremba's ρ, Sloan & Joe's P₂), the
// band it covers (inscribed and covering radius, alias-free fraction) and the table of its wave
// vectors k_m, m = 0 … N−1.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/lattice.hpp"

namespace swell::cli {
namespace {

struct LatticeOptions {
  std::int64_t points = 0;
  std::string kind = "korobov";
  int dim = 2;
  std::vector<double> length;
  std::string json;
};

int run_lattice(const LatticeOptions& o) {
  if (o.kind == "fibonacci" && o.dim != 2) {
    throw InvalidInput(fmt::format("--kind fibonacci: Fibonacci lattices are 2-D (got --dim {}); "
                                   "use --kind korobov for 3-D",
                                   o.dim));
  }
  // One length for every axis, or one per axis; the unit torus when none is given.
  std::vector<double> lengths(static_cast<std::size_t>(o.dim), 1.0);
  if (o.length.size() == 1) {
    lengths.assign(lengths.size(), o.length[0]);
  } else if (!o.length.empty()) {
    if (o.length.size() != lengths.size()) {
      throw InvalidInput(fmt::format("--length: give one length for every axis or {} lengths "
                                     "(--dim {}); got {}",
                                     o.dim, o.dim, o.length.size()));
    }
    lengths = o.length;
  }
  for (const double l : lengths) {
    if (!(std::isfinite(l) && l > 0)) {
      throw InvalidInput(fmt::format("--length: every length must be finite and > 0 m (got {:g})", l));
    }
  }
  const reference::RankOneLattice lattice =
      o.kind == "fibonacci"
          ? reference::fibonacci_lattice(reference::fibonacci_index(o.points), lengths[0], lengths[1])
          : reference::korobov_lattice(o.points, lengths);
  const reference::LatticeMerits merits = reference::lattice_merits(lattice);
  const reference::LatticeBand band = reference::lattice_band(lattice);

  if (!o.json.empty()) {
    nlohmann::json wave_vectors = nlohmann::json::array();
    for (std::int64_t m = 0; m < lattice.points(); ++m) {
      const auto k = lattice.wave_vector(m);
      wave_vectors.push_back(std::vector<std::int32_t>(k.begin(), k.end()));
    }
    const nlohmann::json document = {
        {"points", lattice.points()},
        {"kind", o.kind},
        {"dim", lattice.dimension()},
        {"generator", lattice.generator()},
        {"lengths", lattice.lengths()},
        {"description", lattice.describe()},
        {"merits",
         {{"shortest_dual_vector", merits.shortest_dual_vector},
          {"lambda1", merits.lambda1},
          {"zaremba_rho", merits.zaremba_rho},
          {"p2", merits.p2}}},
        {"band",
         {{"inscribed_radius", band.inscribed_radius},
          {"covering_radius", band.covering_radius},
          {"alias_free_fraction", band.alias_free_fraction}}},
        {"wave_vectors", std::move(wave_vectors)}};
    write_json(o.json, document);
    if (o.json == "-") return 0;
  }
  fmt::print("swell lattice: {}\n", lattice.describe());
  fmt::print("generator          ({})\n", fmt::join(lattice.generator(), ", "));
  fmt::print("spectral test      shortest dual vector ({}), λ₁ = {:.6g} rad/m\n",
             fmt::join(merits.shortest_dual_vector, ", "), merits.lambda1);
  fmt::print("QMC merits         Zaremba ρ = {:g}, P₂ = {:.6g}\n", merits.zaremba_rho, merits.p2);
  fmt::print("band               inscribed radius λ₁/2 = {:.6g} rad/m, covering radius = {:.6g} "
             "rad/m, alias-free fraction = {:.4f} ({})\n",
             band.inscribed_radius, band.covering_radius, band.alias_free_fraction,
             lattice.dimension() == 2 ? "a square grid: π/4 = 0.7854" : "a cubic grid: π/6 = 0.5236");
  fmt::print("wave vectors       m: k_m (integer), |K_m| = ‖2π k_m / L‖ rad/m\n");
  for (std::int64_t m = 0; m < lattice.points(); ++m) {
    const auto k = lattice.wave_vector(m);
    const auto big_k = lattice.wave_number(m);
    fmt::print("{:>10}: ({}) {:.6g}{}\n", m, fmt::join(k, ", "),
               std::sqrt(big_k[0] * big_k[0] + big_k[1] * big_k[1] + big_k[2] * big_k[2]),
               lattice.carries_energy(m) ? "" : "  (no energy)");
  }
  return 0;
}

}  // namespace

Action add_lattice_command(CLI::App& app) {
  auto o = std::make_shared<LatticeOptions>();
  app.add_option("--points", o->points, "N, the number of points")->required();
  app.add_option("--kind", o->kind,
                 "korobov (g = (1, a, a²) with a by the spectral test; any N; default) or "
                 "fibonacci (N a Fibonacci number, g = (1, F_{j−1}); 2-D)")
      ->check(CLI::IsMember({"korobov", "fibonacci"}));
  app.add_option("--dim", o->dim, "dimension s: 2 (a patch) or 3 (default 2)")
      ->check(CLI::IsMember({2, 3}));
  app.add_option("--length", o->length,
                 "box lengths LX[,LY[,LZ]] in m (one for every axis; default 1): the metric of "
                 "the spectral test and of the wave vectors")
      ->delimiter(',');
  app.add_option("--json", o->json, "write JSON to FILE, or - for standard output");
  app.footer(
      "Prints the generator, the merits (shortest dual vector and λ₁ of the spectral test, "
      "Zaremba's ρ, P₂), the band (inscribed radius λ₁/2, covering radius, alias-free "
      "fraction) and the wave vector k_m of every residue class m. JSON: {points, kind, dim, "
      "generator, lengths, description, merits {shortest_dual_vector, lambda1, zaremba_rho, p2}, "
      "band {inscribed_radius, covering_radius, alias_free_fraction}, wave_vectors}.");
  return [o] { return run_lattice(*o); };
}

}  // namespace swell::cli
