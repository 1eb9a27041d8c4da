// The shadow-terminator offset (geometry/terminator.h).
#include "geometry/terminator.h"

#include <algorithm>
#include <cstddef>

#include "core/transform.h"
#include "geometry/shapes/mesh.h"

namespace pt {

Vec3f terminator_offset(Vec3f p, const Vec3f v[3], const Vec3f n[3], Vec3f w) {
  // w[i] (p - dot(p - v[i], n[i]) n[i]) summed, less p; only for the corners
  // whose tangent plane p lies below.
  Vec3f offset(0.0f);
  const float weights[3] = {w.x, w.y, w.z};
  for (int i = 0; i < 3; ++i) {
    const float below = dot(p - v[i], n[i]);
    if (below < 0.0f) offset -= n[i] * (weights[i] * below);
  }
  return offset;
}

float terminator_amount(float cos_ns, float cos_ng, float cutoff) {
  if (!(cutoff > 0.0f)) return 0.0f;
  const float a = cos_ns < cutoff ? 2.0f - (cos_ng + cos_ns) / cutoff : 1.0f - cos_ng / cutoff;
  return std::clamp(a, 0.0f, 1.0f);
}

Vec3f terminator_offset(const SmoothSurface& s, bool outer) {
  const TriangleMesh& m = *s.mesh;
  const uint32_t* idx = &m.indices[3 * static_cast<std::size_t>(s.tri)];
  const Vec3f v[3] = {m.positions[idx[0]], m.positions[idx[1]], m.positions[idx[2]]};
  const Vec3f w(1.0f - s.b.x - s.b.y, s.b.x, s.b.y);
  const Vec3f face = cross(v[1] - v[0], v[2] - v[0]);
  // The normals as surface() orients the shading normal: to the face's side,
  // all flipped together where their interpolation points the other way.
  Vec3f n[3];
  for (int i = 0; i < 3; ++i) n[i] = m.normals[idx[i]];
  const Vec3f interpolated = n[0] * w.x + n[1] * w.y + n[2] * w.z;
  const float side = (dot(interpolated, face) < 0.0f) == outer ? -1.0f : 1.0f;
  for (Vec3f& ni : n) {
    const float len = length(ni);
    ni = len > 0.0f ? ni * (side / len) : Vec3f(0.0f);
  }
  const Vec3f p = v[0] * w.x + v[1] * w.y + v[2] * w.z;
  Vec3f offset = terminator_offset(p, v, n, w);
  // A vertex normal more than 90 degrees from the face could pull the point
  // through the triangle's plane: then rays would start on the wrong side.
  if (!(dot(offset, face) * (outer ? 1.0f : -1.0f) >= 0.0f) || !is_finite(offset)) return Vec3f(0.0f);
  return s.to_world != nullptr ? s.to_world->vector(offset) : offset;
}

}  // namespace pt
