#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"

namespace swell::validation::ocean_analysis {

Results check_parseval(const Analysis& a, OceanCheckReport&) {
  const auto backend = impls::make_backend(a.options().analysis_backend);
  const double bound = rounding_budget(kSumRounding, kFp64Roundoff, a.log2n());
  auto result = [&](double worst) -> Results {
    return {bounded_check("parseval", a.subject() + " via " + backend->name(), worst, bound,
                    fmt::format("|Σh² − N Σ|ĥ|²| / Σh² ≤ {:.1e}", bound),
                    fmt::format("Parseval holds to {:.1e} over {} frames{}", worst,
                                a.frames().frames.size(), verdict(worst <= bound)))};
  };
  // Through the analysis's own backend the transforms are those the wave series made (the same
  // plan on the same values): their spectral sums are taken from there, not transformed again.
  if (a.options().analysis_backend == kAnalysisBackend) {
    const auto& spectral = a.spectral_energies();
    const std::vector<long double> spatial = sums_of_squares<long double>(heights(a.frames()));
    double worst = 0;
    for (std::size_t f = 0; f < spatial.size(); ++f) {
      worst = std::max(worst, double(std::abs(spatial[f] - spectral[f]) / std::max(spatial[f], 1e-300L)));
    }
    return result(worst);
  }
  impls::TransformSpec spec;
  // A lattice's analysis is one 1-D transform over its N samples (docs/conventions.md §2.1).
  spec.nx = a.sampling().is_lattice() ? static_cast<int>(a.count()) : a.sampling().grid().nx;
  spec.ny = a.sampling().is_lattice() ? 1 : a.sampling().grid().ny;
  spec.kind = impls::Kind::c2c;
  spec.direction = impls::Direction::forward;
  spec.precision = impls::Precision::f64;
  const auto plan = backend->plan(spec);
  double worst = 0;
  // The backend's own (aligned) buffers: with other memory FFTW's execute copies through
  // aligned temporaries on every call. A device backend's buffers are staged through the host.
  const std::size_t bytes = a.count() * sizeof(Complex);
  const auto in_buffer = backend->allocate(bytes), out_buffer = backend->allocate(bytes);
  const bool on_host = in_buffer->host_data() && out_buffer->host_data();
  std::vector<Complex> staging_in(on_host ? 0 : a.count()), staging_out(on_host ? 0 : a.count());
  const std::span<Complex> in(on_host ? static_cast<Complex*>(in_buffer->host_data()) : staging_in.data(), a.count());
  const std::span<Complex> out(on_host ? static_cast<Complex*>(out_buffer->host_data()) : staging_out.data(), a.count());
  for (std::size_t f = 0; f < a.frames().frames.size(); ++f) {
    const auto& h = a.frames().field(int(f), Field::height);
    std::copy(h.begin(), h.end(), in.begin());
    if (!on_host) in_buffer->upload(in.data(), bytes);
    plan->execute(*in_buffer, *out_buffer);
    if (!on_host) out_buffer->download(out.data(), bytes);
    // Sums in long double, so that only the transform's rounding is measured.
    long double spatial = 0, spectral = 0;
    for (double x : h) spatial += (long double)x * x;
    for (const Complex& v : out) spectral += std::norm(v);
    spectral /= (long double)a.count();
    worst = std::max(worst, double(std::abs(spatial - spectral) / std::max(spatial, 1e-300L)));
  }
  return result(worst);
}

}  // namespace swell::validation::ocean_analysis
