#include "accel/embree/user_geometry.h"

#include <type_traits>
#include <variant>

#include "geometry/float_util.h"

namespace pt::embree {

namespace {

// The geometry's user data is the shape, or (kCutout) its CutoutGeometry.
template <class S, bool kCutout>
void bounds_callback(const RTCBoundsFunctionArguments* args) {
  const void* shape = args->geometryUserPtr;
  if constexpr (kCutout) shape = static_cast<const CutoutGeometry*>(shape)->shape;
  const Bounds3f b = primitive_bounds(*static_cast<const S*>(shape), args->primID);
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

void report(const RTCIntersectFunctionNArguments* args, RTCRayN* rays, RTCHitN* hits, unsigned i,
            const PrimHit& hit) {
  const unsigned n = args->N;
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
    if (intersect_primitive(shape, args->primID, ray_from(rays, n, i), hit)) report(args, rays, hits, i, hit);
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

// The callbacks of a shape that may be cut out: the nearest hit the cutout
// test keeps (intersect_kept), in the instance's space as Embree hands the ray.
template <class S>
void cutout_intersect_callback(const RTCIntersectFunctionNArguments* args) {
  const auto& g = *static_cast<const CutoutGeometry*>(args->geometryUserPtr);
  const S& shape = *static_cast<const S*>(g.shape);
  const unsigned n = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  const uint32_t inst = g.instance(args->context->instID[0]);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    PrimHit hit;
    if (intersect_kept(shape, args->primID, ray_from(rays, n, i), hit, *g.test, args->geomID, inst))
      report(args, rays, hits, i, hit);
  }
}

template <class S>
void cutout_occluded_callback(const RTCOccludedFunctionNArguments* args) {
  const auto& g = *static_cast<const CutoutGeometry*>(args->geometryUserPtr);
  const S& shape = *static_cast<const S*>(g.shape);
  const unsigned n = args->N;
  const uint32_t inst = g.instance(args->context->instID[0]);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    PrimHit hit;
    if (intersect_kept(shape, args->primID, ray_from(args->ray, n, i), hit, *g.test, args->geomID, inst)) {
      RTCRayN_tfar(args->ray, n, i) = -kInfinity;
    }
  }
}

template <class S>
RTCGeometry make(RTCDevice device, const S& shape, const CutoutGeometry* cutout) {
  if constexpr (std::is_same_v<S, TriangleMesh>) return nullptr;  // triangle_geometry.h
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  if (geom == nullptr) return nullptr;
  rtcSetGeometryUserPrimitiveCount(geom, primitive_count(shape));
  if (cutout != nullptr) {
    rtcSetGeometryUserData(geom, const_cast<CutoutGeometry*>(cutout));  // read-only in the callbacks
    rtcSetGeometryBoundsFunction(geom, &bounds_callback<S, true>, nullptr);
    rtcSetGeometryIntersectFunction(geom, &cutout_intersect_callback<S>);
    rtcSetGeometryOccludedFunction(geom, &cutout_occluded_callback<S>);
  } else {
    rtcSetGeometryUserData(geom, const_cast<S*>(&shape));  // read-only in the callbacks
    rtcSetGeometryBoundsFunction(geom, &bounds_callback<S, false>, nullptr);
    rtcSetGeometryIntersectFunction(geom, &intersect_callback<S>);
    rtcSetGeometryOccludedFunction(geom, &occluded_callback<S>);
  }
  return geom;
}

}  // namespace

RTCGeometry new_user_geometry(RTCDevice device, const Shape& shape, const CutoutGeometry* cutout) {
  return std::visit([&](const auto& s) { return make(device, s, cutout); }, shape);
}

void cutout_filter(const RTCFilterFunctionNArguments* args) {
  const auto& g = *static_cast<const CutoutGeometry*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    PrimHit hit;
    hit.t = RTCRayN_tfar(args->ray, n, i);  // the candidate's distance
    hit.uv = {RTCHitN_u(args->hit, n, i), RTCHitN_v(args->hit, n, i)};
    const Ray ray{{RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i), RTCRayN_org_z(args->ray, n, i)},
                  {RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i), RTCRayN_dir_z(args->ray, n, i)}};
    const uint32_t object = RTCHitN_geomID(args->hit, n, i), prim = RTCHitN_primID(args->hit, n, i);
    if (!g.test->keeps_hit(ray, object, prim, hit, g.instance(RTCHitN_instID(args->hit, n, i, 0))))
      args->valid[i] = 0;
  }
}

}  // namespace pt::embree
