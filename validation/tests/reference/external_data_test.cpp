// swell against data nobody on this project wrote: MHKiT-Python's validation files
// (data/external/mhkit, see ../shared/data/external/MANIFEST.md).
//  - ValData1.json: 2 × 30 (k, ω) pairs at h = 10 m (Data1) and 50 m (Data11), made with g = 9.81.
//  - ValData2_CDiP.json: two measured CDIP buoy spectra (CDiP1, CDiP6) in m²/Hz with their own
//    non-uniform bin widths, and MHKiT's moments and periods of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "test_support.hpp"
#include "swell/reference/dispersion.hpp"
#include "swell/reference/moments.hpp"

namespace {

using swell::test::rel;

namespace sr = swell::reference;
using nlohmann::json;

json load(const std::string& name) {
  const std::string path = std::string(SWELL_TEST_DATA_DIR) + "/external/mhkit/" + name;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  return json::parse(in);
}

// A JSON list, or an object keyed by index ("0", "1", …) as pandas writes a Series: values in
// index order either way.
std::vector<double> as_vector(const json& j) {
  std::vector<double> v;
  if (j.is_array()) {
    for (const auto& x : j) v.push_back(x.get<double>());
    return v;
  }
  std::vector<std::pair<long, double>> items;
  for (auto it = j.begin(); it != j.end(); ++it) items.emplace_back(std::stol(it.key()), it.value().get<double>());
  std::sort(items.begin(), items.end());
  for (const auto& [i, x] : items) v.push_back(x);
  return v;
}

double as_number(const json& j) { return j.is_array() ? j.at(0).get<double>() : j.get<double>(); }

}  // namespace

// =============================================================================================
// ValData1.json: dispersion

TEST(ExternalMhkitValData1, FileHasTheExpectedShape) {
  const json d = load("ValData1.json");
  for (const char* key : {"Data1", "Data11"}) {
    ASSERT_TRUE(d.contains(key)) << key;
    EXPECT_EQ(as_vector(d[key]["k"]).size(), 30u) << key;
    EXPECT_EQ(as_vector(d[key]["w"]).size(), 30u) << key;
  }
  EXPECT_EQ(as_number(d["Data1"]["h"]), 10.0);
  EXPECT_EQ(as_number(d["Data11"]["h"]), 50.0);
}

TEST(ExternalMhkitValData1, OmegaOfK) {
  const json d = load("ValData1.json");
  for (const char* key : {"Data1", "Data11"}) {
    const double h = as_number(d[key]["h"]);
    const auto disp = sr::Dispersion::finite_depth(h, 9.81);  // the manifest: made with 9.81
    const auto k = as_vector(d[key]["k"]);
    const auto w = as_vector(d[key]["w"]);
    for (std::size_t i = 0; i < k.size(); ++i) {
      // The file is consistent with g = 9.81 to 4e-8 (MANIFEST.md); the issue asks 1e-6.
      EXPECT_LT(rel(disp.omega(k[i]), w[i]), 1e-6) << key << " k = " << k[i];
    }
  }
}

TEST(ExternalMhkitValData1, KOfOmega) {
  const json d = load("ValData1.json");
  for (const char* key : {"Data1", "Data11"}) {
    const double h = as_number(d[key]["h"]);
    const auto disp = sr::Dispersion::finite_depth(h, 9.81);
    const auto k = as_vector(d[key]["k"]);
    const auto w = as_vector(d[key]["w"]);
    for (std::size_t i = 0; i < k.size(); ++i) {
      // k(ω) has condition number c/c_g ≤ 2, so the file's 4e-8 becomes ≤ 8e-8: within 1e-6.
      EXPECT_LT(rel(disp.wavenumber(w[i]), k[i]), 1e-6) << key << " w = " << w[i];
    }
  }
}

// =============================================================================================
// ValData2_CDiP.json: measured spectra and their moments

namespace {

struct Measured {
  std::vector<double> f, s, df;
  json m, metrics;
};

// The spectra are objects keyed by frequency strings ("0.025", "0.1", …), which nlohmann
// iterates in string order; sort the bins by numeric frequency, and take the bin widths from
// the file's own freqBinWidth (non-uniform: 0.005, 0.0075 and 0.01 Hz).
Measured read_cdip(const json& c) {
  std::vector<std::pair<double, std::string>> keys;
  for (auto it = c["S"].begin(); it != c["S"].end(); ++it) keys.emplace_back(std::stod(it.key()), it.key());
  std::sort(keys.begin(), keys.end());
  Measured r;
  for (const auto& [f, key] : keys) {
    r.f.push_back(f);
    r.s.push_back(c["S"][key].get<double>());
    r.df.push_back(c["freqBinWidth"].at(key).get<double>());
  }
  r.m = c["m"];
  r.metrics = c["metrics"];
  return r;
}

}  // namespace

class ExternalMhkitCdip : public ::testing::TestWithParam<const char*> {};

TEST_P(ExternalMhkitCdip, BinsAreSortedNumericallyAndWidthsNonUniform) {
  const auto r = read_cdip(load("ValData2_CDiP.json")[GetParam()]);
  ASSERT_EQ(r.f.size(), 64u);
  EXPECT_TRUE(std::is_sorted(r.f.begin(), r.f.end()));
  EXPECT_DOUBLE_EQ(r.f.front(), 0.025);
  EXPECT_DOUBLE_EQ(r.f.back(), 0.58);
  EXPECT_NE(*std::min_element(r.df.begin(), r.df.end()), *std::max_element(r.df.begin(), r.df.end()));
}

TEST_P(ExternalMhkitCdip, MomentsMatchTheFile) {
  const auto r = read_cdip(load("ValData2_CDiP.json")[GetParam()]);
  const auto st = sr::measured_sea_state_hz(r.f, r.s, r.df);
  // The file's m_n are Σ S fⁿ Δf in Hz (MANIFEST.md); 64-term sums agree to ~1e-15, the issue
  // asks 1e-6.
  EXPECT_LT(rel(st.moments_hz.m_minus1, r.m["-1"].get<double>()), 1e-6);
  EXPECT_LT(rel(st.moments_hz.m0, r.m["0"].get<double>()), 1e-6);
  EXPECT_LT(rel(st.moments_hz.m1, r.m["1"].get<double>()), 1e-6);
  EXPECT_LT(rel(st.moments_hz.m2, r.m["2"].get<double>()), 1e-6);
  EXPECT_LT(rel(st.moments_hz.m4, r.m["4"].get<double>()), 1e-6);
}

TEST_P(ExternalMhkitCdip, PeriodsAndHeightMatchTheFile) {
  const auto r = read_cdip(load("ValData2_CDiP.json")[GetParam()]);
  const auto st = sr::measured_sea_state_hz(r.f, r.s, r.df);
  const auto& mt = r.metrics;
  // All to 1e-6 as the issue asks (the arithmetic agrees to ~1e-15).
  EXPECT_LT(rel(st.hs, mt["Hm0"].get<double>()), 1e-6);   // 4 √m0
  EXPECT_LT(rel(st.te, mt["Te"].get<double>()), 1e-6);    // m−1/m0
  EXPECT_LT(rel(st.tm02, mt["T0"].get<double>()), 1e-6);  // √(m0/m2)
  EXPECT_LT(rel(st.tm01, mt["Tm"].get<double>()), 1e-6);  // the file's "Tm" is m0/m1 = Tm01
  EXPECT_LT(rel(st.tp, mt["Tp"].get<double>()), 1e-6);    // 1/f of the largest bin
  // The file's "Tc" holds m2/m4 (that is Tc², not √(m2/m4) — MANIFEST.md): check it as such.
  EXPECT_LT(rel(st.moments_hz.m2 / st.moments_hz.m4, mt["Tc"].get<double>()), 1e-6);
}

TEST_P(ExternalMhkitCdip, Epsilon4AgainstManifest) {
  const auto r = read_cdip(load("ValData2_CDiP.json")[GetParam()]);
  const auto st = sr::measured_sea_state_hz(r.f, r.s, r.df);
  // The file's "e" (≈ 0.9999999) is wrong upstream; the manifest gives the textbook
  // ε4 = √(1 − m2²/(m0 m4)) to 7 digits, so 1e-6 relative.
  const double want = std::string(GetParam()) == "CDiP1" ? 0.8141674 : 0.7284561;
  EXPECT_LT(rel(st.epsilon4, want), 1e-6);
  EXPECT_GT(std::abs(st.epsilon4 - r.metrics["e"].get<double>()), 0.1);  // not the upstream bug
}

TEST_P(ExternalMhkitCdip, NuIsLonguetHigginsFromTheFilesMoments) {
  // Trap not in the manifest: the file's "v" is NOT Longuet-Higgins' ν = √(m0 m2/m1² − 1). It
  // is IEC TS 62600-101's spectral width ε0 = √(m0 m−2/m−1² − 1) (MHKiT spectral_width), which
  // needs m−2: reproduced below from the file's spectrum. So ν is checked against the file's
  // own moments m0, m1, m2 instead (1e-6 as the issue asks; arithmetic agrees to ~1e-14).
  const auto r = read_cdip(load("ValData2_CDiP.json")[GetParam()]);
  const auto st = sr::measured_sea_state_hz(r.f, r.s, r.df);
  const double m0 = r.m["0"].get<double>(), m1 = r.m["1"].get<double>(), m2 = r.m["2"].get<double>();
  EXPECT_LT(rel(st.nu, std::sqrt(m0 * m2 / (m1 * m1) - 1)), 1e-6);

  double m_2 = 0, m_1 = 0, m0s = 0;
  for (std::size_t i = 0; i < r.f.size(); ++i) {
    m_2 += r.s[i] * r.df[i] / (r.f[i] * r.f[i]);
    m_1 += r.s[i] * r.df[i] / r.f[i];
    m0s += r.s[i] * r.df[i];
  }
  EXPECT_LT(rel(std::sqrt(m0s * m_2 / (m_1 * m_1) - 1), r.metrics["v"].get<double>()), 1e-9)
      << "the file's v is IEC ε0";
  EXPECT_GT(std::abs(st.nu - r.metrics["v"].get<double>()), 0.05) << "ν differs from the file's v";
}

INSTANTIATE_TEST_SUITE_P(Buoys, ExternalMhkitCdip, ::testing::Values("CDiP1", "CDiP6"));
