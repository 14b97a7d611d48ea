#pragma once

namespace swell::bench {

// Registers fft2d/c2c/vkfft/fp32/<N> for N = 16 … 4096: VkFFT's 2-D complex inverse, the
// reference the swell Vulkan backend is measured against (bench/vkfft_anchor.cpp). When the
// anchor was not built, each of them skips with the reason.
void register_vkfft_benchmarks();

}  // namespace swell::bench
