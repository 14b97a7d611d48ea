// One hour of NDBC directional data as E(ω, θ) (ndbc_directional.hpp, docs/ndbc_directional.md),
// on buoy 41010's week (data/external/ndbc41010, byte copies of wavespectra's test files):
//  - the directional-parameter reader: 149 records of 46 bands in each file, 999 exactly where
//    the band's S is 0.000, r1 and r2 in [0, 1] (not × 100);
//  - the frame conversion, by a worked example;
//  - both estimates against wavespectra's own code (its NDBC Fourier series and its MEM), run on
//    the same coefficients;
//  - the table's m0 against Σ S_j Δf_j of the record, ∫D dθ = 1 per band, the mean direction and
//    the Fourier coefficients a1, b1, a2, b2 each estimate reproduces;
//  - the Fourier series' negative lobes over the week, and where the MEM is undefined or needs
//    more directions than 72;
//  - bad input, each named by file, line and field or by the hour and frequency.
#include <gtest/gtest.h>

#include "scratch_support.hpp"
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <utility>
#include <string>
#include <vector>

#include "swell/reference/errors.hpp"
#include "swell/validation/io/ndbc_directional.hpp"
#include "swell/validation/io/ndbc_files.hpp"

namespace {

namespace fs = std::filesystem;
namespace sv = swell::validation;
using swell::InvalidInput;
using C = std::complex<double>;
constexpr double kPi = std::numbers::pi;

const std::string kDir = std::string(SWELL_TEST_DATA_DIR) + "/external/ndbc41010/";
const sv::NdbcDirectionalFiles kFiles{kDir + "41010.data_spec", kDir + "41010.swdir",
                                      kDir + "41010.swdir2", kDir + "41010.swr1",
                                      kDir + "41010.swr2"};

// Double-precision evaluations of the same closed form differ by the rounding of a few sums and
// of cos, exp at arguments below 4π: a few 1e-16, so 1e-12 leaves room without hiding a
// wrong term (the smallest coefficient in play, r2 = 0.01, would move D by 3e-3).
constexpr double kSameFormula = 1e-12;
// The table's sums over 46 bands × 72 directions of values up to ~10 in double precision.
constexpr double kSums = 1e-12;

// A scratch directory of the running test's own, removed at the end.
struct Scratch : swell::test::Scratch {
  Scratch() : swell::test::Scratch("swell_ndbc_") {}
};
using swell::test::expect_invalid;

// The week's five files, read once.
struct Week {
  sv::NdbcDirectionalData data = sv::read_ndbc_directional_files(kFiles);
  const sv::BuoySpectrumFile& spectra = data.spectra;

  // Record i of every file is the same hour (checked in ReadsTheWeeksDirectionalFiles).
  sv::NdbcDirectionalMoments moments(std::size_t i, std::size_t j) const {
    return {data.alpha1.records[i].value[j], data.alpha2.records[i].value[j],
            data.r1.records[i].value[j], data.r2.records[i].value[j]};
  }
  static std::string stamp(const sv::BuoySpectrumRecord& r) {
    char text[32];
    std::snprintf(text, sizeof text, "%04d-%02d-%02d %02d:%02d", r.time.year, r.time.month,
                  r.time.day, r.time.hour, r.minute);
    return text;
  }
};

const Week& week() {
  static const Week w;
  return w;
}

// Σ_k D_k e^{inθ_k} Δθ on uniform samples (the factors e^{inθ_k} computed once per size and n).
C coefficient(const std::vector<double>& d, int n) {
  static std::map<std::pair<std::size_t, int>, std::vector<C>> factors;
  auto& e = factors[{d.size(), n}];
  const double dtheta = 2 * kPi / double(d.size());
  if (e.empty()) {
    for (std::size_t k = 0; k < d.size(); ++k) e.push_back(std::polar(1.0, n * dtheta * double(k)));
  }
  C sum = 0;
  for (std::size_t k = 0; k < d.size(); ++k) sum += d[k] * e[k];
  return sum * dtheta;
}

// The table's D in band j (E · 2π / S), from E(ω, θ) = S/(2π) · D.
std::vector<double> table_spreading(const swell::reference::SpectrumTable& t, std::size_t j,
                                    double s) {
  const std::size_t nd = t.theta.size();
  std::vector<double> d(nd);
  for (std::size_t k = 0; k < nd; ++k) d[k] = t.density[j * nd + k] * 2 * kPi / s;
  return d;
}

// ------------------------------------------------------------------------------ the reader

TEST(NdbcDirectionalReader, ReadsTheWeeksDirectionalFiles) {
  const Week& w = week();
  ASSERT_EQ(w.spectra.records.size(), 149u);
  int missing = 0, zero_with_direction = 0;
  double largest_r = 0;
  for (const auto* f : {&w.data.alpha1, &w.data.alpha2, &w.data.r1, &w.data.r2}) {
    ASSERT_EQ(f->records.size(), 149u) << f->path;
    EXPECT_EQ(f->frequency, w.spectra.frequency) << f->path;
    for (std::size_t i = 0; i < 149; ++i) {
      ASSERT_EQ(f->records[i].time, w.spectra.records[i].time) << f->path << " record " << i;
      ASSERT_EQ(f->records[i].minute, 50);
    }
  }
  for (std::size_t i = 0; i < 149; ++i) {
    for (std::size_t j = 0; j < 46; ++j) {
      const auto m = w.moments(i, j);
      const bool none = std::isnan(m.alpha1_deg);
      // The four files agree on which bands have no direction, and those are bands without
      // energy (S printed 0.000).
      EXPECT_EQ(std::isnan(m.alpha2_deg), none);
      EXPECT_EQ(std::isnan(m.r1), none);
      EXPECT_EQ(std::isnan(m.r2), none);
      if (none) {
        ++missing;
        EXPECT_EQ(w.spectra.records[i].density[j], 0.0) << "record " << i << " band " << j + 1;
      } else {
        zero_with_direction += w.spectra.records[i].density[j] == 0.0;
        largest_r = std::max({largest_r, m.r1, m.r2});
      }
    }
  }
  EXPECT_EQ(missing, 1435);              // band-hours printed 999 in all four files
  EXPECT_EQ(zero_with_direction, 365);   // S = 0.000 but directions printed
  EXPECT_EQ(largest_r, 0.95);            // r as it is, not r × 100
}

// ------------------------------------------------------------------------------ the frame

TEST(NdbcDirectional, ConvertsNauticalComingFromToSwellsDirectionOfTravel) {
  // Worked example: waves coming FROM the east (nautical 90°) travel toward the west, which in
  // swell's frame (counter-clockwise from +x = east) is θ = 180°; 270° − 90° = 180°. From the
  // north (0°) they travel south, θ = 270° (= −90°); from the west (270°) east, θ = 0; from the
  // south (180°) north, θ = 90°.
  EXPECT_NEAR(sv::swell_direction_from_nautical(90), kPi, 1e-15);
  EXPECT_NEAR(sv::swell_direction_from_nautical(0), 1.5 * kPi, 1e-15);
  EXPECT_NEAR(sv::swell_direction_from_nautical(360), 1.5 * kPi, 1e-15);
  EXPECT_EQ(sv::swell_direction_from_nautical(270), 0.0);
  EXPECT_NEAR(sv::swell_direction_from_nautical(180), 0.5 * kPi, 1e-15);
  EXPECT_NEAR(sv::swell_direction_from_nautical(225), 0.25 * kPi, 1e-15);  // from SW, toward NE
  // And both estimates of a narrow sea from the east are symmetric about θ = 180° (sample 36 of
  // 72), with their mean direction there; the series peaks there. (The MEM peaks at 180° ± 15°:
  // it is bimodal for these coefficients.)
  const auto theta = sv::direction_samples(72);
  const sv::NdbcDirectionalMoments from_east{90, 90, 0.9, 0.7};
  const auto fourier = sv::fourier_spreading(from_east, theta);
  const auto mem = sv::mem_spreading(from_east, theta);
  EXPECT_EQ(std::max_element(fourier.begin(), fourier.end()) - fourier.begin(), 36);
  for (const auto* d : {&fourier, &mem}) {
    for (std::size_t k = 1; k < 36; ++k) {
      EXPECT_NEAR((*d)[36 + k], (*d)[36 - k], kSameFormula) << "sample 36 ± " << k;
    }
    EXPECT_NEAR(std::abs(std::arg(coefficient(*d, 1))), kPi, 1e-12);
  }
}

// ------------------------------------------------------------------------------ independent code

// wavespectra @ 82c7cb9 run on 41010's coefficients (numpy, double precision):
//  - fourier: `construct_spectra` of wavespectra/input/ndbc_ascii.py (NDBC's series in the
//    nautical frame, per degree) at the nautical directions 270° − θ_k, times 180/π (per radian);
//  - mem: the maximum entropy loop of `read_awac_strings` in wavespectra/input/awac.py (Lygre &
//    Krogstad's φ1, φ2 and D ∝ (1 − φ1 c1* − φ2 c2*)/|1 − φ1 e^{−iθ} − φ2 e^{−2iθ}|², rescaled
//    to sum to 1 over its directions), given c1 = r1 e^{iα1}, c2 = r2 e^{2iα2} in the nautical
//    frame and its directions dDir = θ_k − π (it evaluates at π/2 − dDir = 270° − θ_k), divided
//    by its Δθ (per radian). The same MEM is written in CDIP's MEM_routines.f and in Sofar's
//    ocean_science_utilities (estimators/mem.py).
struct Golden {
  int k;
  double fourier, mem;
};

TEST(NdbcDirectional, MatchesWavespectrasFourierSeriesAndMaximumEntropy) {
  struct Case {
    const char* time;
    std::size_t band;  // 0-based
    std::vector<Golden> values;
  };
  const std::vector<Case> cases{
      // S = 1.06, α1 = 92°, α2 = 92°, r1 = 0.86, r2 = 0.62 (a narrow swell from the east)
      {"2020-06-01 00:50", 15,
       {{0, 0.08244658951207515, 0.004441378615399566},
        {9, -0.04130631106067344, 0.006264736317392756},
        {18, -0.028162831325646658, 0.01877469364817233},
        {27, 0.37312704935644525, 0.19098091881316942},
        {35, 0.6287972989623626, 0.7837053593982719},
        {36, 0.6296060758027805, 0.7835923283912795},
        {45, 0.332083019974051, 0.14608430585938165},
        {54, -0.04727006162162751, 0.016371644749224742},
        {63, -0.02728398590224135, 0.005914683041776204}}},
      // S = 0.17, α1 = 100°, α2 = 80°, r1 = 0.39, r2 = 0.15 (broad)
      {"2020-06-01 00:50", 18,
       {{0, 0.081767083695462, 0.06635992900183497},
        {9, 0.10428093245876273, 0.10331169509697181},
        {18, 0.13584475876736027, 0.15569548171450356},
        {27, 0.24451491981180265, 0.2144090475762491},
        {36, 0.32627683783936184, 0.35827271971363184},
        {38, 0.32355567197580704, 0.3733334718342191},
        {45, 0.24668947159339524, 0.22499600981195197},
        {54, 0.0927310920653973, 0.08851390425015336},
        {63, 0.04113444850362087, 0.05954859658509977}}},
      // S = 1.21, α1 = 196°, α2 = 208°, r1 = 0.78, r2 = 0.42 (the MEM is bimodal here)
      {"2020-06-08 03:50", 21,
       {{0, 0.15283207309862734, 0.016025068247587676},
        {9, 0.48714117990220984, 0.9579387842285222},
        {10, 0.5081036038670176, 2.0911313477993207},
        {18, 0.4725772262655211, 0.14742119685458796},
        {27, 0.16869014597212748, 0.4507584356433382},
        {36, 0.01596064433997569, 0.019373241970946326},
        {45, 0.052837024785729304, 0.004997923359955526},
        {54, -0.004750171336542698, 0.003343901696629818},
        {63, -0.07204857829248514, 0.004618735735699182}}},
  };
  const Week& w = week();
  const auto theta = sv::direction_samples(72);
  for (const auto& c : cases) {
    const auto mem = sv::read_ndbc_directional(kFiles, c.time, sv::DirectionalMethod::mem);
    const auto it = std::find_if(w.spectra.records.begin(), w.spectra.records.end(),
                                 [&](const auto& r) { return Week::stamp(r) == c.time; });
    ASSERT_NE(it, w.spectra.records.end());
    const std::size_t i = std::size_t(it - w.spectra.records.begin());
    const double s = it->density[c.band];
    const auto fourier = sv::fourier_spreading(w.moments(i, c.band), theta);
    const auto mem_d = table_spreading(mem, c.band, s);
    for (const auto& g : c.values) {
      EXPECT_NEAR(fourier[std::size_t(g.k)], g.fourier, kSameFormula)
          << c.time << " band " << c.band + 1 << " θ sample " << g.k;
      EXPECT_NEAR(mem_d[std::size_t(g.k)], g.mem, kSameFormula * std::max(1.0, g.mem))
          << c.time << " band " << c.band + 1 << " θ sample " << g.k;
    }
  }
}

// ------------------------------------------------------------------------------ the table

// Hours where the MEM is resolved by 72 directions (06-01 00h, 06-08 03h: the week's ends) and a
// stormy one (06-02 00h), read by both methods.
TEST(NdbcDirectional, TableHoldsNdbcsEnergyAndEachBandIntegratesToOne) {
  const Week& w = week();
  const auto bands = sv::spectral_bands(w.spectra.frequency);
  ASSERT_EQ(bands.convention, sv::BandConvention::ndbc_wpm_table);
  for (const char* time : {"2020-06-01 00:50", "2020-06-08 03:50", "2020-06-02 00:50"}) {
    const auto it = std::find_if(w.spectra.records.begin(), w.spectra.records.end(),
                                 [&](const auto& r) { return Week::stamp(r) == time; });
    ASSERT_NE(it, w.spectra.records.end());
    double m0_ndbc = 0;
    for (std::size_t j = 0; j < 46; ++j) m0_ndbc += it->density[j] * bands.width[j];
    for (auto method : {sv::DirectionalMethod::fourier, sv::DirectionalMethod::mem}) {
      const int directions = std::string(time) == "2020-06-02 00:50" ? 360 : 72;
      const auto t = sv::read_ndbc_directional(kFiles, time, method, directions);
      SCOPED_TRACE(std::string(time) + " " + sv::directional_method_name(method));
      ASSERT_TRUE(t.is_directional());
      ASSERT_EQ(t.omega.size(), 46u);
      ASSERT_EQ(t.theta.size(), std::size_t(directions));
      ASSERT_EQ(t.density.size(), 46u * std::size_t(directions));
      const double dtheta = 2 * kPi / directions;
      double m0 = 0;
      for (std::size_t j = 0; j < 46; ++j) {
        EXPECT_NEAR(t.omega[j], 2 * kPi * bands.centre[j], 1e-15);
        EXPECT_NEAR(t.band_width[j], 2 * kPi * bands.width[j], 1e-15);
        double band = 0;
        for (std::size_t k = 0; k < t.theta.size(); ++k) {
          const double e = t.density[j * t.theta.size() + k];
          ASSERT_GE(e, 0.0) << "band " << j + 1 << " sample " << k;
          band += e * dtheta;
        }
        m0 += band * t.band_width[j];
        const double s = it->density[j];
        if (s > 0) {
          // ∫ D dθ = 1: the band's E integrates over θ to S/(2π).
          EXPECT_NEAR(band * 2 * kPi / s, 1.0, kSums) << "band " << j + 1;
        } else {
          EXPECT_EQ(band, 0.0) << "band " << j + 1;
        }
      }
      // m0 = Σ S_j Δf_j with NDBC's WPM widths, to the rounding of the sums.
      EXPECT_NEAR(m0, m0_ndbc, kSums * m0_ndbc);
      EXPECT_NE(t.source.find("41010.data_spec line"), std::string::npos) << t.source;
      EXPECT_NE(t.source.find(time), std::string::npos) << t.source;
    }
  }
}

// The estimates reproduce the buoy's a1 + i b1 = r1 e^{iα1'} and a2 + i b2 = r2 e^{2iα2'} (α'
// in swell's frame), over every band of every hour.
TEST(NdbcDirectional, EstimatesReproduceTheMeasuredFourierCoefficients) {
  const Week& w = week();
  const auto theta72 = sv::direction_samples(72);
  // The MEM is no trigonometric polynomial: its coefficients on N samples converge
  // geometrically, at the rate its own coefficients decay (|z|^N for the pole z of the AR(2)
  // model nearest the unit circle). 3600 samples bring the week's narrowest peak to rounding
  // (its integral to 1e-14, measured independently in double precision).
  const auto theta_fine = sv::direction_samples(3600);
  double fourier_worst = 0, mem_worst = 0;
  int mem_bands = 0, mem_undefined = 0;
  for (std::size_t i = 0; i < w.spectra.records.size(); ++i) {
    for (std::size_t j = 0; j < 46; ++j) {
      const auto m = w.moments(i, j);
      if (std::isnan(m.r1)) continue;
      const C c1 = std::polar(m.r1, sv::swell_direction_from_nautical(m.alpha1_deg));
      const C c2 = std::polar(m.r2, 2 * sv::swell_direction_from_nautical(m.alpha2_deg));
      // The Fourier series is a trigonometric polynomial of degree 2: on N ≥ 5 samples the
      // rectangle rule gives its integral and coefficients exactly.
      const auto f = sv::fourier_spreading(m, theta72);
      fourier_worst = std::max({fourier_worst, std::abs(coefficient(f, 0) - 1.0),
                                std::abs(coefficient(f, 1) - c1),
                                std::abs(coefficient(f, 2) - c2)});
      if (w.spectra.records[i].density[j] == 0) continue;
      try {
        const auto d = sv::mem_spreading(m, theta_fine);
        ++mem_bands;
        mem_worst = std::max({mem_worst, std::abs(coefficient(d, 0) - 1.0),
                              std::abs(coefficient(d, 1) - c1), std::abs(coefficient(d, 2) - c2)});
      } catch (const InvalidInput&) {
        ++mem_undefined;
      }
    }
  }
  EXPECT_LT(fourier_worst, 1e-14);
  EXPECT_LT(mem_worst, 1e-12);
  EXPECT_EQ(mem_bands, 5049);
  EXPECT_EQ(mem_undefined, 5);  // |φ2| > 1 (MemOverTheWeek)
}

// On the table: the mean direction atan2(∫ D sin θ, ∫ D cos θ) of each band is α1 in swell's
// frame and |∫ D e^{iθ}| = r1 — exactly for the Fourier series where nothing is clipped, to
// kMemGridTolerance for the MEM on 72 directions (the tolerance the reader holds it to).
TEST(NdbcDirectional, TableBandsHaveTheMeasuredMeanDirectionAndSpread) {
  const Week& w = week();
  for (const char* time : {"2020-06-01 00:50", "2020-06-08 03:50"}) {
    const auto it = std::find_if(w.spectra.records.begin(), w.spectra.records.end(),
                                 [&](const auto& r) { return Week::stamp(r) == time; });
    const std::size_t i = std::size_t(it - w.spectra.records.begin());
    const auto fourier = sv::read_ndbc_directional(kFiles, time, sv::DirectionalMethod::fourier);
    const auto mem = sv::read_ndbc_directional(kFiles, time, sv::DirectionalMethod::mem);
    int unclipped = 0;
    for (std::size_t j = 0; j < 46; ++j) {
      const double s = it->density[j];
      if (s == 0) continue;
      const auto m = w.moments(i, j);
      const double alpha1 = sv::swell_direction_from_nautical(m.alpha1_deg);
      const C c1 = std::polar(m.r1, alpha1);
      const C c2 = std::polar(m.r2, 2 * sv::swell_direction_from_nautical(m.alpha2_deg));
      SCOPED_TRACE(std::string(time) + " band " + std::to_string(j + 1));

      const auto d_mem = table_spreading(mem, j, s);
      const C mem_c1 = coefficient(d_mem, 1);
      EXPECT_LE(std::abs(mem_c1 - c1), sv::kMemGridTolerance);
      EXPECT_LE(std::abs(coefficient(d_mem, 2) - c2), sv::kMemGridTolerance);
      EXPECT_NEAR(std::abs(mem_c1), m.r1, sv::kMemGridTolerance);
      // The direction of c1 moves by at most asin(tolerance / r1).
      if (m.r1 > 2 * sv::kMemGridTolerance) {
        EXPECT_LE(std::abs(std::arg(mem_c1 / c1)), std::asin(sv::kMemGridTolerance / m.r1));
      }

      const auto raw = sv::fourier_spreading(m, sv::direction_samples(72));
      if (*std::min_element(raw.begin(), raw.end()) < 0) continue;  // clipped: MemOverTheWeek
      ++unclipped;
      const auto d = table_spreading(fourier, j, s);
      const C f_c1 = coefficient(d, 1);
      EXPECT_NEAR(std::abs(f_c1), m.r1, 1e-14);
      if (m.r1 > 0) {
        const double mean = std::atan2(f_c1.imag(), f_c1.real());
        EXPECT_NEAR(std::remainder(mean - alpha1, 2 * kPi), 0.0, 1e-13);
      }
      EXPECT_NEAR(std::abs(coefficient(d, 2) - c2), 0.0, 1e-14);
    }
    EXPECT_GT(unclipped, 0) << time;
  }
}

// ------------------------------------------------------------------------------ the week

// The claim "the Fourier series goes negative in every hour", counted on 72 samples, and what
// clipping costs.
TEST(NdbcDirectional, FourierSeriesGoesNegativeInEveryHourOfTheWeek) {
  const Week& w = week();
  const auto theta = sv::direction_samples(72);
  const double dtheta = 2 * kPi / 72;
  int hours = 0, bands = 0, negative_bands = 0;
  double largest = 0;
  std::string where;
  for (std::size_t i = 0; i < w.spectra.records.size(); ++i) {
    bool negative_hour = false;
    for (std::size_t j = 0; j < 46; ++j) {
      if (w.spectra.records[i].density[j] == 0) continue;
      ++bands;
      const auto d = sv::fourier_spreading(w.moments(i, j), theta);
      double negative = 0;
      for (double x : d) negative += std::max(-x, 0.0) * dtheta;
      if (negative > 0) {
        negative_hour = true;
        ++negative_bands;
      }
      if (negative > largest) {
        largest = negative;
        where = Week::stamp(w.spectra.records[i]) + " band " + std::to_string(j + 1);
      }
    }
    hours += negative_hour;
  }
  EXPECT_EQ(hours, 149);
  EXPECT_EQ(bands, 5054);
  EXPECT_EQ(negative_bands, 4383);
  EXPECT_NEAR(largest, 0.2712, 5e-5);
  EXPECT_EQ(where, "2020-06-07 00:50 band 19");
  // The table says so: the hour of the largest clipped share.
  const auto t = sv::read_ndbc_directional(kFiles, "2020-06-07 00:50",
                                           sv::DirectionalMethod::fourier);
  bool said = false;
  for (const auto& note : t.notes) said = said || note.find("0.2712") != std::string::npos;
  EXPECT_TRUE(said) << t.notes.back();
}

// Where the MEM is undefined (5 hours: |φ2| > 1 in one band each) and where 72 directions do not
// resolve it; 360 directions resolve every hour where it is defined.
TEST(NdbcDirectional, MemOverTheWeek) {
  const Week& w = week();
  std::set<std::string> undefined, unresolved72;
  int resolved72 = 0, resolved360 = 0;
  for (const auto& r : w.spectra.records) {
    const std::string time = Week::stamp(r);
    // 360 directions first: where the MEM is defined they resolve it, so what fails is undefined.
    try {
      sv::ndbc_directional_table(w.data, time, sv::DirectionalMethod::mem, 360);
      ++resolved360;
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("undefined"), std::string::npos) << what;
      ASSERT_NE(what.find(time), std::string::npos) << what;
      ASSERT_NE(what.find("method = \"fourier\""), std::string::npos) << what;
      undefined.insert(time);
    }
    // On 72 an hour can fail in an unresolved band before its undefined one.
    try {
      sv::ndbc_directional_table(w.data, time, sv::DirectionalMethod::mem, 72);
      ++resolved72;
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      ASSERT_NE(what.find(time), std::string::npos) << what;
      ASSERT_NE(what.find("method = \"fourier\""), std::string::npos) << what;
      if (!undefined.count(time)) unresolved72.insert(time);
    }
  }
  EXPECT_EQ(undefined, (std::set<std::string>{"2020-06-02 01:50", "2020-06-05 18:50",
                                              "2020-06-05 23:50", "2020-06-06 13:50",
                                              "2020-06-06 19:50"}));
  EXPECT_EQ(unresolved72.size(), 65u);
  EXPECT_EQ(resolved72, 79);
  EXPECT_EQ(resolved360, 144);
  // An unresolved hour's message says which resolution resolves it.
  expect_invalid(
      [] { sv::read_ndbc_directional(kFiles, "2020-06-04 12:50", sv::DirectionalMethod::mem); },
      {"41010.data_spec 2020-06-04 12:50", "Hz", "narrower than 72 directions resolve",
       "directions = 144 resolves it", "method = \"fourier\""});
}

// ------------------------------------------------------------------------------ bad input

// Five files of one record with three bands (0.100, 0.110, 0.120 Hz: midpoint widths), the
// middle band's directional values given.
struct Synthetic {
  Scratch scratch;
  sv::NdbcDirectionalFiles files;
  explicit Synthetic(const std::string& a1 = "100.0", const std::string& a2 = "100.0",
                     const std::string& r1 = "0.50", const std::string& r2 = "0.30",
                     const std::string& s = "1.000") {
    const std::string stamp = "2020 06 01 00 50";
    auto one = [&](const std::string& header, const std::string& middle, const std::string& rest) {
      return header + "\n" + stamp + " " + rest + " (0.100) " + middle + " (0.110) " + rest +
             " (0.120)\n";
    };
    files.data_spec = scratch.write(
        "b.data_spec", "#YY  MM DD hh mm Sep_Freq  < spec_1 (freq_1) spec_2 (freq_2) ... >\n" +
                           stamp + " 0.200 0.500 (0.100) " + s + " (0.110) 0.400 (0.120)\n");
    const std::string header = "#YY  MM DD hh mm ";
    files.swdir = scratch.write("b.swdir", one(header + "alpha1_1 (freq_1) ... >", a1, "90.0"));
    files.swdir2 = scratch.write("b.swdir2", one(header + "alpha2_1 (freq_1) ... >", a2, "90.0"));
    files.swr1 = scratch.write("b.swr1", one(header + "r1_1 (freq_1) ... >", r1, "0.40"));
    files.swr2 = scratch.write("b.swr2", one(header + "r2_1 (freq_1) ... >", r2, "0.20"));
  }
};

TEST(NdbcDirectional, UndefinedMaximumEntropyNamesTheHourTheFrequencyAndTheFallback) {
  // r1 = 0.95 with r2 = 0: a distribution that concentrated must have r2 ≥ 2 r1² − 1 = 0.805
  // (∫ D cos 2(θ − α) ≥ 2(∫ D cos(θ − α))² − 1 by Jensen), so no D ≥ 0 has these
  // coefficients: |φ2| = r1²/(1 − r1²) = 9.26 > 1.
  const Synthetic impossible("100.0", "100.0", "0.95", "0.00");
  expect_invalid(
      [&] {
        sv::read_ndbc_directional(impossible.files, "2020-06-01 00:50", sv::DirectionalMethod::mem);
      },
      {"b.data_spec 2020-06-01 00:50", "band 2 (0.110 Hz)", "undefined", "r1 = 0.95",
       "|φ2| = 9.256", "use method = \"fourier\""});
  // The Fourier series takes the same hour, clipped.
  const auto t = sv::read_ndbc_directional(impossible.files, "2020-06-01 00:50",
                                           sv::DirectionalMethod::fourier);
  EXPECT_NE(t.notes.back().find("D < 0 on the samples in 1 of 3 bands"), std::string::npos)
      << t.notes.back();
  // |c1| = r1 = 1: φ1 divides by 1 − |c1|² = 0.
  const Synthetic one("100.0", "100.0", "1.00", "1.00");
  expect_invalid(
      [&] { sv::read_ndbc_directional(one.files, "2020-06-01 00:50", sv::DirectionalMethod::mem); },
      {"2020-06-01 00:50", "0.110 Hz", "|c1| = r1 = 1", "use method = \"fourier\""});
}

TEST(NdbcDirectional, BadInputNamesWhatAndWhere) {
  const auto mem = sv::DirectionalMethod::mem;
  const auto fourier = sv::DirectionalMethod::fourier;
  // Times: malformed, impossible, absent (the record has gaps: 06-06 01–09), another minute.
  expect_invalid([&] { sv::read_ndbc_directional(kFiles, "2020-6-1 00:50", fourier); },
                 {"time '2020-6-1 00:50'", "YYYY-MM-DD hh:mm"});
  expect_invalid([&] { sv::read_ndbc_directional(kFiles, "2020-06-01T00:50", fourier); },
                 {"time '2020-06-01T00:50'", "character 11"});
  expect_invalid([&] { sv::read_ndbc_directional(kFiles, "2020-02-30 00:50", fourier); },
                 {"time '2020-02-30 00:50'", "day 30 is outside [1, 29]"});
  expect_invalid([&] { sv::read_ndbc_directional(kFiles, "2020-06-01 24:50", fourier); },
                 {"hour 24"});
  expect_invalid([&] { sv::read_ndbc_directional(kFiles, "2020-06-06 05:50", fourier); },
                 {"41010.data_spec has no record stamped 2020-06-06 05:50",
                  "from 2020-06-01 00:50 to 2020-06-08 03:50"});
  expect_invalid([&] { sv::read_ndbc_directional(kFiles, "2020-06-01 00:40", fourier); },
                 {"41010.data_spec has no record stamped 2020-06-01 00:40",
                  "stamps that hour 2020-06-01 00:50", "line 150"});
  // An hour missing from one file only.
  {
    Synthetic s;
    std::ofstream(s.files.swr2) << "2020 06 01 01 50 0.20 (0.100) 0.30 (0.110) 0.20 (0.120)\n";
    expect_invalid([&] { sv::read_ndbc_directional(s.files, "2020-06-01 00:50", fourier); },
                   {"b.swr2 has no record stamped 2020-06-01 00:50"});
  }
  // Files: missing, in the wrong order, with other bands.
  {
    auto files = kFiles;
    files.swr1 = kDir + "41010.nonexistent";
    expect_invalid([&] { sv::read_ndbc_directional(files, "2020-06-01 00:50", fourier); },
                   {"cannot open", "41010.nonexistent"});
    files = kFiles;
    std::swap(files.swdir, files.swdir2);
    expect_invalid([&] { sv::read_ndbc_directional(files, "2020-06-01 00:50", fourier); },
                   {"41010.swdir2 line 1", "names alpha2 values", "given as the alpha1 file"});
    Synthetic s;
    files = kFiles;
    files.swdir = s.files.swdir;
    expect_invalid([&] { sv::read_ndbc_directional(files, "2020-06-01 00:50", fourier); },
                   {"b.swdir has 3 bands", "41010.data_spec has 46", "band 1"});
  }
  // Missing values in the hour's record, named by file, line and band.
  {
    const Synthetic s("999.0");
    expect_invalid([&] { sv::read_ndbc_directional(s.files, "2020-06-01 00:50", mem); },
                   {"b.swdir line 2, field alpha1_2", "band 2 (0.110 Hz)", "missing",
                    "S = 1 m²/Hz"});
    const Synthetic t("100.0", "100.0", "0.50", "MM");
    expect_invalid([&] { sv::read_ndbc_directional(t.files, "2020-06-01 00:50", fourier); },
                   {"b.swr2 line 2, field r2_2", "missing"});
    const Synthetic u("100.0", "100.0", "0.50", "0.30", "MM");
    expect_invalid([&] { sv::read_ndbc_directional(u.files, "2020-06-01 00:50", fourier); },
                   {"b.data_spec line 2, field spec_2", "'MM'"});
    // 999 where S = 0 is NDBC's way of saying "no direction": accepted, E = 0 there.
    const Synthetic v("999.0", "999.0", "999.00", "999.00", "0.000");
    const auto table = sv::read_ndbc_directional(v.files, "2020-06-01 00:50", mem);
    for (std::size_t k = 0; k < 72; ++k) EXPECT_EQ(table.density[72 + k], 0.0);
  }
  // Values out of range: r × 100 (NDBC's historical files), an angle past 360°, not a number.
  {
    const Synthetic s("100.0", "100.0", "86");
    expect_invalid([&] { sv::read_ndbc_directional(s.files, "2020-06-01 00:50", fourier); },
                   {"b.swr1 line 2, field r1_2", "86 is outside [0, 1]", "r × 100"});
    const Synthetic t("361.0");
    expect_invalid([&] { sv::read_ndbc_directional(t.files, "2020-06-01 00:50", fourier); },
                   {"b.swdir line 2, field alpha1_2", "361° is outside [0, 360]"});
    const Synthetic u("100.0", "east");
    expect_invalid([&] { sv::read_ndbc_directional(u.files, "2020-06-01 00:50", fourier); },
                   {"b.swdir2 line 2, field alpha2_2", "'east' is not a number"});
  }
  // Arguments.
  expect_invalid([&] { sv::read_ndbc_directional(kFiles, "2020-06-01 00:50", fourier, 4); },
                 {"directions", "[5, 36000]", "got 4"});
  expect_invalid([] { sv::parse_directional_method("entropy"); },
                 {"'entropy'", "\"fourier\"", "\"mem\""});
  EXPECT_EQ(sv::parse_directional_method("mem"), mem);
  EXPECT_EQ(sv::parse_directional_method("fourier"), fourier);
}

}  // namespace
