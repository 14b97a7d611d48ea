// The power table's trial seas (validation/src/gate/trial_seas.hpp): a trial evaluated from the
// case's kept factors is its own psi bit for bit, whatever factor it varies and whatever the
// varied one drags along (a TMA γ' moves the peak, and a peak-following spreading with it).
#include "gate/trial_seas.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "swell/reference/ocean_case.hpp"

namespace swell::validation::detail {
namespace {

using reference::OceanCase;
using Varied = TrialSeas::Varied;

OceanCase sea(const std::string& spectrum, const std::string& spreading) {
  OceanCase c;
  c.grid = reference::Grid::create(64, 64, 400, 400);
  c.spectrum = {spectrum, {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
  if (spectrum == "tma") c.depth = 12;
  c.spreading = {spreading, {}, {}};
  if (spreading == "cos2s") c.spreading.numbers["s"] = 10;
  if (spreading == "mitsuyasu") c.spreading.numbers["s_max"] = 25;
  c.wind_dir_deg = 30;
  return c;
}

// Wave vectors around the peak and far from it, in every quadrant, the origin among them.
std::vector<TrialSeas::WaveVector> wave_vectors() {
  std::vector<TrialSeas::WaveVector> out{{0, 0}};
  for (double k : {0.005, 0.03, 0.0629, 0.1, 0.4, 2.0}) {
    for (int a = 0; a < 16; ++a) {
      const double theta = -std::numbers::pi + (a + 0.37) * std::numbers::pi / 8;
      out.push_back({k * std::cos(theta), k * std::sin(theta)});
    }
  }
  return out;
}

void expect_own_psi(const TrialSeas& seas, const reference::DirectionalSpectrum& trial,
                    const std::vector<double>& values, const std::string& what) {
  ASSERT_EQ(values.size(), seas.size());
  int nonzero = 0;
  for (std::size_t i = 0; i < seas.size(); ++i) {
    const auto [kx, ky] = seas.wave_vectors()[i];
    const double expected = trial.psi(kx, ky);
    nonzero += expected > 0;
    // Bit for bit: the power table's report is the same as with the whole evaluation.
    EXPECT_EQ(std::bit_cast<std::uint64_t>(values[i]), std::bit_cast<std::uint64_t>(expected))
        << what << " at k = (" << kx << ", " << ky << "): " << values[i] << " against " << expected;
  }
  EXPECT_GT(nonzero, 40) << what;
}

TEST(TrialSeas, OwnIsTheSeasPsiBitForBit) {
  for (const auto& [spectrum, spreading] :
       std::vector<std::pair<std::string, std::string>>{{"jonswap", "cos2s"}, {"tma", "mitsuyasu"}}) {
    const auto c = sea(spectrum, spreading);
    const TrialSeas seas(c.directional_spectrum(), wave_vectors());
    expect_own_psi(seas, *c.directional_spectrum(), seas.own(), spectrum + " + " + spreading);
  }
}

TEST(TrialSeas, AnotherGammaIsItsOwnPsiBitForBit) {
  for (const auto& [spectrum, spreading] : std::vector<std::pair<std::string, std::string>>{
           {"jonswap", "cos2s"}, {"jonswap", "mitsuyasu"}, {"tma", "mitsuyasu"}, {"tma", "horvath"},
           {"jonswap", "donelan-banner"}}) {
    const auto c = sea(spectrum, spreading);
    const TrialSeas seas(c.directional_spectrum(), wave_vectors());
    std::vector<double> values;
    for (double gamma : {1.0, 1.7, 3.3, 7.0}) {
      OceanCase other = c;
      other.spectrum.numbers["gamma"] = gamma;
      const auto trial = other.directional_spectrum();
      seas.evaluate(*trial, Varied::spectrum, 0, values);
      expect_own_psi(seas, *trial, values, spectrum + " + " + spreading + ", γ " + std::to_string(gamma));
    }
  }
}

TEST(TrialSeas, AnotherSpreadingIsItsOwnPsiBitForBit) {
  for (const std::string spectrum : {"jonswap", "tma"}) {
    const auto c = sea(spectrum, "cos2s");
    const TrialSeas seas(c.directional_spectrum(), wave_vectors());
    std::vector<double> values;
    for (double s : {0.5, 9.9, 10.0, 40.0}) {
      OceanCase other = c;
      other.spreading.numbers["s"] = s;
      const auto trial = other.directional_spectrum();
      seas.evaluate(*trial, Varied::spreading, 0, values);
      expect_own_psi(seas, *trial, values, spectrum + ", s " + std::to_string(s));
    }
  }
}

// Seas that are not S D c_g / k, or not under the case's dispersion and direction, are
// evaluated whole.
TEST(TrialSeas, OtherSeasAreEvaluatedWhole) {
  const auto c = sea("jonswap", "cos2s");
  const TrialSeas seas(c.directional_spectrum(), wave_vectors());
  std::vector<double> values;
  std::vector<OceanCase> others(5, c);
  others[0].energy_factor = 1.5;
  others[1].wind_dir_deg = 75;
  others[2].depth = 30;
  others[3].gravity = 9.7;
  others[4].spectrum = {"phillips", {{"amplitude", 1e-3}, {"wind_speed", 12.0}}, {}};
  others[4].spreading = {};
  for (std::size_t i = 0; i < others.size(); ++i) {
    const auto trial = others[i].directional_spectrum();
    seas.evaluate(*trial, Varied::spectrum, 0, values);
    expect_own_psi(seas, *trial, values, "other sea " + std::to_string(i));
  }
  // A Phillips case's own values too.
  const TrialSeas phillips(others[4].directional_spectrum(), wave_vectors());
  expect_own_psi(phillips, *others[4].directional_spectrum(), phillips.own(), "Phillips' own");
}

// A turned sea Ψ(R(−Δθ) k): the rotated vector's Ψ up to the rounding of the rotation, a few
// ulps of |k| and θ. Ψ's relative sensitivity to ω reaches 5 (ωp/ω)⁴ ≈ 800 in JONSWAP's low
// tail (k = 0.005 here), hence 10⁻¹² relative; a wrong sense of turn misses by order one.
TEST(TrialSeas, ATurnedSeaIsPsiAtTheRotatedWaveVector) {
  for (const auto& [spectrum, spreading] :
       std::vector<std::pair<std::string, std::string>>{{"jonswap", "cos2s"}, {"tma", "mitsuyasu"}}) {
    const auto c = sea(spectrum, spreading);
    const auto psi = c.directional_spectrum();
    const TrialSeas seas(psi, wave_vectors());
    std::vector<double> values;
    for (double degrees : {0.01, 3.0, 90.0, 179.0}) {
      const double turn = degrees * std::numbers::pi / 180, cr = std::cos(turn), sr = std::sin(turn);
      seas.evaluate(*psi, Varied::direction, turn, values);
      for (std::size_t i = 0; i < seas.size(); ++i) {
        const auto [kx, ky] = seas.wave_vectors()[i];
        const double expected = psi->psi(cr * kx + sr * ky, -sr * kx + cr * ky);
        EXPECT_NEAR(values[i], expected, 1e-12 * std::abs(expected) + 1e-300)
            << spectrum << " turned " << degrees << "° at k = (" << kx << ", " << ky << ")";
      }
    }
  }
}

}  // namespace
}  // namespace swell::validation::detail
