#include "accel/bvh/binning.h"

#include <emmintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace pt::bvh::detail {

namespace {

// Ranges at least this large are binned by parallel tasks.
constexpr uint32_t kParallelBinning = 32768;

// A box in SSE registers (lane 3 unused).
struct Box4 {
  __m128 lo = _mm_set1_ps(std::numeric_limits<float>::infinity());
  __m128 hi = _mm_set1_ps(-std::numeric_limits<float>::infinity());

  void extend(__m128 l, __m128 h) {
    lo = _mm_min_ps(lo, l);
    hi = _mm_max_ps(hi, h);
  }
  void extend(const Box4& b) { extend(b.lo, b.hi); }
  // Surface area; only ever asked of non-empty boxes.
  float area() const {
    alignas(16) float d[4];
    _mm_store_ps(d, _mm_sub_ps(hi, lo));
    return 2.0f * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
  }
  Bounds3f bounds() const {
    alignas(16) float l[4], h[4];
    _mm_store_ps(l, lo);
    _mm_store_ps(h, hi);
    return Bounds3f{{l[0], l[1], l[2]}, {h[0], h[1], h[2]}};
  }
};

inline __m128 load_lo(const PrimRef& r) { return _mm_load_ps(&r.lo.x); }
inline __m128 load_hi(const PrimRef& r) { return _mm_load_ps(&r.hi.x); }
inline __m128 centre4(const PrimRef& r) {
  const __m128 half = _mm_set1_ps(0.5f);
  return _mm_add_ps(_mm_mul_ps(load_lo(r), half), _mm_mul_ps(load_hi(r), half));
}

// Bins for a range of n primitives: the setting, but no more than n / 2 (at
// least 4): a few primitives gain nothing from a fine sweep, which would cost
// more than binning them.
int bin_count(const BuildSettings& s, uint32_t n) {
  return std::clamp(std::min(s.bins, static_cast<int>(std::min<uint32_t>(n / 2, kMaxBins))), 4, kMaxBins);
}

// Maps centres to bins on all three axes at once.
struct BinMap {
  int bins = 0;
  __m128 lo, scale, last;
  bool usable[3] = {};

  BinMap(const Bounds3f& cbox, int bin_count) : bins(bin_count) {
    alignas(16) float s[4] = {0, 0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      const float extent = cbox.hi[a] - cbox.lo[a];
      const float k = extent > 0.0f ? static_cast<float>(bins) / extent : 0.0f;
      usable[a] = extent > 0.0f && std::isfinite(k);
      s[a] = usable[a] ? k : 0.0f;
    }
    lo = _mm_setr_ps(cbox.lo.x, cbox.lo.y, cbox.lo.z, 0.0f);
    scale = _mm_load_ps(s);
    last = _mm_set1_ps(static_cast<float>(bins - 1));
  }
  // Bin of the centre on each axis, clamped to [0, bins - 1]; NaN gives 0
  // (max returns its second operand, 0, for a NaN first operand).
  __m128i bin(__m128 c) const {
    const __m128 f = _mm_mul_ps(_mm_sub_ps(c, lo), scale);
    return _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), last));
  }
  // Whether the centre's bin on `axis` is below `plane` (1 <= plane < bins):
  // the same arithmetic as bin(), compared before truncation. (Centres are
  // finite: the geometry was validated.)
  bool below(__m128 c, int axis, int plane) const {
    alignas(16) float f[4];
    _mm_store_ps(f, _mm_mul_ps(_mm_sub_ps(c, lo), scale));
    return f[axis] < static_cast<float>(plane);
  }
};

struct Bins {
  Box4 box[3][kMaxBins];
  uint32_t count[3][kMaxBins] = {};

  void add(const PrimRef& r, const BinMap& map) {
    alignas(16) int32_t b[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(b), map.bin(centre4(r)));
    const __m128 lo = load_lo(r), hi = load_hi(r);
    for (int a = 0; a < 3; ++a) {
      box[a][b[a]].extend(lo, hi);
      ++count[a][b[a]];
    }
  }
  void merge(const Bins& o, int bins) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < bins; ++b) {
        box[a][b].extend(o.box[a][b]);
        count[a][b] += o.count[a][b];
      }
    }
  }
};

// Box and centre bounds accumulated together.
struct RangeBounds {
  Box4 box, cbox;
  void add(const PrimRef& r) {
    const __m128 c = centre4(r);
    box.extend(load_lo(r), load_hi(r));
    cbox.extend(c, c);
  }
  Range to_range(uint32_t begin, uint32_t end) const { return Range{begin, end, box.bounds(), cbox.bounds()}; }
};

}  // namespace

Vec3f centre_of(const PrimRef& r) {
  alignas(16) float c[4];
  _mm_store_ps(c, centre4(r));
  return {c[0], c[1], c[2]};
}

Range make_range(const PrimRef* refs, uint32_t begin, uint32_t end) {
  RangeBounds b;
  for (uint32_t i = begin; i < end; ++i) b.add(refs[i]);
  return b.to_range(begin, end);
}

Split find_sah_split(const PrimRef* refs, const Range& range, const BuildSettings& settings) {
  const int bins = bin_count(settings, range.size());
  const BinMap map(range.cbox, bins);
  Split best;
  if (!map.usable[0] && !map.usable[1] && !map.usable[2]) return best;

  Bins binned;
  if (range.size() >= kParallelBinning) {
    // Any grouping gives the same bins: min, max and integer sums are exact.
    binned = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(range.begin, range.end, 8192), Bins(),
        [&](const tbb::blocked_range<uint32_t>& r, Bins acc) {
          for (uint32_t i = r.begin(); i != r.end(); ++i) acc.add(refs[i], map);
          return acc;
        },
        [bins](Bins a, const Bins& b) {
          a.merge(b, bins);
          return a;
        });
  } else {
    for (uint32_t i = range.begin; i < range.end; ++i) binned.add(refs[i], map);
  }

  float best_cost = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (!map.usable[a]) continue;
    // Right side of plane p holds bins [p, bins).
    float right_area[kMaxBins];
    uint32_t right_count[kMaxBins];
    Box4 acc;
    uint32_t n = 0;
    for (int b = bins - 1; b >= 1; --b) {
      acc.extend(binned.box[a][b]);
      n += binned.count[a][b];
      right_area[b] = acc.area();
      right_count[b] = n;
    }
    acc = Box4();
    n = 0;
    for (int p = 1; p < bins; ++p) {
      acc.extend(binned.box[a][p - 1]);
      n += binned.count[a][p - 1];
      if (n == 0 || right_count[p] == 0) continue;
      const float cost = acc.area() * leaf_cost(n, settings) + right_area[p] * leaf_cost(right_count[p], settings);
      if (cost < best_cost) {  // strict: ties keep the lowest axis and plane
        best_cost = cost;
        best = Split{SplitKind::Sah, a, p, cost};
      }
    }
  }
  return best;
}

std::pair<Range, Range> apply_split(PrimRef* refs, const Range& range, const Split& split,
                                    const BuildSettings& settings) {
  if (split.kind == SplitKind::Sah) {
    const BinMap map(range.cbox, bin_count(settings, range.size()));
    auto goes_left = [&](const PrimRef& r) { return map.below(centre4(r), split.axis, split.plane); };
    RangeBounds left, right;
    uint32_t i = range.begin, j = range.end;
    for (;;) {
      while (i < j && goes_left(refs[i])) left.add(refs[i++]);
      while (i < j && !goes_left(refs[j - 1])) right.add(refs[--j]);
      if (i >= j) break;
      std::swap(refs[i], refs[j - 1]);
    }
    return {left.to_range(range.begin, i), right.to_range(i, range.end)};
  }
  // Object median along the axis of largest centre extent; when every centre
  // coincides, the halves of the range as it is.
  const uint32_t mid = range.begin + range.size() / 2;
  const Vec3f extent = range.cbox.extent();
  const int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
  if (extent[axis] > 0.0f) {
    std::nth_element(refs + range.begin, refs + mid, refs + range.end, [axis](const PrimRef& a, const PrimRef& b) {
      const float ca = centre_of(a)[axis], cb = centre_of(b)[axis];
      return ca < cb || (ca == cb && a.id < b.id);
    });
  }
  return {make_range(refs, range.begin, mid), make_range(refs, mid, range.end)};
}

}  // namespace pt::bvh::detail
