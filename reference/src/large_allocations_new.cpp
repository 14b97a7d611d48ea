// The global operator new of swell's own programs (the `swell` command, the benchmarks, the
// test suites — not the libraries, whose users keep their allocator): allocations of 2 MiB
// and more go on transparent huge pages (swell/reference/huge_pages.hpp), everything smaller to
// malloc as before. Frames, spectra, wave series and the analysis's arrays are std::vectors of
// 2 MiB and more at 512², and each is written once soon after it is allocated: in 4 KiB pages
// their first touch cost the gate (gate/512/64) ~35 000 page faults, about 0.5 s of CPU on the
// reference VM (docs/performance.md §7).
//
// Only operator new(size_t) is replaced: libstdc++'s new[] and nothrow new call it, and its
// operator delete calls std::free, which releases posix_memalign's blocks as malloc's. Left out
// under AddressSanitizer, whose runtime supplies its own new and delete.
#include <cstdlib>
#include <new>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "swell/reference/huge_pages.hpp"

#ifndef SWELL_SANITIZED_ALLOCATIONS
#if defined(__GLIBC__)
namespace {
// glibc maps each malloc block above its mmap threshold on its own and unmaps it when freed;
// but each such block freed raises the threshold to its size (up to 32 MiB), after which
// blocks of that size come from its arenas, which keep what is freed resident. swell's passes
// make and free arrays of 2 to 32 MiB frame after frame, and `swell gate` at 2048² × 16 frames
// peaked a tenth higher resident with glibc's threshold than with it fixed at 2 MiB
// (docs/performance.md §7). A threshold set by mallopt stays where it is set.
[[maybe_unused]] const bool mmap_threshold_fixed =
    mallopt(M_MMAP_THRESHOLD, int(swell::reference::kHugePageBytes)) == 1;
}  // namespace
#endif

void* operator new(std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  for (;;) {
    void* data = bytes >= swell::reference::kHugePageBytes ? swell::reference::allocate_on_huge_pages(bytes)
                                                      : std::malloc(bytes);
    if (data) return data;
    // What the standard asks of operator new when memory runs out: the new_handler, or bad_alloc.
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}
#endif
