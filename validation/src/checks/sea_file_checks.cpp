#include "checks/sea_file_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "swell/reference/ocean_case.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/table_spectrum.hpp"
#include "swell/validation/io/spectrum_table_file.hpp"

namespace swell::validation {
namespace {

using namespace swell::reference;
constexpr double kPi = std::numbers::pi;

// The two-peak sea of data/external/twopeak in wavespectra's netCDF layout, read as its case
// declares it, against the moments its JSON states (computed in Python from the same numbers,
// independently of swell): m0 by the trapezoid rule, m1 and m2 as the exact integrals of the
// piecewise-linear E(f) (the interpolant the case's truth is), the mean direction of the first
// circular moment. The library's quadrature promises 1e-9 relative.
void two_peak_table_checks(const std::filesystem::path& data_dir, std::vector<CheckResult>& out) {
  const auto folder = data_dir / "external/twopeak";
  std::ifstream in(folder / "twopeak_ochi_hubble.json");
  if (!in) throw InvalidInput("cannot read " + (folder / "twopeak_ochi_hubble.json").string());
  const auto facts = nlohmann::json::parse(in);
  SpectrumTableDeclaration d;
  d.file = folder / "twopeak_ochi_hubble.nc";
  d.frequency_unit = "Hz";
  d.density_unit = "m2/Hz/deg";
  d.direction_convention = "nautical_from";
  d.direction_unit = "deg";
  d.select = {{"time", 0}, {"site", 0}};
  const auto table = std::make_shared<const SpectrumTable>(read_spectrum_table(d));
  const auto s = table_frequency_spectrum(table);
  const std::string subject = "twopeak_ochi_hubble.nc (wavespectra efth, Hz, nautical from, m2/Hz/deg)";
  const double m0 = facts.at("m0").get<double>();
  out.push_back(relative_check("table.netcdf_m0", subject, spectral_moment(*s, 0), m0, 2e-9,
                               "m0 against the file's JSON (trapezoid rule = the interpolant's)"));
  out.push_back(relative_check("table.netcdf_m1", subject, spectral_moment(*s, 1),
                               2 * kPi * facts.at("m1_hz_interp").get<double>(), 2e-9,
                               "m1 in rad/s against 2π × the JSON's m1(f) of the interpolant"));
  out.push_back(relative_check("table.netcdf_m2", subject, spectral_moment(*s, 2),
                               4 * kPi * kPi * facts.at("m2_hz_interp").get<double>(), 2e-9,
                               "m2 in rad/s against 4π² × the JSON's m2(f) of the interpolant"));
  const auto psi = table_directional_spectrum(table, Dispersion::deep());
  const double direction = psi->mean_direction() * 180 / kPi;
  out.push_back(error_bound_check(
      "table.netcdf_mean_direction", subject,
      std::abs(std::remainder(direction - facts.at("mean_dir_toward_ccw_from_x_deg").get<double>(), 360.0)),
      1e-9, "|mean direction − the JSON's| in degrees (nautical 261.93° from = 8.07° toward, ccw from +x)"));
  // The parametric sea the file was sampled from: (2.4² + 1.7²)/16; the table's 32 frequencies
  // (0.035…0.6 Hz, ×1.1 apart) and linear interpolation hold it to 0.2 %.
  out.push_back(relative_check("table.netcdf_against_parametric_m0", subject, spectral_moment(*s, 0),
                               facts.at("parametric_m0_for_comparison").get<double>(), 2e-3,
                               "the table's m0 against the two Ochi–Hubble components' Hs²/16"));
}

// A parametric spectrum tabulated every Δω keeps its m0 to the trapezoid rule's error: the
// linear interpolant's m0 differs from ∫ S over the table's range by at most (Δω²/12) ∫|S''|.
void tabulated_jonswap_checks(std::vector<CheckResult>& out) {
  const auto jonswap = make_frequency_spectrum({"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}});
  const double low = 0.3, high = 6.0;
  const double inside = spectral_moment(*jonswap, 0, Band{low, high});
  double curvature = 0;  // ∫|S''| dω by central differences on a 1e-4 grid
  const double h = 1e-4;
  for (double w = low; w < high; w += h) {
    curvature += std::abs(((*jonswap)(w + h) - 2 * (*jonswap)(w) + (*jonswap)(w - h)) / (h * h)) * h;
  }
  for (double step : {0.01, 0.1}) {
    auto table = std::make_shared<SpectrumTable>();
    const int points = int(std::lround((high - low) / step));
    for (int i = 0; i <= points; ++i) {
      table->omega.push_back(low + i * step);
      table->density.push_back((*jonswap)(low + i * step));
    }
    table->source = fmt::format("JONSWAP Hs 3 Tp 8 γ 3.3 every {} rad/s", step);
    const double m0 = spectral_moment(*table_frequency_spectrum(table), 0);
    out.push_back(error_bound_check("table.interpolated_m0", table->source, std::abs(m0 - inside) / inside,
                                    step * step / 12 * curvature / inside + 2e-9,
                                    "|m0 of the linear interpolant − ∫ S| / ∫ S ≤ (Δω²/12) ∫|S''| / ∫ S"));
  }
}

// A composite sea's m0 is the sum of its components': JONSWAP (Hs 2.5, exact normalization)
// plus a Gaussian swell (Hs 1.5, σ 0.05 rad/s; its cut at ω = 0 removes Φ(−ωp/σ) ≈ 1e-70),
// through the directional spectrum the checks integrate.
void composite_checks(std::vector<CheckResult>& out) {
  SeaComponent wind, swell;
  wind.spectrum = {"jonswap", {{"hs", 2.5}, {"tp", 7.0}, {"gamma", 3.3}}, {}};
  wind.spreading = {"cos2s", {{"s", 10.0}}, {}};
  wind.wind_dir_deg = 30;
  swell.spectrum = {"gaussian", {{"hs", 1.5}, {"tp", 14.0}, {"sigma", 0.05}}, {}};
  swell.spreading = {"cos2s", {{"s", 40.0}}, {}};
  swell.wind_dir_deg = 75;
  OceanCase sea;
  sea.grid = Grid::create(64, 64, 200, 200);
  sea.set_components({wind, swell});
  out.push_back(relative_check("composite.m0_is_the_sum", "jonswap Hs 2.5 + gaussian Hs 1.5",
                               spectral_moment(sea.directional_spectrum()->omnidirectional(), 0),
                               (2.5 * 2.5 + 1.5 * 1.5) / 16, 1e-8, "m0 of the summed spectrum against Σ Hs²/16"));
}

}  // namespace

void sea_file_checks(const std::filesystem::path& data_dir, std::vector<CheckResult>& out) {
  two_peak_table_checks(data_dir, out);
  tabulated_jonswap_checks(out);
  composite_checks(out);
}

}  // namespace swell::validation
