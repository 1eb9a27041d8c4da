// Embree user geometry for the analytic shapes: the bounds, intersect and
// occluded callbacks call the src/geometry routines directly (one template
// instance per shape type: no virtual calls, no allocation per ray).
#pragma once

#include <embree3/rtcore.h>

#include "geometry/shapes.h"

namespace pt::embree {

// A committed one-primitive user geometry whose user data points at `shape`
// (which must outlive it). The caller attaches and releases it.
RTCGeometry new_user_geometry(RTCDevice device, const Sphere& shape);
RTCGeometry new_user_geometry(RTCDevice device, const Quad& shape);
RTCGeometry new_user_geometry(RTCDevice device, const Cylinder& shape);

}  // namespace pt::embree
