// The moments of an NDBC spectrum on its bands, 4√m0 against WVHT and the pairing by hour
// (buoy_spectrum.hpp, docs/buoy_fit.md §4); the files' readers are in io/ndbc_files.cpp.
#include "swell/validation/fit/buoy_spectrum.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "swell/reference/errors.hpp"

namespace swell::validation {

double spectral_moment_hz(const std::vector<double>& density, const SpectralBands& bands, int n) {
  if (density.size() != bands.centre.size()) {
    throw InvalidInput(fmt::format("a spectrum of {} values on {} bands", density.size(),
                                   bands.centre.size()));
  }
  double m = 0;
  for (std::size_t j = 0; j < density.size(); ++j) {
    m += density[j] * std::pow(bands.centre[j], n) * bands.width[j];
  }
  return m;  // NaN propagates from a missing band
}

double moment_significant_height(const std::vector<double>& density, const SpectralBands& bands) {
  return 4.0 * std::sqrt(spectral_moment_hz(density, bands, 0));
}

double moment_height_rounding(const std::vector<double>& density, const SpectralBands& bands,
                              double quantum) {
  double total_width = 0;
  for (double w : bands.width) total_width += w;
  const double m0 = spectral_moment_hz(density, bands, 0);
  const double dm0 = 0.5 * quantum * total_width;
  return 4.0 * std::max(std::sqrt(m0 + dm0) - std::sqrt(m0),
                        std::sqrt(m0) - std::sqrt(std::max(0.0, m0 - dm0)));
}

bool height_agrees_with_wvht(double hs_moments, double wvht, const std::vector<double>& density,
                             const SpectralBands& bands, double quantum) {
  return std::abs(hs_moments - wvht) <=
         0.05 + moment_height_rounding(density, bands, quantum) + 1e-9;
}

std::vector<PairedBuoyHour> pair_by_hour(const BuoySpectrumFile& spectra,
                                         const std::vector<BuoySummaryRecord>& summaries) {
  std::map<long, const BuoySummaryRecord*> by_hour;
  for (const auto& s : summaries) {
    const auto [it, fresh] = by_hour.emplace(s.time.key(), &s);
    if (!fresh) {
      throw InvalidInput(fmt::format("the summary holds {} twice (lines {} and {})", s.time.iso(),
                                     it->second->line, s.line));
    }
  }
  std::map<long, const BuoySpectrumRecord*> spectra_by_hour;
  for (const auto& r : spectra.records) {
    const auto [it, fresh] = spectra_by_hour.emplace(r.time.key(), &r);
    if (!fresh) {
      throw InvalidInput(fmt::format("{} holds {} twice (lines {} and {})", spectra.path,
                                     r.time.iso(), it->second->line, r.line));
    }
  }
  std::vector<PairedBuoyHour> out;
  for (const auto& [key, record] : spectra_by_hour) {
    const auto it = by_hour.find(key);
    out.push_back({record, it == by_hour.end() ? nullptr : it->second});
  }
  return out;
}

}  // namespace swell::validation
