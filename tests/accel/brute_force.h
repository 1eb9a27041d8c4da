// Test-only reference: the nearest hit by looping over every primitive with
// the src/geometry routines, for comparison with the acceleration backends.
#pragma once

#include <variant>

#include "accel/accelerator.h"
#include "geometry/shapes.h"

namespace pt::test {

inline bool brute_intersect(const SceneGeometry& g, const Ray& ray, Hit& hit) {
  Ray r = ray;
  bool found = false;
  auto record = [&](const PrimHit& h, std::size_t shape, uint32_t prim) {
    hit.t = h.t;
    hit.uv = h.uv;
    hit.shape = static_cast<uint32_t>(shape);
    hit.prim = prim;
    r.tmax = h.t;
    found = true;
  };
  for (std::size_t i = 0; i < g.shapes.size(); ++i) {
    PrimHit h;
    if (const auto* m = std::get_if<TriangleMesh>(&g.shapes[i])) {
      for (uint32_t k = 0; k < m->triangle_count(); ++k) {
        if (intersect(*m, k, r, h)) record(h, i, k);
      }
    } else if (std::visit(
                   [&](const auto& s) {
                     if constexpr (std::is_same_v<std::decay_t<decltype(s)>, TriangleMesh>) {
                       return false;
                     } else {
                       return intersect_primitive(s, 0, r, h);  // whole shapes, and the infinite plane
                     }
                   },
                   g.shapes[i])) {
      record(h, i, 0);
    }
  }
  return found;
}

inline bool brute_occluded(const SceneGeometry& g, const Ray& ray) {
  Hit hit;
  return brute_intersect(g, ray, hit);
}

}  // namespace pt::test
