// Binned SAH split search and in-place partition (internal to the builder).
//
// Primitives are binned by their box centre into `bins` equal intervals of the
// range's centre bounds on each axis; the SAH sweep evaluates the bins - 1
// planes between them. Everything here is deterministic: the reductions are
// min/max and integer sums, ties go to the lowest axis and the lowest plane.
// Boxes are handled four lanes at a time with SSE2 (baseline x86-64).
#pragma once

#include <cstdint>
#include <utility>

#include "accel/bvh/build.h"

namespace pt::bvh::detail {

inline constexpr int kMaxBins = 32;

// A contiguous range of PrimRefs with the bounds of their boxes and centres.
struct Range {
  uint32_t begin = 0, end = 0;
  Bounds3f box;   // union of the primitive boxes
  Bounds3f cbox;  // bounds of the primitive centres (centre_of)
  uint32_t size() const { return end - begin; }
};

enum class SplitKind { Sah, Median, None };

struct Split {
  SplitKind kind = SplitKind::None;
  int axis = 0;
  int plane = 0;     // Sah: bins [0, plane) go left
  float cost = 0;    // Sah: A_L * C(N_L) + A_R * C(N_R), not yet divided by A
};

// The centre the builder bins by: lo / 2 + hi / 2 (no overflow for large boxes).
Vec3f centre_of(const PrimRef& r);

// Leaf cost of n primitives: whole blocks.
inline float leaf_cost(uint32_t n, const BuildSettings& s) {
  const auto block = static_cast<uint32_t>(s.leaf_block);
  return s.block_cost * static_cast<float>((n + block - 1) / block);
}

// The best SAH split of `range` (kind None when no axis has centre extent).
// Bins in parallel (TBB) when the range is large.
Split find_sah_split(const PrimRef* refs, const Range& range, const BuildSettings& settings);

// Partitions `range` by `split` (Sah or Median); both sides are non-empty.
std::pair<Range, Range> apply_split(PrimRef* refs, const Range& range, const Split& split,
                                    const BuildSettings& settings);

// Bounds of refs[begin, end).
Range make_range(const PrimRef* refs, uint32_t begin, uint32_t end);

}  // namespace pt::bvh::detail
