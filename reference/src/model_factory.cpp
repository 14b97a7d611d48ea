#include "swell/reference/model_factory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>

#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"

namespace swell::reference {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

const std::vector<ParameterInfo> kCommon = {
    {"gravity", "m/s²", "gravitational acceleration (default 9.81)"},
    {"depth", "m", "water depth for the dispersion relation (default inf: deep water)"},
    {"wind_dir", "deg", "direction the waves travel toward, counter-clockwise from +x (default 0)"},
};
const std::vector<ParameterInfo> kJonswap = {
    {"hs", "m", "significant wave height (with tp or omega_p)"},
    {"tp", "s", "peak period"},
    {"omega_p", "rad/s", "peak angular frequency (alternative to tp)"},
    {"alpha", "", "Phillips constant α (with tp or omega_p)"},
    {"u10", "m/s", "wind speed at 10 m (with fetch)"},
    {"fetch", "m", "fetch (with u10)"},
    {"gamma", "", "peak enhancement γ ≥ 1 (default 3.3)"},
    {"sigma_a", "", "peak width below ωp (default 0.07)"},
    {"sigma_b", "", "peak width above ωp (default 0.09)"},
    {"normalization", "exact|dnv", "with hs: exact (default) or DNV's 1 − 0.287 ln γ"},
};

std::vector<ParameterInfo> with_common(std::vector<ParameterInfo> own) {
  own.insert(own.end(), kCommon.begin(), kCommon.end());
  return own;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::string parameter_names(const std::vector<ParameterInfo>& infos) {
  std::vector<std::string> names;
  for (const auto& info : infos) names.push_back(info.name);
  return join(names);
}

class Reader {
 public:
  Reader(const ModelSpec& spec, std::string what, const std::vector<ParameterInfo>& allowed)
      : spec_(spec), what_(std::move(what)) {
    std::set<std::string> known;
    for (const auto& info : allowed) known.insert(info.name);
    auto check = [&](const std::string& name) {
      if (!known.count(name)) {
        throw InvalidInput(what_ + " '" + spec_.model + "' does not take parameter '" + name +
                           "'; valid: " + parameter_names(allowed));
      }
    };
    for (const auto& [name, value] : spec.numbers) check(name);
    for (const auto& [name, value] : spec.choices) check(name);
    for (const auto& [name, value] : spec.numbers) {
      require(!std::isnan(value), what_ + " parameter " + name, "a number", value);
    }
  }
  std::optional<double> number(const std::string& name) const {
    auto it = spec_.numbers.find(name);
    return it == spec_.numbers.end() ? std::nullopt : std::optional<double>(it->second);
  }
  double number_or(const std::string& name, double fallback) const {
    return number(name).value_or(fallback);
  }
  double required(const std::string& name, const std::string& meaning) const {
    auto value = number(name);
    if (!value) throw InvalidInput(spec_.model + " needs " + name + " (" + meaning + ")");
    return *value;
  }
  std::string choice(const std::string& name, const std::vector<std::string>& valid) const {
    auto it = spec_.choices.find(name);
    if (it == spec_.choices.end()) return valid.front();
    if (std::find(valid.begin(), valid.end(), it->second) == valid.end()) {
      throw InvalidInput(spec_.model + ": " + name + " '" + it->second + "' is not one of: " +
                         join(valid));
    }
    return it->second;
  }
  bool has_choice(const std::string& name) const { return spec_.choices.count(name) > 0; }
  const std::string& model() const { return spec_.model; }

 private:
  const ModelSpec& spec_;
  std::string what_;
};

// tp or omega_p, not both; the peak angular frequency.
std::optional<double> peak_omega_of(const Reader& r) {
  auto tp = r.number("tp"), omega_p = r.number("omega_p");
  if (tp && omega_p) throw InvalidInput(r.model() + ": give tp or omega_p, not both");
  if (tp) {
    require(*tp > 0 && std::isfinite(*tp), "tp (peak period)", "finite and > 0 s", *tp);
    return 2.0 * std::numbers::pi / *tp;
  }
  return omega_p;
}

std::shared_ptr<const Jonswap> make_jonswap(const Reader& r) {
  const double g = r.number_or("gravity", kStandardGravity);
  const Jonswap::Shape shape{r.number_or("gamma", 3.3), r.number_or("sigma_a", 0.07),
                             r.number_or("sigma_b", 0.09)};
  const auto hs = r.number("hs"), alpha = r.number("alpha"), u10 = r.number("u10"),
             fetch = r.number("fetch");
  const auto omega_p = peak_omega_of(r);
  const int forms = (hs ? 1 : 0) + (alpha ? 1 : 0) + ((u10 || fetch) ? 1 : 0);
  const std::string usage =
      "; give exactly one of: hs with tp (or omega_p); alpha with tp (or omega_p); u10 with fetch";
  if (forms != 1) throw InvalidInput(r.model() + ": ambiguous or missing parameters" + usage);
  if (!hs && r.has_choice("normalization")) {
    throw InvalidInput(r.model() + ": normalization applies only to the hs form (hs with tp)");
  }
  if (u10 || fetch) {
    if (!u10 || !fetch || omega_p) {
      throw InvalidInput(r.model() + ": the wind form takes u10 and fetch and no peak" + usage);
    }
    return Jonswap::from_wind_fetch(*u10, *fetch, shape, g);
  }
  if (!omega_p) throw InvalidInput(r.model() + " needs tp or omega_p" + usage);
  if (alpha) return Jonswap::from_alpha(*alpha, *omega_p, shape, g);
  const auto normalization = r.choice("normalization", {"exact", "dnv"}) == "dnv"
                                 ? JonswapNormalization::dnv
                                 : JonswapNormalization::exact;
  require(std::isfinite(*omega_p) && *omega_p > 0, "omega_p", "finite and > 0 rad/s", *omega_p);
  return Jonswap::from_hs_tp(*hs, 2.0 * std::numbers::pi / *omega_p, shape, normalization, g);
}

}  // namespace

std::vector<std::string> frequency_model_names() {
  return {"phillips", "pierson-moskowitz", "bretschneider", "jonswap",     "tma",
          "gaussian", "ochi-hubble",       "torsethaugen"};
}

std::vector<std::string> spreading_model_names() {
  return {"cos2s", "mitsuyasu", "hasselmann", "donelan-banner", "cos-power", "horvath"};
}

std::vector<ParameterInfo> model_parameters(const std::string& model) {
  if (model == "pierson-moskowitz") {
    return with_common({{"u19_5", "m/s", "wind speed at 19.5 m (wind form)"},
                        {"hs", "m", "significant wave height (Bretschneider form, with tp)"},
                        {"tp", "s", "peak period"}});
  }
  if (model == "bretschneider") {
    return with_common({{"hs", "m", "significant wave height"}, {"tp", "s", "peak period"}});
  }
  if (model == "jonswap") return with_common(kJonswap);
  if (model == "tma") {
    auto infos = with_common(kJonswap);
    infos.push_back({"depth_factor", "exact|thompson-vincent",
                     "Kitaigorodskii factor: exact (default) or Thompson–Vincent"});
    return infos;
  }
  if (model == "phillips") {
    return with_common({{"amplitude", "", "Phillips constant A (dimensionless: Ψ in m⁴ is A/k⁴)"},
                        {"wind_speed", "m/s", "wind speed V (L = V²/g)"},
                        {"exponent", "", "directional exponent p of |k̂·ŵ|^p (default 2)"},
                        {"small_wave_cutoff", "m", "l in e^(−k²l²) (default 0)"},
                        {"against_wind_factor", "", "scale of waves against the wind, 0…1 (default 1)"}});
  }
  if (model == "gaussian") {
    return with_common({{"hs", "m", "significant height of the full Gaussian (4√m0 if σ ≪ ωp)"},
                        {"tp", "s", "peak period (ωp = 2π/Tp)"},
                        {"sigma", "rad/s", "width σ of the Gaussian in ω, > 0"}});
  }
  if (model == "ochi-hubble") {
    return with_common({{"hs1", "m", "significant wave height of component 1"},
                        {"tp1", "s", "peak period of component 1"},
                        {"lambda1", "", "shape λ1 of component 1, > 0 (1: Bretschneider)"},
                        {"hs2", "m", "significant wave height of component 2"},
                        {"tp2", "s", "peak period of component 2"},
                        {"lambda2", "", "shape λ2 of component 2, > 0 (1: Bretschneider)"}});
  }
  if (model == "torsethaugen") {
    return with_common({{"hs", "m", "significant wave height of the sea (both peaks)"},
                        {"tp", "s", "peak period of the primary peak, 2√Hs…25 s"}});
  }
  if (model == "cos2s") return {{"s", "", "spreading exponent"}};
  if (model == "mitsuyasu") return {{"s_max", "", "spreading exponent at the peak"}};
  if (model == "hasselmann") return {{"wave_age", "", "U10/cp at the peak (default 1.17)"}};
  if (model == "donelan-banner") return {};
  if (model == "horvath") {
    return {{"wave_age", "", "U10/cp at the peak (default 1.17)"},
            {"swell", "", "Horvath's swell elongation ξ ≥ 0 (default 0)"},
            {"spread_blend", "", "weight b of a uniform spread, 0…1 (default 0)"}};
  }
  if (model == "cos-power") {
    return {{"p", "", "exponent of |cos θ|"},
            {"one_sided", "yes|no", "no energy against the mean direction (default no)"}};
  }
  throw InvalidInput("unknown model '" + model + "'; valid spectra: " +
                     join(frequency_model_names()) + "; valid spreading: " +
                     join(spreading_model_names()));
}

Dispersion make_dispersion(const ModelSpec& spec) {
  auto number = [&](const std::string& name, double fallback) {
    auto it = spec.numbers.find(name);
    return it == spec.numbers.end() ? fallback : it->second;
  };
  return Dispersion::finite_depth(number("depth", kInfiniteDepth),
                                  number("gravity", kStandardGravity));
}

namespace {

FrequencySpectrumPtr build_frequency_spectrum(const ModelSpec& spec) {
  const auto& names = frequency_model_names();
  if (std::find(names.begin(), names.end(), spec.model) == names.end()) {
    throw InvalidInput(unknown_model_message(ModelKind::spectrum, spec.model));
  }
  const Reader r(spec, "spectrum model", model_parameters(spec.model));
  const Dispersion dispersion = make_dispersion(spec);  // validates depth and gravity
  const double g = dispersion.gravity();

  if (spec.model == "bretschneider") {
    return PiersonMoskowitz::bretschneider(r.required("hs", "m"), r.required("tp", "s"));
  }
  if (spec.model == "pierson-moskowitz") {
    const auto u = r.number("u19_5");
    if (u && (r.number("hs") || r.number("tp"))) {
      throw InvalidInput("pierson-moskowitz: give u19_5 (wind form) or hs and tp, not both");
    }
    if (u) return PiersonMoskowitz::from_wind(*u, g);
    if (!r.number("hs") && !r.number("tp")) {
      throw InvalidInput("pierson-moskowitz needs u19_5 (wind form) or hs and tp");
    }
    return PiersonMoskowitz::bretschneider(r.required("hs", "m"), r.required("tp", "s"));
  }
  if (spec.model == "jonswap") return make_jonswap(r);
  if (spec.model == "gaussian") {
    return GaussianSwell::create(r.required("hs", "significant wave height in m"),
                                 r.required("tp", "peak period in s"),
                                 r.required("sigma", "width of the Gaussian in ω, rad/s"));
  }
  if (spec.model == "ochi-hubble") {
    auto component = [&](const std::string& j) {
      return OchiHubbleComponent{
          r.required("hs" + j, "significant wave height of component " + j + " in m"),
          r.required("tp" + j, "peak period of component " + j + " in s"),
          r.required("lambda" + j, "shape of component " + j + ", > 0")};
    };
    const auto first = component("1");
    return OchiHubble::create(first, component("2"));
  }
  if (spec.model == "torsethaugen") {
    return Torsethaugen::create(r.required("hs", "significant wave height in m"),
                                r.required("tp", "peak period in s"), g);
  }
  if (spec.model == "tma") {
    const double depth = r.required("depth", "water depth in m");
    const auto factor = r.choice("depth_factor", {"exact", "thompson-vincent"}) == "exact"
                            ? TmaFactor::exact
                            : TmaFactor::thompson_vincent;
    return Tma::create(make_jonswap(r), depth, factor);
  }
  // phillips
  Phillips::Parameters p;
  p.amplitude = r.required("amplitude", "Phillips constant A, dimensionless");
  p.wind_speed = r.required("wind_speed", "wind speed V in m/s");
  p.wind_direction = r.number_or("wind_dir", 0) * kDegree;
  p.exponent = r.number_or("exponent", 2);
  p.small_wave_cutoff = r.number_or("small_wave_cutoff", 0);
  p.against_wind_factor = r.number_or("against_wind_factor", 1);
  return Phillips::create(p, dispersion);
}

}  // namespace

FrequencySpectrumPtr make_frequency_spectrum(const ModelSpec& spec) {
  try {
    auto spectrum = build_frequency_spectrum(spec);
    // Its energy m0 must exist: hs = 1e300 m builds (m0 = hs²/16 overflows only when asked)
    // and hs = 1e-300 m underflows to a sea of no energy. One quadrature, about 0.1 ms.
    const double m0 = spectral_moment(*spectrum, 0);
    if (!(std::isfinite(m0) && m0 > 0)) {
      throw NumericalError(fmt::format("its energy m0 = {:g} m² is not finite and positive", m0));
    }
    return spectrum;
  } catch (const NumericalError& e) {
    // Each parameter is in its own valid range, yet together they lie so far outside any sea
    // (tp = 4e65 s puts the peak at ω = 1.6e-65 rad/s) that the normalization or a moment
    // cannot be computed: that is bad input, not a numerical failure of swell's.
    std::string given;
    for (const auto& [name, value] : spec.numbers) {
      given += fmt::format("{}{} = {:g}", given.empty() ? "" : ", ", name, value);
    }
    throw InvalidInput(fmt::format("spectrum model '{}' cannot be evaluated with {}: {}",
                                   spec.model, given.empty() ? "these parameters" : given,
                                   e.what()));
  }
}

SpreadingPtr make_spreading(const ModelSpec& spec, double omega_p) {
  const auto& names = spreading_model_names();
  if (std::find(names.begin(), names.end(), spec.model) == names.end()) {
    throw InvalidInput(unknown_model_message(ModelKind::spreading, spec.model));
  }
  const Reader r(spec, "spreading model", model_parameters(spec.model));
  if (spec.model == "cos2s") return Cos2s::constant(r.required("s", "spreading exponent"));
  if (spec.model == "mitsuyasu") {
    return Cos2s::mitsuyasu(r.required("s_max", "spreading exponent at the peak"), omega_p);
  }
  if (spec.model == "hasselmann") return Cos2s::hasselmann(omega_p, r.number_or("wave_age", 1.17));
  if (spec.model == "donelan-banner") return DonelanBanner::create(omega_p);
  if (spec.model == "horvath") {
    Horvath::Parameters p;
    p.wave_age = r.number_or("wave_age", p.wave_age);
    p.swell = r.number_or("swell", p.swell);
    p.spread_blend = r.number_or("spread_blend", p.spread_blend);
    return Horvath::create(omega_p, p);
  }
  return CosPower::create(r.required("p", "exponent of |cos θ|"),
                          r.choice("one_sided", {"no", "yes"}) == "yes");
}

namespace {

// Levenshtein distance between two short names, case and '-'/'_' ignored.
std::size_t name_distance(std::string a, std::string b) {
  auto fold = [](std::string& s) {
    for (auto& c : s) c = c == '_' ? '-' : char(std::tolower(static_cast<unsigned char>(c)));
  };
  fold(a);
  fold(b);
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string unknown_model_message(ModelKind kind, const std::string& name) {
  const bool spectrum = kind == ModelKind::spectrum;
  const auto valid = spectrum ? frequency_model_names() : spreading_model_names();
  const auto other = spectrum ? spreading_model_names() : frequency_model_names();
  const std::string what = spectrum ? "spectrum" : "spreading";
  if (!spectrum && name == "phillips") {
    return "'phillips' is not a spreading model: the Phillips spectrum carries its own "
           "directionality (|k̂·ŵ|^p, its exponent p and against_wind_factor are spectrum "
           "parameters). Set [spectrum] model = \"phillips\" (--model phillips) with its wind "
           "direction there ([spectrum] wind_dir_deg or --wind-dir), and give no [spreading] "
           "section (no --spreading)";
  }
  if (std::find(other.begin(), other.end(), name) != other.end()) {
    return spectrum
        ? fmt::format("'{}' is a spreading model, not a spectrum: put it in [spreading] model "
                      "(--spreading {}) and name a frequency spectrum in [spectrum] model (one of "
                      "{})",
                      name, name, join(valid))
        : fmt::format("'{}' is a spectrum, not a spreading model: put it in [spectrum] model "
                      "(--model {}) and name a spreading in [spreading] model (one of {})",
                      name, name, join(valid));
  }
  std::string nearest;
  std::size_t best = 4;  // suggest only a close name: at most 3 edits
  for (const auto& candidate : valid) {
    const std::size_t d = name_distance(name, candidate);
    if (d < best) {
      best = d;
      nearest = candidate;
    }
  }
  return fmt::format("unknown {} model '{}'{}; valid: {}", what, name,
                     nearest.empty() ? "" : fmt::format(" (did you mean '{}'?)", nearest),
                     join(valid));
}

}  // namespace swell::reference
