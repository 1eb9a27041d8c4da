// A triangle mesh as Embree's own triangle geometry (RTC_GEOMETRY_TYPE_TRIANGLE,
// intersected by Embree's SIMD test; with RTC_SCENE_FLAG_ROBUST that is its
// Plücker test). primID == triangle index, and Embree's hit (u, v) are the
// barycentrics of p1 and p2, our PrimHit::uv for a triangle.
//
// Buffers are shared with the mesh where its layout allows (no copy):
//  - vertices: Embree reads 16 bytes for the last FLOAT3 vertex, so the
//    positions are shared when their vector has a spare element of capacity
//    (the mesh readers reserve one); otherwise Embree gets its own copy;
//  - indices: shared, unless the mesh has exactly degenerate triangles
//    (degenerate_triangle: zero cross product). Those must never be hit (a
//    zero-area hit has no normal) and Embree's test does not refuse them all,
//    so Embree gets a copy of the indices in which each degenerate triangle
//    refers to vertex UINT32_MAX: Embree leaves primitives with an index out of
//    range out of its BVH, and every other triangle keeps its index (primID).
#pragma once

#include <embree3/rtcore.h>

#include <cstddef>

#include "geometry/shapes/mesh.h"

namespace pt::embree {

struct TriangleBuffers {
  bool vertices_shared = false;
  bool indices_shared = false;
  std::size_t degenerate = 0;  // triangles left out of Embree's BVH
};

// A new, uncommitted geometry over `mesh` (which must outlive it; null on an
// Embree error). Call it inside the worker pool's arena: the search for
// degenerate triangles and the copy of the indices are TBB-parallel. The caller sets what every geometry gets (mask, and a filter
// function where one is needed), commits, attaches and releases it.
RTCGeometry new_triangle_geometry(RTCDevice device, const TriangleMesh& mesh, TriangleBuffers& buffers);

}  // namespace pt::embree
