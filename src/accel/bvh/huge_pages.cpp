#include "accel/bvh/huge_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pt::bvh {

void* allocate_huge(std::size_t bytes) {
  // aligned_alloc wants a multiple of the alignment; the tail past `bytes` is
  // address space only until touched (at most one huge page of it).
  const std::size_t rounded = (bytes + kHugeArrayBytes - 1) / kHugeArrayBytes * kHugeArrayBytes;
  void* p = std::aligned_alloc(kHugeArrayBytes, rounded);
#if defined(__linux__)
  if (p != nullptr) madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure changes nothing but speed
#endif
  return p;
}

void free_huge(void* p) { std::free(p); }

}  // namespace pt::bvh
