// The SPIR-V of impls/shaders, compiled by glslc at build time (impls/CMakeLists.txt) into
// comma-separated words: no shader compiler at run time.
#include "context.hpp"

namespace swell::impls::vk {

const std::vector<std::uint32_t>& fft_lines_spirv(Precision precision) {
  static const std::vector<std::uint32_t> fp32 = {
#include "fft_lines_fp32.inc"
  };
  static const std::vector<std::uint32_t> fp64 = {
#include "fft_lines_fp64.inc"
  };
  return precision == Precision::f64 ? fp64 : fp32;
}

const std::vector<std::uint32_t>& fft_lines_shuffle_spirv(Precision precision) {
  static const std::vector<std::uint32_t> fp32 = {
#include "fft_lines_shuffle_fp32.inc"
  };
  static const std::vector<std::uint32_t> fp64 = {
#include "fft_lines_shuffle_fp64.inc"
  };
  return precision == Precision::f64 ? fp64 : fp32;
}

const std::vector<std::uint32_t>& fft_frame_spirv(Precision precision) {
  static const std::vector<std::uint32_t> fp32 = {
#include "fft_frame_fp32.inc"
  };
  static const std::vector<std::uint32_t> fp64 = {
#include "fft_frame_fp64.inc"
  };
  return precision == Precision::f64 ? fp64 : fp32;
}

const std::vector<std::uint32_t>& fft_frame_shuffle_spirv(Precision precision) {
  static const std::vector<std::uint32_t> fp32 = {
#include "fft_frame_shuffle_fp32.inc"
  };
  static const std::vector<std::uint32_t> fp64 = {
#include "fft_frame_shuffle_fp64.inc"
  };
  return precision == Precision::f64 ? fp64 : fp32;
}

const std::vector<std::uint32_t>& frame_evolve_spirv(Precision precision) {
  static const std::vector<std::uint32_t> fp32 = {
#include "frame_evolve_fp32.inc"
  };
  static const std::vector<std::uint32_t> fp64 = {
#include "frame_evolve_fp64.inc"
  };
  return precision == Precision::f64 ? fp64 : fp32;
}

}  // namespace swell::impls::vk
