// The ray sets the benchmark times and the cross-check compares, generated
// once per scene (outside any timed region) and traced unchanged through each
// backend:
//  - camera: one ray through the centre of each pixel;
//  - shadow: from each camera ray's hit point to a light (spawn_ray_to), the
//    lights taken in turn pixel by pixel; answered with occluded();
//  - diffuse: from each camera ray's hit point, a cosine-distributed direction
//    about the geometric normal on the side the camera ray came from
//    (spawn_ray): incoherent bounce rays.
// Hit points come from the reference backend given to make_ray_sets.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "bench_scene.h"

namespace pt {
class WorkerPool;
}

namespace pt::bench {

struct RaySet {
  std::vector<Ray> rays;
  std::vector<uint32_t> pixel;  // the pixel (y * width + x) each ray belongs to
};

struct RaySets {
  int width = 0, height = 0;
  RaySet camera, shadow, diffuse;
};

RaySets make_ray_sets(const BenchScene& scene, const Accelerator& reference, WorkerPool& pool, uint64_t seed = 1);

}  // namespace pt::bench
