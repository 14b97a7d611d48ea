#include "swell/reference/wave_noise.hpp"

#include <Random123/boxmuller.hpp>
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

namespace swell::reference {
namespace {

using Philox = r123::Philox4x32_R<10>;  // Philox4x32-10

Philox::ctr_type draw(std::uint64_t seed, int n, int m, std::uint32_t stream,
                      std::uint32_t cascade) {
  const Philox::key_type key = {{static_cast<std::uint32_t>(seed),
                                 static_cast<std::uint32_t>(seed >> 32)}};
  const Philox::ctr_type counter = {{static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(m),
                                     stream, cascade}};
  return Philox{}(counter, key);
}

std::uint64_t join(std::uint32_t low, std::uint32_t high) {
  return std::uint64_t(low) | (std::uint64_t(high) << 32);
}

}  // namespace

NormalPair wave_noise(std::uint64_t seed, int n, int m, std::uint32_t stream,
                      std::uint32_t cascade) {
  const auto w = draw(seed, n, m, stream, cascade);
  const r123::double2 xi = r123::boxmuller(join(w[0], w[1]), join(w[2], w[3]));
  return {xi.x, xi.y};
}

UniformPair wave_uniforms(std::uint64_t seed, int n, int m, std::uint32_t stream) {
  const auto w = draw(seed, n, m, stream, 0);
  return {r123::u01<double>(join(w[0], w[1])), r123::u01<double>(join(w[2], w[3]))};  // (0, 1]
}

}  // namespace swell::reference
