#include "sphstab/core/huge_page_allocator.hpp"

#include <sys/mman.h>

#include <cstdlib>

namespace sphstab::detail {

void* allocate_huge_pages(std::size_t bytes) {
  // Whole huge pages: madvise applies to the pages the range covers, and a huge page needs all of its 2 MiB.
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (rounded < bytes) throw std::bad_alloc();
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  if (p == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // advice only: ordinary pages where it is refused
#endif
  return p;
}

void free_huge_pages(void* p) noexcept { std::free(p); }

}  // namespace sphstab::detail
