// Alpha cutouts as the backends see them (docs/textures.md, "Alpha cutouts"):
// which shapes may have holes, and the test that decides, for one candidate
// hit, whether the surface is there. Both backends call the same test on every
// candidate of a shape that may be cut out, for nearest-hit and any-hit
// (shadow) queries alike (Embree: filter functions on its own triangles, the
// test in the user geometry's callbacks; our BVH: the leaf routines of its
// cutout traversal), so the two agree hit for hit. A scene without cutouts
// passes no CutoutTest, and neither backend then runs any of this.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "geometry/shapes.h"

namespace pt {

struct CutoutTest {
  // Per object id: whether the shape's own material has a cutout.
  std::vector<uint8_t> shape;
  // Per instance: -1 if it keeps its shapes' own materials, else whether its
  // material (which replaces theirs) has a cutout.
  std::vector<int8_t> instance;
  // Whether the surface is there at a candidate hit of primitive `prim` of
  // object `object` placed by `inst` (kNoInstance: placed directly): `ray` is
  // in the shape's own space (an instance's object space), `hit` as the
  // shape's intersection routine found it. Thread-safe; called only where
  // may_cut(object, inst).
  using Keeps = bool (*)(const void* context, const Ray& ray, uint32_t object, uint32_t prim, const PrimHit& hit,
                         uint32_t inst);
  Keeps keeps = nullptr;
  const void* context = nullptr;

  bool may_cut(uint32_t object, uint32_t inst) const {
    if (inst != kNoInstance && instance[inst] >= 0) return instance[inst] != 0;
    return shape[object] != 0;
  }
  // Whether any placement of the object may be cut out: its own material, or
  // an instance's that replaces it.
  bool may_cut_anywhere(uint32_t object) const {
    if (shape[object] != 0) return true;
    for (int8_t i : instance) {
      if (i > 0) return true;
    }
    return false;
  }
  bool keeps_hit(const Ray& ray, uint32_t object, uint32_t prim, const PrimHit& hit, uint32_t inst) const {
    return !may_cut(object, inst) || keeps(context, ray, object, prim, hit, inst);
  }
};

// The nearest hit of primitive `prim` of `shape` in (ray.tmin, ray.tmax) that
// the cutout test keeps: past a hit it drops, the next one along the ray (a
// convex shape has at most two, a triangle one; bounded all the same).
template <class S>
bool intersect_kept(const S& shape, uint32_t prim, Ray ray, PrimHit& hit, const CutoutTest& cutouts, uint32_t object,
                    uint32_t inst) {
  for (int k = 0; k < 4; ++k) {
    if (!intersect_primitive(shape, prim, ray, hit)) return false;
    if (cutouts.keeps_hit(ray, object, prim, hit, inst)) return true;
    ray.tmin = hit.t;
  }
  return false;
}

}  // namespace pt
