// Test-only reference: the nearest hit by looping over every primitive with
// the src/geometry routines, for comparison with the acceleration backends.
#pragma once

#include <variant>
#include <vector>

#include "accel/accelerator.h"
#include "geometry/shapes.h"

namespace pt::test {

inline bool brute_intersect(const SceneGeometry& g, const Ray& ray, Hit& hit) {
  Ray r = ray;
  bool found = false;
  // Every shape of `ids` (all shapes placed directly, or one prototype's)
  // against `local` (the ray in their space, same t), which shares r.tmax.
  auto test_shapes = [&](const std::vector<uint32_t>& ids, uint32_t instance, const Transform* t) {
    for (uint32_t i : ids) {
      Ray local = t ? t->to_object(r) : r;
      auto record = [&](const PrimHit& h, uint32_t prim) {
        hit.t = h.t;
        hit.uv = h.uv;
        hit.shape = i;
        hit.prim = prim;
        hit.instance = instance;
        r.tmax = local.tmax = h.t;
        found = true;
      };
      PrimHit h;
      if (const auto* m = std::get_if<TriangleMesh>(&g.shapes[i])) {
        for (uint32_t k = 0; k < m->triangle_count(); ++k) {
          if (intersect(*m, k, local, h)) record(h, k);
        }
      } else if (std::visit(
                     [&](const auto& s) {
                       if constexpr (std::is_same_v<std::decay_t<decltype(s)>, TriangleMesh>) {
                         return false;
                       } else {
                         return intersect_primitive(s, 0, local, h);  // whole shapes, and the infinite plane
                       }
                     },
                     g.shapes[i])) {
        record(h, 0);
      }
    }
  };
  const std::vector<bool> direct = placed_directly(g);
  std::vector<uint32_t> top;
  for (uint32_t i = 0; i < g.shapes.size(); ++i) {
    if (direct[i]) top.push_back(i);
  }
  test_shapes(top, kNoInstance, nullptr);
  for (uint32_t k = 0; k < g.instances.size(); ++k) {
    test_shapes(g.prototypes[g.instances[k].prototype], k, &g.instances[k].transform);
  }
  return found;
}

inline bool brute_occluded(const SceneGeometry& g, const Ray& ray) {
  Hit hit;
  return brute_intersect(g, ray, hit);
}

}  // namespace pt::test
