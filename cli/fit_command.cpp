// swell fit --input DIR_OR_PATTERN [--input …] --case FILE [--sigma] [--frame F]
//           [--interval profile|wald] [--json FILE|-]
// swell fit --spectrum FILE [--summary FILE] [--dof NU] [--json FILE|-] [--plot FILE.png]
//
// The second form fits JONSWAP to every hour of an NDBC buoy spectrum (docs/buoy_fit.md); see
// run_buoy_fit below.
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

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "commands.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/fit/buoy_fit.hpp"
#include "swell/validation/fit/buoy_record.hpp"
#include "swell/validation/fit/buoy_spectrum.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"
#include "swell/validation/results/report.hpp"

namespace swell::cli {
namespace {

namespace fs = std::filesystem;

struct FitOptions {
  std::vector<std::string> inputs;
  std::string case_file;
  bool sigma = false;
  int frame = 0;
  std::string interval = "profile";
  std::string json;
  // The buoy form.
  std::string spectrum, summary, plot;
  double dof = validation::BuoyFitOptions{}.dof;
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
    const auto case_file = validation::read_case_file(case_path);
    validation::require_single_grid(case_file, "swell fit");
    return validation::read_frames(case_file);
  }
  validation::CaseFile with_channels = case_file;
  if (with_channels.input.channels.empty()) {
    with_channels.input.channels[reference::Field::height] =
        reference::channel_name(reference::Field::height);
  }
  return validation::read_frames(with_channels, input);
}

int run_fit(const FitOptions& o) {
  const auto case_file = validation::read_case_file(o.case_file);
  validation::require_single_grid(case_file, "swell fit");
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
    write_json(o.json, validation::jonswap_fit_json(fit, truth, free_scale, options.interval));
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

// ---------------------------------------------------------------- swell fit --spectrum


// Runs gnuplot on `script` inside `dir`; "" on success, else what went wrong. (The same as the
// report's figures do; kept here because this figure is a two-panel multiplot with interval
// bars, which their single-panel Figure does not draw.)
std::string render_gnuplot(const fs::path& dir, const std::string& script) {
  const std::string log = (dir / (script + ".log")).string();
  const pid_t child = fork();
  if (child < 0) return "fork failed";
  if (child == 0) {
    if (chdir(dir.c_str()) != 0) _exit(126);
    if (!std::freopen(log.c_str(), "w", stderr)) _exit(126);
    execlp("gnuplot", "gnuplot", script.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(child, &status, 0);
  std::error_code ignored;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    fs::remove(log, ignored);
    return "";
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return "gnuplot could not be started";
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return fmt::format("gnuplot exited with status {}: {}",
                     WIFEXITED(status) ? WEXITSTATUS(status) : -1, text);
}

// <stem>.dat and <stem>.gp beside <stem>.png: Hs (WVHT, 4√m0, fitted with its 95 % interval)
// and Tp (peak band, the summary's dominant period, fitted with its interval) over the record.
std::string write_buoy_plot(const std::string& png,
                            const std::vector<validation::BuoyRecordHour>& rows,
                            const std::string& title) {
  const fs::path path(png);
  if (path.extension() != ".png") {
    throw InvalidInput("--plot " + png + ": the figure is a PNG; give a name ending in .png");
  }
  // Absolute: gnuplot runs inside it, and its log is opened after the chdir.
  const fs::path dir = fs::absolute(path.has_parent_path() ? path.parent_path() : fs::path("."));
  std::error_code error;
  fs::create_directories(dir, error);
  const std::string stem = path.stem().string();
  const double t0 = rows.front().time.hours_since_2000();
  std::ofstream dat(dir / (stem + ".dat"));
  if (!dat) throw InvalidInput("--plot " + png + ": cannot write " + (dir / (stem + ".dat")).string());
  dat << "# " << title << " — written by `swell fit --spectrum`\n"
      << "# day hs_wvht hs_moments hs_fit hs_lo hs_hi flagged tp_peak_band tp_dominant tp_fit tp_lo "
         "tp_hi  (m, s; NaN: missing; lo/hi: 95 % profile-likelihood interval, quasi-likelihood where φ > 1)\n";
  auto v = [](double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : std::string("NaN"); };
  for (const auto& r : rows) {
    const double day = (r.time.hours_since_2000() - t0) / 24.0;
    const bool has = r.fit.has_value();
    dat << fmt::format("{:.4f} {} {} {} {} {} {} {} {} {} {} {}\n", day, v(r.wvht), v(r.hs_moments),
                       v(has ? r.fit->hs.value : NAN), v(has ? r.fit->hs.ci95_low : NAN),
                       v(has ? r.fit->hs.ci95_high : NAN), has && r.fit->misfit.flagged ? 1 : 0,
                       v(r.tp_peak), v(r.dominant_period), v(has ? r.fit->tp.value : NAN),
                       v(has ? r.fit->tp.ci95_low : NAN), v(has ? r.fit->tp.ci95_high : NAN));
  }
  dat.close();
  std::ofstream gp(dir / (stem + ".gp"));
  const std::string d = "'" + stem + ".dat'";
  gp << "# " << title << " — written by `swell fit --spectrum`; edit and run `gnuplot " << stem
     << ".gp` here to restyle\n"
     << "set terminal pngcairo size 1100,800 noenhanced font ',10'\n"
     << "set output '" << stem << ".png'\n"
     << "set multiplot layout 2,1 title '" << title << "'\n"
     << "set grid\nset key outside right top\nset xlabel 'days from " << rows.front().time.iso()
     << "'\n"
     << "set ylabel 'Hs [m]'\n"
     << "plot " << d << " using 1:($7==0?$4:NaN):5:6 with yerrorbars pt 7 ps 0.5 lc rgb '#1f77b4' "
        "title 'fitted JONSWAP Hs, 95 % quasi-likelihood interval', \\\n"
     << "     " << d << " using 1:($7==1?$4:NaN) with points pt 6 ps 0.6 lc rgb '#1f77b4' "
        "title 'fitted Hs, flagged: not one JONSWAP', \\\n"
     << "     " << d << " using 1:3 with lines lw 1.5 lc rgb '#2ca02c' title '4 sqrt(m0) of the bands', \\\n"
     << "     " << d << " using 1:2 with steps lw 1 lc rgb '#d62728' title 'WVHT (summary, 0.1 m)'\n"
     << "set ylabel 'period [s]'\n"
     << "plot " << d << " using 1:($7==0?$10:NaN):11:12 with yerrorbars pt 7 ps 0.5 lc rgb '#1f77b4' "
        "title 'fitted JONSWAP Tp, 95 % quasi-likelihood interval', \\\n"
     << "     " << d << " using 1:($7==1?$10:NaN) with points pt 6 ps 0.6 lc rgb '#1f77b4' "
        "title 'fitted Tp, flagged: not one JONSWAP', \\\n"
     << "     " << d << " using 1:8 with steps lw 1.5 lc rgb '#2ca02c' title 'Tp of the peak band', \\\n"
     << "     " << d << " using 1:9 with points pt 2 ps 0.6 lc rgb '#d62728' "
        "title 'dominant period (SwP or WWP)'\n"
     << "unset multiplot\n";
  gp.close();
  return render_gnuplot(dir, stem + ".gp");
}

// Fits every hour of an NDBC spectral-density file; with --summary, pairs each hour with the
// summary's (by hour: spectra at :50, summaries at :40) and compares 4√m0 with WVHT. Exit 0 when
// every hour with energy was fitted and converged, 1 when one did not converge, 2 on bad input.
// A flagged hour (one JONSWAP cannot describe it) is information, not failure.
int run_buoy_fit(const FitOptions& o) {
  require(std::isfinite(o.dof) && o.dof > 0, "--dof", "finite and > 0", o.dof);
  validation::BuoyFitOptions options;
  options.dof = o.dof;
  const auto record = validation::fit_buoy_record(o.spectrum, o.summary, options);
  if (!o.json.empty()) write_json(o.json, validation::buoy_record_json(record));
  if (o.json != "-") fmt::print("{}", validation::render_buoy_record(record));
  if (!o.plot.empty()) {
    const std::string problem =
        write_buoy_plot(o.plot, record.hours, fmt::format("{}: fitted JONSWAP against measured Hs and Tp",
                                                  fs::path(o.spectrum).filename().string()));
    if (!problem.empty()) {
      fmt::print(stderr, "swell: the figure's .dat and .gp are written, its PNG is not: {}\n", problem);
    } else if (o.json != "-") {
      fmt::print("figure: {} (with its .dat and .gp)\n", o.plot);
    }
  }
  if (record.summary.not_converged > 0) {
    fmt::print(stderr, "swell: numerical failure: the fit did not converge in {} hour(s)\n",
               record.summary.not_converged);
    return 1;
  }
  return 0;
}

// Which form was asked for; a mix, or neither, is bad input with the rule in the message.
int run_fit_command(const FitOptions& o) {
  const bool frames = !o.inputs.empty() || !o.case_file.empty();
  if (!o.spectrum.empty()) {
    if (frames) {
      throw InvalidInput(
          "--spectrum (a buoy spectrum) cannot be combined with --input/--case (frames): give "
          "one of the two forms");
    }
    if (o.sigma || o.frame != 0 || o.interval != "profile") {
      throw InvalidInput("--sigma, --frame and --interval belong to the frames form (--input); "
                         "--spectrum fits Hs, Tp, γ with profile-likelihood intervals");
    }
    return run_buoy_fit(o);
  }
  if (!o.summary.empty() || !o.plot.empty()) {
    throw InvalidInput("--summary and --plot belong to the buoy form: give --spectrum FILE");
  }
  if (o.inputs.empty() || o.case_file.empty()) {
    throw InvalidInput(
        "swell fit needs --input PATTERN and --case FILE (frames), or --spectrum FILE (an NDBC "
        "buoy spectrum)");
  }
  return run_fit(o);
}

}  // namespace

Action add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  app.add_option("--input", o->inputs,
                 "one realization: a directory written by swell synth, or a frame file pattern "
                 "(frame_%04d.exr); repeat for more independent realizations")
      ->take_all();
  app.add_option("--case", o->case_file, "case file (docs/case_files.md) whose spectrum is fitted");
  app.add_flag("--sigma", o->sigma, "also fit the peak widths σa and σb");
  app.add_option("--frame", o->frame, "which frame of each realization (default 0)");
  app.add_option("--interval", o->interval,
                 "95 % intervals: profile (likelihood ratio, default; calibrated over grids of 2 "
                 "to 20 peak wavelengths) or wald (estimate ± 1.96 se)")
      ->check(CLI::IsMember({"profile", "wald"}));
  app.add_option("--json", o->json, "write JSON to FILE, or - for standard output");
  app.add_option("--spectrum", o->spectrum,
                 "instead of frames: an NDBC spectral-density file (.data_spec), every hour "
                 "fitted (docs/buoy_fit.md)");
  app.add_option("--summary", o->summary,
                 "with --spectrum: the NDBC hourly summary (.spec), paired by hour; compares "
                 "4√m0 with WVHT and prints the buoy's periods");
  app.add_option("--dof", o->dof,
                 "with --spectrum: degrees of freedom of a 0.01 Hz band (ν_j = dof·Δf_j/0.01 Hz); "
                 "default 24, NDBC's 20-minute WPM record (TD 96-01)");
  app.add_option("--plot", o->plot,
                 "with --spectrum: a PNG of fitted against measured Hs and Tp over the record "
                 "(gnuplot; .dat and .gp beside it)");
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
      "peak_wave_vectors, truth, negative_log_likelihood, iterations}. See docs/fit.md.\n"
      "With --spectrum FILE [--summary FILE] instead: every hour of an NDBC buoy spectrum, "
      "fitted with the band values' χ²_ν/ν law (values under 0.01 m²/Hz as the intervals they "
      "were rounded from), 4√m0 against WVHT, and a misfit flag (a second significant peak, or "
      "a fitted energy that disagrees with the measured beyond its quasi-likelihood scatter at "
      "p < 0.001), quasi-likelihood intervals scaled by φ = deviance/dof where it exceeds 1; text, --json (hours[…], summary) and "
      "--plot. See docs/buoy_fit.md.");
  return [o] { return run_fit_command(*o); };
}

}  // namespace swell::cli
