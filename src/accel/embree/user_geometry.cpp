#include "accel/embree/user_geometry.h"

#include <type_traits>
#include <variant>

#include "geometry/float_util.h"

namespace pt::embree {

namespace {

template <class S>
void bounds_callback(const RTCBoundsFunctionArguments* args) {
  const Bounds3f b = primitive_bounds(*static_cast<const S*>(args->geometryUserPtr), args->primID);
  RTCBounds* o = args->bounds_o;
  o->lower_x = b.lo.x;
  o->lower_y = b.lo.y;
  o->lower_z = b.lo.z;
  o->upper_x = b.hi.x;
  o->upper_y = b.hi.y;
  o->upper_z = b.hi.z;
}

// Embree's interval is closed, [tnear, tfar]; ours is open: widen by one ulp
// each side, exactly undoing the narrowing in embree_accel.cpp.
inline Ray ray_from(RTCRayN* rays, unsigned n, unsigned i) {
  return Ray{{RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i)},
             {RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i)},
             fp::next_float_down(RTCRayN_tnear(rays, n, i)),
             fp::next_float_up(RTCRayN_tfar(rays, n, i))};
}

// rtcIntersect1 calls these with N == 1; the loop also serves packets.
template <class S>
void intersect_callback(const RTCIntersectFunctionNArguments* args) {
  const S& shape = *static_cast<const S*>(args->geometryUserPtr);
  const unsigned n = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    PrimHit hit;
    if (!intersect_primitive(shape, args->primID, ray_from(rays, n, i), hit)) continue;
    RTCRayN_tfar(rays, n, i) = hit.t;
    RTCHitN_Ng_x(hits, n, i) = 0.0f;  // unused by the renderer: surface() computes normals
    RTCHitN_Ng_y(hits, n, i) = 0.0f;
    RTCHitN_Ng_z(hits, n, i) = 0.0f;
    RTCHitN_u(hits, n, i) = hit.uv.x;
    RTCHitN_v(hits, n, i) = hit.uv.y;
    RTCHitN_primID(hits, n, i) = args->primID;
    RTCHitN_geomID(hits, n, i) = args->geomID;
    RTCHitN_instID(hits, n, i, 0) = args->context->instID[0];
  }
}

template <class S>
void occluded_callback(const RTCOccludedFunctionNArguments* args) {
  const S& shape = *static_cast<const S*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    PrimHit hit;
    if (intersect_primitive(shape, args->primID, ray_from(args->ray, n, i), hit)) {
      RTCRayN_tfar(args->ray, n, i) = -kInfinity;
    }
  }
}

template <class S>
RTCGeometry make(RTCDevice device, const S& shape) {
  if constexpr (std::is_same_v<S, TriangleMesh>) return nullptr;  // triangle_geometry.h
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  if (geom == nullptr) return nullptr;
  rtcSetGeometryUserPrimitiveCount(geom, primitive_count(shape));
  rtcSetGeometryUserData(geom, const_cast<S*>(&shape));  // read-only in the callbacks
  rtcSetGeometryBoundsFunction(geom, &bounds_callback<S>, nullptr);
  rtcSetGeometryIntersectFunction(geom, &intersect_callback<S>);
  rtcSetGeometryOccludedFunction(geom, &occluded_callback<S>);
  return geom;
}

}  // namespace

RTCGeometry new_user_geometry(RTCDevice device, const Shape& shape) {
  return std::visit([&](const auto& s) { return make(device, s); }, shape);
}

}  // namespace pt::embree
