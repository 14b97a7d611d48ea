#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"

namespace swell::validation::ocean_analysis {

namespace {

// Another backend's plan and its own (aligned) buffers: with other memory FFTW's execute copies
// through aligned temporaries on every call. A device backend's buffers are staged through the
// host.
struct OtherBackend {
  std::unique_ptr<impls::Backend> backend;
  std::unique_ptr<impls::Plan> plan;
  std::unique_ptr<impls::Buffer> in_buffer, out_buffer;
  bool on_host = false;
  std::vector<Complex> staging_in, staging_out;
};

}  // namespace

void ParsevalFold::start(const Analysis& a) {
  auto other = std::make_shared<OtherBackend>();
  other->backend = impls::make_backend(a.options().analysis_backend);
  backend_name = other->backend->name();
  impls::TransformSpec spec;
  // A lattice's analysis is one 1-D transform over its N samples (docs/conventions.md §2.1).
  spec.nx = a.sampling().is_lattice() ? static_cast<int>(a.count()) : a.sampling().grid().nx;
  spec.ny = a.sampling().is_lattice() ? 1 : a.sampling().grid().ny;
  spec.kind = impls::Kind::c2c;
  spec.direction = impls::Direction::forward;
  spec.precision = impls::Precision::f64;
  other->plan = other->backend->plan(spec);
  const std::size_t bytes = a.count() * sizeof(Complex);
  other->in_buffer = other->backend->allocate(bytes);
  other->out_buffer = other->backend->allocate(bytes);
  other->on_host = other->in_buffer->host_data() && other->out_buffer->host_data();
  if (!other->on_host) {
    other->staging_in.resize(a.count());
    other->staging_out.resize(a.count());
  }
  state = other;
}

void ParsevalFold::add(const Analysis& a, const std::vector<double>& h) {
  auto& o = *static_cast<OtherBackend*>(state.get());
  const std::size_t bytes = a.count() * sizeof(Complex);
  const std::span<Complex> in(o.on_host ? static_cast<Complex*>(o.in_buffer->host_data()) : o.staging_in.data(), a.count());
  const std::span<Complex> out(o.on_host ? static_cast<Complex*>(o.out_buffer->host_data()) : o.staging_out.data(), a.count());
  std::copy(h.begin(), h.end(), in.begin());
  if (!o.on_host) o.in_buffer->upload(in.data(), bytes);
  o.plan->execute(*o.in_buffer, *o.out_buffer);
  if (!o.on_host) o.out_buffer->download(out.data(), bytes);
  // Sums in long double, so that only the transform's rounding is measured.
  long double spatial = 0, spectral = 0;
  for (double x : h) spatial += (long double)x * x;
  for (const Complex& v : out) spectral += std::norm(v);
  spectral /= (long double)a.count();
  worst = std::max(worst, double(std::abs(spatial - spectral) / std::max(spatial, 1e-300L)));
}

Results check_parseval(const Analysis& a, OceanCheckReport&) {
  const FramePass& p = a.pass();
  const bool own = a.options().analysis_backend == kAnalysisBackend;
  const std::string backend = own ? impls::make_backend(kAnalysisBackend)->name() : p.parseval.backend_name;
  const double bound = rounding_budget(kSumRounding, kFp64Roundoff, a.log2n());
  double worst = p.parseval.worst;
  // Through the analysis's own backend the transforms are those the pass made (the same plan
  // on the same values): their spectral sums are taken from there, not transformed again.
  if (own) {
    worst = 0;
    for (std::size_t f = 0; f < p.spatial_energies.size(); ++f) {
      const long double spatial = p.spatial_energies[f];
      worst = std::max(worst, double(std::abs(spatial - p.spectral_energies[f]) / std::max(spatial, 1e-300L)));
    }
  }
  return {bounded_check("parseval", a.subject() + " via " + backend, worst, bound,
                        fmt::format("|Σh² − N Σ|ĥ|²| / Σh² ≤ {:.1e}", bound),
                        fmt::format("Parseval holds to {:.1e} over {} frames{}", worst,
                                    a.frame_count(), verdict(worst <= bound)))};
}

}  // namespace swell::validation::ocean_analysis
