#include "swell/validation/checks/reference_checks.hpp"

#include <algorithm>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>
#include <tuple>

#include "checks/sea_file_checks.hpp"
#include "swell/reference/directional.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"

#ifndef SWELL_SOURCE_DATA_DIR
#define SWELL_SOURCE_DATA_DIR ""
#endif
#ifndef SWELL_INSTALL_DATA_DIR
#define SWELL_INSTALL_DATA_DIR ""
#endif

namespace swell::validation {
namespace {

using namespace swell::reference;
constexpr double kPi = std::numbers::pi;

// Log-spaced points lo … hi inclusive.
std::vector<double> log_space(double lo, double hi, int count) {
  std::vector<double> points(count);
  for (int i = 0; i < count; ++i) points[i] = lo * std::pow(hi / lo, double(i) / (count - 1));
  return points;
}

// A second quadrature, independent of reference/'s Gauss–Kronrod: double-exponential rules,
// asked for 1e-12 (their estimate, like Gauss–Kronrod's, cannot go far below rounding).
double tanh_sinh_integral(const std::function<double(double)>& f, double a, double b) {
  boost::math::quadrature::tanh_sinh<double> rule;
  return rule.integrate(f, a, b, 1e-12);
}
double exp_sinh_integral(const std::function<double(double)>& f, double a) {
  boost::math::quadrature::exp_sinh<double> rule;
  return rule.integrate(f, a, std::numeric_limits<double>::infinity(), 1e-12);
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw InvalidInput("cannot open reference data " + path.string());
  try {
    return nlohmann::json::parse(file);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput("reference data " + path.string() + " is not valid JSON: " + e.what());
  }
}

// ------------------------------------------------------------------ dispersion

void dispersion_checks(const std::filesystem::path& data_dir, std::vector<CheckResult>& out) {
  const std::vector<Dispersion> relations = {
      Dispersion::deep(),
      Dispersion::finite_depth(1.0),
      Dispersion::finite_depth(10.0),
      Dispersion::finite_depth(50.0),
      Dispersion::capillary_gravity(kSeaWaterTensionOverDensity),
      Dispersion::capillary_gravity(kSeaWaterTensionOverDensity, 0.05)};
  const auto wavenumbers = log_space(1e-4, 1e3, 141);
  for (const auto& d : relations) {
    double worst_round_trip = 0, worst_group = 0;
    for (double k : wavenumbers) {
      worst_round_trip = std::max(worst_round_trip, std::abs(d.wavenumber(d.omega(k)) - k) / k);
      // Central difference with step 1e-5 k: truncation ~1e-10, rounding ~1e-11 relative.
      const double h = 1e-5 * k;
      const double fd = (d.omega(k + h) - d.omega(k - h)) / (2 * h);
      worst_group = std::max(worst_group, std::abs(d.group_velocity(k) - fd) / fd);
    }
    out.push_back(error_bound_check("dispersion.round_trip", d.describe(), worst_round_trip, 1e-12,
                                    "max |k(ω(k)) − k|/k over k = 1e-4…1e3 rad/m"));
    out.push_back(error_bound_check("dispersion.group_velocity", d.describe(), worst_group, 1e-7,
                                    "max rel diff of dω/dk from a central difference"));
  }

  // MHKiT's validation pairs (ValData1.json), made with g = 9.81.
  const auto data = read_json(data_dir / "external/mhkit/ValData1.json");
  for (const auto& [name, set] : data.items()) {
    const double depth = set.at("h").get<double>();
    const auto d = Dispersion::finite_depth(depth);
    const auto ks = set.at("k").get<std::vector<double>>();
    const auto ws = set.at("w").get<std::vector<double>>();
    double worst_k = 0, worst_w = 0;
    for (std::size_t i = 0; i < ks.size(); ++i) {
      worst_k = std::max(worst_k, std::abs(d.wavenumber(ws[i]) - ks[i]) / ks[i]);
      worst_w = std::max(worst_w, std::abs(d.omega(ks[i]) - ws[i]) / ws[i]);
    }
    const auto subject = fmt::format("MHKiT ValData1 {} (h = {} m, {} pairs)", name, depth, ks.size());
    out.push_back(error_bound_check("dispersion.mhkit_k_of_omega", subject, worst_k, 1e-6,
                                    "max rel err of k(ω) against MHKiT"));
    out.push_back(error_bound_check("dispersion.mhkit_omega_of_k", subject, worst_w, 1e-6,
                                    "max rel err of ω(k) against MHKiT"));
  }
}

// ------------------------------------------------------------------ spreading

void spreading_checks(std::vector<CheckResult>& out) {
  const double omega_p = 0.8;
  const std::vector<SpreadingPtr> models = {
      Cos2s::constant(1),      Cos2s::constant(10),         Cos2s::constant(80),
      Cos2s::mitsuyasu(25, omega_p), Cos2s::hasselmann(omega_p), DonelanBanner::create(omega_p),
      CosPower::create(2),     CosPower::create(5, true),   Horvath::create(omega_p),
      Horvath::create(omega_p, {0.9, 1.2, 0.3})};
  for (const auto& model : models) {
    double worst = 0;
    for (double r : {0.3, 0.7, 0.95, 1.0, 1.3, 2.5, 6.0}) {
      const double omega = r * omega_p;
      auto d = [&](double theta) { return (*model)(omega, theta); };
      // Split at 0 (the peak) and ±π/2 (the edge of one-sided models).
      const double integral = tanh_sinh_integral(d, -kPi, -kPi / 2) +
                              tanh_sinh_integral(d, -kPi / 2, 0) +
                              tanh_sinh_integral(d, 0, kPi / 2) + tanh_sinh_integral(d, kPi / 2, kPi);
      worst = std::max(worst, std::abs(integral - 1));
    }
    std::string subject = model->name();
    for (const auto& p : model->parameters()) subject += fmt::format(" {}={:g}", p.name, p.value);
    out.push_back(error_bound_check("spreading.normalization", subject, worst, 1e-9,
                                    "max |∫D dθ − 1| over ω/ωp = 0.3…6 (tanh-sinh)"));
  }

  // Horvath (2015) against D(ω, θ) from the paper's formulas in 30-digit mpmath (ωp = 0.8):
  // (ω, θ, U10/cp, ξ, b, D), from below the peak to far above it, with swell and blend.
  struct HorvathValue {
    double omega, theta, wave_age, swell, blend, d;
  };
  const HorvathValue values[] = {
      {0.5, 0.3, 1.17, 0.0, 0.0, 0.31501783792984065},
      {0.8, -1.0, 1.17, 0.5, 0.0, 0.066080017354092106},
      {0.82, 0.7, 2.0, 0.0, 0.0, 0.27928966861672576},
      {1.6, 0.4, 0.9, 1.2, 0.3, 0.47338835027229985},
      {4.0, kPi, 1.17, 0.8, 0.25, 0.039788735772973834},
      {0.2, -0.15, 1.17, 2.0, 0.6, 0.72628144454919155},
      {1.2, 0.05, 3.0, 0.3, 0.1, 0.4084822525240131},
      {2.4, -2.2, 1.17, 0.0, 0.0, 0.086857063600661377}};
  double worst = 0;
  for (const auto& v : values) {
    const auto d = Horvath::create(omega_p, {v.wave_age, v.swell, v.blend});
    worst = std::max(worst, std::abs((*d)(v.omega, v.theta) - v.d) / v.d);
  }
  out.push_back(error_bound_check("spreading.horvath_paper_values", "horvath, 8 (ω, θ, ξ, b)",
                                  worst, 1e-12,
                                  "max rel diff of D from the paper's formulas (mpmath)"));
  // b = 1 is the uniform spread, exactly.
  const auto uniform = Horvath::create(omega_p, {1.17, 1.5, 1.0});
  worst = 0;
  for (double r : {0.3, 1.0, 4.0}) {
    for (double theta : {-3.0, 0.0, 1.0, kPi}) {
      worst = std::max(worst, std::abs((*uniform)(r * omega_p, theta) - 0.5 / kPi));
    }
  }
  out.push_back(error_bound_check("spreading.horvath_uniform_limit", "spread_blend = 1", worst, 0.0,
                                  "max |D − 1/(2π)| over ω, θ"));
}

// ------------------------------------------------------------------ frequency spectra

void spectrum_checks(std::vector<CheckResult>& out) {
  const double hs = 3.0, tp = 8.0, omega_p = 2 * kPi / tp;

  // Pierson–Moskowitz / Bretschneider: m_n = (Hs²/16) ωp^n (5/4)^(n/4) Γ(1 − n/4).
  const auto pm = PiersonMoskowitz::bretschneider(hs, tp);
  for (int n : {-1, 0, 1, 2}) {
    const double closed = hs * hs / 16 * std::pow(omega_p, n) * std::pow(1.25, n / 4.0) *
                          std::tgamma(1 - n / 4.0);
    out.push_back(relative_check("moments.pierson_moskowitz_closed_form",
                                 fmt::format("bretschneider Hs={} Tp={}: m{}", hs, tp, n),
                                 spectral_moment(*pm, n), closed, 1e-9,
                                 "quadrature against (Hs²/16) ωp^n (5/4)^(n/4) Γ(1 − n/4)"));
  }

  // JONSWAP with γ = 1 is Bretschneider, pointwise.
  const auto j1 = Jonswap::from_hs_tp(hs, tp, {1.0, 0.07, 0.09});
  double worst = 0;
  for (double omega : log_space(0.3 * omega_p, 6 * omega_p, 200)) {
    worst = std::max(worst, std::abs((*j1)(omega) - (*pm)(omega)) / (*pm)(omega));
  }
  out.push_back(error_bound_check("spectrum.jonswap_gamma1_is_pm", "Hs=3 Tp=8", worst, 1e-9,
                                  "max rel diff of JONSWAP(γ=1) from Bretschneider"));

  // Exact normalization, confirmed by an independent quadrature (tanh-sinh + exp-sinh).
  for (double gamma : {1.0, 2.0, 3.3, 5.0, 7.0}) {
    const auto j = Jonswap::from_hs_tp(hs, tp, {gamma, 0.07, 0.09});
    auto s = [&](double w) { return (*j)(w); };
    const double m0 = tanh_sinh_integral(s, 0, omega_p) + exp_sinh_integral(s, omega_p);
    out.push_back(relative_check("spectrum.jonswap_exact_hs", fmt::format("γ = {}", gamma),
                                 4 * std::sqrt(m0), hs, 1e-9, "Hs of exact-normalized JONSWAP"));
  }
  // DNV's approximate normalization 1 − 0.287 ln γ, with σa = 0.07, σb = 0.09. Its error is
  // quoted as −0.5 % … +0.2 % for γ in 1.5…5; that holds for Hs. On m0 (twice the Hs error)
  // it reaches +0.29 % near γ = 3.8, measured here and by an independent computation.
  for (double gamma : {1.5, 2.0, 3.3, 3.8, 5.0}) {
    const auto j = Jonswap::from_hs_tp(hs, tp, {gamma, 0.07, 0.09}, JonswapNormalization::dnv);
    const double m0 = spectral_moment(*j, 0);
    out.push_back(range_check("spectrum.jonswap_dnv_hs_error", fmt::format("γ = {}", gamma),
                              4 * std::sqrt(m0) / hs - 1, -0.005, 0.002,
                              fmt::format("Hs/Hs_target − 1 of DNV's 1 − 0.287 ln γ (m0 error {:+.3f} %)",
                                          100 * (m0 / (hs * hs / 16) - 1))));
  }

  // TMA: Φ against Kitaigorodskii's definition Φ = [k⁻³ dk/dω]_h / [k⁻³ dk/dω]_∞
  //      = ω⁵ / (2 g² k³ c_g), with c_g here written out from ω² = g k tanh(kh).
  const double g = kStandardGravity;
  for (double depth : {2.0, 10.0, 40.0}) {
    double worst_phi = 0;
    const auto d = Dispersion::finite_depth(depth);
    for (double omega : log_space(0.05, 5.0, 60)) {
      const double k = d.wavenumber(omega), kh = k * depth;
      const double cg = 0.5 * omega / k * (1 + 2 * kh / std::sinh(2 * kh));
      const double definition = std::pow(omega, 5) / (2 * g * g * k * k * k * cg);
      worst_phi = std::max(worst_phi, std::abs(kitaigorodskii_exact(omega, depth) - definition) /
                                          definition);
    }
    out.push_back(error_bound_check("spectrum.tma_kitaigorodskii", fmt::format("h = {} m", depth),
                                    worst_phi, 1e-12,
                                    "max rel diff of Φ from ω⁵/(2g²k³c_g), ω = 0.05…5 rad/s"));
  }
  const auto jonswap = Jonswap::from_hs_tp(hs, tp);
  const auto deep_tma = Tma::create(jonswap, 1e4);
  worst = 0;
  for (double omega : log_space(0.5 * omega_p, 4 * omega_p, 100)) {
    worst = std::max(worst, std::abs((*deep_tma)(omega) - (*jonswap)(omega)) / (*jonswap)(omega));
  }
  out.push_back(error_bound_check("spectrum.tma_deep_limit", "h = 1e4 m, Tp = 8 s", worst, 1e-12,
                                  "max rel diff of TMA from JONSWAP"));
}

// ------------------------------------------------------------------ swell and two-peak spectra

// Largest relative difference of S at ω = x ωp from a table of independent values.
double worst_relative(const FrequencySpectrum& s, double omega_p, const std::vector<double>& ratios,
                      const std::vector<double>& expected) {
  double worst = 0;
  for (std::size_t i = 0; i < ratios.size(); ++i) {
    worst = std::max(worst, std::abs(s(ratios[i] * omega_p) - expected[i]) / expected[i]);
  }
  return worst;
}

void swell_spectrum_checks(std::vector<CheckResult>& out) {
  // Gaussian swell (DNV-RP-C205), cut at ω = 0: with a = ωp/σ and the standard normal Φ, φ,
  // m0 = (Hs²/16) Φ(a), m1 = (Hs²/16)(ωp Φ + σ φ), m2 = (Hs²/16)((ωp² + σ²) Φ + ωp σ φ).
  for (auto [hs, tp, sigma] : {std::tuple{3.0, 10.0, 0.2}, std::tuple{1.0, 8.0, 0.5}}) {
    const auto g = GaussianSwell::create(hs, tp, sigma);
    const double wp = 2 * kPi / tp, a = wp / sigma, scale = hs * hs / 16;
    const double cdf = 0.5 * std::erfc(-a / std::sqrt(2.0));
    const double pdf = std::exp(-0.5 * a * a) / std::sqrt(2 * kPi);
    const double closed[] = {scale * cdf, scale * (wp * cdf + sigma * pdf),
                             scale * ((wp * wp + sigma * sigma) * cdf + wp * sigma * pdf)};
    for (int n : {0, 1, 2}) {
      out.push_back(relative_check(
          "moments.gaussian_truncated_closed_form",
          fmt::format("gaussian Hs={} Tp={} σ={} rad/s: m{}", hs, tp, sigma, n),
          spectral_moment(*g, n), closed[n], 1e-9,
          "quadrature against the moments of a normal density cut at ω = 0"));
    }
  }

  // Ochi–Hubble: WAFO's published example OchiHubble(Hm0 = 7, par = 2) at ω = 1, 2, 3 rad/s,
  // printed to 8 decimals (pywafo, wafo/spectrum/models.py).
  const double hm0 = 7.0;
  const auto wafo = OchiHubble::create(
      {0.84 * hm0, 2 * kPi * std::exp(0.016 * hm0) / 0.41, 2.55},
      {0.54 * hm0, 2 * kPi * std::exp(0.026 * hm0) / 0.88, 1.82 * std::exp(-0.089 * hm0)});
  double worst = 0;
  const double published[] = {0.90155636, 0.04185445, 0.00583207};
  for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs((*wafo)(i + 1.0) - published[i]));
  out.push_back(error_bound_check("spectrum.ochi_hubble_wafo", "WAFO OchiHubble(Hm0=7, par=2)",
                                  worst, 5e-9, "max |S − WAFO's printed value| at ω = 1, 2, 3"));
  // Each component's moments in closed form: m_n = (Hs²/16) ωp^n ((4λ+1)/4)^(n/4)
  // Γ(λ − n/4)/Γ(λ); a λ = 0.3 component has the slow ω^−2.2 tail.
  for (auto [a, b] : {std::pair{OchiHubbleComponent{3, 14, 3}, OchiHubbleComponent{2, 7, 1.5}},
                      std::pair{OchiHubbleComponent{1, 10, 2}, OchiHubbleComponent{0.8, 5, 0.3}}}) {
    const auto oh = OchiHubble::create(a, b);
    auto closed = [](const OchiHubbleComponent& c, int n) {
      const double wp = 2 * kPi / c.tp;
      return c.hs * c.hs / 16 * std::pow(wp, n) * std::pow((4 * c.lambda + 1) / 4, n / 4.0) *
             std::exp(std::lgamma(c.lambda - n / 4.0) - std::lgamma(c.lambda));
    };
    for (int n : {-1, 0, 1, 2}) {
      if (n >= oh->tail_exponent() - 1) continue;
      out.push_back(relative_check(
          "moments.ochi_hubble_closed_form",
          fmt::format("ochi-hubble λ = {}, {}: m{}", a.lambda, b.lambda, n),
          spectral_moment(*oh, n), closed(a, n) + closed(b, n), 1e-9,
          "quadrature against Σ (Hs²/16) ωp^n c^(n/4) Γ(λ − n/4)/Γ(λ)"));
    }
  }
  // λ = 1 is the Bretschneider spectrum.
  const auto oh1 = OchiHubble::create({3.0, 8.0, 1.0}, {1.0, 5.0, 1.0});
  const auto pm_a = PiersonMoskowitz::bretschneider(3.0, 8.0);
  const auto pm_b = PiersonMoskowitz::bretschneider(1.0, 5.0);
  worst = 0;
  for (double omega : log_space(0.4, 5.0, 200)) {
    const double want = (*pm_a)(omega) + (*pm_b)(omega);
    worst = std::max(worst, std::abs((*oh1)(omega) - want) / want);
  }
  out.push_back(error_bound_check("spectrum.ochi_hubble_lambda1_is_bretschneider",
                                  "Hs = 3, 1 m, Tp = 8, 5 s", worst, 1e-12,
                                  "max rel diff of Ochi–Hubble(λ = 1) from Bretschneider"));

  // Torsethaugen (simplified, DNV-RP-C205) against a 30-digit transcription of DNV's formulas
  // in S(f) (mpmath), at ω = x ωp, and against 4Subsea's waveresponse (the paper's algorithm,
  // g = 9.80665) run with DNV's exponent 0.857; m0/(Hs²/16) against mpmath quadrature — not 1,
  // because DNV's G0 = 3.26 and Aγ are rounded fits.
  const std::vector<double> ratios = {0.5, 0.8, 1.0, 1.3, 2.0, 3.0};
  struct TorsethaugenCase {
    double hs, tp;
    std::vector<double> dnv;
    double m0_ratio;
  };
  const std::vector<TorsethaugenCase> torsethaugen = {
      {4, 8, {0.29061072280691304, 1.0154861613668077, 2.1689281521830715, 0.75343088777611641,
              0.17436898835547997, 0.036072473661372455}, 1.02339960453147},
      {6, 12, {2.2903701689969377e-5, 2.7238151026345937, 7.369622660033775, 3.1436048502715009,
               0.74685108900168517, 0.15511390351634812}, 1.01909993028458},
      {2, 14, {1.1499391172012035e-6, 0.13860647506848924, 0.82035741219281849,
               0.18225984909559211, 0.20855437073644803, 0.072083492449426969}, 1.01383233267775},
      {1, 6.5, {9.2869081527668097e-6, 0.04485281420219434, 0.077528481692127069,
                0.051972787868227158, 0.012367935378364926, 0.0025686595739903307}, 0.998714612509},
  };
  for (const auto& c : torsethaugen) {
    const auto t = Torsethaugen::create(c.hs, c.tp);
    const auto subject =
        fmt::format("torsethaugen Hs={} Tp={} ({})", c.hs, c.tp,
                    t->swell_dominated() ? "swell dominated" : "wind-sea dominated");
    out.push_back(error_bound_check("spectrum.torsethaugen_dnv_transcription", subject,
                                    worst_relative(*t, 2 * kPi / c.tp, ratios, c.dnv), 1e-12,
                                    "max rel diff of S from mpmath, ω/ωp = 0.5…3"));
    out.push_back(relative_check("moments.torsethaugen_m0_ratio", subject,
                                 spectral_moment(*t, 0) / (c.hs * c.hs / 16), c.m0_ratio, 1e-8,
                                 "m0/(Hs²/16) against mpmath quadrature"));
  }
  const std::vector<std::pair<std::pair<double, double>, std::vector<double>>> waveresponse = {
      {{4, 8}, {0.29061072240957536, 1.0154415814299735, 2.1693364676981099, 0.75337705647832154,
                0.17435603185187618, 0.036069782718185117}},
      {{6, 12}, {2.2902279524294233e-05, 2.7236594291702483, 7.3713223664530299,
                 3.1434132105831076, 0.74680471457725195, 0.15510427198724797}},
  };
  for (const auto& [sea, values] : waveresponse) {
    const auto t = Torsethaugen::create(sea.first, sea.second, 9.80665);
    out.push_back(error_bound_check(
        "spectrum.torsethaugen_waveresponse",
        fmt::format("Hs={} Tp={} g=9.80665", sea.first, sea.second),
        worst_relative(*t, 2 * kPi / sea.second, ratios, values), 1e-12,
        "max rel diff of S from waveresponse's algorithm with DNV's 0.857"));
  }
}

// ------------------------------------------------------------------ Ψ(k) Jacobian

void directional_checks(std::vector<CheckResult>& out) {
  struct Case {
    std::string subject;
    DirectionalSpectrumPtr psi;
  };
  const double tp = 8.0, omega_p = 2 * kPi / tp;
  const std::vector<Case> cases = {
      {"jonswap Hs=3 Tp=8 γ=3.3, cos2s s=10, deep, θw=30°",
       SpreadSpectrum::create(Jonswap::from_hs_tp(3, tp), Cos2s::constant(10), Dispersion::deep(),
                              kPi / 6)},
      {"tma h=20 m, donelan-banner, θw=−100°",
       SpreadSpectrum::create(Tma::create(Jonswap::from_hs_tp(3, tp), 20.0),
                              DonelanBanner::create(omega_p), Dispersion::finite_depth(20.0),
                              -100 * kPi / 180)},
      {"phillips A=1e-3 V=12 p=2 l=0.1, against-wind 0.3",
       Phillips::create({1e-3, 12.0, 0.4, 2.0, 0.1, 0.3}, Dispersion::deep())}};
  for (const auto& c : cases) {
    const auto& psi = *c.psi;
    // ∫∫ Ψ dk in polar coordinates: tanh-sinh in θ inside Gauss–Kronrod in k, split at the
    // peak wave number. Against m0 of the omnidirectional S(ω) (a 1-D integral in ω).
    const double k_peak = psi.dispersion().wavenumber(psi.omnidirectional().peak_omega());
    auto ring = [&](double k) {
      if (k == 0) return 0.0;
      auto f = [&](double theta) {
        return psi.psi(k * std::cos(theta), k * std::sin(theta)) * k;
      };
      const double t0 = psi.mean_direction();
      return tanh_sinh_integral(f, t0 - kPi, t0) + tanh_sinh_integral(f, t0, t0 + kPi);
    };
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    const double total = GK::integrate(ring, 0.0, 0.5 * k_peak, 12, 1e-11) +
                         GK::integrate(ring, 0.5 * k_peak, 2 * k_peak, 12, 1e-11) +
                         GK::integrate(ring, 2 * k_peak, std::numeric_limits<double>::infinity(),
                                       12, 1e-11);
    out.push_back(relative_check("directional.psi_integrates_to_m0", c.subject, total,
                                 spectral_moment(psi.omnidirectional(), 0), 1e-8,
                                 "∫∫Ψ dk (polar) against ∫S dω"));
  }
}

// ------------------------------------------------------------------ measured spectra

void measured_spectrum_checks(const std::filesystem::path& data_dir,
                              std::vector<CheckResult>& out) {
  // MHKiT's CDIP buoy spectra with their expected moments (Hz, the file's own bin widths).
  // ε4 in the file is wrong upstream; the values below are the textbook ε4 from the manifest.
  const std::map<std::string, double> epsilon4 = {{"CDiP1", 0.8141674}, {"CDiP6", 0.7284561}};
  const auto data = read_json(data_dir / "external/mhkit/ValData2_CDiP.json");
  for (const auto& [name, record] : data.items()) {
    std::vector<std::pair<double, std::string>> bins;
    for (const auto& [key, value] : record.at("S").items()) bins.emplace_back(std::stod(key), key);
    std::sort(bins.begin(), bins.end());
    std::vector<double> f, s, df;
    for (const auto& [frequency, key] : bins) {
      f.push_back(frequency);
      s.push_back(record.at("S").at(key).get<double>());
      df.push_back(record.at("freqBinWidth").at(key).get<double>());
    }
    const auto state = measured_sea_state_hz(f, s, df);
    const auto& m = record.at("m");
    const auto& metrics = record.at("metrics");
    const std::string subject = "MHKiT ValData2 " + name;
    auto check = [&](const std::string& what, double measured, double expected) {
      out.push_back(relative_check("moments.cdip_" + what, subject, measured, expected, 1e-6,
                                   what + " against the file"));
    };
    check("m_1", state.moments_hz.m_minus1, m.at("-1").get<double>());
    check("m0", state.moments_hz.m0, m.at("0").get<double>());
    check("m1", state.moments_hz.m1, m.at("1").get<double>());
    check("m2", state.moments_hz.m2, m.at("2").get<double>());
    check("m4", state.moments_hz.m4, m.at("4").get<double>());
    check("hm0", state.hs, metrics.at("Hm0").get<double>());
    check("te", state.te, metrics.at("Te").get<double>());
    check("tm02", state.tm02, metrics.at("T0").get<double>());
    check("tm01", state.tm01, metrics.at("Tm").get<double>());
    check("tp", state.tp, metrics.at("Tp").get<double>());
    // The file's "v" is not Longuet-Higgins' ν but the IEC 62600-101 spectral width
    // √(m0 m−2/m−1² − 1); ν is checked against the file's own moments instead.
    const double m0f = m.at("0").get<double>(), m1f = m.at("1").get<double>(),
                 m2f = m.at("2").get<double>();
    check("nu", state.nu, std::sqrt(m0f * m2f / (m1f * m1f) - 1));
    if (epsilon4.count(name)) check("epsilon4", state.epsilon4, epsilon4.at(name));
  }
}

}  // namespace

std::vector<CheckResult> run_reference_checks(const std::filesystem::path& data_dir) {
  std::vector<CheckResult> results;
  dispersion_checks(data_dir, results);
  spreading_checks(results);
  spectrum_checks(results);
  swell_spectrum_checks(results);
  directional_checks(results);
  measured_spectrum_checks(data_dir, results);
  sea_file_checks(data_dir, results);
  return results;
}

std::filesystem::path default_data_directory() {
  if (const char* env = std::getenv("SWELL_DATA_DIR"); env && *env) return env;
  const std::filesystem::path source = SWELL_SOURCE_DATA_DIR;
  if (!source.empty() && std::filesystem::exists(source / "external")) return source;
  return SWELL_INSTALL_DATA_DIR;
}

}  // namespace swell::validation
