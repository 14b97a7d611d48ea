// Links swell's exported targets and uses them: Bretschneider's m0 is Hs²/16 exactly.
#include <cmath>
#include <cstdio>

#include "swell/reference/moments.hpp"
#include "swell/validation/check_result.hpp"

int main() {
  const auto spectrum = swell::reference::PiersonMoskowitz::bretschneider(2.0, 7.0);
  const auto result = swell::validation::relative_check(
      "consumer.m0", "bretschneider", swell::reference::spectral_moment(*spectrum, 0), 0.25, 1e-9,
      "m0 = Hs²/16");
  std::printf("%s: %s\n", result.check.c_str(), result.reason.c_str());
  return result.passed ? 0 : 1;
}
