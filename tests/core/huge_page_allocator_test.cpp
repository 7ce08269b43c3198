// HugePageAllocator (core/huge_page_allocator.hpp): the two size classes, the alignment and advice of the large one,
// and a vector's values across growth from one class into the other.
#include "sphstab/core/huge_page_allocator.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <string>

namespace sphstab {
namespace {

/// The VmFlags line of the mapping that holds `p` (/proc/self/smaps), or "" where none is found.
std::string vm_flags_of(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {  // a mapping's first line: lo-hi perms ...
      inside = lo <= a && a < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST(HugePageAllocator, LargeAllocationsAreAlignedToHugePagesAndAdvised) {
  HugePageAllocator<double> alloc;
  const std::size_t n = kHugePageMinBytes / sizeof(double);  // exactly the threshold: the large class
  double* p = alloc.allocate(n);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kHugePageBytes, 0u);
  for (std::size_t k = 0; k < n; ++k) p[k] = static_cast<double>(k);  // the whole range is usable
  EXPECT_EQ(p[n - 1], static_cast<double>(n - 1));
  if (std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled")) {
    // madvise(MADV_HUGEPAGE) marks the mapping "hg" whatever the system-wide THP mode.
    const std::string flags = vm_flags_of(p);
    EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
  }
  alloc.deallocate(p, n);
}

TEST(HugePageAllocator, SmallAllocationsKeepTheirTypesAlignment) {
  HugePageAllocator<long double> alloc;
  long double* p = alloc.allocate(3);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % alignof(long double), 0u);
  alloc.deallocate(p, 3);
}

TEST(HugePageAllocator, AVectorKeepsItsValuesWhenItGrowsIntoHugePages) {
  HugePageVector<int> v;
  const int small = 1000, large = static_cast<int>(3 * kHugePageMinBytes / sizeof(int));
  for (int k = 0; k < small; ++k) v.push_back(k * k);
  v.resize(large, -1);  // the small block's values moved into the large one
  for (int k = 0; k < small; ++k) ASSERT_EQ(v[k], k * k);
  EXPECT_EQ(v[small], -1);
  EXPECT_EQ(v[large - 1], -1);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % kHugePageBytes, 0u);
  v.resize(small);
  v.shrink_to_fit();  // and back into the small class
  for (int k = 0; k < small; ++k) ASSERT_EQ(v[k], k * k);
}

TEST(HugePageAllocator, AnOverflowingCountIsBadAllocNotAWrappedSize) {
  HugePageAllocator<double> alloc;
  EXPECT_THROW((void)alloc.allocate(std::size_t(-1) / 4), std::bad_array_new_length);
}

}  // namespace
}  // namespace sphstab
