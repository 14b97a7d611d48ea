#include "checks/probes/series_analysis.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::probe_analysis {

using reference::ProbeAmplitudes;
using reference::ProbeCase;
constexpr double kPi = std::numbers::pi;

namespace {

// Eigen-directions of R with λ below this are left out of the whitening: there the probes see
// one phase (waves long against the array) and R's small eigenvalues hang on where within its
// sector an engine puts each direction.
constexpr double kSmallestEigenvalue = 0.2;

// One line's whitened power u = Z^H A Z, A = Σ_kept e e^H/λ, Z = X/√(S Δω/2) over the probes,
// and its law's mean and variance: Rayleigh amplitudes make Z complex Gaussian with covariance R,
// so u ~ Gamma(r, 1) over the r kept eigen-directions; n equal phasors of independent phases make
// Z = n^(−½) Σ_j e^(iψ_j) v_j, E u = tr(A R) = r and Var u = Σ_{j≠l} |G_jl|², G = V^H A V/n.
struct WhitenedLine {
  double u = 0, mean = 0, variance = 0;
};

// The directions of a frequency's lines as the engine declares them, and what the gate tries
// in their place to name a failure.
struct Hypothesis {
  double k_factor_deep = 0;  // > 0: k = ω²/g instead of the case's
  double turn = 0;           // rad added to every direction
};

WhitenedLine whiten(const std::vector<Complex>& x, double expected, const std::vector<double>& thetas, double k,
                    const std::vector<std::array<double, 2>>& positions, bool rayleigh) {
  const int p = int(positions.size()), n = int(thetas.size());
  Eigen::MatrixXcd steering(p, n);  // v_j,p = e^(−i k ê_j·x_p)
  for (int j = 0; j < n; ++j) {
    for (int q = 0; q < p; ++q) {
      const double along = std::cos(thetas[std::size_t(j)]) * positions[std::size_t(q)][0] +
                           std::sin(thetas[std::size_t(j)]) * positions[std::size_t(q)][1];
      steering(q, j) = std::polar(1.0, -k * along);
    }
  }
  const Eigen::MatrixXcd r = steering * steering.adjoint() / double(n);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> solver(r);
  Eigen::MatrixXcd a = Eigen::MatrixXcd::Zero(p, p);
  int kept = 0;
  for (int m = 0; m < p; ++m) {
    const double lambda = solver.eigenvalues()(m);
    if (lambda < kSmallestEigenvalue) continue;
    a += solver.eigenvectors().col(m) * solver.eigenvectors().col(m).adjoint() / lambda;
    ++kept;
  }
  Eigen::VectorXcd z(p);
  for (int q = 0; q < p; ++q) z(q) = x[std::size_t(q)] / std::sqrt(expected / 2);
  WhitenedLine out;
  out.u = (z.adjoint() * a * z)(0).real();
  out.mean = kept;
  if (rayleigh) {
    out.variance = kept;
  } else {
    const Eigen::MatrixXcd g = steering.adjoint() * a * steering / double(n);
    double sum = 0;
    for (int j = 0; j < n; ++j) {
      for (int l = 0; l < n; ++l) {
        if (j != l) sum += std::norm(g(j, l));
      }
    }
    out.variance = sum;
  }
  return out;
}

struct CoherenceTest {
  double p = 1, ratio = 1;  // Fisher's p over rings; the worst ring's Σu/Σ E u
  std::size_t lines = 0;
};

// Rings of consecutive lines, each ring's Σ u by the Gamma of its mean and variance (exact for
// Rayleigh amplitudes), Fisher's method over the rings.
CoherenceTest coherence_test(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                             const std::vector<std::vector<double>>& thetas, const Hypothesis& hypothesis) {
  const auto dispersion = c.sea.dispersion();
  const bool rayleigh = c.synthesis.amplitudes == ProbeAmplitudes::rayleigh;
  std::vector<WhitenedLine> whitened;
  for (std::size_t i = 0; i < lines.bins.size(); ++i) {
    const std::size_t q = lines.bins[i];
    bool clear = true;
    std::vector<Complex> x;
    for (const auto& s : spectra) {
      // As series.spectrum: lines whose expected power stands 10⁶ above the rounding's.
      clear = clear && lines.expected[i] > 1e6 * 2 * s.rounding * s.rounding;
      x.push_back(s.x[q]);
    }
    if (!clear || thetas[i].empty()) continue;
    const double omega = lines.omega[i];
    const double k = hypothesis.k_factor_deep > 0 ? omega * omega / c.sea.gravity : dispersion.wavenumber(omega);
    std::vector<double> turned = thetas[i];
    for (double& t : turned) t += hypothesis.turn;
    whitened.push_back(whiten(x, lines.expected[i], turned, k, c.layout.positions, rayleigh));
  }
  CoherenceTest out;
  out.lines = whitened.size();
  if (whitened.empty()) return out;
  const int count = int(whitened.size()), rings = std::clamp(count / 64, 1, 24);
  std::vector<double> p_values;
  double worst = 2;
  for (int r = 0; r < rings; ++r) {
    double sum = 0, mean = 0, variance = 0;
    for (int i = r * count / rings; i < (r + 1) * count / rings; ++i) {
      sum += whitened[std::size_t(i)].u, mean += whitened[std::size_t(i)].mean;
      variance += whitened[std::size_t(i)].variance;
    }
    if (!(mean > 0)) continue;
    double p_value;
    if (variance > 0) {
      const double shape = mean * mean / variance, scale = variance / mean;
      p_value = std::min(1.0, 2 * std::min(stats::gamma_lower_p(shape, sum / scale),
                                           stats::gamma_upper_p(shape, sum / scale)));
    } else {
      p_value = std::abs(sum - mean) <= 1e-9 * mean ? 1.0 : 0.0;
    }
    p_values.push_back(p_value);
    if (p_value < worst) worst = p_value, out.ratio = sum / mean;
  }
  out.p = p_values.empty() ? 1.0 : stats::fisher_combined_p(p_values);
  return out;
}

// The direction read by beamforming (Bartlett's, the direct Fourier transform method): for each
// line B(θ) = |a(θ)^H Z|² with a_p = e^(−ik ê(θ)·x_p)/√P, summed over the lines holding 10⁻² of
// the strongest line's power and more; its mean direction and mean resultant length. The same
// estimator applied to the declared covariance, a^H R a, gives what the declared spreading looks
// like through this array (the beam's width spreads both alike), so the two compare.
struct Beamformed {
  double measured_direction = 0, measured_length = 0, declared_direction = 0, declared_length = 0;
  std::size_t lines = 0;
};

Beamformed beamform(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra,
                    const std::vector<std::vector<double>>& thetas) {
  constexpr int kBeams = 120;
  const auto dispersion = c.sea.dispersion();
  const auto& positions = c.layout.positions;
  const std::size_t probes = positions.size();
  double strongest = 0;
  for (double e : lines.expected) strongest = std::max(strongest, e);
  std::vector<double> measured(kBeams, 0.0), declared(kBeams, 0.0);
  Beamformed out;
  for (std::size_t i = 0; i < lines.bins.size(); ++i) {
    if (lines.expected[i] < 1e-2 * strongest || thetas[i].empty()) continue;
    const double k = dispersion.wavenumber(lines.omega[i]), scale = std::sqrt(lines.expected[i] / 2);
    const auto plane_wave = [&](double theta, std::size_t p) {
      return std::polar(1.0, -k * (std::cos(theta) * positions[p][0] + std::sin(theta) * positions[p][1]));
    };
    std::vector<Complex> sources;  // v_j,p of the declared directions, j-major
    for (double direction : thetas[i]) {
      for (std::size_t p = 0; p < probes; ++p) sources.push_back(plane_wave(direction, p));
    }
    std::vector<Complex> steer(probes);
    for (int b = 0; b < kBeams; ++b) {
      const double theta = 2 * kPi * b / kBeams;
      Complex beam = 0;
      for (std::size_t p = 0; p < probes; ++p) {
        steer[p] = std::conj(plane_wave(theta, p));
        beam += steer[p] * spectra[p].x[lines.bins[i]] / scale;
      }
      measured[std::size_t(b)] += std::norm(beam) / double(probes);
      // a^H R a = (1/n) Σ_j |a^H v_j|².
      double expected = 0;
      for (std::size_t j = 0; j < thetas[i].size(); ++j) {
        Complex projection = 0;
        for (std::size_t p = 0; p < probes; ++p) projection += steer[p] * sources[j * probes + p];
        expected += std::norm(projection);
      }
      declared[std::size_t(b)] += expected / double(thetas[i].size()) / double(probes);
    }
    ++out.lines;
  }
  Complex m = 0, d = 0;
  double m_total = 0, d_total = 0;
  for (int b = 0; b < kBeams; ++b) {
    const Complex turn = std::polar(1.0, 2 * kPi * b / kBeams);
    m += measured[std::size_t(b)] * turn, d += declared[std::size_t(b)] * turn;
    m_total += measured[std::size_t(b)], d_total += declared[std::size_t(b)];
  }
  out.measured_direction = std::arg(m), out.measured_length = m_total > 0 ? std::abs(m) / m_total : 0;
  out.declared_direction = std::arg(d), out.declared_length = d_total > 0 ? std::abs(d) / d_total : 0;
  return out;
}

}  // namespace

void coherence(const ProbeCase& c, const LineBins& lines, const std::vector<ProbeSpectrum>& spectra, double alpha,
               ProbeCheckReport& report) {
  // The engine's directions per frequency: the medians of D's equal-probability sectors (they do
  // not depend on the seed), for the lines judged: those holding 10⁻⁴ of the strongest line's
  // power and more (the rest add little and cost as much).
  const auto sea = c.spectrum();
  double strongest = 0;
  for (double e : lines.expected) strongest = std::max(strongest, e);
  std::vector<std::vector<double>> by_frequency(lines.bins.size());
  for (std::size_t i = 0; i < lines.bins.size(); ++i) {
    if (lines.expected[i] >= 1e-4 * strongest) {
      by_frequency[i] = reference::sector_directions(*sea, lines.omega[i], c.synthesis.n_directions);
    }
  }
  const auto test = coherence_test(c, lines, spectra, by_frequency, {});
  if (test.lines == 0) {
    report.skipped.push_back({"series.coherence", SkipReason::too_few_wave_vectors,
                              "no line stands 10⁶ above the rounding at every probe"});
    return;
  }
  std::string reason = fmt::format("{} lines over {} probes: the worst ring's whitened power is {:.3f} × its mean "
                                   "(p = {:.2g})",
                                   test.lines, spectra.size(), test.ratio, test.p);
  const auto beams = beamform(c, lines, spectra, by_frequency);
  if (beams.lines > 0) {
    const auto degrees = [](double radians) { return std::remainder(radians * 180 / kPi, 360.0); };
    reason += fmt::format("; beamformed over {} lines: travel toward {:.1f}°, mean resultant length {:.3f} (the "
                          "declared spreading through this array: {:.1f}°, {:.3f})",
                          beams.lines, degrees(beams.measured_direction), beams.measured_length,
                          degrees(beams.declared_direction), beams.declared_length);
  }
  if (test.p < alpha) {
    const auto reversed = coherence_test(c, lines, spectra, by_frequency, {0, kPi});
    const auto deep = coherence_test(c, lines, spectra, by_frequency, {1, 0});
    if (reversed.p >= alpha) {
      reason += " — the probes' cross-spectra are those of the declared spreading turned by 180°: the waves "
                "travel against the declared direction";
    } else if (deep.p >= alpha && std::isfinite(c.sea.depth)) {
      reason += fmt::format(" — the probes' cross-spectra follow deep-water k = ω²/g where the case's depth is {:g} "
                            "m (a deep-water dispersion in finite depth)",
                            c.sea.depth);
    } else {
      reason += " — the probes' cross-spectra do not follow ∫ D(θ) e^(−ik·Δx) dθ of the declared spreading at the "
                "case's k(ω) (another spreading or direction, probes elsewhere than declared, or a power scale "
                "series.energy names)";
    }
  }
  report.results.push_back(statistical_check(
      "series.coherence", c.describe(), test.ratio, 1, test.p, alpha,
      fmt::format("p ≥ α = {:.0e} (each line's probe vector whitened by R = Σ_j e^(−ik ê_j·Δx)/n of the declared "
                  "directions, eigenvalues ≥ {:g}: Gamma per ring of lines, {}; Fisher's method)",
                  alpha, kSmallestEigenvalue,
                  c.synthesis.amplitudes == ProbeAmplitudes::rayleigh ? "exact for Rayleigh amplitudes"
                                                                      : "by its mean and variance"),
      reason));
}

}  // namespace swell::validation::probe_analysis
