// Dispatch over the Shape variant (not on any per-ray path: backends call the
// concrete routines directly).
#include <type_traits>
#include <variant>

#include "geometry/float_util.h"
#include "geometry/shapes.h"

namespace pt {

namespace {

Bounds3f mesh_bounds(const TriangleMesh& m) {
  Bounds3f b;
  const std::size_t n = m.positions.size();
  for (uint32_t idx : m.indices) {
    if (idx < n) b.extend(m.positions[idx]);
  }
  return fp::pad(b);
}

}  // namespace

Bounds3f bounds(const Shape& s) {
  return std::visit(
      [](const auto& shape) -> Bounds3f {
        if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, TriangleMesh>) {
          return mesh_bounds(shape);
        } else {
          return bounds(shape);
        }
      },
      s);
}

SurfaceGeometry surface(const Shape& s, uint32_t prim, const Ray& ray, const PrimHit& hit) {
  return std::visit(
      [&](const auto& shape) -> SurfaceGeometry {
        if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, TriangleMesh>) {
          return surface(shape, prim, ray, hit);
        } else {
          return surface(shape, ray, hit);
        }
      },
      s);
}

}  // namespace pt
