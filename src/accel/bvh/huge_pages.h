// An allocator for the BVH's large traversal arrays (nodes, triangle blocks):
// arrays of 2 MiB or more are aligned to 2 MiB and, on Linux, marked for
// transparent huge pages (madvise MADV_HUGEPAGE) before they are first
// touched. Traversal reads them at random; with 4 KiB pages the arrays of a
// scene of a few hundred thousand triangles span thousands of pages, more than
// the TLB holds, and incoherent rays pay a page walk on many node and block
// loads. Embree advises huge pages for its own allocations the same way; where
// the system's THP setting is "madvise" (a common default) ours were not.
// Smaller arrays are ordinary allocations. Measured: docs/bvh.md.
#pragma once

#include <cstddef>
#include <new>

namespace pt::bvh {

// Huge-page-aligned storage of at least `bytes` (>= kHugeArrayBytes), or
// nullptr; freed with free_huge().
void* allocate_huge(std::size_t bytes);
void free_huge(void* p);
inline constexpr std::size_t kHugeArrayBytes = std::size_t{2} << 20;

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugeArrayBytes) {
      if (void* p = allocate_huge(bytes)) return static_cast<T*>(p);
      throw std::bad_alloc();
    }
    return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) >= kHugeArrayBytes) {
      free_huge(p);
    } else {
      ::operator delete(p, std::align_val_t(alignof(T)));
    }
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept { return false; }
};

}  // namespace pt::bvh
