#include "accel/bvh/huge_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pt::bvh {

void* allocate_huge(std::size_t bytes) {
  // aligned_alloc wants a multiple of the alignment. Only the huge pages that
  // lie wholly inside `bytes` are advised: a huge page is resident whole once
  // any byte of it is touched, so advising the rounded-up tail made the last
  // partly used page cost up to 2 MiB of memory that holds nothing (30 B a
  // triangle on the 69k-triangle bunny); the tail stays on small pages.
  const std::size_t rounded = (bytes + kHugeArrayBytes - 1) / kHugeArrayBytes * kHugeArrayBytes;
  void* p = std::aligned_alloc(kHugeArrayBytes, rounded);
#if defined(__linux__)
  const std::size_t whole = bytes / kHugeArrayBytes * kHugeArrayBytes;
  if (p != nullptr && whole > 0) madvise(p, whole, MADV_HUGEPAGE);  // a hint: failure changes nothing but speed
#endif
  return p;
}

void free_huge(void* p) { std::free(p); }

}  // namespace pt::bvh
