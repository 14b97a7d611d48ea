#include "swell/validation/fit/buoy_record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "swell/reference/errors.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"
#include "swell/validation/results/report.hpp"

namespace swell::validation {
namespace {

nlohmann::json misfit_json(const BuoyMisfit& m) {
  return {{"deviance", json_number(m.deviance)},
          {"deviance_dof", m.deviance_dof},
          {"deviance_p", json_number(m.deviance_p)},
          {"dispersion", json_number(m.dispersion)},
          {"energy_model", json_number(m.energy_model)},
          {"energy_measured", json_number(m.energy_measured)},
          {"energy_t", json_number(m.energy_t)},
          {"energy_t_limit", json_number(m.energy_t_limit)},
          {"energy_misfit", m.energy_misfit},
          {"second_peak", m.second_peak},
          {"second_peak_frequency", m.second_peak ? json_number(m.second_peak_frequency) : nullptr},
          {"second_peak_energy_fraction",
           m.second_peak ? json_number(m.second_peak_energy_fraction) : nullptr},
          {"second_peak_z", m.second_peak ? json_number(m.second_peak_z) : nullptr},
          {"flagged", m.flagged},
          {"reason", m.reason}};
}

}  // namespace

BuoyRecordFit fit_buoy_record(const std::string& spectrum_file, const std::string& summary_file,
                              const BuoyFitOptions& options) {
  BuoyRecordFit record;
  record.spectrum_file = spectrum_file;
  record.summary_file = summary_file;
  record.options = options;
  record.spectra = read_ndbc_spectral_density(spectrum_file);
  if (!summary_file.empty()) record.summaries = read_ndbc_summary(summary_file);
  record.bands = spectral_bands(record.spectra.frequency);
  const auto& bands = record.bands;
  const auto paired = pair_by_hour(record.spectra, record.summaries);

  auto& sum = record.summary;
  for (const auto& p : paired) {
    BuoyRecordHour r;
    r.time = p.spectrum->time;
    r.spectrum = p.spectrum;
    r.summary = p.summary;
    const auto& s = p.spectrum->density;
    r.hs_moments = moment_significant_height(s, bands);
    r.hs_rounding = moment_height_rounding(s, bands, options.quantum);
    r.tp_peak = peak_band_period(s, bands);
    if (p.summary) {
      r.wvht = p.summary->wvht;
      r.apd = p.summary->average_period;
      const double swh = p.summary->swell_height, wwh = p.summary->wind_sea_height;
      const bool swell = std::isfinite(swh) && (!std::isfinite(wwh) || swh >= wwh);
      r.dominant_source = swell ? "SwP" : "WWP";
      r.dominant_period = swell ? p.summary->swell_period : p.summary->wind_sea_period;
      if (!std::isfinite(r.dominant_period)) {  // e.g. SwH 0.0 with SwP "MM": take the other
        r.dominant_source = swell ? "WWP" : "SwP";
        r.dominant_period = swell ? p.summary->wind_sea_period : p.summary->swell_period;
      }
      if (!std::isfinite(r.dominant_period)) r.dominant_source.clear();
      if (std::isfinite(r.wvht) && std::isfinite(r.hs_moments)) {
        r.wvht_agrees = height_agrees_with_wvht(r.hs_moments, r.wvht, s, bands, options.quantum);
      }
    }
    try {
      r.fit = fit_buoy_spectrum(s, bands, options);
      if (!r.fit->converged) ++sum.not_converged;
    } catch (const InvalidInput& e) {
      // One hour without energy does not make the file bad input; it is reported.
      r.fit_error = fmt::format("{} line {}: {}", spectrum_file, p.spectrum->line, e.what());
    }
    record.hours.push_back(std::move(r));
  }

  for (const auto& r : record.hours) {
    if (r.summary) ++sum.paired_hours;
    if (r.wvht_agrees) {
      ++sum.wvht_compared;
      sum.wvht_agree += *r.wvht_agrees;
      const double d = std::abs(r.hs_moments - r.wvht);
      if (d >= sum.wvht_largest_difference) {
        sum.wvht_largest_difference = d;
        sum.wvht_largest_at = r.time.iso();
      }
    }
    if (r.fit) {
      ++sum.fitted;
      sum.flagged += r.fit->misfit.flagged;
      sum.second_peaks += r.fit->misfit.second_peak;
      sum.energy_misfits += r.fit->misfit.energy_misfit;
      sum.deviance_rejects += r.fit->misfit.deviance_p < kDevianceAlpha;
      sum.dispersions.push_back(r.fit->misfit.dispersion);
    }
  }
  std::sort(sum.dispersions.begin(), sum.dispersions.end());
  return record;
}

nlohmann::json buoy_record_json(const BuoyRecordFit& record) {
  const auto& options = record.options;
  const auto& sum = record.summary;
  nlohmann::json hours = nlohmann::json::array();
  for (const auto& r : record.hours) {
    nlohmann::json h = {
        {"time", r.time.iso()},
        {"spectrum_line", r.spectrum->line},
        {"summary_line", r.summary ? nlohmann::json(r.summary->line) : nlohmann::json(nullptr)},
        {"separation_frequency", json_number(r.spectrum->separation_frequency)},
        {"hs_moments", json_number(r.hs_moments)},
        {"hs_moments_rounding", json_number(r.hs_rounding)},
        {"tp_peak_band", json_number(r.tp_peak)},
        {"wvht", json_number(r.wvht)},
        {"wvht_difference", json_number(r.hs_moments - r.wvht)},
        {"wvht_agrees", r.wvht_agrees ? nlohmann::json(*r.wvht_agrees) : nlohmann::json(nullptr)},
        {"dominant_period", json_number(r.dominant_period)},
        {"dominant_period_source",
         r.dominant_source.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.dominant_source)},
        {"average_period", json_number(r.apd)}};
    if (r.fit) {
      h["fit"] = {{"hs", estimate_json(r.fit->hs)},
                  {"tp", estimate_json(r.fit->tp)},
                  {"gamma", estimate_json(r.fit->gamma)}};
      h["converged"] = r.fit->converged;
      h["interval_dispersion"] = json_number(r.fit->dispersion);
      h["misfit"] = misfit_json(r.fit->misfit);
      h["bands_used"] = r.fit->bands_used;
      h["censored_bands"] = r.fit->censored_bands;
      h["window_low"] = json_number(r.fit->window_low);
      h["bands_below_window"] = r.fit->bands_below_window;
      h["negative_log_likelihood"] = json_number(r.fit->negative_log_likelihood);
    } else {
      h["fit"] = nullptr;
      h["fit_error"] = r.fit_error;
    }
    hours.push_back(std::move(h));
  }
  return {{"spectrum_file", record.spectrum_file},
          {"summary_file", record.summary_file.empty() ? nlohmann::json(nullptr)
                                                       : nlohmann::json(record.summary_file)},
          {"band_convention", band_convention_name(record.bands.convention)},
          {"dof_per_0_01_hz", json_number(options.dof)},
          {"quantum", json_number(options.quantum)},
          {"sigma_a", options.sigma_a},
          {"sigma_b", options.sigma_b},
          {"deviance_alpha", kDevianceAlpha},
          {"shape_alpha", kShapeAlpha},
          {"hours", hours},
          {"summary",
           {{"hours", record.hours.size()},
            {"paired", sum.paired_hours},
            {"wvht_compared", sum.wvht_compared},
            {"wvht_agree", sum.wvht_agree},
            {"wvht_largest_difference",
             sum.wvht_compared ? json_number(sum.wvht_largest_difference) : nullptr},
            {"fitted", sum.fitted},
            {"flagged", sum.flagged},
            {"second_peak", sum.second_peaks},
            {"energy_misfit", sum.energy_misfits},
            {"deviance_rejects", sum.deviance_rejects},
            {"not_converged", sum.not_converged}}}};
}

std::string render_buoy_record(const BuoyRecordFit& record) {
  const auto& options = record.options;
  const auto& bands = record.bands;
  const auto& sum = record.summary;
  std::string out = fmt::format(
      "swell fit --spectrum: JONSWAP (Hs, Tp, γ; σa {}, σb {}) by maximum likelihood, band "
      "values χ²_ν/ν with ν = {:g} per 0.01 Hz; {}\n"
      "{} hours; bands: {} ({} from {:.4f} to {:.4f} Hz)\n\n",
      options.sigma_a, options.sigma_b, options.dof, record.spectrum_file, record.hours.size(),
      band_convention_name(bands.convention), bands.centre.size(), bands.centre.front(),
      bands.centre.back());
  out += fmt::format("{:<17} {:>5} {:>4} {:>6} {:>22} {:>5} {:>4} {:>22} {:>18} {:>4} {:>7} {:>5}  {}\n",
                     "hour", "4√m0", "WVHT", "Δ", "fitted Hs [95 %]", "Tp pk", "dom",
                     "fitted Tp [95 %]", "γ [95 %]", "APD", "p(dev)", "φ", "misfit");
  auto interval = [](const Estimate& e, int precision) {
    return fmt::format("{:.{}f} [{:.{}f}, {:.{}f}]{}", e.value, precision, e.ci95_low, precision,
                       e.ci95_high, precision, e.calibrated ? " " : "*");
  };
  for (const auto& r : record.hours) {
    const std::string dominant =
        std::isfinite(r.dominant_period) ? fmt::format("{:.1f}", r.dominant_period) : "—";
    const std::string difference =
        r.wvht_agrees ? fmt::format("{:+.3f}{}", r.hs_moments - r.wvht, *r.wvht_agrees ? "" : "!")
                      : "—";
    const std::string wvht = std::isfinite(r.wvht) ? fmt::format("{:.1f}", r.wvht) : "—";
    if (!r.fit) {
      out += fmt::format("{:<17} {:>5.2f} {:>4} {:>6}  no fit: {}\n", r.time.iso(), r.hs_moments,
                         wvht, difference, r.fit_error);
      continue;
    }
    const auto& f = *r.fit;
    std::string misfit = f.misfit.second_peak
                             ? fmt::format("2nd peak {:.1f} s ({:.0f} %)",
                                           1 / f.misfit.second_peak_frequency,
                                           100 * f.misfit.second_peak_energy_fraction)
                             : std::string();
    if (f.misfit.energy_misfit) {
      misfit += fmt::format("{}energy {:.0f} % (t {:+.1f})", misfit.empty() ? "" : ", ",
                            100 * f.misfit.energy_model / f.misfit.energy_measured,
                            f.misfit.energy_t);
    }
    out += fmt::format(
        "{:<17} {:>5.2f} {:>4} {:>6} {:>22} {:>5.1f} {:>4} {:>22} {:>18} {:>4} {:>7.1e} {:>5.1f}  {}\n",
        r.time.iso(), r.hs_moments, wvht, difference, interval(f.hs, 2), r.tp_peak, dominant,
        interval(f.tp, 2), interval(f.gamma, 1),
        std::isfinite(r.apd) ? fmt::format("{:.1f}", r.apd) : "—", f.misfit.deviance_p,
        f.misfit.dispersion, misfit);
  }
  out += fmt::format(
      "\n*: no calibrated 95 % interval (the hour is flagged, or the profile does not close); "
      "the JSON gives the reason.\n"
      "Intervals: profile likelihood, quasi-likelihood where φ = deviance/dof > 1 (threshold "
      "1.92·φ; McCullagh & Nelder 1989 §9.2). p(dev): the χ² test of exact JONSWAP at this ν "
      "(graded information, not the flag).\n"
      "dom: the summary's SwP or WWP, whichever belongs to the larger of SwH and WWH (the summary "
      "has no DPD); APD: its average period.\n");
  if (!record.summary_file.empty()) {
    out += fmt::format(
        "\nWVHT: {} of {} hours paired with the summary; 4√m0 agrees with WVHT (within 0.05 m "
        "and the 0.001 m²/Hz rounding of S) in {} of {}; largest |4√m0 − WVHT| = {:.3f} m ({})\n",
        sum.paired_hours, record.hours.size(), sum.wvht_agree, sum.wvht_compared,
        sum.wvht_largest_difference, sum.wvht_largest_at);
  }
  const auto& dispersions = sum.dispersions;
  const auto quantile = [&](double q) {
    return dispersions.empty() ? NAN : dispersions[std::size_t(q * double(dispersions.size() - 1) + 0.5)];
  };
  out += fmt::format(
      "misfit: {} of {} fitted hours flagged as not one JONSWAP ({} with a second significant "
      "peak, {} whose fitted energy disagrees with the measured at p < {:g}); φ = deviance/dof "
      "{:.1f}–{:.1f}, median {:.1f}; the χ² test rejects exact JONSWAP (p < {:g}) in {} hours\n",
      sum.flagged, sum.fitted, sum.second_peaks, sum.energy_misfits, kShapeAlpha, quantile(0),
      quantile(1), quantile(0.5), kDevianceAlpha, sum.deviance_rejects);
  return out;
}

}  // namespace swell::validation
