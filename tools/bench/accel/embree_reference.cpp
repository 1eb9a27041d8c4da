// The benchmark's yardstick: the Embree backend with Embree's own triangle
// geometry (embree::MeshTriangles::Native); analytic shapes, ray conversion,
// scene flags and validation are the backend's own (see embree_reference.h).
#include "embree_reference.h"

#include "accel/embree/embree_accel.h"

namespace pt::bench {

std::unique_ptr<Accelerator> build_embree_reference(const SceneGeometry& geometry, WorkerPool& pool,
                                                    Diagnostics& diag) {
  return embree::build(geometry, pool, diag, embree::MeshTriangles::Native);
}

}  // namespace pt::bench
