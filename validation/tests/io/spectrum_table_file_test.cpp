// Spectra from files (docs/case_files.md §Spectra from files): the two-peak netCDF sea of
// data/external/twopeak read in wavespectra's layout gives the moments and mean direction its
// JSON states (computed independently, in Python, from the same numbers); WAVEWATCH III's
// layout and a CSV table read the same way; the declared conventions convert exactly; and every
// bad file or missing declaration is refused naming what and where.
#include <gtest/gtest.h>
#include <netcdf.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/table_spectrum.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/spectrum_table_file.hpp"

namespace {

namespace fs = std::filesystem;
namespace sr = swell::reference;
namespace sv = swell::validation;
using std::numbers::pi;

const fs::path kTwoPeak = fs::path(SWELL_TEST_DATA_DIR) / "external/twopeak/twopeak_ochi_hubble.nc";

nlohmann::json two_peak_facts() {
  std::ifstream in(fs::path(SWELL_TEST_DATA_DIR) / "external/twopeak/twopeak_ochi_hubble.json");
  return nlohmann::json::parse(in);
}

sv::SpectrumTableDeclaration wavespectra_declaration() {
  sv::SpectrumTableDeclaration d;
  d.file = kTwoPeak;
  d.frequency_unit = "Hz";
  d.density_unit = "m2/Hz/deg";
  d.direction_convention = "nautical_from";
  d.direction_unit = "deg";
  d.select = {{"time", 0}, {"site", 0}};
  return d;
}

std::string refusal(const sv::SpectrumTableDeclaration& d) {
  try {
    (void)sv::read_spectrum_table(d);
  } catch (const swell::InvalidInput& e) {
    return e.what();
  }
  return "accepted";
}

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("swell_table_test_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
};

void check(int status) {
  if (status != NC_NOERR) throw std::runtime_error(nc_strerror(status));
}

// A small netCDF file written here: efth over (`outer` of length `stations`, frequency,
// direction) with WAVEWATCH III's names, values v(i, j) = (i + 1)·(j + 1) unless `value` says.
void write_ww3(const fs::path& path, const std::vector<double>& frequency,
               const std::vector<double>& direction, int stations,
               const std::function<double(int, std::size_t, std::size_t)>& value) {
  int id, d_station, d_freq, d_dir, v_freq, v_dir, v_efth;
  check(nc_create(path.c_str(), NC_CLOBBER, &id));
  check(nc_def_dim(id, "station", std::size_t(stations), &d_station));
  check(nc_def_dim(id, "frequency", frequency.size(), &d_freq));
  check(nc_def_dim(id, "direction", direction.size(), &d_dir));
  check(nc_def_var(id, "frequency", NC_DOUBLE, 1, &d_freq, &v_freq));
  check(nc_def_var(id, "direction", NC_DOUBLE, 1, &d_dir, &v_dir));
  const int dims[3] = {d_station, d_freq, d_dir};
  check(nc_def_var(id, "efth", NC_DOUBLE, 3, dims, &v_efth));
  check(nc_enddef(id));
  check(nc_put_var_double(id, v_freq, frequency.data()));
  check(nc_put_var_double(id, v_dir, direction.data()));
  std::vector<double> values;
  for (int s = 0; s < stations; ++s) {
    for (std::size_t i = 0; i < frequency.size(); ++i) {
      for (std::size_t j = 0; j < direction.size(); ++j) values.push_back(value(s, i, j));
    }
  }
  check(nc_put_var_double(id, v_efth, values.data()));
  check(nc_close(id));
}

}  // namespace

TEST(SpectrumTableFile, TwoPeakNetcdfGivesTheMomentsItsJsonStates) {
  const auto facts = two_peak_facts();
  const auto table = std::make_shared<const sr::SpectrumTable>(
      sv::read_spectrum_table(wavespectra_declaration()));
  ASSERT_EQ(table->omega.size(), 32u);
  ASSERT_EQ(table->theta.size(), 36u);
  const auto s = sr::table_frequency_spectrum(table);
  // The interpolant's exact moments: m0 equals the trapezoid rule's (linear pieces), m1 and m2
  // the JSON's "_interp" values (exact integrals of the piecewise-linear E(f)), converted to
  // rad/s (m_n(ω) = (2π)^n m_n(f)). The library's quadrature promises 1e-9 relative.
  EXPECT_NEAR(sr::spectral_moment(*s, 0), facts["m0"].get<double>(), 2e-9 * facts["m0"].get<double>());
  EXPECT_NEAR(sr::spectral_moment(*s, 1), 2 * pi * facts["m1_hz_interp"].get<double>(),
              2e-9 * 2 * pi * facts["m1_hz_interp"].get<double>());
  EXPECT_NEAR(sr::spectral_moment(*s, 2), 4 * pi * pi * facts["m2_hz_interp"].get<double>(),
              2e-9 * 4 * pi * pi * facts["m2_hz_interp"].get<double>());
  // The mean direction, nautical coming-from 261.93° = travelling toward 8.07° counter-clockwise
  // from +x; the JSON weights frequencies by the trapezoid rule as the table's mean does.
  const auto psi = sr::table_directional_spectrum(table, sr::Dispersion::deep());
  EXPECT_NEAR(psi->mean_direction() * 180 / pi, facts["mean_dir_toward_ccw_from_x_deg"].get<double>(), 1e-9);
  // Parametric m0 of the two Ochi–Hubble components, (2.4² + 1.7²)/16 = 0.5406: the table's grid
  // (0.035…0.6 Hz) and its linear interpolation keep it within 0.2 %.
  EXPECT_NEAR(sr::spectral_moment(*s, 0), facts["parametric_m0_for_comparison"].get<double>(),
              2e-3 * facts["parametric_m0_for_comparison"].get<double>());
}

TEST(SpectrumTableFile, DeclaredUnitsConvertExactly) {
  // The same numbers declared per radian and in rad/s: E scales by exactly the unit ratios.
  const auto base = sv::read_spectrum_table(wavespectra_declaration());
  auto d = wavespectra_declaration();
  d.density_unit = "m2/Hz/rad";
  const auto per_rad = sv::read_spectrum_table(d);
  d.density_unit = "m2.s/rad/rad";
  d.frequency_unit = "rad/s";
  const auto angular = sv::read_spectrum_table(d);
  for (std::size_t k = 0; k < base.density.size(); k += 37) {
    EXPECT_NEAR(per_rad.density[k], base.density[k] * pi / 180, 1e-15 * base.density[k] + 1e-300);
    EXPECT_NEAR(angular.density[k], base.density[k] * 2 * pi * pi / 180, 1e-14 * base.density[k] + 1e-300);
  }
  EXPECT_NEAR(angular.omega[3], base.omega[3] / (2 * pi), 1e-15);
  // toward_ccw_from_x keeps the angles; nautical_from maps θn to 270° − θn.
  d = wavespectra_declaration();
  d.direction_convention = "toward_ccw_from_x";
  const auto toward = sv::read_spectrum_table(d);
  EXPECT_NEAR(toward.theta[1], 10 * pi / 180, 1e-15);
  EXPECT_NEAR(base.theta[0], 0.0, 1e-15);  // 270° − 270° (the file's 270° from)
}

TEST(SpectrumTableFile, MissingOrUnknownDeclarationsAreNamed) {
  auto d = wavespectra_declaration();
  d.frequency_unit = "";
  EXPECT_NE(refusal(d).find("frequency_unit is not declared"), std::string::npos) << refusal(d);
  d = wavespectra_declaration();
  d.direction_convention = "";
  EXPECT_NE(refusal(d).find("direction_convention is not declared"), std::string::npos);
  d = wavespectra_declaration();
  d.direction_unit = "degrees";
  EXPECT_NE(refusal(d).find("direction_unit \"degrees\""), std::string::npos);
  d = wavespectra_declaration();
  d.density_unit = "m2/Hz";  // a 1-D unit for a 2-D table
  EXPECT_NE(refusal(d).find("density_unit \"m2/Hz\""), std::string::npos);
  d = wavespectra_declaration();
  d.variable = "spec";
  EXPECT_NE(refusal(d).find("no variable 'spec'"), std::string::npos) << refusal(d);
  d = wavespectra_declaration();
  d.select = {{"time", 1}};
  EXPECT_NE(refusal(d).find("select time = 1 is outside"), std::string::npos) << refusal(d);
  d = wavespectra_declaration();
  d.select = {{"station", 0}};
  EXPECT_NE(refusal(d).find("select names 'station'"), std::string::npos) << refusal(d);
}

TEST(SpectrumTableFile, WavewatchLayoutNeedsItsStationChosenAndReadsTheOneChosen) {
  Scratch s;
  const fs::path file = s.dir / "ww3.nc";
  // Directions as WAVEWATCH III lists them: descending from a start, cyclically.
  write_ww3(file, {0.05, 0.1, 0.2}, {90, 60, 30, 0, 330, 300, 270, 240, 210, 180, 150, 120}, 2,
            [](int station, std::size_t i, std::size_t j) { return (station + 1) * (i + 1.0) + 0.01 * j; });
  sv::SpectrumTableDeclaration d;
  d.file = file;
  d.frequency_unit = "Hz";
  d.density_unit = "m2/Hz/deg";
  d.direction_convention = "nautical_from";
  d.direction_unit = "deg";
  d.variable = "efth";
  d.frequency_variable = "frequency";
  d.direction_variable = "direction";
  EXPECT_NE(refusal(d).find("select = {station = INDEX}"), std::string::npos) << refusal(d);
  d.select = {{"station", 1}};
  const auto t = sv::read_spectrum_table(d);
  // Station 1, row 2: 2·3 + 0.01 j per degree per Hz; the direction 270° from is θ = 0 here.
  const double per_swell_unit = 180 / pi / (2 * pi);
  EXPECT_NEAR(t.density[2 * 12 + 0], (6 + 0.01 * 6) * per_swell_unit, 1e-12);
}

TEST(SpectrumTableFile, BadValuesAndUnsortedAxesAreNamedByRowAndColumn) {
  Scratch s;
  sv::SpectrumTableDeclaration d;
  d.frequency_unit = "Hz";
  d.density_unit = "m2/Hz/deg";
  d.direction_convention = "nautical_from";
  d.direction_unit = "deg";
  d.frequency_variable = "frequency";
  d.direction_variable = "direction";
  d.select = {{"station", 0}};
  d.file = s.dir / "negative.nc";
  write_ww3(d.file, {0.05, 0.1}, {0, 90, 180, 270}, 1,
            [](int, std::size_t i, std::size_t j) { return i == 1 && j == 2 ? -1.0 : 1.0; });
  EXPECT_NE(refusal(d).find("row 1"), std::string::npos) << refusal(d);
  EXPECT_NE(refusal(d).find("column 2"), std::string::npos) << refusal(d);
  d.file = s.dir / "unsorted_frequency.nc";
  write_ww3(d.file, {0.1, 0.05}, {0, 90, 180, 270}, 1, [](int, std::size_t, std::size_t) { return 1.0; });
  EXPECT_NE(refusal(d).find("frequency is not sorted"), std::string::npos) << refusal(d);
  d.file = s.dir / "unsorted_direction.nc";
  write_ww3(d.file, {0.05, 0.1}, {0, 180, 90, 270}, 1, [](int, std::size_t, std::size_t) { return 1.0; });
  EXPECT_NE(refusal(d).find("not sorted around the circle"), std::string::npos) << refusal(d);
  d.file = s.dir / "nan.nc";
  write_ww3(d.file, {0.05, 0.1}, {0, 90, 180, 270}, 1,
            [](int, std::size_t i, std::size_t j) { return i == 0 && j == 3 ? std::nan("") : 1.0; });
  EXPECT_NE(refusal(d).find("row 0"), std::string::npos) << refusal(d);
  EXPECT_NE(refusal(d).find("column 3"), std::string::npos) << refusal(d);
}

TEST(SpectrumTableFile, CsvTableReadsItsUnitsAndRefusesBadRowsByLine) {
  Scratch s;
  const fs::path file = s.dir / "s.csv";
  std::ofstream(file) << "frequency_hz,density\n0.05,0.0\n0.1,2.0\n0.2,1.0\n0.3,0.0\n";
  sv::SpectrumTableDeclaration d;
  d.file = file;
  d.frequency_unit = "Hz";
  d.density_unit = "m2/Hz";
  auto t = std::make_shared<const sr::SpectrumTable>(sv::read_spectrum_table(d));
  EXPECT_FALSE(t->is_directional());
  // m0 of the linear interpolant: trapezoid in f, 0.05·1 + 0.1·1.5 + 0.1·0.5 = 0.25 m² — the same
  // whichever variable it is integrated in.
  EXPECT_NEAR(sr::spectral_moment(*sr::table_frequency_spectrum(t), 0), 0.25, 1e-9 * 0.25);
  d.frequency_unit = "";
  EXPECT_NE(refusal(d).find("frequency_unit is not declared"), std::string::npos);
  d.frequency_unit = "Hz";
  std::ofstream(file) << "f,S\n0.05,0.0\n0.1,-2.0\n";
  EXPECT_NE(refusal(d).find("s.csv:3: column 2 (density)"), std::string::npos) << refusal(d);
  std::ofstream(file) << "f,S\n0.1,1.0\n0.05,2.0\n";
  EXPECT_NE(refusal(d).find("s.csv:3: column 1 (frequency)"), std::string::npos) << refusal(d);
  std::ofstream(file) << "f,S\n0.1,1.0,3\n";
  EXPECT_NE(refusal(d).find("expected 2 columns"), std::string::npos) << refusal(d);
}

TEST(SpectrumTableFile, ATabulatedJonswapKeepsItsMomentsToTheInterpolationError) {
  // JONSWAP (Hs 3 m, Tp 8 s, γ 3.3) sampled in S(ω) every Δω from 0.3 to 6 rad/s. Its linear
  // interpolant's m0 differs from the spectrum's m0 over [0.3, 6] by the trapezoid rule's error,
  // at most (Δω²/12) ∫|S''| dω (each panel's error is (h³/12) S''(ξ)); beyond the table lies
  // what it does not hold (here ∫ above 6 rad/s is 2.4e-4 of m0, the ω⁻⁵ tail).
  Scratch s;
  const auto jonswap = sr::make_frequency_spectrum({"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}});
  const double inside = sr::spectral_moment(*jonswap, 0, sr::Band{0.3, 6.0});
  // ∫|S''| dω by the test's own differences on a 1e-4 grid.
  double curvature = 0;
  const double h = 1e-4;
  for (double w = 0.3; w < 6.0; w += h) {
    const double second = ((*jonswap)(w + h) - 2 * (*jonswap)(w) + (*jonswap)(w - h)) / (h * h);
    curvature += std::abs(second) * h;
  }
  for (double step : {0.01, 0.1}) {
    const fs::path file = s.dir / "jonswap.csv";
    std::ofstream out(file);
    out.precision(17);
    out << "omega,S\n";
    const int points = int(std::lround(5.7 / step));
    for (int i = 0; i <= points; ++i) out << 0.3 + i * step << "," << (*jonswap)(0.3 + i * step) << "\n";
    out.close();
    sv::SpectrumTableDeclaration d;
    d.file = file;
    d.frequency_unit = "rad/s";
    d.density_unit = "m2.s/rad";
    const auto t = std::make_shared<const sr::SpectrumTable>(sv::read_spectrum_table(d));
    const double table_m0 = sr::spectral_moment(*sr::table_frequency_spectrum(t), 0);
    const double bound = step * step / 12 * curvature;
    std::printf("[ measure  ] JONSWAP tabulated every %g rad/s: m0 %.9g against %.9g on [0.3, 6] "
                "(%.2e relative; bound %.2e) and %.9g in all\n", step, table_m0, inside,
                std::abs(table_m0 / inside - 1), bound / inside, 9.0 / 16);
    EXPECT_LT(std::abs(table_m0 - inside), bound + 2e-9 * inside) << "Δω = " << step;
  }
}

TEST(SpectrumTableFile, ACaseFileTakesATableRelativeToItself) {
  Scratch s;
  fs::copy_file(kTwoPeak, s.dir / "sea.nc");
  const std::string text = R"([grid]
n = [64, 64]
length = [400.0, 400.0]
[time]
dt = 0.5
frames = 2
[spectrum]
model = "table"
file = "sea.nc"
frequency_unit = "Hz"
density_unit = "m2/Hz/deg"
direction_convention = "nautical_from"
direction_unit = "deg"
select = {time = 0, site = 0}
)";
  std::ofstream(s.dir / "case.toml") << text;
  const auto c = sv::read_case_file(s.dir / "case.toml");
  ASSERT_TRUE(c.ocean.table);
  EXPECT_EQ(c.ocean.table->theta.size(), 36u);
  // Written back and read again: the same case (the file by its absolute path).
  const std::string written = sv::case_toml(c);
  EXPECT_NE(written.find("select = {site = 0, time = 0}"), std::string::npos) << written;
  std::ofstream(s.dir / "again.toml") << written;
  const auto again = sv::read_case_file(s.dir / "again.toml");
  EXPECT_EQ(again.ocean.table->density, c.ocean.table->density);
  // A 2-D table with a spreading model is refused; a missing unit is named with the case file.
  std::ofstream(s.dir / "bad.toml") << text + "[spreading]\nmodel = \"cos2s\"\ns = 4.0\n";
  EXPECT_THROW(sv::read_case_file(s.dir / "bad.toml"), swell::InvalidInput);
  std::string missing = text;
  missing.erase(missing.find("direction_unit = \"deg\"\n"), 23);
  std::ofstream(s.dir / "missing.toml") << missing;
  try {
    (void)sv::read_case_file(s.dir / "missing.toml");
    ADD_FAILURE() << "a missing direction_unit was accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("missing.toml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("direction_unit is not declared"), std::string::npos) << e.what();
  }
}
