// Embree user geometry for the analytic shapes (spheres, quads, cylinders,
// discs, polygons, cones): the bounds, intersect and occluded callbacks call
// the src/geometry routines directly (one template instance per shape type: no
// virtual calls, no allocation per ray). Meshes are Embree's own triangle
// geometry (triangle_geometry.h).
#pragma once

#include <embree3/rtcore.h>

#include "accel/cutout.h"
#include "geometry/shapes.h"

namespace pt::embree {

// What the callbacks of a geometry that may be cut out read (its user data):
// the shape, the scene's cutout test, and the geomID of instance 0 (hits
// through an instance carry instance_base + its id).
struct CutoutGeometry {
  const void* shape = nullptr;  // the alternative held by the Shape (user geometry only)
  const CutoutTest* test = nullptr;
  uint32_t instance_base = 0;

  uint32_t instance(unsigned inst_id) const {
    return inst_id == RTC_INVALID_GEOMETRY_ID ? kNoInstance : inst_id - instance_base;
  }
};

// The filter function of Embree's own triangles (every mesh: triangle_geometry.h) that
// may be cut out, for intersection and occlusion queries alike: drops the
// candidates the cutout test does not keep. Its user data is a CutoutGeometry.
void cutout_filter(const RTCFilterFunctionNArguments* args);

// A new, uncommitted user geometry (primitive_count(shape) primitives) whose
// user data points at the alternative held by `shape` (which must outlive it);
// null for a TriangleMesh (not user geometry) or on an Embree error. The caller
// sets what every geometry gets (the mask), commits, attaches and releases it.
// With `cutout` (which must outlive it too, its `shape` set to that
// alternative), its callbacks skip the hits the cutout test drops.
RTCGeometry new_user_geometry(RTCDevice device, const Shape& shape, const CutoutGeometry* cutout = nullptr);

}  // namespace pt::embree
