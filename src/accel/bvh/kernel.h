// The traversal loop shared by the kernels, parameterised on each kernel's
// SIMD routines (an `Ops` object built once per ray):
//   uint32_t ops.intersect_node(const Node8&, float tmax_exit, float dist[8]):
//       mask of the children whose box the ray enters before tmax_exit (the
//       current tmax widened by kExitScale), their entry distances in dist;
//   bool ops.intersect_leaf<kAnyHit>(const TriangleBlock* blocks, uint32_t count, uint32_t object,
//                                    RayQuery&, HitRecord&): the leaf's `count` blocks, nearest hit
//       (the first block's lowest lane on a tie, as if tested in order) or any hit.
//
// Included only by the kernels (kernel_sse2.cpp; kernel_wide.h for AVX2 and
// AVX-512) and the traversal-order test, whose Ops types live in
// anonymous namespaces, so every instantiation has internal linkage and is
// compiled for its file's instruction set; the non-template helpers are
// `static` for the same reason (an inline function with external linkage
// could be emitted as the AVX-512 file's copy and linked into the SSE2
// kernel's callers). Plain code only: no std:: calls
// (see layout.h).
#pragma once

#include <cstdint>

#include "accel/bvh/layout.h"

namespace pt::bvh::kernel {

// Stack entries: at most 7 per level (kMaxDepth = 64 in build.h) plus the root.
inline constexpr int kStackSize = 512;

// Exit distances are widened by 1 + 2 gamma(3) so that rounding in the slab
// test never culls a box the ray touches (Ize, "Robust BVH Ray Traversal",
// JCGT 2013; pbrt-v4). gamma(n) = n u / (1 - n u), u = 2^-24.
inline constexpr float kExitScale = 1.0f + 2.0f * ((3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f));

// The reciprocal direction of axis a for the exit planes, with the widening
// folded in: an exit is (plane - org) * (rdir * kExitScale), the same number
// of roundings as ((plane - org) * rdir) * kExitScale, the same bound (Ize),
// and no multiply after the node's minimum (tmax is widened by the same
// factor, outside the chain that waits for the node).
static inline float exit_rdir(const RayQuery& q, int a) { return q.rdir[a] * kExitScale; }

// A slab distance (plane - org) * r is NaN (0 * inf) only for an origin on a
// plane with an infinite reciprocal (a zero or tiny direction component). The
// kernels take the bounds as two-level trees, max(max(nx, ny), max(nz, tmin))
// and min(min(fx, fy), min(fz, tmax)), for every ray: max/min return their
// second operand when either is NaN, and tmin, tmax are never NaN, so the
// outer operation's second operand is a number and the result is never NaN;
// a NaN inner operand drops at most one real distance with it, so the entry
// can come out smaller and the exit larger, never the other way: a box may be
// visited needlessly, never culled wrongly (docs/bvh.md, session 16; the
// tests' axis-parallel rays on slab planes check it).

struct StackEntry {
  uint32_t ref;
  float dist;  // entry distance of the box; stale once a closer hit is found
};

static inline uint32_t item_count(uint32_t ref) { return ((ref >> kLeafCountShift) & (kMaxLeafItems - 1)) + 1; }

// Any hit, two or more hit children (`first`, and the rest in `mask`):
// farthest entry first: a shadow ray leaves a surface, and what blocks it
// lies towards its end far more often than among the boxes around its origin
// (measured: docs/bvh.md). Pushes all but the farthest, unsorted, and returns
// the farthest. Static: each kernel's file gets its own copy, compiled for its
// instruction set (a shared inline copy could be the AVX2 one; layout.h).
__attribute__((always_inline)) static inline uint32_t push_nearer_entries(const Node8& node, const float* dist,
                                                                           uint32_t first, uint32_t mask,
                                                                           StackEntry* stack, int& sp) {
  uint32_t far = first;
  do {
    const uint32_t i = static_cast<uint32_t>(__builtin_ctz(mask));
    mask &= mask - 1;
    if (dist[i] > dist[far]) {
      stack[sp++] = StackEntry{node.child[far], dist[far]};
      far = i;
    } else {
      stack[sp++] = StackEntry{node.child[i], dist[i]};
    }
  } while (mask != 0);
  return node.child[far];
}

// Depth-first traversal from `root`: nearest child first for the nearest hit,
// farthest child first for any hit. `leaf(ref)` tests a leaf and returns
// whether it found a hit.
template <bool kAnyHit, bool kCount, class Ops, class Leaf>
inline bool traverse(const Ops& ops, const Node8* nodes, uint32_t root, RayQuery& q, Counters* counters,
                     Leaf&& leaf) {
  StackEntry stack[kStackSize];
  int sp = 0;
  uint32_t ref = root;
  bool found = false;
  // The current tmax widened for the exits (kExitScale), kept in a register
  // across the node tests and pops: q.tmax changes only in a leaf that finds
  // a hit.
  float tmax_exit = q.tmax * kExitScale;
  for (;;) {
    if ((ref & kLeafBit) == 0) {
      const Node8& node = nodes[ref];
      if constexpr (kCount) ++counters->nodes;
      alignas(32) float dist[8];
      uint32_t mask = ops.intersect_node(node, tmax_exit, dist);
      if (mask != 0) {
        const uint32_t first = static_cast<uint32_t>(__builtin_ctz(mask));
        mask &= mask - 1;
        if (mask == 0) {
          ref = node.child[first];
          continue;
        }
        if constexpr (kAnyHit) {
          ref = push_nearer_entries(node, dist, first, mask, stack, sp);
          continue;
        } else {
          const uint32_t second = static_cast<uint32_t>(__builtin_ctz(mask));
          if ((mask & (mask - 1)) == 0) {
            // Two hit children (the commonest case after one): the nearer
            // descended into, the other pushed, chosen without a branch (the
            // insertion sort's order: the lower slot on a tie).
            const uint32_t swap = 0u - static_cast<uint32_t>(dist[second] < dist[first]);
            const uint32_t near = first ^ ((first ^ second) & swap);
            const uint32_t far = near ^ first ^ second;
            stack[sp++] = StackEntry{node.child[far], dist[far]};
            ref = node.child[near];
            continue;
          }
          // Insertion sort by entry distance (stable: ties keep slot order).
          StackEntry hits[8];
          int n = 1;
          hits[0] = StackEntry{node.child[first], dist[first]};
          do {
            const uint32_t i = static_cast<uint32_t>(__builtin_ctz(mask));
            mask &= mask - 1;
            const StackEntry e{node.child[i], dist[i]};
            int k = n++;
            while (k > 0 && hits[k - 1].dist > e.dist) {
              hits[k] = hits[k - 1];
              --k;
            }
            hits[k] = e;
          } while (mask != 0);
          for (int k = n - 1; k >= 1; --k) stack[sp++] = hits[k];
          ref = hits[0].ref;
          continue;
        }
      }
    } else if (leaf(ref)) {
      found = true;
      if constexpr (kAnyHit) return true;
      tmax_exit = q.tmax * kExitScale;
    }
    // Pop the next subtree that can still hold a closer hit.
    for (;;) {
      if (sp == 0) return found;
      const StackEntry e = stack[--sp];
      if (kAnyHit || e.dist <= tmax_exit) {
        ref = e.ref;
        break;
      }
    }
  }
}

template <bool kAnyHit, bool kCount, class Ops>
inline bool traverse_blas(const Ops& ops, const BlasData& b, RayQuery& q, HitRecord& hit, Counters* counters) {
  if (b.kind == BlasKind::Triangles) {
    return traverse<kAnyHit, kCount>(ops, b.nodes, b.root, q, counters, [&](uint32_t ref) {
      const TriangleBlock* block = b.blocks + (ref & kLeafIndexMask);
      const uint32_t count = item_count(ref);
      if constexpr (kCount) {
        for (uint32_t i = 0; i < count; ++i) {
          for (uint32_t lane = 0; lane < 4; ++lane) counters->prims += block[i].prim[lane] != kNoPrim ? 1u : 0u;
        }
      }
      return ops.template intersect_leaf<kAnyHit>(block, count, b.object, q, hit);
    });
  }
  return traverse<kAnyHit, kCount>(ops, b.nodes, b.root, q, counters, [&](uint32_t ref) {
    const uint32_t first = ref & kLeafIndexMask;
    const uint32_t count = item_count(ref);
    bool found = false;
    for (uint32_t i = 0; i < count; ++i) {
      if constexpr (kCount) ++counters->prims;
      if (intersect_analytic(b.prims, first + i, q, hit)) {
        found = true;
        if constexpr (kAnyHit) return true;
      }
    }
    return found;
  });
}

// A bottom level some of whose shapes may be cut out: every candidate goes
// through the reference routines and the cutout test (leaf_tests.cpp), lane
// by lane in lane order, as the reference order of the SIMD filter.
template <bool kAnyHit, bool kCount, class Ops>
bool traverse_blas_cutout(const Ops& ops, const BlasData& b, const CutoutTest& cutouts, RayQuery& q, HitRecord& hit,
                          Counters* counters) {
  if (b.kind == BlasKind::Triangles) {
    return traverse<kAnyHit, kCount>(ops, b.nodes, b.root, q, counters, [&](uint32_t ref) {
      const TriangleBlock* block = b.blocks + (ref & kLeafIndexMask);
      const uint32_t count = item_count(ref);
      bool found = false;
      for (uint32_t i = 0; i < count; ++i) {
        for (uint32_t lane = 0; lane < 4; ++lane) {
          if (block[i].prim[lane] == kNoPrim) continue;
          if constexpr (kCount) ++counters->prims;
          if (intersect_block_lane_cutout(block[i], lane, b.object, b.instance, cutouts, q, hit)) {
            found = true;
            if constexpr (kAnyHit) return true;
          }
        }
      }
      return found;
    });
  }
  return traverse<kAnyHit, kCount>(ops, b.nodes, b.root, q, counters, [&](uint32_t ref) {
    const uint32_t first = ref & kLeafIndexMask;
    const uint32_t count = item_count(ref);
    bool found = false;
    for (uint32_t i = 0; i < count; ++i) {
      if constexpr (kCount) ++counters->prims;
      if (intersect_analytic_cutout(b.prims, first + i, b.instance, cutouts, q, hit)) {
        found = true;
        if constexpr (kAnyHit) return true;
      }
    }
    return found;
  });
}

// One bottom level in a scene with cutouts.
template <bool kAnyHit, bool kCount, class Ops>
bool traverse_blas_of(const Ops& ops, const BlasData& b, const CutoutTest* cutouts, RayQuery& q, HitRecord& hit,
                      Counters* counters) {
  if (cutouts != nullptr && b.cutout != 0) return traverse_blas_cutout<kAnyHit, kCount>(ops, b, *cutouts, q, hit, counters);
  return traverse_blas<kAnyHit, kCount>(ops, b, q, hit, counters);
}

// A top-level item placed by an instance: the ray taken to its object space
// (same t parameter), traversed with a kernel state of its own. Out of line,
// so the loop over items placed directly compiles as it did before instancing.
// `cutouts`: the scene's, or null (a scene without any, or an instance of a
// prototype nothing of which may be cut out).
template <bool kAnyHit, bool kCount, class Ops>
__attribute__((noinline)) bool traverse_instance(const BlasData& b, RayQuery& q, HitRecord& hit, Counters* counters,
                                                 const CutoutTest* cutouts = nullptr) {
  RayQuery local;
  if (!to_object_space(*b.transform, q, local)) return false;
  const Ops local_ops(local);
  if (!traverse_blas_of<kAnyHit, kCount>(local_ops, b, cutouts, local, hit, counters)) return false;
  q.tmax = local.tmax;
  hit.instance = b.instance;
  return true;
}

// The top level, its leaf items tested by `item(blas, q, hit)`.
template <bool kAnyHit, bool kCount, class Ops, class Item>
inline bool traverse_top(const Ops& ops, const SceneData& s, RayQuery& q, Counters* counters, Item&& item) {
  return traverse<kAnyHit, kCount>(ops, s.nodes, s.root, q, counters, [&](uint32_t ref) {
    const BlasData* blas = s.blas + (ref & kLeafIndexMask);
    const uint32_t count = item_count(ref);
    bool found = false;
    for (uint32_t i = 0; i < count; ++i) {
      if (item(blas[i])) {
        found = true;
        if constexpr (kAnyHit) return true;
      }
    }
    return found;
  });
}

// A scene with instances: its top level's items are tested for a transform.
// Out of line, so that traverse_scene() below, which every scene without
// instances runs, compiles as it did before instancing (measured: inlined,
// the larger function cost our BVH 4-7% on scenes without any instance).
template <bool kAnyHit, bool kCount, class Ops>
__attribute__((noinline)) bool traverse_instanced_scene(const SceneData& s, RayQuery& q, HitRecord& hit,
                                                        Counters* counters) {
  const Ops ops(q);
  return traverse_top<kAnyHit, kCount>(ops, s, q, counters, [&](const BlasData& b) {
    return b.transform == nullptr ? traverse_blas<kAnyHit, kCount>(ops, b, q, hit, counters)
                                  : traverse_instance<kAnyHit, kCount, Ops>(b, q, hit, counters);
  });
}

// A scene with cutouts (and perhaps instances): bottom levels that may be
// cut out take the cutout leaf routines. Out of line for the same reason.
template <bool kAnyHit, bool kCount, class Ops>
__attribute__((noinline)) bool traverse_cutout_scene(const SceneData& s, RayQuery& q, HitRecord& hit,
                                                     Counters* counters) {
  const Ops ops(q);
  const auto item = [&](const BlasData& b) {
    return b.transform == nullptr ? traverse_blas_of<kAnyHit, kCount>(ops, b, s.cutouts, q, hit, counters)
                                  : traverse_instance<kAnyHit, kCount, Ops>(b, q, hit, counters, s.cutouts);
  };
  if (s.blas_count == 1 && s.blas[0].transform == nullptr) return item(s.blas[0]);  // no top level
  return traverse_top<kAnyHit, kCount>(ops, s, q, counters, item);
}

template <bool kAnyHit, bool kCount, class Ops>
inline bool traverse_scene(const SceneData& s, RayQuery& q, HitRecord& hit, Counters* counters) {
  if (s.blas_count == 0) return false;
  if (s.general != 0) {
    return s.cutouts != nullptr ? traverse_cutout_scene<kAnyHit, kCount, Ops>(s, q, hit, counters)
                                : traverse_instanced_scene<kAnyHit, kCount, Ops>(s, q, hit, counters);
  }
  // A hit recorded by a leaf test has instance kNoInstanceId (HitRecord's default).
  const Ops ops(q);
  if (s.blas_count == 1) return traverse_blas<kAnyHit, kCount>(ops, s.blas[0], q, hit, counters);
  return traverse_top<kAnyHit, kCount>(ops, s, q, counters, [&](const BlasData& b) {
    return traverse_blas<kAnyHit, kCount>(ops, b, q, hit, counters);
  });
}

}  // namespace pt::bvh::kernel
