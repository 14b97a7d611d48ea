// Large arrays on transparent huge pages (swell/reference/huge_pages.hpp): the allocation helper,
// HostBuffer, and the global operator new that swell's programs link
// (reference/src/large_allocations_new.cpp; this test program links it as every other does).
#include <gtest/gtest.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <complex>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <vector>

#include "swell/reference/huge_pages.hpp"
#include "swell/impls/transform.hpp"

namespace {

using swell::reference::kHugePageBytes;

bool on_huge_page_boundary(const void* p) {
  return reinterpret_cast<std::uintptr_t>(p) % kHugePageBytes == 0;
}

TEST(HugePages, AllocationsStartOnA2MiBBoundaryAndTheWholeRoundedSizeIsTheCallers) {
  for (std::size_t bytes : {kHugePageBytes, kHugePageBytes + 1, 3 * kHugePageBytes - 8}) {
    void* data = swell::reference::allocate_on_huge_pages(bytes);
    ASSERT_NE(data, nullptr) << bytes;
    EXPECT_TRUE(on_huge_page_boundary(data)) << bytes;
    // The whole rounded size is the caller's (madvise covers it): write its last byte too.
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    static_cast<volatile unsigned char*>(data)[rounded - 1] = 1;
    std::free(data);
  }
}

TEST(HugePages, AnImpossibleSizeIsNullNotAWrappedSmallBlock) {
  // SIZE_MAX rounded up to 2 MiB wraps around to 0: must not become a tiny allocation.
  EXPECT_EQ(swell::reference::allocate_on_huge_pages(std::numeric_limits<std::size_t>::max()), nullptr);
  EXPECT_EQ(swell::reference::allocate_on_huge_pages(std::numeric_limits<std::size_t>::max() / 2), nullptr);
}

TEST(HugePages, HostBuffersOf2MiBAndMoreAreOnHugePageBoundariesAndZeroed) {
  swell::impls::HostBuffer buffer(3 * kHugePageBytes / 2);
  EXPECT_TRUE(on_huge_page_boundary(buffer.host_data()));
  const auto* bytes = static_cast<const unsigned char*>(buffer.host_data());
  for (std::size_t i = 0; i < buffer.bytes(); i += 4093) ASSERT_EQ(bytes[i], 0) << i;
  swell::impls::HostBuffer small(1000);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(small.host_data()) % 64, 0u);
}

// Under AddressSanitizer its runtime's operator new is used instead (huge_pages.hpp).
#ifndef SWELL_SANITIZED_ALLOCATIONS
TEST(HugePages, TheProgramsOperatorNewPutsLargeVectorsOnHugePages) {
  // A frame's field at 512² (2 MiB of doubles) and a larger one; with the default operator new
  // these land 16 bytes past a 4 KiB page boundary.
  std::vector<double> field(512 * 512, 1.0);
  EXPECT_TRUE(on_huge_page_boundary(field.data()));
  auto larger = std::make_unique<std::complex<double>[]>(512 * 512 + 3);
  EXPECT_TRUE(on_huge_page_boundary(larger.get()));
}

#if defined(__GLIBC__)
// glibc's mmap threshold stays at 2 MiB after a mapped block is freed (large_allocations_new.cpp):
// a second malloc of the same size is mapped again (counted in hblkhd), not taken from an arena
// that keeps it resident once freed. With glibc's own dynamic threshold the first block's free
// raises it to 8 MiB, and the second block comes from the arena (measured: hblkhd stays 0).
void* volatile kept_block = nullptr;  // volatile: the compiler may not drop the malloc/free pairs
TEST(HugePages, MallocBlocksOf2MiBAndMoreStayMappedAfterOneIsFreed) {
  constexpr std::size_t kBytes = std::size_t(8) << 20;
  const auto mapped = [] { return mallinfo2().hblkhd; };
  for (int round = 0; round < 2; ++round) {
    const std::size_t before = mapped();
    kept_block = std::malloc(kBytes);
    ASSERT_NE(kept_block, nullptr);
    static_cast<char*>(kept_block)[kBytes - 1] = 1;
    EXPECT_GE(mapped(), before + kBytes) << "round " << round;
    std::free(kept_block);
  }
}
#endif

TEST(HugePages, OperatorNewThrowsBadAllocWhenMemoryCannotExist) {
  const std::size_t impossible = std::numeric_limits<std::size_t>::max() / 2;
  EXPECT_THROW((void)::operator new(impossible), std::bad_alloc);
  EXPECT_EQ(::operator new(impossible, std::nothrow), nullptr);
}
#endif

}  // namespace
