#include "swell/impls/space_time.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "swell/reference/errors.hpp"
#include "swell/reference/wave_noise.hpp"

namespace swell::impls {
namespace {

using reference::OceanCase;
using reference::RankOneLattice;
using Vector = std::array<std::int32_t, 3>;

constexpr std::int32_t kMaxBandIndex = 1 << 15;
constexpr std::int64_t kMaxBandWaves = std::int64_t{1} << 26;

std::string vector_text(const Vector& h) { return fmt::format("({}, {}, {})", h[0], h[1], h[2]); }

// SplitMix64's finalizer (Steele, Lea & Flood 2014): a fixed, platform-independent scramble.
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t hash(const Vector& h) {
  std::uint64_t x = 0x9e3779b97f4a7c15ULL;
  for (std::int32_t c : h) x = mix(x + static_cast<std::uint32_t>(c));
  return x;
}

bool is_smooth(std::int64_t n) {  // 2^i 3^j 5^k
  for (std::int64_t p : {2, 3, 5}) {
    while (n % p == 0) n /= p;
  }
  return n == 1;
}

std::int64_t next_size(std::int64_t n, SpaceTimeSearch::Sizes sizes) {
  if (sizes == SpaceTimeSearch::Sizes::powers_of_two) {
    std::int64_t p = 1;
    while (p < n) p *= 2;
    return p;
  }
  while (!is_smooth(n)) ++n;
  return n;
}

// The Korobov search's state for one set: the vectors in hashed order, and a stamp per class
// (stamp[r] == epoch: class r taken in the current try), so a try costs what it visits: about
// √N vectors (415 at N = 96000, 1050 at N = 559872, measured) at 3–4 ns each. (A bit table,
// cleared by the list of what a try set, fits in L2 but measured 40% slower.)
class KorobovSearch {
 public:
  explicit KorobovSearch(const SpaceTimeSet& set) {
    const auto& waves = set.waves();
    std::vector<std::pair<std::uint64_t, std::size_t>> order(waves.size());
    for (std::size_t i = 0; i < waves.size(); ++i) order[i] = {hash(waves[i].h), i};
    std::sort(order.begin(), order.end());
    h0_.reserve(waves.size());
    h1_.reserve(waves.size());
    h2_.reserve(waves.size());
    for (const auto& [key, i] : order) {
      h0_.push_back(waves[i].h[0]);
      h1_.push_back(waves[i].h[1]);
      h2_.push_back(waves[i].h[2]);
    }
    mirror_ = set.mirror_symmetric();
  }

  std::optional<std::int64_t> run(std::int64_t points, std::int64_t max_tries, std::int64_t& tries) {
    if (points < static_cast<std::int64_t>(h0_.size())) return std::nullopt;  // pigeonhole
    stamp_.assign(static_cast<std::size_t>(points), 0);
    epoch_ = 0;
    // The components reduced mod N once per size, so each try's sums are non-negative.
    auto reduce = [points](const std::vector<std::int64_t>& from, std::vector<std::uint64_t>& to) {
      to.resize(from.size());
      for (std::size_t i = 0; i < from.size(); ++i) {
        const std::int64_t r = from[i] % points;
        to[i] = static_cast<std::uint64_t>(r < 0 ? r + points : r);
      }
    };
    reduce(h0_, r0_);
    reduce(h1_, r1_);
    reduce(h2_, r2_);
    const std::int64_t last = mirror_ ? points / 2 : points - 1;
    for (std::int64_t a = 1; a <= last; ++a) {
      if (tries >= max_tries) return std::nullopt;
      ++tries;
      if (injective(points, a)) return a;
    }
    return std::nullopt;
  }

 private:
  // One try. v = r0 + r1 a + r2 a² < N + 2N² ≤ 2^61 is reduced by Barrett's method with
  // M = ⌊2^64 / N⌋: q = ⌊v M / 2^64⌋ falls short of ⌊v / N⌋ by at most 2 (v < 2^64), so two
  // conditional subtractions finish it: exact integers, a multiply instead of a 64-bit
  // division (measured 10–15% faster; the random accesses to the stamps dominate).
  bool injective(std::int64_t points, std::int64_t a) {
    if (++epoch_ == 0) {  // wrapped: forget every stamp
      std::fill(stamp_.begin(), stamp_.end(), 0);
      epoch_ = 1;
    }
    const auto n = static_cast<std::uint64_t>(points);
    const auto ua = static_cast<std::uint64_t>(a);
    const std::uint64_t a2 = (ua * ua) % n;  // a < N ≤ 2^30: exact
    __extension__ using U128 = unsigned __int128;
    const std::uint64_t m = static_cast<std::uint64_t>((U128(1) << 64) / n);
    for (std::size_t i = 0; i < r0_.size(); ++i) {
      const std::uint64_t v = r0_[i] + r1_[i] * ua + r2_[i] * a2;
      std::uint64_t r = v - static_cast<std::uint64_t>((U128(v) * m) >> 64) * n;
      if (r >= n) r -= n;
      if (r >= n) r -= n;
      std::uint32_t& s = stamp_[static_cast<std::size_t>(r)];
      if (s == epoch_) return false;
      s = epoch_;
    }
    return true;
  }

  std::vector<std::int64_t> h0_, h1_, h2_;
  std::vector<std::uint64_t> r0_, r1_, r2_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
  bool mirror_ = false;
};

void require_matching_lattice(const SpaceTimeSet& set, const RankOneLattice& lattice) {
  if (lattice.dimension() != 3) {
    throw InvalidInput(fmt::format("a space-time lattice must be 3-D over (Lx, Ly, T); {} is {}-D",
                                   lattice.describe(), lattice.dimension()));
  }
  for (int d = 0; d < 3; ++d) {
    const double want = set.lengths()[static_cast<std::size_t>(d)];
    const double got = lattice.lengths()[static_cast<std::size_t>(d)];
    if (std::abs(got - want) > 1e-12 * want) {
      throw InvalidInput(fmt::format(
          "space-time lattice {} spans {:g} × {:g} × {:g} but the frequency set is over "
          "(Lx, Ly, T) = ({:g} m, {:g} m, {:g} s)",
          lattice.describe(), lattice.lengths()[0], lattice.lengths()[1], lattice.lengths()[2],
          set.lengths()[0], set.lengths()[1], set.lengths()[2]));
    }
  }
}

}  // namespace

// ------------------------------------------------------------------ band

SpaceTimeBand SpaceTimeBand::grid(int n) {
  require(n >= 2 && n <= kMaxBandIndex, "space-time grid band n", "in [2, 2^15]", n);
  SpaceTimeBand band;
  band.kind = Kind::grid;
  band.grid_points = n;
  return band;
}

SpaceTimeBand SpaceTimeBand::disc(double k_max) {
  require(std::isfinite(k_max) && k_max > 0, "space-time disc band k_max", "finite and > 0 (rad/m)",
          k_max);
  SpaceTimeBand band;
  band.kind = Kind::disc;
  band.k_max = k_max;
  return band;
}

std::vector<std::array<std::int32_t, 2>> SpaceTimeBand::wave_vectors(double lx, double ly) const {
  require(std::isfinite(lx) && lx > 0, "patch length lx", "finite and > 0 (m)", lx);
  require(std::isfinite(ly) && ly > 0, "patch length ly", "finite and > 0 (m)", ly);
  std::vector<std::array<std::int32_t, 2>> out;
  if (kind == Kind::grid) {
    require(grid_points >= 2 && grid_points <= kMaxBandIndex, "space-time grid band n",
            "in [2, 2^15]", grid_points);
    // Grid indices [−n/2, n/2) less the Nyquist −n/2 of an even n, and k = 0 (grid.hpp).
    const int high = (grid_points - 1) / 2;
    out.reserve(std::size_t(2 * high + 1) * std::size_t(2 * high + 1));
    for (int m = -high; m <= high; ++m) {
      for (int n = -high; n <= high; ++n) {
        if (n != 0 || m != 0) out.push_back({n, m});
      }
    }
    return out;
  }
  require(std::isfinite(k_max) && k_max > 0, "space-time disc band k_max", "finite and > 0 (rad/m)",
          k_max);
  const double dkx = 2 * std::numbers::pi / lx, dky = 2 * std::numbers::pi / ly;
  const double nx_max = std::floor(k_max / dkx), ny_max = std::floor(k_max / dky);
  if (nx_max >= kMaxBandIndex || ny_max >= kMaxBandIndex ||
      (2 * nx_max + 1) * (2 * ny_max + 1) > double(kMaxBandWaves)) {
    throw InvalidInput(fmt::format(
        "space-time disc band |K| ≤ {:g} rad/m over {:g} × {:g} m reaches index ({:g}, {:g}): at "
        "most 2^15 per axis and 2^26 wave vectors",
        k_max, lx, ly, nx_max, ny_max));
  }
  const int hx = static_cast<int>(nx_max), hy = static_cast<int>(ny_max);
  for (int m = -hy; m <= hy; ++m) {
    for (int n = -hx; n <= hx; ++n) {
      if ((n != 0 || m != 0) && std::hypot(n * dkx, m * dky) <= k_max) out.push_back({n, m});
    }
  }
  return out;
}

std::string SpaceTimeBand::describe() const {
  if (kind == Kind::grid) return fmt::format("{0}×{0} grid band", grid_points);
  return fmt::format("disc |K| ≤ {:g} rad/m", k_max);
}

// ------------------------------------------------------------------ frequency set

SpaceTimeSet SpaceTimeSet::create(const OceanCase& ocean_case, const SpaceTimeBand& band) {
  ocean_case.validate();
  const double period = ocean_case.loop_period;
  require(std::isfinite(period) && period > 0, "loop_period",
          "finite and > 0 s for a space-time surface (ω must be a multiple of 2π/T)", period);
  const double lx = ocean_case.grid.lx, ly = ocean_case.grid.ly;
  const auto ks = band.wave_vectors(lx, ly);
  if (ocean_case.is_summed_cascades()) {
    throw InvalidInput("a space-time surface samples one cascade, not a summed cascade set");
  }
  const auto spectrum = ocean_case.directional_spectrum();  // with a cascade's band weight
  // The amplitude exactly as impls::initial_amplitude computes it (synthesizer.cpp), bit for
  // bit: the same Δk, the same Ψ argument and the same product order. Every band vector
  // carries energy (k ≠ 0; a band has no Nyquist row), whatever the case's own grid.
  const double dkx = ocean_case.grid.dkx(), dky = ocean_case.grid.dky();
  auto amplitude = [&](int n, int m) {
    const double psi = spectrum->psi(n * dkx, m * dky);
    const auto xi = reference::wave_noise(ocean_case.seed, n, m, 0,
                                          static_cast<std::uint32_t>(ocean_case.cascade));
    return std::complex<double>(xi.xi1, xi.xi2) * std::sqrt(0.5 * psi * dkx * dky * 0.5);
  };
  const double omega0 = 2 * std::numbers::pi / period;
  SpaceTimeSet set;
  set.lengths_ = {lx, ly, period};
  set.waves_.reserve(2 * ks.size());
  for (const auto& [n, m] : ks) {
    const double k = std::hypot(n * dkx, m * dky);
    // ω = q ω0 exactly up to the rounding of q ω0 / ω0 (OceanCase::omega quantizes down).
    const double q_real = std::round(ocean_case.omega(k) / omega0);
    if (!(q_real >= 0 && q_real < 2147483647.0)) {
      throw InvalidInput(fmt::format(
          "ω(k) T / 2π = {:g} at k = ({}, {}) is beyond the 2^31 − 1 of a frequency index", q_real,
          n, m));
    }
    const auto q = static_cast<std::int32_t>(q_real);
    const std::complex<double> a = amplitude(n, m);                // travels along +k
    const std::complex<double> b = std::conj(amplitude(-n, -m));  // along −k
    if (q == 0) {
      set.waves_.push_back({{n, m, 0}, a + b});
    } else {
      set.waves_.push_back({{n, m, -q}, a});
      set.waves_.push_back({{n, m, q}, b});
    }
  }
  set.finish();
  return set;
}

SpaceTimeSet SpaceTimeSet::from_waves(std::array<double, 3> lengths, std::vector<SpaceTimeWave> waves) {
  SpaceTimeSet set;
  set.lengths_ = lengths;
  set.waves_ = std::move(waves);
  set.finish();
  return set;
}

void SpaceTimeSet::finish() {
  static constexpr std::array<const char*, 3> names = {"Lx (m)", "Ly (m)", "T (s)"};
  for (std::size_t d = 0; d < 3; ++d) {
    require(std::isfinite(lengths_[d]) && lengths_[d] > 0,
            fmt::format("space-time length {}", names[d]), "finite and > 0", lengths_[d]);
  }
  if (waves_.empty()) throw InvalidInput("a space-time frequency set needs at least one vector");
  std::sort(waves_.begin(), waves_.end(),
            [](const SpaceTimeWave& x, const SpaceTimeWave& y) { return x.h < y.h; });
  double largest = 0;
  max_abs_ = {0, 0, 0};
  for (std::size_t i = 0; i < waves_.size(); ++i) {
    const auto& w = waves_[i];
    for (std::size_t d = 0; d < 3; ++d) {
      if (w.h[d] == std::numeric_limits<std::int32_t>::min()) {
        throw InvalidInput("space-time frequency vector " + vector_text(w.h) +
                           ": components must be within ±(2^31 − 1)");
      }
      max_abs_[d] = std::max(max_abs_[d], std::abs(w.h[d]));
    }
    if (i > 0 && waves_[i - 1].h == w.h) {
      throw InvalidInput("space-time frequency vector " + vector_text(w.h) +
                         " appears twice (merge coincident vectors into one coefficient)");
    }
    if (!std::isfinite(w.coefficient.real()) || !std::isfinite(w.coefficient.imag())) {
      throw InvalidInput("space-time frequency vector " + vector_text(w.h) +
                         " has a non-finite coefficient");
    }
    largest = std::max(largest, std::abs(w.coefficient));
  }
  auto find = [&](const Vector& h) -> const SpaceTimeWave* {
    const auto it = std::lower_bound(waves_.begin(), waves_.end(), h,
                                     [](const SpaceTimeWave& x, const Vector& v) { return x.h < v; });
    return it != waves_.end() && it->h == h ? &*it : nullptr;
  };
  // A real surface: c_(−h) = conj(c_h). A set made from a case satisfies it exactly; a foreign
  // one is allowed the rounding of its own arithmetic.
  const double tolerance = 8 * 0x1p-53 * largest;
  mirror_symmetric_ = true;
  for (const auto& w : waves_) {
    const SpaceTimeWave* partner = find({-w.h[0], -w.h[1], -w.h[2]});
    if (partner == nullptr) {
      throw InvalidInput("space-time frequency set is not closed under h ↦ −h: " +
                         vector_text(w.h) + " has no partner (a real surface needs both)");
    }
    if (std::abs(partner->coefficient - std::conj(w.coefficient)) > tolerance) {
      throw InvalidInput(fmt::format(
          "space-time coefficients of {} and its partner are not conjugate (|c(−h) − conj c(h)| = "
          "{:.3g} > 8 u max |c| = {:.3g}): not a real surface",
          vector_text(w.h), std::abs(partner->coefficient - std::conj(w.coefficient)), tolerance));
    }
    if (mirror_symmetric_ && find({w.h[0], -w.h[1], w.h[2]}) == nullptr) mirror_symmetric_ = false;
  }
}

std::string SpaceTimeSet::describe() const {
  return fmt::format("{} space-time frequency vectors, |n| ≤ {}, |m| ≤ {}, q ≤ {}", waves_.size(),
                     max_abs_[0], max_abs_[1], max_abs_[2]);
}

// ------------------------------------------------------------------ classes and the search

std::int64_t space_time_class(const std::array<std::int32_t, 3>& h,
                              std::span<const std::int64_t> generator, std::int64_t points) {
  require(points >= 1, "lattice points N", "≥ 1", double(points));
  if (generator.size() != 3) {
    throw InvalidInput(fmt::format("a space-time generator has 3 components (got {})", generator.size()));
  }
  // Each component reduced mod N first: products below N² ≤ 2^60, the sum below 2^62.
  std::int64_t r = 0;
  for (std::size_t d = 0; d < 3; ++d) {
    std::int64_t c = h[d] % points;
    if (c < 0) c += points;
    const std::int64_t g = generator[d];
    require(g >= 0 && g < points, "generator component", "in [0, N)", double(g));
    r = (r + c * g) % points;
  }
  return r;
}

std::optional<std::array<std::size_t, 2>> first_collision(const SpaceTimeSet& set,
                                                          const RankOneLattice& lattice) {
  require_matching_lattice(set, lattice);
  const auto& waves = set.waves();
  std::vector<std::pair<std::int64_t, std::size_t>> classes(waves.size());
  for (std::size_t i = 0; i < waves.size(); ++i) {
    classes[i] = {space_time_class(waves[i].h, lattice.generator(), lattice.points()), i};
  }
  std::sort(classes.begin(), classes.end());
  for (std::size_t i = 1; i < classes.size(); ++i) {
    if (classes[i].first == classes[i - 1].first)
      return std::array<std::size_t, 2>{classes[i - 1].second, classes[i].second};
  }
  return std::nullopt;
}

void require_injective(const SpaceTimeSet& set, const RankOneLattice& lattice) {
  const auto collision = first_collision(set, lattice);
  if (!collision) return;
  const auto& a = set.waves()[(*collision)[0]].h;
  const auto& b = set.waves()[(*collision)[1]].h;
  const auto& g = lattice.generator();
  throw InvalidInput(fmt::format(
      "space-time lattice {} (g = ({}, {}, {})) puts frequency vectors {} and {} in one residue "
      "class {}: h ↦ h·g mod N must be injective on the {} (choose_space_time_korobov finds such a "
      "generator)",
      lattice.describe(), g[0], g[1], g[2], vector_text(a), vector_text(b),
      space_time_class(a, g, lattice.points()), set.describe()));
}

std::string to_string(SpaceTimeSearch::Sizes sizes) {
  return sizes == SpaceTimeSearch::Sizes::powers_of_two ? "powers_of_two" : "smooth";
}

std::optional<std::int64_t> find_space_time_multiplier(const SpaceTimeSet& set, std::int64_t points,
                                                       std::int64_t max_tries, std::int64_t* tries) {
  require(points >= 2 && points <= reference::kMaxLatticePoints, "lattice points N",
          "in [2, 2^30]", double(points));
  std::int64_t local = 0;
  std::int64_t& counter = tries ? *tries : local;
  KorobovSearch search(set);
  return search.run(points, max_tries, counter);
}

SpaceTimeChoice choose_space_time_korobov(const SpaceTimeSet& set, const SpaceTimeSearch& search) {
  require(search.max_points >= 2 && search.max_points <= reference::kMaxLatticePoints,
          "SpaceTimeSearch max_points", "in [2, 2^30]", double(search.max_points));
  require(search.max_tries >= 1, "SpaceTimeSearch max_tries", "≥ 1", double(search.max_tries));
  const std::int64_t start =
      std::max({static_cast<std::int64_t>(set.size()), search.min_points, std::int64_t{2}});
  KorobovSearch korobov(set);
  SpaceTimeChoice choice;
  std::int64_t first = 0, last = 0;
  for (std::int64_t n = next_size(start, search.sizes);
       n <= search.max_points && choice.tries < search.max_tries;
       n = next_size(n + 1, search.sizes)) {
    if (first == 0) first = n;
    last = n;
    ++choice.sizes_tried;
    if (const auto a = korobov.run(n, search.max_tries, choice.tries)) {
      choice.points = n;
      choice.multiplier = *a;
      return choice;
    }
  }
  throw InvalidInput(fmt::format(
      "no Korobov generator g = (1, a, a² mod N) is injective on the {} for N from {} to {} ({} "
      "sizes, {}): {} multipliers tried (max_tries = {}, max_points = {}); raise max_tries or "
      "max_points{}",
      set.describe(), first, last, choice.sizes_tried, to_string(search.sizes), choice.tries,
      search.max_tries, search.max_points,
      search.sizes == SpaceTimeSearch::Sizes::powers_of_two ? ", or search smooth sizes" : ""));
}

std::shared_ptr<const RankOneLattice> space_time_lattice(const SpaceTimeSet& set,
                                                         const SpaceTimeChoice& choice) {
  const auto& l = set.lengths();
  return std::make_shared<const RankOneLattice>(
      reference::korobov_lattice(choice.points, choice.multiplier, {l[0], l[1], l[2]}));
}

// ------------------------------------------------------------------ synthesis

SpaceTimeSynthesizer::SpaceTimeSynthesizer(SpaceTimeSet set,
                                           std::shared_ptr<const RankOneLattice> lattice,
                                           SpaceTimeOptions options)
    : set_(std::move(set)), lattice_(std::move(lattice)) {
  if (!lattice_) throw InvalidInput("space-time synthesis needs a lattice (got null)");
  require_matching_lattice(set_, *lattice_);
  const std::int64_t points = lattice_->points();
  require(points <= std::numeric_limits<int>::max(), "space-time lattice points N",
          "≤ 2^31 − 1 (a transform's size is an int)", double(points));
  if (options.require_injective) require_injective(set_, *lattice_);
  classes_.reserve(set_.size());
  for (const auto& w : set_.waves()) {
    classes_.push_back(space_time_class(w.h, lattice_->generator(), points));
  }
  backend_ = make_backend(options.backend);
  TransformSpec spec;
  spec.nx = static_cast<int>(points);
  spec.ny = 1;
  spec.kind = Kind::c2r;
  spec.direction = Direction::inverse;
  spec.precision = Precision::f64;
  plan_ = backend_->plan(spec);
  scratch_.resize(static_cast<std::size_t>(points / 2 + 1));
}

SpaceTimeSynthesizer::~SpaceTimeSynthesizer() = default;

void SpaceTimeSynthesizer::place(std::span<std::complex<double>> half_spectrum) const {
  const std::int64_t points = lattice_->points();
  if (half_spectrum.size() != static_cast<std::size_t>(points / 2 + 1)) {
    throw InvalidInput(fmt::format("space-time half spectrum holds {} values, N/2 + 1 = {} needed",
                                   half_spectrum.size(), points / 2 + 1));
  }
  std::fill(half_spectrum.begin(), half_spectrum.end(), std::complex<double>(0));
  // Classes r ≤ N/2 only: the vector of class N − r is the conjugate partner. Classes 0 and
  // N/2 are their own partners' classes, so both members land there and the sum is real (only
  // without injectivity can they be occupied: h·g ≡ 0 or N/2 for h ≠ 0 means h and −h collide).
  const auto& waves = set_.waves();
  for (std::size_t i = 0; i < waves.size(); ++i) {
    const std::int64_t r = classes_[i];
    if (2 * r <= points) half_spectrum[static_cast<std::size_t>(r)] += waves[i].coefficient;
  }
}

void SpaceTimeSynthesizer::heights(std::span<double> heights) const {
  const std::int64_t points = lattice_->points();
  if (heights.size() != static_cast<std::size_t>(points)) {
    throw InvalidInput(fmt::format("space-time heights hold {} values, the lattice has N = {}",
                                   heights.size(), points));
  }
  place(scratch_);
  plan_->execute(std::span<const std::complex<double>>(scratch_), heights);
}

std::vector<double> SpaceTimeSynthesizer::heights() const {
  std::vector<double> out(static_cast<std::size_t>(lattice_->points()));
  heights(out);
  return out;
}

}  // namespace swell::impls
