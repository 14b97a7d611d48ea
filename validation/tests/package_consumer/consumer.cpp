// Links swell's exported targets and uses them: Bretschneider's m0 is Hs²/16 exactly.
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "swell/reference/moments.hpp"
#include "swell/impls/transform.hpp"
// A room's header, and an old flat path (forwarding for one release).
#include "swell/validation/check_result.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/results/check_result.hpp"

int main() {
  const auto spectrum = swell::reference::PiersonMoskowitz::bretschneider(2.0, 7.0);
  const auto result = swell::validation::relative_check(
      "consumer.m0", "bretschneider", swell::reference::spectral_moment(*spectrum, 0), 0.25, 1e-9,
      "m0 = Hs²/16");
  std::printf("%s: %s\n", result.check.c_str(), result.reason.c_str());
  // And a transform through the exported backends: the forward DFT of an impulse is all ones.
  const auto backend = swell::impls::make_backend("radix2");
  swell::impls::TransformSpec spec;
  spec.nx = 8;
  const auto plan = backend->plan(spec);
  std::vector<std::complex<double>> in(8), out(8);
  in[0] = 1;
  plan->execute(std::span<const std::complex<double>>(in), std::span<std::complex<double>>(out));
  for (const auto& value : out) {
    if (std::abs(value - std::complex<double>(1, 0)) > 1e-15) return 1;
  }
  return result.passed ? 0 : 1;
}
