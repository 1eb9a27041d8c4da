// The Embree 3 backend behind build_accelerator(AccelKind::Embree, ...):
// meshes as Embree's own triangle geometry, the analytic shapes as user
// geometry calling src/geometry (docs/geometry.md, "Embree backend").
#pragma once

#include <memory>

#include "accel/accelerator.h"
#include "accel/cutout.h"

namespace pt::embree {

// `cutouts` (null: none; it must outlive the accelerator): see accel/cutout.h.
// Meshes become Embree's own triangle geometry, analytic shapes user geometry
// (docs/geometry.md).
std::unique_ptr<Accelerator> build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                                   const CutoutTest* cutouts = nullptr);

}  // namespace pt::embree
