#pragma once
// Large arrays on transparent huge pages (docs/performance.md §7).
//
// Every first touch of a 4 KiB page is a page fault. On the virtual machines swell's CI and many
// users run on, a fault costs ~14 µs (the 2-core reference VM: 128 MiB written for the first
// time took 450 ms in 4 KiB pages, 11 ms in 2 MiB pages), so a gate of 64 frames of 512² spent
// a third of its CPU faulting in its frames and analysis arrays. A 2 MiB page is one fault.
#include <cstddef>

// Defined where AddressSanitizer supplies operator new and delete: swell's own operator new
// (reference/src/large_allocations_new.cpp) is then left out.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SWELL_SANITIZED_ALLOCATIONS 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define SWELL_SANITIZED_ALLOCATIONS 1
#endif

namespace swell::reference {

inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// `bytes` rounded up to whole 2 MiB pages; 0 when that does not fit in a size_t.
constexpr std::size_t round_to_huge_pages(std::size_t bytes) {
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  return rounded < bytes ? 0 : rounded;
}

// Asks Linux for transparent huge pages on the whole 2 MiB pages inside [data, data + bytes),
// before they are first touched (THP "madvise" mode, Debian's default). Only advice: where THP
// is off or compiled out it changes nothing.
void advise_huge_pages(void* data, std::size_t bytes) noexcept;

// `bytes` (≥ 1) rounded up to whole 2 MiB pages (round_to_huge_pages), on a 2 MiB boundary,
// advised as above; not zeroed. nullptr when out of memory. Release with std::free.
void* allocate_on_huge_pages(std::size_t bytes) noexcept;

}  // namespace swell::reference
