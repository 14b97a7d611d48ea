// swell spectrum --model M [params] | --case FILE  [--omega a:b:n | --omega w1,w2,...] [--json FILE|-]
// Prints S(ω) at the requested frequencies and the moments of the whole spectrum; for a case,
// each component's and the sea's (their sum).
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <set>

#include "commands.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/moments.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/results/report.hpp"

namespace swell::cli {
namespace {

using reference::ModelSpec;
using validation::json_number;

// "a:b:n" → n points from a to b inclusive; "w1,w2,…" → those values. ω in rad/s, ≥ 0.
std::vector<double> parse_omega(const std::string& text) {
  auto number = [&](const std::string& token) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(token, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != token.size() || token.empty() || !std::isfinite(value) || value < 0) {
      throw InvalidInput("--omega: '" + token + "' is not a finite ω ≥ 0 in rad/s (expected "
                         "a:b:n or w1,w2,…)");
    }
    return value;
  };
  std::vector<double> omegas;
  if (text.find(':') != std::string::npos) {
    const auto first = text.find(':'), second = text.find(':', first + 1);
    if (second == std::string::npos || text.find(':', second + 1) != std::string::npos) {
      throw InvalidInput("--omega: '" + text + "' must be a:b:n (start, stop, count)");
    }
    const double a = number(text.substr(0, first));
    const double b = number(text.substr(first + 1, second - first - 1));
    const double n = number(text.substr(second + 1));
    if (n < 1 || n != std::floor(n) || n > 1e7) {
      throw InvalidInput("--omega: the count n in a:b:n must be a whole number in 1…1e7 (got " +
                         text.substr(second + 1) + ")");
    }
    if (n > 1 && !(b > a)) throw InvalidInput("--omega: a:b:n needs b > a (got " + text + ")");
    for (int i = 0; i < int(n); ++i) omegas.push_back(n == 1 ? a : a + (b - a) * i / (n - 1));
  } else {
    std::size_t start = 0;
    while (true) {
      const auto comma = text.find(',', start);
      omegas.push_back(number(text.substr(start, comma - start)));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  return omegas;
}

std::string flag_of(const std::string& parameter) {
  std::string flag = "--" + parameter;
  for (auto& c : flag) c = c == '_' ? '-' : c;
  return flag;
}

// " (diverges: S ~ ω⁻⁵ tail)" for the tail exponent p (superscript digits where p is whole).
std::string tail_note(double p) {
  if (p != std::floor(p) || p < 0 || p > 99) return fmt::format(" (diverges: S ~ ω^−{:g} tail)", p);
  static const char* const kDigits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string exponent = "⁻";
  for (char c : std::to_string(static_cast<int>(p))) exponent += kDigits[c - '0'];
  return " (diverges: S ~ ω" + exponent + " tail)";
}

struct SpectrumOptions {
  std::string case_path;
  std::string model;
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> choices;
  std::map<std::string, CLI::Option*> number_options, choice_options;
  std::string omega;
  std::string json;
};

std::string parameter_text(const std::vector<reference::Parameter>& parameters) {
  std::string out;
  for (const auto& p : parameters) {
    out += fmt::format("{}{} = {:.6g}{}", out.empty() ? "" : ", ", p.name, p.value,
                       p.unit.empty() ? "" : " " + p.unit);
  }
  return out;
}

void print_moments(const reference::SeaState& state, const std::string& indent,
                   double tail_exponent) {
  const auto& m = state.moments;
  fmt::print("{0}m_1 = {1:.9g} m²·s/rad{2}   m0 = {3:.9g} m²   m1 = {4:.9g} m²·rad/s\n"
             "{0}m2 = {5:.9g} m²·(rad/s)²   m4 = {6:.9g} m²·(rad/s)⁴{7}\n"
             "{0}Hs = {8:.6g} m   Tp = {9:.6g} s   Tm01 = {10:.6g} s   Tm02 = {11:.6g} s   Te = {12:.6g} s\n"
             "{0}ε4 = {13:.6g}   ν = {14:.6g}\n",
             indent, m.m_minus1, std::isinf(m.m_minus1) ? " (diverges: S(0⁺) > 0)" : "", m.m0, m.m1,
             m.m2, m.m4, std::isinf(m.m4) ? tail_note(tail_exponent) : "", state.hs, state.tp,
             state.tm01, state.tm02, state.te, state.epsilon4, state.nu);
}

// A case's sea: each component's omnidirectional S(ω) (its energy factor and fade applied) and
// the sum, whose moments are the sea's.
int run_case_spectrum(const SpectrumOptions& o) {
  const auto case_file = validation::read_case_file(o.case_path);
  // A probes case's sea as its lines see it (a long-crested one needs no spreading model).
  const auto ocean = case_file.is_probe_case() ? case_file.probe_case().synthesized_sea() : case_file.ocean;
  const std::string description =
      case_file.is_probe_case() ? case_file.probe_case().describe() : ocean.describe();
  std::vector<reference::DirectionalSpectrumPtr> parts;
  for (const auto& c : ocean.components()) parts.push_back(ocean.component_spectrum(c));
  // The components as declared, for the listing.
  const auto components = case_file.ocean.components();
  const auto sea = ocean.sea_spectrum();
  const auto& total = sea->omnidirectional();
  const double omega_p = total.peak_omega();
  const auto omegas = o.omega.empty()
                          ? parse_omega(fmt::format("{:.17g}:{:.17g}:16", 0.25 * omega_p, 4 * omega_p))
                          : parse_omega(o.omega);
  std::vector<std::vector<double>> values(parts.size() + 1);
  for (double w : omegas) {
    for (std::size_t i = 0; i < parts.size(); ++i) values[i].push_back(parts[i]->omnidirectional()(w));
    values.back().push_back(total(w));
  }
  std::vector<reference::SeaState> states;
  for (const auto& p : parts) states.push_back(reference::sea_state(p->omnidirectional()));
  const auto sea_state = reference::sea_state(total);

  if (!o.json.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const auto& c = components[i];
      nlohmann::json params = nlohmann::json::object();
      for (const auto& p : parts[i]->omnidirectional().parameters()) params[p.name] = json_number(p.value);
      nlohmann::json spreading = nullptr;
      if (!c.spreading.model.empty()) {
        spreading = {{"model", c.spreading.model}, {"params", c.spreading.numbers}};
      }
      list.push_back({{"model", c.spectrum.model}, {"params", params}, {"spreading", spreading},
                      {"wind_dir_deg", c.wind_dir_deg}, {"energy_factor", c.energy_factor},
                      {"short_wave_fade", c.short_wave_fade}, {"S", values[i]},
                      {"moments", validation::sea_state_json(states[i])}});
    }
    nlohmann::json document = {{"case", o.case_path},
                               {"description", description},
                               {"omega", omegas},
                               {"components", list},
                               {"S", values.back()},
                               {"moments", validation::sea_state_json(sea_state)},
                               {"units", {{"omega", "rad/s"}, {"S", "m^2 s/rad"},
                                          {"m_n", "m^2 (rad/s)^n"}, {"periods", "s"}}}};
    write_json(o.json, document);
    if (o.json == "-") return 0;
  }

  fmt::print("case: {}\n{}\n\n", o.case_path, description);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto& c = components[i];
    fmt::print("component {}: {} ({}){}\n", i, c.spectrum.model,
               parameter_text(parts[i]->omnidirectional().parameters()),
               c.spreading.model.empty() ? std::string()
                                         : fmt::format(", spreading {}, toward {:g}°",
                                                       c.spreading.model, c.wind_dir_deg));
  }
  fmt::print("\n{:>14}", "omega [rad/s]");
  for (std::size_t i = 0; i < parts.size(); ++i) fmt::print("  {:>16}", fmt::format("S{} [m²·s/rad]", i));
  fmt::print("  {:>16}\n", "sea [m²·s/rad]");
  for (std::size_t k = 0; k < omegas.size(); ++k) {
    fmt::print("{:>14.6g}", omegas[k]);
    for (const auto& column : values) fmt::print("  {:>16.9g}", column[k]);
    fmt::print("\n");
  }
  for (std::size_t i = 0; i < parts.size(); ++i) {
    fmt::print("\nmoments of component {} (angular frequency):\n", i);
    print_moments(states[i], "  ", parts[i]->omnidirectional().tail_exponent());
  }
  fmt::print("\nmoments of the sea, the sum of its components (angular frequency):\n");
  print_moments(sea_state, "  ", total.tail_exponent());
  return 0;
}

int run_spectrum(const SpectrumOptions& o) {
  if (!o.case_path.empty()) {
    if (!o.model.empty()) throw InvalidInput("give --model or --case, not both");
    for (const auto& [name, option] : o.number_options) {
      if (option->count()) throw InvalidInput(flag_of(name) + " with --case: the case file gives every parameter");
    }
    for (const auto& [name, option] : o.choice_options) {
      if (option->count()) throw InvalidInput(flag_of(name) + " with --case: the case file gives every parameter");
    }
    return run_case_spectrum(o);
  }
  if (o.model.empty()) throw InvalidInput("give --model (a spectrum model) or --case FILE (a case file's sea)");
  ModelSpec spec{o.model, {}, {}};
  for (const auto& [name, option] : o.number_options) {
    if (option->count()) spec.numbers[name] = o.numbers.at(name);
  }
  for (const auto& [name, option] : o.choice_options) {
    if (option->count()) spec.choices[name] = o.choices.at(name);
  }
  const auto spectrum = reference::make_frequency_spectrum(spec);
  const double omega_p = spectrum->peak_omega();
  // Without --omega: 16 points from ωp/4 to 4ωp.
  const auto omegas = o.omega.empty()
                          ? parse_omega(fmt::format("{:.17g}:{:.17g}:16", 0.25 * omega_p, 4 * omega_p))
                          : parse_omega(o.omega);
  std::vector<double> values;
  for (double w : omegas) values.push_back((*spectrum)(w));
  const auto state = reference::sea_state(*spectrum);

  if (!o.json.empty()) {
    nlohmann::json params = nlohmann::json::object();
    for (const auto& p : spectrum->parameters()) params[p.name] = json_number(p.value);
    nlohmann::json document = {{"model", spectrum->name()},
                               {"params", params},
                               {"omega", omegas},
                               {"S", values},
                               {"moments", validation::sea_state_json(state)},
                               {"units", {{"omega", "rad/s"}, {"S", "m^2 s/rad"},
                                          {"m_n", "m^2 (rad/s)^n"}, {"periods", "s"}}}};
    write_json(o.json, document);
    if (o.json == "-") return 0;
  }

  fmt::print("model: {}\nparameters: {}\n\n{:>14}  {:>16}\n", spectrum->name(),
             parameter_text(spectrum->parameters()), "omega [rad/s]", "S [m²·s/rad]");
  for (std::size_t i = 0; i < omegas.size(); ++i) {
    fmt::print("{:>14.6g}  {:>16.9g}\n", omegas[i], values[i]);
  }
  fmt::print("\nmoments of the whole spectrum (angular frequency):\n");
  print_moments(state, "  ", spectrum->tail_exponent());
  return 0;
}

}  // namespace

Action add_spectrum_command(CLI::App& app) {
  auto o = std::make_shared<SpectrumOptions>();
  const auto models = reference::frequency_model_names();
  app.add_option("--model", o->model, "spectrum model (or --case)")
      ->check(model_name_check(reference::ModelKind::spectrum));
  app.add_option("--case", o->case_path,
                 "a case file (docs/case_files.md): each component of its sea and their sum");
  // One flag per parameter any model takes; each model rejects the ones it does not take.
  std::set<std::string> seen;
  for (const auto& model : models) {
    for (const auto& info : reference::model_parameters(model)) {
      if (!seen.insert(info.name).second) continue;
      const bool is_choice = info.unit.find('|') != std::string::npos;
      const auto help = info.meaning + (info.unit.empty() ? "" : " [" + info.unit + "]");
      if (is_choice) {
        o->choice_options[info.name] =
            app.add_option(flag_of(info.name), o->choices[info.name], help);
      } else {
        o->number_options[info.name] =
            app.add_option(flag_of(info.name), o->numbers[info.name], help);
      }
    }
  }
  app.add_option("--omega", o->omega, "frequencies in rad/s: a:b:n or w1,w2,… (default ωp/4:4ωp:16)");
  app.add_option("--json", o->json, "write JSON to FILE, or - for standard output");
  // Each model with the parameters it takes and their units, spectra then spreadings.
  auto listing = [](const std::vector<std::string>& names) {
    std::string out;
    for (const auto& model : names) {
      std::string parameters;
      for (const auto& info : reference::model_parameters(model)) {
        if (info.name == "gravity" || info.name == "depth" || info.name == "wind_dir") continue;
        parameters += (parameters.empty() ? "" : ", ") + info.name + (info.unit.empty() ? "" : " [" + info.unit + "]");
      }
      out += "\n  " + model + ": " + (parameters.empty() ? "none" : parameters);
    }
    return out;
  };
  app.footer("Spectrum models and their parameters:" + listing(models) +
             "\nSpreading models (case files' [spreading], swell synth --spreading):" +
             listing(reference::spreading_model_names()) +
             "\nAny spectrum of a case file also takes energy_factor (the engine's energy over the "
             "declared) and short_wave_fade [m] (Ψ·e^(−k²l²)); tables: model = \"table\" or \"ndbc\" "
             "(docs/case_files.md).\n"
             "A parameter a model does not take is an error. JSON: {model, params, omega, S, "
             "moments: {m0, m1, m2, m4, m_1, hs, tp, tm01, tm02, te, …}}; a moment that "
             "diverges (m4 of an ω⁻⁵ tail, m_1 of a spectrum with S(0⁺) > 0) is null. With "
             "--case: the omnidirectional S(ω) of each component of the case's sea (its "
             "energy_factor and short_wave_fade applied) and of the sea, their sum, with the "
             "moments of each; JSON {case, description, omega, components: [{model, params, "
             "spreading, wind_dir_deg, energy_factor, short_wave_fade, S, moments}], S, moments}.");
  return [o] { return run_spectrum(*o); };
}

}  // namespace swell::cli
