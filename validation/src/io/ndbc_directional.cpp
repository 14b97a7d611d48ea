// One hour of NDBC directional data as E(ω, θ) (ndbc_directional.hpp, docs/ndbc_directional.md).
#include "swell/validation/io/ndbc_directional.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "swell/reference/errors.hpp"
#include "swell/validation/io/ndbc_files.hpp"

namespace swell::validation {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;
constexpr int kMinDirections = 5;  // the samples integrate the degree-2 series' products exactly
constexpr int kMaxDirections = 36000;

void check_directions(int directions) {
  require(directions >= kMinDirections && directions <= kMaxDirections, "directions",
          fmt::format("an integer in [{}, {}] (θ samples over the circle; at least 5 so that the "
                      "samples integrate the degree-2 Fourier series exactly)",
                      kMinDirections, kMaxDirections),
          directions);
}

// The stamp asked for, as the files print it.
struct Stamp {
  int year = 0, month = 0, day = 0, hour = 0, minute = 0;
  std::string text;
};

int days_in_month(int year, int month) {
  static constexpr std::array<int, 12> kDays{31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return month == 2 && leap ? 29 : kDays[std::size_t(month - 1)];
}

// "YYYY-MM-DD hh:mm", every digit present, every field in its range.
Stamp parse_stamp(const std::string& time) {
  const std::string form = "YYYY-MM-DD hh:mm";
  auto malformed = [&](const std::string& why) {
    return InvalidInput(fmt::format("time '{}': {}; expected \"{}\" as the files stamp their "
                                    "records (e.g. \"2020-06-01 00:50\")",
                                    time, why, form));
  };
  if (time.size() != form.size()) {
    throw malformed(fmt::format("{} characters, not {}", time.size(), form.size()));
  }
  for (std::size_t i = 0; i < form.size(); ++i) {
    const bool digit = std::isalpha(static_cast<unsigned char>(form[i]));  // a letter of the form
    if (digit ? !std::isdigit(static_cast<unsigned char>(time[i])) : time[i] != form[i]) {
      const std::string expected = digit ? "a digit" : fmt::format("'{}'", form[i]);
      throw malformed(fmt::format("character {} is '{}', not {}", i + 1, time[i], expected));
    }
  }
  Stamp s;
  s.text = time;
  s.year = std::stoi(time.substr(0, 4));
  s.month = std::stoi(time.substr(5, 2));
  s.day = std::stoi(time.substr(8, 2));
  s.hour = std::stoi(time.substr(11, 2));
  s.minute = std::stoi(time.substr(14, 2));
  auto in_range = [&](const char* field, int value, int lo, int hi) {
    if (value < lo || value > hi) {
      throw malformed(fmt::format("{} {} is outside [{}, {}]", field, value, lo, hi));
    }
  };
  in_range("month", s.month, 1, 12);
  in_range("day", s.day, 1, days_in_month(s.year, s.month));
  in_range("hour", s.hour, 0, 23);
  in_range("minute", s.minute, 0, 59);
  return s;
}

std::string stamp_text(const BuoyHour& h, int minute) {
  return fmt::format("{:04d}-{:02d}-{:02d} {:02d}:{:02d}", h.year, h.month, h.day, h.hour, minute);
}

// The record stamped `stamp` in one file. Throws InvalidInput when the file lacks the hour, stamps
// it with another minute, or holds it twice.
template <typename Record>
const Record& find_record(const std::vector<Record>& records, const Stamp& stamp,
                          const std::string& path) {
  const Record* found = nullptr;
  const Record* same_hour = nullptr;
  for (const Record& r : records) {
    if (r.time.year != stamp.year || r.time.month != stamp.month || r.time.day != stamp.day ||
        r.time.hour != stamp.hour) {
      continue;
    }
    if (r.minute != stamp.minute) {
      same_hour = &r;
      continue;
    }
    if (found) {
      throw InvalidInput(fmt::format("{} holds {} twice (lines {} and {})", path, stamp.text,
                                     found->line, r.line));
    }
    found = &r;
  }
  if (found) return *found;
  if (same_hour) {
    throw InvalidInput(fmt::format("{} has no record stamped {}: it stamps that hour {} (line {})",
                                   path, stamp.text, stamp_text(same_hour->time, same_hour->minute),
                                   same_hour->line));
  }
  const auto [first, last] = std::minmax_element(
      records.begin(), records.end(), [](const Record& a, const Record& b) {
        return a.time.key() * 100 + a.minute < b.time.key() * 100 + b.minute;
      });
  throw InvalidInput(fmt::format("{} has no record stamped {} (its {} records run from {} to {})",
                                 path, stamp.text, records.size(),
                                 stamp_text(first->time, first->minute),
                                 stamp_text(last->time, last->minute)));
}

// Σ_k D(θ_k) e^{inθ_k} Δθ on uniform samples θ_k = 2πk/N: the rectangle rule for the n-th
// Fourier coefficient ∫ D e^{inθ} dθ, exact for a trigonometric polynomial of degree < N − n and
// geometrically convergent for a smooth periodic D (at the rate its coefficients decay).
std::complex<double> grid_coefficient(const std::vector<double>& d, int n) {
  const double dtheta = 2 * kPi / double(d.size());
  std::complex<double> sum = 0;
  for (std::size_t k = 0; k < d.size(); ++k) sum += d[k] * std::polar(1.0, n * dtheta * double(k));
  return sum * dtheta;
}

// How well samples of a spreading function represent it: their integral, and the largest
// departure of the samples, normalized by it, from the integral 1 and the coefficients c1, c2
// they should reproduce.
struct GridFit {
  double integral = 0;
  double error = 0;
};

GridFit grid_fit(const std::vector<double>& d, const std::complex<double>& c1,
                 const std::complex<double>& c2) {
  const double integral = grid_coefficient(d, 0).real();
  const double error = std::max({std::abs(integral - 1),
                                 std::abs(grid_coefficient(d, 1) / integral - c1),
                                 std::abs(grid_coefficient(d, 2) / integral - c2)});
  return {integral, error};
}

std::complex<double> first_coefficient(const NdbcDirectionalMoments& m) {
  return std::polar(m.r1, swell_direction_from_nautical(m.alpha1_deg));
}
std::complex<double> second_coefficient(const NdbcDirectionalMoments& m) {
  return std::polar(m.r2, 2 * swell_direction_from_nautical(m.alpha2_deg));
}

}  // namespace

const char* directional_method_name(DirectionalMethod method) {
  return method == DirectionalMethod::fourier ? "fourier" : "mem";
}

DirectionalMethod parse_directional_method(const std::string& name) {
  for (auto m : {DirectionalMethod::fourier, DirectionalMethod::mem}) {
    if (name == directional_method_name(m)) return m;
  }
  throw InvalidInput(fmt::format(
      "directional method '{}' is not one of \"fourier\" (Longuet-Higgins et al. 1963, NDBC's "
      "formula, negative lobes clipped), \"mem\" (maximum entropy, Lygre & Krogstad 1986)",
      name));
}

double swell_direction_from_nautical(double from_deg) {
  // Coming from φ (clockwise from north) is travelling toward φ + 180°, clockwise from north;
  // clockwise from north is 90° − (counter-clockwise from east). So θ = 90° − (φ + 180°)
  // = −90° − φ ≡ 270° − φ (docs/conventions.md §3.1).
  double deg = std::fmod(270.0 - from_deg, 360.0);
  if (deg < 0) deg += 360.0;
  double rad = deg * kDegree;
  return rad >= 2 * kPi ? 0.0 : rad;
}

std::vector<double> direction_samples(int directions) {
  check_directions(directions);
  std::vector<double> theta(static_cast<std::size_t>(directions));
  for (int k = 0; k < directions; ++k) theta[std::size_t(k)] = 2 * kPi * k / directions;
  return theta;
}

std::vector<double> fourier_spreading(const NdbcDirectionalMoments& m,
                                      const std::vector<double>& theta) {
  // NDBC's formula (https://www.ndbc.noaa.gov/faq/measdes.shtml; Longuet-Higgins et al. 1963):
  // D(φ) = (1/π)[1/2 + r1 cos(φ − α1) + r2 cos(2(φ − α2))], φ nautical. With φ = 270° − θ and
  // α' = 270° − α, φ − α = α' − θ, so cos(φ − α) = cos(θ − α'): the same series in swell's
  // frame, and |dφ/dθ| = 1 keeps it per radian.
  const double a1 = swell_direction_from_nautical(m.alpha1_deg);
  const double a2 = swell_direction_from_nautical(m.alpha2_deg);
  std::vector<double> d(theta.size());
  for (std::size_t k = 0; k < theta.size(); ++k) {
    d[k] = (0.5 + m.r1 * std::cos(theta[k] - a1) + m.r2 * std::cos(2 * (theta[k] - a2))) / kPi;
  }
  return d;
}

std::vector<double> mem_spreading(const NdbcDirectionalMoments& m,
                                  const std::vector<double>& theta, const std::string& where) {
  using C = std::complex<double>;
  // Lygre & Krogstad (1986): the distribution of largest (Burg) entropy ∫ log D among those
  // whose Fourier coefficients ∫ D e^{inθ} dθ are 1, c1, c2 is the AR(2) spectrum of the
  // Yule–Walker solution φ1, φ2 of those autocorrelations. The map θ → 270° − θ is a rotation and a
  // reflection, under which c, φ and D transform alike, so the form holds in swell's frame with
  // the coefficients converted there.
  const C c1 = first_coefficient(m);
  const C c2 = second_coefficient(m);
  const std::string fallback = "use method = \"fourier\" for this hour";
  const std::string given = fmt::format("r1 = {}, α1 = {}°, r2 = {}, α2 = {}°", m.r1,
                                        m.alpha1_deg, m.r2, m.alpha2_deg);
  auto undefined = [&](const std::string& why) {
    return InvalidInput(fmt::format("{}{}the maximum entropy estimate is undefined for {}: {}; {}",
                                    where, where.empty() ? "" : ": ", given, why, fallback));
  };
  if (!(std::abs(c1) < 1)) {
    throw undefined(fmt::format("|c1| = r1 = {} ≥ 1 (1 − |c1|² divides φ1)", std::abs(c1)));
  }
  const C phi1 = (c1 - c2 * std::conj(c1)) / (1.0 - std::norm(c1));
  const C phi2 = c2 - c1 * phi1;
  // (1 − |c1|²)(1 − |φ2|²) by the Levinson recursion: real, and positive exactly when some
  // non-negative distribution has these coefficients (|φ2| < 1).
  const double numerator = (1.0 - phi1 * std::conj(c1) - phi2 * std::conj(c2)).real();
  if (!std::isfinite(numerator) || !(numerator > 0)) {
    throw undefined(fmt::format(
        "1 − φ1 c1* − φ2 c2* = {:.4g} is not positive (|φ2| = {:.4g} ≥ 1: no non-negative "
        "distribution has these coefficients)",
        numerator, std::abs(phi2)));
  }
  std::vector<double> d(theta.size());
  for (std::size_t k = 0; k < theta.size(); ++k) {
    const C e1 = std::polar(1.0, -theta[k]);
    const double denominator = std::norm(1.0 - phi1 * e1 - phi2 * e1 * e1);
    d[k] = numerator / (2 * kPi * denominator);
    if (!std::isfinite(d[k]) || !(denominator > 0)) {
      throw undefined(fmt::format("|1 − φ1 e^(−iθ) − φ2 e^(−2iθ)|² = {:.4g} at θ = {:.6g} rad",
                                  denominator, theta[k]));
    }
  }
  return d;
}

NdbcDirectionalData read_ndbc_directional_files(const NdbcDirectionalFiles& files) {
  NdbcDirectionalData data;
  data.spectra = read_ndbc_spectral_density(files.data_spec);
  data.alpha1 = read_ndbc_directional_parameter(files.swdir, NdbcDirectionalParameter::alpha1);
  data.alpha2 = read_ndbc_directional_parameter(files.swdir2, NdbcDirectionalParameter::alpha2);
  data.r1 = read_ndbc_directional_parameter(files.swr1, NdbcDirectionalParameter::r1);
  data.r2 = read_ndbc_directional_parameter(files.swr2, NdbcDirectionalParameter::r2);
  const std::vector<double>& f = data.spectra.frequency;
  for (const NdbcParameterFile* p : {&data.alpha1, &data.alpha2, &data.r1, &data.r2}) {
    if (p->frequency == f) continue;
    const std::size_t n = std::min(p->frequency.size(), f.size());
    std::size_t j = 0;
    while (j < n && p->frequency[j] == f[j]) ++j;
    throw InvalidInput(fmt::format(
        "{} has {} bands and {} has {}: they differ first at band {} ({} against {}) — the five "
        "files must list the same bands",
        p->path, p->frequency.size(), files.data_spec, f.size(), j + 1,
        j < p->frequency.size() ? fmt::format("{} Hz", p->frequency[j]) : "none",
        j < f.size() ? fmt::format("{} Hz", f[j]) : "none"));
  }
  return data;
}

reference::SpectrumTable read_ndbc_directional(const NdbcDirectionalFiles& files,
                                               const std::string& time, DirectionalMethod method,
                                               int directions) {
  // The arguments first, so that a wrong one is named before any file is read.
  check_directions(directions);
  parse_stamp(time);
  return ndbc_directional_table(read_ndbc_directional_files(files), time, method, directions);
}

reference::SpectrumTable ndbc_directional_table(const NdbcDirectionalData& data,
                                                const std::string& time, DirectionalMethod method,
                                                int directions) {
  const std::vector<double> theta = direction_samples(directions);
  const double dtheta = 2 * kPi / directions;
  const Stamp stamp = parse_stamp(time);

  const BuoySpectrumFile& spectra = data.spectra;
  const BuoySpectrumRecord& spectrum = find_record(spectra.records, stamp, spectra.path);
  struct Parameter {
    const NdbcParameterFile* file;
    const NdbcParameterRecord* record;
  };
  std::array<Parameter, 4> parameters{};
  std::size_t i = 0;
  for (const NdbcParameterFile* p : {&data.alpha1, &data.alpha2, &data.r1, &data.r2}) {
    if (p->frequency != spectra.frequency) {
      throw InvalidInput(fmt::format("{} and {} list different bands", p->path, spectra.path));
    }
    parameters[i++] = {p, &find_record(p->records, stamp, p->path)};
  }

  const SpectralBands bands = spectral_bands(spectra.frequency);
  const std::size_t nf = bands.centre.size();
  const std::size_t nd = theta.size();

  reference::SpectrumTable table;
  table.theta = theta;
  table.density.assign(nf * nd, 0.0);
  for (std::size_t j = 0; j < nf; ++j) {
    table.omega.push_back(2 * kPi * bands.centre[j]);
    table.band_width.push_back(2 * kPi * bands.width[j]);
  }

  int without_energy = 0, without_direction = 0, with_energy = 0;
  int clipped = 0;
  double largest_clipped = 0, largest_clipped_hz = 0;
  double largest_shift = 0, largest_shift_hz = 0;
  double largest_mem_error = 0, largest_mem_error_hz = 0;
  for (std::size_t j = 0; j < nf; ++j) {
    const std::string band = fmt::format("band {} ({:.3f} Hz)", j + 1, spectra.frequency[j]);
    const double s = spectrum.density[j];
    if (!std::isfinite(s)) {
      throw InvalidInput(fmt::format("{} line {}, field spec_{}, {} of {}: 'MM' (missing); the "
                                     "hour's spectrum must have every band",
                                     spectra.path, spectrum.line, j + 1, band, stamp.text));
    }
    std::array<double, 4> v{};
    bool missing = false;
    for (std::size_t p = 0; p < 4; ++p) {
      v[p] = parameters[p].record->value[j];
      missing = missing || !std::isfinite(v[p]);
    }
    if (s == 0) {
      // No energy (printed 0.000): E = 0 whatever D is, and NDBC prints no direction (999).
      ++without_energy;
      without_direction += missing;
      continue;
    }
    ++with_energy;
    for (std::size_t p = 0; p < 4; ++p) {
      if (std::isfinite(v[p])) continue;
      const Parameter& q = parameters[p];
      throw InvalidInput(fmt::format(
          "{} line {}, field {}_{}, {} of {}: missing ('MM' or 999) where {} has energy "
          "(S = {} m²/Hz, line {})",
          q.file->path, q.record->line, ndbc_directional_parameter_name(q.file->parameter), j + 1,
          band, stamp.text, spectra.path, s, spectrum.line));
    }
    const NdbcDirectionalMoments m{v[0], v[1], v[2], v[3]};
    const std::string where = fmt::format("{} {}, {}", spectra.path, stamp.text, band);
    std::vector<double> d;
    double integral = 0;
    if (method == DirectionalMethod::fourier) {
      d = fourier_spreading(m, theta);
      double negative = 0;
      for (double& x : d) {
        if (x < 0) {
          negative -= x * dtheta;
          x = 0;
        }
        integral += x * dtheta;
      }
      if (negative > 0) {
        ++clipped;
        if (negative > largest_clipped) {
          largest_clipped = negative;
          largest_clipped_hz = spectra.frequency[j];
        }
        // What clipping costs: the clipped band no longer has the measured first coefficient.
        const double shift =
            std::abs(grid_coefficient(d, 1) / integral - first_coefficient(m));
        if (shift > largest_shift) {
          largest_shift = shift;
          largest_shift_hz = spectra.frequency[j];
        }
      }
    } else {
      d = mem_spreading(m, theta, where);
      const std::complex<double> c1 = first_coefficient(m), c2 = second_coefficient(m);
      const GridFit fit = grid_fit(d, c1, c2);
      integral = fit.integral;
      if (!(fit.error <= kMemGridTolerance)) {
        std::optional<int> enough;
        for (int n = 2 * directions; n <= kMaxDirections && !enough; n *= 2) {
          const auto finer = mem_spreading(m, direction_samples(n), where);
          if (grid_fit(finer, c1, c2).error <= kMemGridTolerance) enough = n;
        }
        throw InvalidInput(fmt::format(
            "{}: the maximum entropy estimate's peak is narrower than {} directions resolve "
            "(r1 = {}, α1 = {}°, r2 = {}, α2 = {}°): the samples give ∫D = {:.4g} and miss 1, "
            "c1 or c2 by {:.3g} > {}; {}",
            where, directions, m.r1, m.alpha1_deg, m.r2, m.alpha2_deg, fit.integral, fit.error,
            kMemGridTolerance,
            enough ? fmt::format("directions = {} resolves it, or use method = \"fourier\"",
                                 *enough)
                   : std::string("use method = \"fourier\"")));
      }
      if (fit.error > largest_mem_error) {
        largest_mem_error = fit.error;
        largest_mem_error_hz = spectra.frequency[j];
      }
    }
    // S in m²/Hz over ω = 2πf: S_ω = S_f / 2π (m²·s/rad); D normalized on the samples.
    const double scale = s / (2 * kPi) / integral;
    for (std::size_t k = 0; k < nd; ++k) table.density[j * nd + k] = scale * d[k];
  }

  const auto& q = parameters;
  table.source = fmt::format(
      "{} line {}, {} line {}, {} line {}, {} line {}, {} line {} ({}); {} on {} directions",
      spectra.path, spectrum.line, q[0].file->path, q[0].record->line, q[1].file->path,
      q[1].record->line, q[2].file->path, q[2].record->line, q[3].file->path, q[3].record->line,
      stamp.text,
      directional_method_name(method), directions);
  table.notes.push_back(fmt::format(
      "E(ω, θ) = S(f)/(2π) · D(θ) in m²·s/rad², ω = 2πf at the {} band centres, band_width = "
      "2πΔf; θ = 270° − the files' nautical directions (coming from, clockwise from north), "
      "i.e. the direction of travel counter-clockwise from east",
      band_convention_name(bands.convention)));
  table.notes.push_back(fmt::format(
      "{} of {} bands have S = 0 (printed 0.000) and hold E = 0 ({} of them without directions, "
      "999)",
      without_energy, nf, without_direction));
  if (method == DirectionalMethod::fourier) {
    table.notes.push_back(
        clipped == 0
            ? fmt::format("fourier: D ≥ 0 on the samples in all {} bands with energy; nothing "
                          "clipped",
                          with_energy)
            : fmt::format("fourier: D < 0 on the samples in {} of {} bands with energy, set to 0 "
                          "and each band rescaled to Σ D Δθ = 1; the largest negative share "
                          "clipped is {:.4f} of the band's ∫D (at {:.3f} Hz); clipping moves a "
                          "band's first Fourier coefficient a1 + i b1 by up to {:.3f} (at {:.3f} "
                          "Hz)",
                          clipped, with_energy, largest_clipped, largest_clipped_hz,
                          largest_shift, largest_shift_hz));
  } else {
    table.notes.push_back(fmt::format(
        "mem: the samples, rescaled to Σ D(θ_k) Δθ = 1, reproduce the integral 1 and the "
        "coefficients c1, c2 of each of the {} bands with energy to {:.3g} (largest at {:.3f} Hz; "
        "tolerance {})",
        with_energy, largest_mem_error, largest_mem_error_hz, kMemGridTolerance));
  }
  return table;
}

}  // namespace swell::validation
