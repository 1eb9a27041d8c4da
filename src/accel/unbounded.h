// Shapes without bounds (the infinite plane, geometry/shapes/plane.h) are no
// primitive of either backend: an unbounded box must never enter a BVH, and
// SAH costs and Embree's scene box stay those of the bounded shapes. This
// layer, above both backends, tests them itself, so `--accel=embree` and
// `--accel=bvh` agree on them exactly and a plane reaches the horizon.
// A scene without such shapes gets its backend unwrapped (no extra call).
#pragma once

#include <memory>

#include "accel/accelerator.h"

namespace pt {

// `backend` (built over `geometry`, which must outlive the result) with the
// unbounded shapes of `geometry` tested above it; `backend` itself if there
// are none (or if it is null). A plane that may be cut out goes through
// `cutouts` (null: none) as the backends' shapes do.
std::unique_ptr<Accelerator> with_unbounded_shapes(std::unique_ptr<Accelerator> backend,
                                                   const SceneGeometry& geometry,
                                                   const CutoutTest* cutouts = nullptr);

}  // namespace pt
