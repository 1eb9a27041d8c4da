// An analytic shape (any shape intersected as a whole: sphere, quad,
// cylinder, ...) in a bottom-level leaf: a typed reference generated from the
// Shape variant's list (geometry/shapes.h), and its object id. Not for the
// kernels (layout.h declares the type only; see there why).
#pragma once

#include <cstdint>

#include "geometry/shapes.h"

namespace pt::bvh {

struct AnalyticPrim {
  ShapeRef shape;   // the shape in SceneGeometry
  uint32_t object;  // its object id
};

}  // namespace pt::bvh
