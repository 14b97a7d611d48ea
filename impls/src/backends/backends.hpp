#pragma once
// Internal: the factories the registry (registry.cpp) maps names to.
#include <memory>

#include "swell/impls/transform.hpp"

namespace swell::impls {

std::unique_ptr<Backend> make_naive_backend(const BackendOptions& options);
std::unique_ptr<Backend> make_radix2_backend(const BackendOptions& options);
std::unique_ptr<Backend> make_fftw_backend(const BackendOptions& options);
std::unique_ptr<Backend> make_null_backend(const BackendOptions& options);
#ifdef SWELL_HAVE_VULKAN
std::unique_ptr<Backend> make_vulkan_backend(const BackendOptions& options);  // vulkan/fft.cpp
#endif

}  // namespace swell::impls
