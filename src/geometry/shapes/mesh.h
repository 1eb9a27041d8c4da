// The triangle mesh: its data and the routines that follow from it (in
// geometry/triangle.cpp). One primitive per triangle: the per-primitive
// routines take the triangle index.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/shape_base.h"

namespace pt {

struct TriangleMesh {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<Vec3f> normals;     // empty or one per vertex
  std::vector<Vec2f> uvs;         // empty or one per vertex
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Watertight ray/triangle test (Woop, Benthin, Wald 2013). uv = barycentrics of p1, p2.
// Never hits an exactly degenerate triangle (degenerate_triangle below).
bool intersect_triangle(Vec3f p0, Vec3f p1, Vec3f p2, const Ray& ray, PrimHit& hit);

// Zero area in float (repeated or exactly collinear corners): never hit by any
// backend (the Embree backend leaves such triangles out of Embree's buffers).
inline bool degenerate_triangle(Vec3f p0, Vec3f p1, Vec3f p2) { return cross(p1 - p0, p2 - p0) == Vec3f(0.0f); }
inline bool degenerate_triangle(const TriangleMesh& m, std::size_t tri) {
  const uint32_t* idx = &m.indices[3 * tri];
  return degenerate_triangle(m.positions[idx[0]], m.positions[idx[1]], m.positions[idx[2]]);
}

// Zero area as the validation rule of a file's "triangle" measures it (check
// below warns about it): the length of the corners' cross product is 0 in float.
inline bool zero_area_triangle(Vec3f p0, Vec3f p1, Vec3f p2) { return length(cross(p1 - p0, p2 - p0)) == 0.0f; }

Bounds3f bounds(const TriangleMesh& m);                 // every referenced vertex
Bounds3f bounds(const TriangleMesh& m, uint32_t tri);   // one triangle
bool intersect(const TriangleMesh& m, uint32_t tri, const Ray& ray, PrimHit& hit);
SurfaceGeometry surface(const TriangleMesh& m, uint32_t tri, const Ray& ray, const PrimHit& hit);
// From the triangle's texture coordinates (its barycentrics (b1, b2) without
// them, or where they are degenerate): constant over the triangle.
UvDerivatives uv_derivatives(const TriangleMesh& m, uint32_t tri, const SurfaceGeometry& sg);
inline uint32_t primitive_count(const TriangleMesh& m) { return static_cast<uint32_t>(m.triangle_count()); }

// A single triangle (a scene file's "triangle"): a one-triangle mesh.
inline TriangleMesh make_triangle(Vec3f v0, Vec3f v1, Vec3f v2) {
  TriangleMesh m;
  m.positions = {v0, v1, v2};
  m.indices = {0, 1, 2};
  return m;
}

// Validation: index count a multiple of 3, indices in range, finite positions,
// one normal and uv per vertex (or none); problems on the field "file" (the
// mesh file, if any). A file's "triangle" (checker type "triangle") only warns
// when it has zero area.
void check(const TriangleMesh& m, ShapeChecker& c);

// Sampling by area: a triangle in proportion to its area.
TriangleAreaSampler make_area_sampler(const TriangleMesh& m);

}  // namespace pt
