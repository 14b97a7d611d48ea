// swell fit --input DIR_OR_PATTERN [--input …] --case FILE [--sigma] [--frame F]
//           [--interval profile|wald] [--json FILE|-]
//
// Fits JONSWAP (Hs, Tp, γ, and with --sigma σa, σb) to the height field of frames by maximum
// Whittle likelihood (docs/fit.md) and prints each estimate with its standard error and 95 %
// interval (profile likelihood by default, Wald on request; the method is printed with each),
// next to the case's own values when its spectrum is in the JONSWAP family. Where an interval
// cannot be calibrated (a patch of fewer than 2 peak wavelengths, a profile that does not
// close, a singular information) it prints "cannot" and the reason instead of the interval.
// Each --input is one realization (an independent surface of the case, e.g. another seed): a
// directory written by `swell synth` (its case.toml's [input] names the files) or a frame file
// pattern such as "out/frame_%04d.exr" read with the case's [input] channels (height "h" if it
// names none). The case's spreading, dispersion and depth are held fixed.
//
// Exit 0 when the fit converged (with or without calibrated intervals), 1 when it did not or,
// with --sigma, its Fisher information is singular (numerical failure), 2 for bad input. A truth outside its interval is reported, not failed on:
// a 95 % interval misses 5 % of the time (calibrated over seeds in swell_fit_tests).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>

#include "commands.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/case_file.hpp"
#include "swell/validation/frame_io.hpp"
#include "swell/validation/jonswap_fit.hpp"
#include "swell/validation/report.hpp"

namespace swell::cli {
namespace {

namespace fs = std::filesystem;
using validation::json_number;

struct FitOptions {
  std::vector<std::string> inputs;
  std::string case_file;
  bool sigma = false;
  int frame = 0;
  std::string interval = "profile";
  std::string json;
};

// One realization: a `swell synth` directory (read with its own case file, whose grid the fit
// then compares with --case's) or a pattern read with --case's [input].
reference::FrameSequence read_realization(const std::string& input,
                                          const validation::CaseFile& case_file) {
  std::error_code error;
  if (fs::is_directory(input, error)) {
    const fs::path case_path = fs::path(input) / "case.toml";
    if (!fs::exists(case_path, error)) {
      throw InvalidInput("--input " + input +
                         ": a directory without case.toml (give a directory written by swell "
                         "synth, or a frame file pattern such as DIR/frame_%04d.exr)");
    }
    return validation::read_frames(validation::read_case_file(case_path));
  }
  validation::CaseFile with_channels = case_file;
  if (with_channels.input.channels.empty()) {
    with_channels.input.channels[reference::Field::height] =
        reference::channel_name(reference::Field::height);
  }
  return validation::read_frames(with_channels, input);
}

// An uncalibrated interval is not given as "ci95" (null there), so that no reader takes it for
// a 95 % interval; what the method gave is under "ci95_uncalibrated", with the reason.
nlohmann::json estimate_json(const validation::Estimate& e) {
  const nlohmann::json interval = {json_number(e.ci95_low), json_number(e.ci95_high)};
  nlohmann::json j = {{"value", json_number(e.value)},
                      {"ci95", e.calibrated ? interval : nlohmann::json(nullptr)},
                      {"se", json_number(e.standard_error)},
                      {"method", e.method},
                      {"calibrated", e.calibrated},
                      {"effective_ordinates", json_number(e.effective_ordinates)}};
  if (!e.calibrated) {
    j["ci95_uncalibrated"] = interval;
    j["reason"] = e.reason;
  }
  return j;
}

int run_fit(const FitOptions& o) {
  const auto case_file = validation::read_case_file(o.case_file);
  const auto& ocean = case_file.ocean;
  // Bad case before reading any frame: the spectrum must be in the family.
  const auto truth = validation::case_jonswap_parameters(ocean);
  // The validity rule every command shares, before any frame is read: per sample and
  // realization, the frames' height (8 bytes) and its periodogram (8), and the fit's model and
  // its derivatives (8 per parameter, 5 at most).
  const double samples = double(ocean.sampling().size());
  const double bytes = samples * (16.0 * double(o.inputs.size()) * ocean.frames + 48);
  reference::require_valid_sampling(ocean, reference::kFloat64, std::uint64_t(std::min(bytes, 1.8e19)),
                                    "swell fit");
  std::vector<reference::FrameSequence> realizations;
  for (const auto& input : o.inputs) realizations.push_back(read_realization(input, case_file));
  validation::JonswapFitOptions options;
  options.fit_sigma = o.sigma;
  options.frame = o.frame;
  options.interval = o.interval == "wald" ? validation::IntervalMethod::wald
                                          : validation::IntervalMethod::profile_likelihood;
  const auto fit = validation::fit_jonswap(ocean, realizations, options);

  // The case's value of each parameter, when it means the same as the estimate: with
  // scale = "free" the engine's energy is unknown, so Hs has no truth.
  const bool free_scale = case_file.scale == validation::SpectrumScale::free;
  struct Row {
    const char* name;
    const char* unit;
    validation::Estimate estimate;
    std::optional<double> truth;
  };
  std::vector<Row> rows = {{"hs", "m", fit.hs, free_scale ? std::nullopt : std::optional(truth.hs)},
                           {"tp", "s", fit.tp, truth.tp},
                           {"gamma", "", fit.gamma, truth.gamma}};
  if (fit.sigma_a) rows.push_back({"sigma_a", "", *fit.sigma_a, truth.sigma_a});
  if (fit.sigma_b) rows.push_back({"sigma_b", "", *fit.sigma_b, truth.sigma_b});

  if (!o.json.empty()) {
    nlohmann::json parameters = nlohmann::json::object(), truths = nlohmann::json::object();
    for (const auto& row : rows) {
      parameters[row.name] = estimate_json(row.estimate);
      if (row.truth) truths[row.name] = json_number(*row.truth);
    }
    nlohmann::json document = {
        {"fit", parameters},
        {"converged", fit.converged},
        {"wave_vectors", fit.wave_vectors},
        {"realizations", fit.realizations},
        {"interval", validation::interval_method_name(options.interval)},
        {"peak_wavelengths", json_number(fit.peak_wavelengths)},
        {"peak_wave_vectors", fit.peak_wave_vectors},
        {"truth", truths},
        {"negative_log_likelihood", json_number(fit.negative_log_likelihood)},
        {"iterations", fit.iterations}};
    write_json(o.json, document);
  }
  if (o.json != "-") {
    fmt::print(
        "swell fit: JONSWAP by maximum Whittle likelihood; case {}\n"
        "{} realization{}, frame {}, {} wave vectors each; held at the case's values: "
        "spreading, dispersion, depth{}\n\n",
        ocean.describe(), fit.realizations, fit.realizations == 1 ? "" : "s", o.frame,
        fit.wave_vectors, o.sigma ? "" : ", σa, σb");
    fmt::print("patch: {:.3g} peak wavelengths (at the case's Tp); {} wave vector{} in the "
               "peak's half-power band\n\n",
               fit.peak_wavelengths, fit.peak_wave_vectors, fit.peak_wave_vectors == 1 ? "" : "s");
    fmt::print("{:<10} {:>12} {:>11}  {:<27} {:<19} {}\n", "parameter", "estimate",
               "std. error", "95 % interval", "method", "case");
    std::vector<std::string> reasons;
    for (const auto& row : rows) {
      const auto& e = row.estimate;
      const std::string name =
          fmt::format("{}{}", row.name, *row.unit ? fmt::format(" [{}]", row.unit) : "");
      std::string truth_text = "—";
      if (row.truth) {
        const bool inside = e.ci95_low <= *row.truth && *row.truth <= e.ci95_high;
        truth_text = e.calibrated
                         ? fmt::format("{:.6g} ({})", *row.truth, inside ? "inside" : "outside")
                         : fmt::format("{:.6g}", *row.truth);
      }
      std::string interval =
          fmt::format("[{:>11.6g}, {:>11.6g}]", e.ci95_low, e.ci95_high);
      if (!e.calibrated) {
        // One note per distinct reason (the resolution rule gives the same one to all).
        auto it = std::find(reasons.begin(), reasons.end(), e.reason);
        if (it == reasons.end()) it = reasons.insert(reasons.end(), e.reason);
        interval = fmt::format("cannot (note {})", it - reasons.begin() + 1);
      }
      fmt::print("{:<10} {:>12.6g} {:>11.3g}  {:<27} {:<19} {}\n", name, e.value,
                 e.standard_error, interval, e.method, truth_text);
    }
    for (std::size_t i = 0; i < reasons.size(); ++i) {
      fmt::print("\nnote {}: no calibrated 95 % interval: {}\n", i + 1, reasons[i]);
    }
    if (free_scale) fmt::print("(scale = \"free\": the case's Hs is not the engine's)\n");
    fmt::print("\nconverged: {} ({} iterations; {})\n", fit.converged ? "yes" : "no",
               fit.iterations, fit.report);
  }
  if (!fit.converged) {
    fmt::print(stderr, "swell: numerical failure: the fit did not converge: {}{}\n", fit.report,
               fit.peak_wavelengths < 2
                   ? fmt::format("; the patch holds only {:.2f} peak wavelengths, too few to "
                                 "resolve the spectral peak (docs/fit.md §4)",
                                 fit.peak_wavelengths)
                   : std::string());
    return 1;
  }
  return 0;
}

}  // namespace

Action add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  app.add_option("--input", o->inputs,
                 "one realization: a directory written by swell synth, or a frame file pattern "
                 "(frame_%04d.exr); repeat for more independent realizations")
      ->required()
      ->take_all();
  app.add_option("--case", o->case_file, "case file (docs/case_files.md) whose spectrum is fitted")
      ->required();
  app.add_flag("--sigma", o->sigma, "also fit the peak widths σa and σb");
  app.add_option("--frame", o->frame, "which frame of each realization (default 0)");
  app.add_option("--interval", o->interval,
                 "95 % intervals: profile (likelihood ratio, default; calibrated over grids of 2 "
                 "to 20 peak wavelengths) or wald (estimate ± 1.96 se)")
      ->check(CLI::IsMember({"profile", "wald"}));
  app.add_option("--json", o->json, "write JSON to FILE, or - for standard output");
  app.footer(
      "Fits Hs, Tp, γ (with --sigma also σa, σb) of an exactly normalized JONSWAP spectrum to the "
      "periodogram of the height field by maximum Whittle likelihood (Ceres); 95 % intervals are "
      "profile-likelihood intervals (or Wald with --interval wald), each with its method, and "
      "'cannot' with the reason where none holds its level (a patch of fewer than 2 peak "
      "wavelengths, a profile that does not close). The case's spreading, dispersion and depth "
      "(tma: its depth factor) are held fixed. Exit 0 when converged, 1 on numerical failure, 2 "
      "on bad input. JSON: {fit: {hs: {value, ci95 (null if not calibrated), se, method, "
      "calibrated, effective_ordinates[, ci95_uncalibrated, reason]}, tp, gamma[, sigma_a, "
      "sigma_b]}, converged, wave_vectors, realizations, interval, peak_wavelengths, "
      "peak_wave_vectors, truth, negative_log_likelihood, iterations}. See docs/fit.md.");
  return [o] { return run_fit(*o); };
}

}  // namespace swell::cli
