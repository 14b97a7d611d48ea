#include "swell/reference/sampling_validity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/phase.hpp"

namespace swell::reference {
namespace {

// Where the spectrum's energy lies: the angular frequencies below which 1 % and 99 % of m0
// are, by bisection on the band-limited m0 (quadrature), and their wave numbers. For messages
// only: a failing case pays for it, a passing one does not.
struct EnergyBand {
  double omega_low = 0, omega_high = 0, k_low = 0, k_high = 0;
  bool known = false;
};

EnergyBand energy_band(const OceanCase& ocean_case) {
  EnergyBand band;
  try {
    const auto spectrum = ocean_case.directional_spectrum();
    const FrequencySpectrum& s = spectrum->omnidirectional();
    const double m0 = spectral_moment(s, 0);
    auto quantile = [&](double level) {
      double lo = s.peak_omega(), hi = lo;
      while (spectral_moment(s, 0, Band{0, lo}) > level * m0 && lo > 1e-300) lo /= 2;
      while (spectral_moment(s, 0, Band{0, hi}) < level * m0 && hi < 1e300) hi *= 2;
      for (int i = 0; i < 60 && hi > lo * (1 + 1e-6); ++i) {
        const double mid = std::sqrt(lo * hi);
        (spectral_moment(s, 0, Band{0, mid}) < level * m0 ? lo : hi) = mid;
      }
      return std::sqrt(lo * hi);
    };
    band.omega_low = quantile(0.01);
    band.omega_high = quantile(0.99);
    const Dispersion dispersion = ocean_case.dispersion();
    band.k_low = dispersion.wavenumber(band.omega_low);
    band.k_high = dispersion.wavenumber(band.omega_high);
    band.known = std::isfinite(band.k_low) && std::isfinite(band.k_high);
  } catch (const std::exception&) {
    band.known = false;  // the message then gives the grid's band alone
  }
  return band;
}

// The largest |k| of a wave vector that carries energy: index n/2 − 1 for even n (−n/2 is
// Nyquist), (n − 1)/2 for odd n, 0 for one sample; 0 when only k = 0 and Nyquist remain.
double largest_energy_wavenumber(const Grid& g) {
  auto largest_index = [](int n) { return n % 2 == 0 ? n / 2 - 1 : (n - 1) / 2; };
  return std::hypot(largest_index(g.nx) * g.dkx(), largest_index(g.ny) * g.dky());
}

std::string describe_grid(const Grid& g) {
  return g.nx == g.ny && g.lx == g.ly ? fmt::format("{}² over {:g} m", g.nx, g.lx)
                                      : fmt::format("{}×{} over {:g}×{:g} m", g.nx, g.ny, g.lx, g.ly);
}

// The same for any sampling: "512² over 200 m grid", "korobov N=4096 g=(1,1159) over 200×200 m".
std::string describe_samples(const Sampling& sampling) {
  return sampling.is_lattice() ? sampling.describe() : describe_grid(sampling.grid()) + " grid";
}

// The largest |k| that carries energy: a grid's corner below Nyquist; a lattice's longest k_m.
double largest_energy_wavenumber(const Sampling& sampling) {
  if (!sampling.is_lattice()) return largest_energy_wavenumber(sampling.grid());
  double largest2 = 0;
  for (std::size_t c = 0; c < sampling.size(); ++c) {
    if (!sampling.carries_energy(c)) continue;
    const auto [n, m] = sampling.wave_index(c);
    const double kx = n * sampling.dkx(), ky = m * sampling.dky();
    largest2 = std::max(largest2, kx * kx + ky * ky);
  }
  return std::sqrt(largest2);
}

// Where a case file sets the sample count, for the messages.
const char* size_key(const Sampling& sampling) {
  return sampling.is_lattice() ? "[sampling] points" : "[grid] n";
}


}  // namespace

std::string human_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024 && u < 6) {
    bytes /= 1024;
    ++u;
  }
  return fmt::format("{:.3g} {}", bytes, units[u]);
}

SamplingSummary summarize_sampling(const OceanCase& ocean_case,
                                   const std::vector<double>* travelling) {
  const Sampling sampling = ocean_case.sampling();
  const auto spectrum = ocean_case.directional_spectrum();
  SamplingSummary out;
  out.m0 = spectral_moment(spectrum->omnidirectional(), 0);
  const double dkx = sampling.dkx(), dky = sampling.dky();
  out.k_min = std::min(dkx, dky);
  out.k_max = largest_energy_wavenumber(sampling);

  double sx = 0, sy = 0, dx = 0, dy = 0, dxx = 0, dyy = 0, dxy = 0;
  for (std::size_t c = 0; c < sampling.size(); ++c) {
    if (!sampling.carries_energy(c)) continue;
    const auto [n, m] = sampling.wave_index(c);
    const double kx = n * dkx, ky = m * dky, k = std::hypot(kx, ky);
    double power = 0;
    if (travelling) {
      power = 2 * (*travelling)[c];
    } else {
      const double psi = spectrum->psi(kx, ky);
      if (psi == 0) continue;  // Δk² may overflow where Ψ vanishes (a 1e-300 m patch)
      power = psi * dkx * dky;
    }
    if (power == 0) continue;
    if (!std::isfinite(power) || power < 0) {
      throw InvalidInput(fmt::format(
          "the case's spectrum gives Ψ(k) Δkx Δky = {:g} m² at k = ({:g}, {:g}) rad/m of its "
          "{}: the wave vectors (Δk = 2π/L = {:g} rad/m) lie where the spectrum cannot be "
          "evaluated; choose the patch length so that Δk is a fraction of the peak wave number",
          power, kx, ky, describe_samples(sampling), out.k_min));
    }
    out.m0_on_grid += power;
    sx += kx * kx * power;
    sy += ky * ky * power;
    dx += kx / k * (kx / k) * power;
    dy += ky / k * (ky / k) * power;
    dxx += (kx / k * kx) * (kx / k * kx) * power;
    dyy += (ky / k * ky) * (ky / k * ky) * power;
    dxy += (kx / k * ky) * (kx / k * ky) * power;
  }
  out.fraction = out.m0 > 0 ? out.m0_on_grid / out.m0 : 0;
  out.slope_variance = std::max(sx, sy);
  out.displacement_variance = std::max(dx, dy);
  out.strain_variance = std::max({dxx, dyy, dxy});
  return out;
}

std::uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  std::uint64_t value = 0;
  while (meminfo >> key >> value >> unit) {
    if (key == "MemAvailable:") return value * 1024;  // kB
  }
  return 0;
}

void require_memory(std::uint64_t bytes_needed, std::string_view command, std::string_view what) {
  const std::uint64_t available = available_memory_bytes();
  if (available == 0 || bytes_needed <= available) return;
  throw InvalidInput(fmt::format(
      "{} needs about {} bytes ({}) for {}, and the machine has {} bytes ({}) available: use a "
      "smaller grid ([grid] n) or fewer frames",
      command.empty() ? std::string_view("this command") : command, bytes_needed,
      human_bytes(double(bytes_needed)), what, available, human_bytes(double(available))));
}

void require_valid_sampling(const OceanCase& ocean_case, const NumberFormat& numbers,
                            std::uint64_t bytes_needed, std::string_view command,
                            const std::vector<double>* travelling) {
  const Sampling sampling = ocean_case.sampling();
  if (bytes_needed > 0) require_memory(bytes_needed, command, "the " + describe_samples(sampling));

  // Times first: it needs no pass over the grid.
  {
    // The fastest wave the grid carries, as the synthesizer's own check sees it.
    const double largest_k = largest_energy_wavenumber(sampling);
    const double omega_max = ocean_case.omega(largest_k);
    const double t_last = ocean_case.t0 + double(ocean_case.frames - 1) * ocean_case.dt;
    const double time_max = std::max(std::abs(ocean_case.t0), std::abs(t_last));
    const double phase = time_max == 0 || omega_max == 0 ? 0 : omega_max * time_max;
    if (!(phase <= kLargestPhase)) {
      throw InvalidInput(fmt::format(
          "[time] t0 = {:g} s, dt = {:g} s, frames = {}: frame times up to |t| = {:g} s make the "
          "fastest wave's phase ω t = {:.3g} rad (ω = {:.4g} rad/s at |k| = {:.4g} rad/m), "
          "beyond the {:.3g} rad ({}) that a phase can carry with every bit of a double "
          "(reference/phase.hpp); frames must stay within |t| ≤ {:.4g} s on these samples",
          ocean_case.t0, ocean_case.dt, ocean_case.frames, time_max, phase,
          omega_max, largest_k, kLargestPhase, "2⁵⁰", kLargestPhase / omega_max));
    }
  }

  if (travelling && travelling->size() != sampling.size()) {
    throw InternalError("require_valid_sampling: travelling power of the wrong size");
  }
  const SamplingSummary s = summarize_sampling(ocean_case, travelling);
  if (s.k_max == 0) {
    throw InvalidInput(fmt::format(
        "the {} has no wave vector that carries energy (only k = 0 and the self-conjugate "
        "Nyquist entries, which carry none): {} must be at least 3{}",
        describe_samples(sampling), size_key(sampling),
        sampling.is_lattice() ? "" : " along one axis"));
  }
  if (!(s.fraction >= kSmallestEnergyFraction)) {
    const EnergyBand band = energy_band(ocean_case);
    std::string where = band.known
        ? fmt::format(", while 98 % of the spectrum's energy lies at |k| = {:.3g} … {:.3g} rad/m "
                      "(ω = {:.3g} … {:.3g} rad/s{})",
                      band.k_low, band.k_high, band.omega_low, band.omega_high,
                      std::isfinite(ocean_case.depth)
                          ? fmt::format(", with the dispersion of depth {:g} m", ocean_case.depth)
                          : std::string())
        : std::string();
    throw InvalidInput(fmt::format(
        "the {} carries {:.3g} of the spectrum's m0 = {:.4g} m² (at least {:g} is needed "
        "for a surface that can be judged): its wave vectors span |k| = {:.3g} … {:.3g} rad/m "
        "(Δk = 2π/L to {}){}; choose {} so that the {} covers that band",
        describe_samples(sampling), s.fraction, s.m0, kSmallestEnergyFraction, s.k_min, s.k_max,
        sampling.is_lattice() ? "the longest k_m" : "π n/L", where,
        sampling.is_lattice() ? "[grid] length and [sampling] points" : "[grid] length and n",
        sampling.is_lattice() ? "lattice" : "grid"));
  }

  // Range: every field's rms between smallest normal / u and largest / 64 (√ for the λ∂D
  // terms, which the Jacobian multiplies).
  const double lambda = std::abs(ocean_case.choppiness);
  const double lowest = numbers.smallest_normal / numbers.unit_roundoff;
  struct FieldRms {
    const char* what;
    double rms;
    bool multiplied;  // J multiplies two of them: their limit is √largest
    const char* parameter;
  };
  const FieldRms fields[] = {
      {"height", std::sqrt(s.m0_on_grid), false, "the spectrum's scale (hs, alpha)"},
      {"slopes", std::sqrt(s.slope_variance), false, "the spectrum's scale"},
      {"displacements λD", lambda * std::sqrt(s.displacement_variance), false,
       "[synthesis] choppiness"},
      {"Jacobian terms λ∂D/∂x", lambda * std::sqrt(s.strain_variance), true,
       "[synthesis] choppiness"},
  };
  for (const FieldRms& f : fields) {
    if (f.rms == 0) continue;  // zero by definition (λ = 0: no displacement, J = 1 exactly)
    const double highest = (f.multiplied ? std::sqrt(numbers.largest) : numbers.largest) / 64;
    if (!(f.rms <= highest)) {
      throw InvalidInput(fmt::format(
          "the {} of this case have an rms of {:.3g} on its {}, above the {:.3g} that {} "
          "values can hold with room for the largest samples{}: reduce {} (choppiness = {:g})",
          f.what, f.rms, describe_samples(sampling), highest, numbers.name,
          f.multiplied ? " (J multiplies two of them)" : "", f.parameter, ocean_case.choppiness));
    }
    if (!(f.rms >= lowest)) {
      throw InvalidInput(fmt::format(
          "the {} of this case have an rms of {:.3g} on its {}, below the {:.3g} under which "
          "{} values lose precision to underflow: raise {} (choppiness = {:g}, or synthesize and "
          "store in fp64)",
          f.what, f.rms, describe_samples(sampling), lowest, numbers.name, f.parameter,
          ocean_case.choppiness));
    }
  }
}

}  // namespace swell::reference
