// Embree user geometry for the analytic shapes (spheres, quads, cylinders,
// discs, polygons, cones): the bounds, intersect and occluded callbacks call
// the src/geometry routines directly (one template instance per shape type: no
// virtual calls, no allocation per ray). Meshes are Embree's own triangle
// geometry (triangle_geometry.h).
#pragma once

#include <embree3/rtcore.h>

#include "geometry/shapes.h"

namespace pt::embree {

// A new, uncommitted user geometry (primitive_count(shape) primitives) whose
// user data points at the alternative held by `shape` (which must outlive it);
// null for a TriangleMesh (not user geometry) or on an Embree error. The caller
// sets what every geometry gets (mask, filter functions), commits, attaches and
// releases it.
RTCGeometry new_user_geometry(RTCDevice device, const Shape& shape);

}  // namespace pt::embree
