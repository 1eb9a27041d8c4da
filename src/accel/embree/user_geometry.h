// Embree user geometry for every shape: the bounds, intersect and occluded
// callbacks call the src/geometry routines directly (one template instance per
// shape type: no virtual calls, no allocation per ray). A mesh is one
// geometry with one primitive per triangle, intersected by our watertight
// triangle routine (docs/geometry.md says why not Embree's own).
#pragma once

#include <embree3/rtcore.h>

#include "geometry/shapes.h"

namespace pt::embree {

// A committed user geometry (primitive_count(shape) primitives) whose user
// data points at the alternative held by `shape` (which must outlive it). The
// caller attaches and releases it.
RTCGeometry new_user_geometry(RTCDevice device, const Shape& shape);

}  // namespace pt::embree
