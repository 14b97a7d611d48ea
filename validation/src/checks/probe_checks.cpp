#include "swell/validation/checks/probe_checks.hpp"

#include <fmt/format.h>

#include "checks/probes/series_analysis.hpp"
#include "checks/probes/skewness_kurtosis.hpp"
#include "swell/reference/errors.hpp"

namespace swell::validation {

using namespace probe_analysis;
using reference::ProbeAmplitudes;
using reference::ProbeCase;
using reference::ProbeDirections;
using reference::ProbeFrequencies;

int probe_statistical_check_count(const ProbeCase& c) {
  const int simulated = moment_null_simulated(c) ? 2 : 0;  // skewness, kurtosis
  if (!line_bins(c).periodic) return 2 + simulated;         // Welch: spectrum, energy
  // series.direction, where one direction per frequency meets three probes or more (it may
  // still skip, leaving its share unspent: conservative).
  // series.coherence where several directions per frequency meet two probes or more.
  const int direction =
      (c.synthesis.directions == ProbeDirections::single_per_frequency && c.layout.positions.size() >= 3) ||
              (c.synthesis.directions == ProbeDirections::double_summation && c.layout.positions.size() >= 2)
          ? 1
          : 0;
  if (c.synthesis.amplitudes == ProbeAmplitudes::rayleigh) return 3 + simulated + direction;
  return (equal_phasor_scheme(c) ? 3 : 0) + simulated + direction;  // spectrum, energy, moments
}

ProbeCheckReport run_probe_checks(const ProbeCase& c, const std::vector<std::vector<double>>& elevation,
                                  const std::vector<double>& rounding, double alpha) {
  if (elevation.size() != c.layout.positions.size() || rounding.size() != elevation.size()) {
    throw InvalidInput(fmt::format("{} series for {} probes", elevation.size(), c.layout.positions.size()));
  }
  for (const auto& series : elevation) {
    if (series.size() != c.layout.samples) {
      throw InvalidInput(fmt::format("a series of {} samples where the case has {}", series.size(), c.layout.samples));
    }
  }
  // The stored values' rounding and the engine's arithmetic in double.
  std::vector<double> allowed(rounding);
  for (std::size_t p = 0; p < allowed.size(); ++p) allowed[p] += engine_arithmetic_allowance(c, p);
  ProbeCheckReport report;
  const std::size_t period = repeat_period_samples(c);
  if (period > 0 && c.layout.samples > period) repeat_period(c, elevation, allowed, report);
  const LineBins lines = line_bins(c);
  if (!lines.periodic) {
    welch_spectrum_and_energy(c, elevation, allowed, alpha, report);
    skewness_and_kurtosis(c, elevation, alpha, report);
    report.skipped.push_back({"series.stray_energy", SkipReason::scheme_not_judged,
                              "the lines do not fall on the record's bins: no bin is free of them"});
    report.skipped.push_back({"series.phase", SkipReason::scheme_not_judged,
                              "the lines do not fall on the record's bins: phases between probes are judged on "
                              "records of whole repeat periods"});
    return report;
  }
  std::vector<ProbeSpectrum> spectra;
  for (std::size_t p = 0; p < elevation.size(); ++p) spectra.push_back(probe_spectrum(elevation[p], allowed[p]));
  line_spectrum_and_energy(c, lines, spectra, alpha, report);
  spectral_moments(c, lines, spectra, alpha, report);
  skewness_and_kurtosis(c, elevation, alpha, report);
  stray_energy(c, lines, spectra, report);
  if (c.synthesis.directions != ProbeDirections::double_summation && spectra.size() >= 2) {
    same_amplitude(c, lines, spectra, report);
  }
  if (c.synthesis.directions == ProbeDirections::long_crested && spectra.size() >= 2) {
    phase(c, lines, spectra, report);
  } else if (c.synthesis.directions == ProbeDirections::single_per_frequency && spectra.size() >= 2) {
    plane_waves(c, lines, spectra, alpha, report);
  } else if (spectra.size() >= 2) {
    coherence(c, lines, spectra, alpha, report);
  } else {
    report.skipped.push_back({"series.phase", SkipReason::scheme_not_judged,
                              "one probe: no phase between probes"});
  }
  report.notes.push_back(fmt::format("{} lines on bins q = {} i of the record's {} samples ({} whole repeat "
                                     "period{})",
                                     lines.bins.size(), lines.whole_periods, c.layout.samples, lines.whole_periods,
                                     lines.whole_periods == 1 ? "" : "s"));
  return report;
}

}  // namespace swell::validation
