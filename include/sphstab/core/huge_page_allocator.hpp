#pragma once
/// \file huge_page_allocator.hpp
/// A std::allocator for the large work arrays a run touches for the first time at its start (the pair loop's packed
/// particles and kept pairs, the neighbour search's row blocks): an allocation of at least kHugePageMinBytes is
/// aligned to 2 MiB, rounded up to whole 2 MiB and advised as a transparent huge page (Linux madvise MADV_HUGEPAGE),
/// so that its first touch faults once per 2 MiB instead of once per 4 KiB page. Smaller ones are plain operator new.
/// Where the kernel has transparent huge pages off, or madvise fails, the memory is ordinary pages: only the fault
/// count changes, never a value.
#include <cstddef>
#include <limits>
#include <new>
#include <vector>

namespace sphstab {

/// The smallest allocation advised as huge pages: at 1 MiB the rounding to 2 MiB wastes at most half of it.
inline constexpr std::size_t kHugePageMinBytes = std::size_t{1} << 20;
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

namespace detail {
/// At least `bytes` bytes aligned to kHugePageBytes and advised as huge pages; throws std::bad_alloc.
void* allocate_huge_pages(std::size_t bytes);
void free_huge_pages(void* p) noexcept;
}  // namespace detail

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugePageMinBytes) return static_cast<T*>(detail::allocate_huge_pages(bytes));
    return static_cast<T*>(::operator new (bytes, std::align_val_t{alignof(T)}));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) >= kHugePageMinBytes)
      detail::free_huge_pages(p);
    else
      ::operator delete (p, std::align_val_t{alignof(T)});
  }
  friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) noexcept { return true; }
};

/// A work array on HugePageAllocator.
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace sphstab
