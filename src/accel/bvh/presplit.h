// Pre-splits of large triangles (Karras and Aila, "Fast parallel construction
// of high-quality bounding volume hierarchies", HPG 2013: early split
// clipping; Embree's pre-splits do the same): before the build, a triangle
// whose box is large against the triangle itself is cut along planes of a
// dyadic grid over the mesh's bounds into pieces, each a reference of its own
// with the tight box of its part of the triangle. The builder still sees
// nothing but boxes (build.h); blas.cpp stores a triangle once per leaf
// however many of its pieces the leaf holds.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/bvh/build.h"
#include "geometry/shapes.h"

namespace pt::bvh {

// A triangle's pieces at most.
inline constexpr int kMaxPieces = 16;

// References to the triangles of `mesh`, in triangle order, a triangle's
// pieces together (id = the triangle index). `extra` is the budget of added
// pieces as a fraction of the triangle count, shared out in proportion to each
// triangle's box surface area less twice its area (the area its box wastes);
// 0 gives one reference a triangle, its box bounds(mesh, i). Deterministic:
// the same mesh and budget give the same references for any thread count.
// Call inside WorkerPool::run (parallel over triangles).
std::vector<PrimRef> triangle_refs(const TriangleMesh& mesh, float extra);

}  // namespace pt::bvh
