#include "swell/reference/huge_pages.hpp"

#include <cstdint>
#include <cstdlib>

#include <sys/mman.h>

namespace swell::reference {

void advise_huge_pages(void* data, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePageBytes - 1) & ~std::uintptr_t(kHugePageBytes - 1);
  const std::uintptr_t last = (begin + bytes) & ~std::uintptr_t(kHugePageBytes - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

void* allocate_on_huge_pages(std::size_t bytes) noexcept {
  const std::size_t rounded = round_to_huge_pages(bytes);
  if (rounded == 0) return nullptr;  // no such allocation exists
  void* data = nullptr;
  if (posix_memalign(&data, kHugePageBytes, rounded) != 0) return nullptr;
  advise_huge_pages(data, rounded);
  return data;
}

}  // namespace swell::reference
