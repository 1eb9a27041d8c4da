// The Embree 3 backend behind build_accelerator(AccelKind::Embree, ...).
#pragma once

#include <memory>

#include "accel/accelerator.h"
#include "accel/cutout.h"

namespace pt::embree {

// How triangle meshes reach Embree.
enum class MeshTriangles {
  // User geometry, one primitive per triangle, calling our watertight routine
  // (the renderer's --accel=embree; docs/geometry.md says why).
  Watertight,
  // Embree's own triangle geometry and intersector (RTC_GEOMETRY_TYPE_TRIANGLE):
  // faster, but not watertight at vertices. The accelerator benchmark's yardstick.
  Native,
};

// `cutouts` (null: none; it must outlive the accelerator): see accel/cutout.h.
std::unique_ptr<Accelerator> build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                                   MeshTriangles meshes = MeshTriangles::Watertight,
                                   const CutoutTest* cutouts = nullptr);

}  // namespace pt::embree
