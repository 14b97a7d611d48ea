#pragma once
// One hour of an NDBC buoy's directional wave data as a 2-D spectrum E(ω, θ) in swell's form
// (reference::SpectrumTable; docs/ndbc_directional.md). NDBC publishes, per band f_j, the
// spectral density S(f_j) and four directional parameters α1, α2, r1, r2 (ndbc_files.hpp); the
// directional distribution D(θ) they describe is estimated by one of two methods:
//
//   fourier  the truncated Fourier series (Longuet-Higgins, Cartwright & Smith 1963), NDBC's own
//            formula (https://www.ndbc.noaa.gov/faq/measdes.shtml), negative lobes clipped;
//   mem      the maximum entropy method of Lygre & Krogstad (1986), which is ≥ 0 by construction
//            and reproduces all four Fourier coefficients.
//
// Then E(ω, θ) = S(f)/(2π) · D(θ) with ω = 2πf, in m²·s/rad², θ the direction toward which the
// waves travel, in radians counter-clockwise from east (docs/conventions.md §3.1).
#include <string>
#include <vector>

#include "swell/reference/spectrum_table.hpp"
#include "swell/validation/io/ndbc_files.hpp"

namespace swell::validation {

enum class DirectionalMethod { fourier, mem };
// "fourier", "mem": the names a case file or a command line uses.
const char* directional_method_name(DirectionalMethod method);
// The method of that name; throws InvalidInput naming the valid ones for any other.
DirectionalMethod parse_directional_method(const std::string& name);

// The five files of one station's realtime directional product.
struct NdbcDirectionalFiles {
  std::string data_spec;  // S(f), m²/Hz
  std::string swdir;      // α1, degrees, nautical (coming from, clockwise from true north)
  std::string swdir2;     // α2, degrees, nautical, modulo 180°
  std::string swr1;       // r1 in [0, 1]
  std::string swr2;       // r2 in [0, 1]
};

// One band's directional parameters as NDBC prints them.
struct NdbcDirectionalMoments {
  double alpha1_deg = 0;  // nautical: the direction the waves come from, clockwise from north
  double alpha2_deg = 0;
  double r1 = 0;
  double r2 = 0;
};

// A nautical "coming from" direction (degrees clockwise from true north) as swell's direction of
// travel, in radians counter-clockwise from east (+x east, +y north), in [0, 2π):
// θ = 270° − φ, mod 360°. Waves from the east (φ = 90°) travel west (θ = 180°).
double swell_direction_from_nautical(double from_deg);

// The θ samples of a table of `directions` directions: θ_j = 2π j / directions, j = 0 … n−1.
std::vector<double> direction_samples(int directions);

// The Fourier estimate at swell's directions θ (radians), per radian, as NDBC writes it in its own
// (nautical) frame — D(φ) = (1/π)[1/2 + r1 cos(φ − α1) + r2 cos(2(φ − α2))] — evaluated at
// φ = 270° − θ. Not clipped: it is negative wherever the series undershoots. Its integral over
// the circle is 1 and its first two Fourier coefficients are a1 + i b1 = r1 e^{iα1'} and
// a2 + i b2 = r2 e^{2iα2'}, α' the directions converted to swell's frame.
std::vector<double> fourier_spreading(const NdbcDirectionalMoments& moments,
                                      const std::vector<double>& theta);

// The maximum entropy estimate at swell's directions θ (radians), per radian (Lygre & Krogstad
// 1986, eq. 13, with e^{−iθ} in both terms — CDIP's MEM code records a sign typo in the paper's
// eq. 13 there; this sign reproduces c1 = ∫ D e^{iθ} dθ, and wavespectra and CDIP use it), with
// c1 = r1 e^{iα1'}, c2 = r2 e^{2iα2'} in swell's frame:
//   φ1 = (c1 − c2 c1*)/(1 − |c1|²),  φ2 = c2 − c1 φ1,
//   D(θ) = (1/2π) (1 − φ1 c1* − φ2 c2*) / |1 − φ1 e^{−iθ} − φ2 e^{−2iθ}|².
// Not renormalized on the samples. Throws InvalidInput naming `where` (the hour and band, for
// messages) and the fallback where it is undefined: |c1| ≥ 1, a numerator
// 1 − φ1 c1* − φ2 c2* = (1 − |c1|²)(1 − |φ2|²) that is not positive (|φ2| ≥ 1: no non-negative
// distribution has these coefficients, which estimated and rounded coefficients can be), or a
// value that is not finite.
std::vector<double> mem_spreading(const NdbcDirectionalMoments& moments,
                                  const std::vector<double>& theta, const std::string& where = "");

// Reads the hour stamped `time` ("YYYY-MM-DD hh:mm", the files' own year, month, day, hour and
// minute, e.g. "2020-06-01 00:50") from the five files into E(ω_j, θ_k):
//  - ω_j = 2π f_j at the centres of NDBC's band table, band_width_j = 2π Δf_j (rad/s), so that
//    m0 = Σ_j Σ_k E_jk Δθ band_width_j = Σ_j S_j Δf_j, NDBC's own m0 (bands that are not the
//    table's take midpoints between their centres: spectral_bands; `notes` name which);
//  - θ_k = direction_samples(directions), directions ≥ 5 (so that the samples integrate the
//    degree-2 Fourier series exactly) and ≤ 36000;
//  - D on the samples, normalized so that Σ_k D(θ_k) Δθ = 1 in every band:
//    fourier: negative samples set to 0, then rescaled (`notes` say in how many bands, the
//    largest negative share clipped, and how far clipping moves a band's first coefficient);
//    mem: rescaled, provided the rescaled samples reproduce the integral 1 and the coefficients
//    c1, c2 within kMemGridTolerance — else the estimate's peak is narrower than the samples
//    resolve, and InvalidInput says how many directions resolve it;
//  - a band whose S is 0 holds 0 at every θ; NDBC prints 999 (missing) for its directions, which
//    is accepted there and only there.
// Throws InvalidInput naming what and where for a missing or malformed file, a malformed time, an
// hour absent from any of the files (or stamped with another minute), files with different
// bands, a missing value ("MM", 999) in a band with energy (file, line, band), or an hour where
// the MEM is undefined (hour, frequency, and the fallback: method = "fourier").
reference::SpectrumTable read_ndbc_directional(const NdbcDirectionalFiles& files,
                                               const std::string& time, DirectionalMethod method,
                                               int directions = 72);

// The five files read once, for taking several hours from them.
struct NdbcDirectionalData {
  BuoySpectrumFile spectra;
  NdbcParameterFile alpha1, alpha2, r1, r2;
};
// Reads the five files (ndbc_files.hpp's readers, each file's header checked against its role)
// and checks that they list the same bands; throws InvalidInput as those readers do, or naming
// the first band where a file departs from the data_spec's.
NdbcDirectionalData read_ndbc_directional_files(const NdbcDirectionalFiles& files);
// read_ndbc_directional on files already read.
reference::SpectrumTable ndbc_directional_table(const NdbcDirectionalData& data,
                                                const std::string& time, DirectionalMethod method,
                                                int directions = 72);

// How closely the MEM's samples, rescaled to Σ D(θ_k) Δθ = 1, must reproduce the integral 1 and
// the coefficients c1 = a1 + i b1, c2 = a2 + i b2 the estimate is built to match: 0.005, half the
// last digit NDBC prints r1 and r2 to (0.01), so that the table holds what the buoy measured to
// the precision it was published with. The rectangle rule is exact for the Fourier series but
// not for the MEM, whose peaks narrow toward a spike as |φ2| → 1 (on 41010's week, 72 directions
// miss this in 65 of the 144 hours where the MEM is defined, 360 directions in none).
inline constexpr double kMemGridTolerance = 0.005;

}  // namespace swell::validation
