// Shapes placed through transforms (SceneGeometry's prototypes and instances).
#include <cmath>
#include <utility>
#include <variant>

#include "geometry/shapes.h"

namespace pt {

std::vector<bool> placed_directly(const SceneGeometry& g) {
  std::vector<bool> direct(g.shapes.size(), true);
  for (const std::vector<uint32_t>& p : g.prototypes) {
    for (uint32_t s : p) {
      if (s < direct.size()) direct[s] = false;
    }
  }
  return direct;
}

Bounds3f world_bounds(const SceneGeometry& g) {
  Bounds3f out;
  const std::vector<bool> direct = placed_directly(g);
  for (std::size_t i = 0; i < g.shapes.size(); ++i) {
    if (direct[i]) out.extend(bounds(g.shapes[i]));
  }
  std::vector<Bounds3f> proto(g.prototypes.size());
  for (std::size_t p = 0; p < g.prototypes.size(); ++p) {
    for (uint32_t s : g.prototypes[p]) proto[p].extend(bounds(g.shapes[s]));
  }
  for (const Instance& inst : g.instances) out.extend(inst.transform.bounds(proto[inst.prototype]));
  return out;
}

namespace {

Vec3f unit_normal(const Transform& t, Vec3f n) {
  const Vec3f w = t.normal(n);
  // Scaled before normalising, so a tiny normal does not flush to zero.
  const float m = max_component(abs(w));
  return m > 0.0f && std::isfinite(m) ? normalize(w / m) : n;
}

}  // namespace

SurfaceGeometry to_world(const SurfaceGeometry& s, const Transform& t) {
  SurfaceGeometry w = s;
  w.p = t.point(s.p);
  // The rounding of the transform to world space, and of the way back that
  // every ray leaving the point takes before it meets the shape again.
  w.p_error = t.point_error(s.p, s.p_error) + t.inverse_error(w.p);
  w.ng = unit_normal(t, s.ng);
  w.ns = unit_normal(t, s.ns);
  return w;
}

}  // namespace pt
