// Cost of the reference computations that the checks lean on: k(ω) by Newton, spectrum
// evaluation, moments by quadrature and a grid-band-limited m0. Run:
//   build/bench/swell_reference_bench --benchmark_format=json
#include <benchmark/benchmark.h>

#include <cmath>

#include "swell/reference/directional.hpp"
#include "swell/reference/moments.hpp"

namespace {
using namespace swell::reference;

void BM_WavenumberFiniteDepth(benchmark::State& state) {
  const auto d = Dispersion::finite_depth(10.0);
  double omega = 0.1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(d.wavenumber(omega));
    omega = omega < 10 ? omega * 1.01 : 0.1;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_WavenumberFiniteDepth);

void BM_JonswapEvaluate(benchmark::State& state) {
  const auto s = Jonswap::from_hs_tp(3.0, 8.0);
  double omega = 0.2;
  for (auto _ : state) {
    benchmark::DoNotOptimize((*s)(omega));
    omega = omega < 5 ? omega * 1.001 : 0.2;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_JonswapEvaluate);

void BM_JonswapSeaState(benchmark::State& state) {
  const auto s = Jonswap::from_hs_tp(3.0, 8.0);
  for (auto _ : state) benchmark::DoNotOptimize(sea_state(*s).hs);
}
BENCHMARK(BM_JonswapSeaState)->Unit(benchmark::kMicrosecond);

void BM_GridSeaState(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto psi = SpreadSpectrum::create(Jonswap::from_hs_tp(3.0, 8.0), Cos2s::constant(10),
                                          Dispersion::deep(), 0.5);
  const auto grid = Grid::create(n, n, 500.0, 500.0);
  for (auto _ : state) benchmark::DoNotOptimize(grid_sea_state(*psi, grid).moments.m0);
  state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(BM_GridSeaState)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
