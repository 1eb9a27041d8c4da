// A perfect (tinted) mirror: all light arriving from the mirror direction of
// wo is reflected, times `tint`. A delta lobe: it has no density to evaluate.
// Local shading frame: wo.z > 0.
#pragma once

#include "render/materials/bsdf_sample.h"

namespace pt {

struct MirrorBrdf {
  RGB tint{1, 1, 1};

  bool sample(Vec3f wo, BsdfSample& s) const {
    if (!(wo.z > 0.0f)) return false;
    s.wi = {-wo.x, -wo.y, wo.z};
    s.weight = tint;
    s.pdf = 1.0f;
    s.delta = true;
    return true;
  }
};

}  // namespace pt
