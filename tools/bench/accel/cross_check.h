// Traces the same rays through two backends and classifies every ray:
//  - agree:      both miss, or both hit the same primitive (of the same
//                instance) at distances within the tolerance (relative to
//                max(t, |origin| / |dir|, 1e-3));
//  - tie:        both hit at distances within the tolerance but different
//                primitives or placements (coincident or touching surfaces: exact ties,
//                documented, not disagreements);
//  - hit_miss:   one hits, the other does not;
//  - distance:   both hit, at distances differing beyond the tolerance.
// Shadow rays compare occluded() answers (agree or hit_miss only).
// An image marks the pixels with a disagreement (see disagreement_image).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "core/image.h"
#include "ray_sets.h"

namespace pt {
class WorkerPool;
}

namespace pt::bench {

enum class Verdict : uint8_t { Agree, Tie, HitMiss, Distance };

struct CrossCheckCounts {
  std::size_t rays = 0, agree = 0, tie = 0, hit_miss = 0, distance = 0;
  std::size_t disagreements() const { return hit_miss + distance; }
};

struct CrossCheck {
  float tolerance = 1e-4f;
  CrossCheckCounts camera, shadow, diffuse;
  // Per pixel, the worst verdict over its rays (HitMiss > Distance > Tie > Agree).
  std::vector<Verdict> pixel;
  int width = 0, height = 0;
  std::size_t disagreements() const {
    return camera.disagreements() + shadow.disagreements() + diffuse.disagreements();
  }
};

CrossCheck cross_check(const Accelerator& a, const Accelerator& b, const RaySets& rays, WorkerPool& pool,
                       float tolerance = 1e-4f);

// The camera view in grey (backend a's camera hits, shaded by the angle to
// the geometric normal) with disagreeing pixels in colour: red = hit versus
// miss, yellow = distance, blue = tie.
Image disagreement_image(const CrossCheck& check, const RaySets& rays, const SceneGeometry& geometry,
                         const Accelerator& a, WorkerPool& pool);

}  // namespace pt::bench
