#pragma once
// radix2's arithmetic roof (docs/performance.md §1): the rate of its fastest kernel alone, for
// the benchmarks to set beside each radix2 transform, as the copy roofline sets the bandwidth.
#include "swell/impls/transform.hpp"

namespace swell::impls {

struct Radix2KernelRate {
  int lanes = 0;  // signals per vector: one vector butterfly is `lanes` radix-2 butterflies
  double seconds_per_vector_butterfly = 0;
};

// The middle stages' kernel of radix2 (three radix-2 stages fused in registers, spans 8, 16, 32)
// swept over one 128-element chunk of its scratch, which stays in L1 — no gather, no scatter, no
// transposes, no cache misses: what every butterfly of a transform would cost at best in this
// design. The best of `repetitions` timings of 2000 sweeps each, in this process, now. A 2-D
// c2c transform of n × n points does n² log2(n²) / 2 butterflies; at this rate it would take
// n² log2(n²) / (2 · lanes) · seconds_per_vector_butterfly.
Radix2KernelRate measure_radix2_kernel_rate(Precision precision, int repetitions = 9);

}  // namespace swell::impls
