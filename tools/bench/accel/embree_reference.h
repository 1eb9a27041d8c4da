// The benchmark's yardstick: Embree with its own triangle geometry
// (RTC_GEOMETRY_TYPE_TRIANGLE, Plücker test) for meshes, and the user geometry
// of the Embree backend (src/accel/embree) for analytic shapes; scene flags
// ROBUST, build quality HIGH. Whatever --accel=embree does with meshes, this
// is "Embree's throughput" in the goals. Not a renderer backend: its
// triangle hits do not come from our watertight routine.
#pragma once

#include <memory>

#include "accel/accelerator.h"

namespace pt::bench {

// Returns nullptr and reports to `diag` on failure.
std::unique_ptr<Accelerator> build_embree_reference(const SceneGeometry& geometry, WorkerPool& pool,
                                                    Diagnostics& diag);

}  // namespace pt::bench
