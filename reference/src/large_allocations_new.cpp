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

#include "swell/reference/huge_pages.hpp"

#ifndef SWELL_SANITIZED_ALLOCATIONS
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
