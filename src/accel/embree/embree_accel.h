// The Embree 3 backend behind build_accelerator(AccelKind::Embree, ...):
// meshes as Embree's own triangle geometry, the analytic shapes as user
// geometry calling src/geometry (docs/geometry.md, "Embree backend").
#pragma once

#include <memory>

#include "accel/accelerator.h"

namespace pt::embree {

std::unique_ptr<Accelerator> build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag);

}  // namespace pt::embree
