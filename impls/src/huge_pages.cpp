#include "swell/impls/huge_pages.hpp"

#include <cstdlib>

#include <sys/mman.h>

namespace swell::impls {

void* allocate_on_huge_pages(std::size_t bytes) noexcept {
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (rounded < bytes) return nullptr;  // wrapped around: no such allocation exists
  void* data = nullptr;
  if (posix_memalign(&data, kHugePageBytes, rounded) != 0) return nullptr;
#ifdef MADV_HUGEPAGE
  // Before the first touch: the pages faulted in afterwards are huge ones (THP "madvise" mode,
  // Debian's default). Fails harmlessly where THP is compiled out.
  madvise(data, rounded, MADV_HUGEPAGE);
#endif
  return data;
}

}  // namespace swell::impls
