// The infinite plane: its data and every routine that follows from it. It has
// no bounds, so it is no primitive of either acceleration backend
// (primitive_count() == 0, bounds() empty): the accelerator layer above both
// backends (accel/unbounded.h) tests the planes of a scene itself, so the two
// backends agree on them exactly and the plane reaches the horizon. Texture
// coordinates are planar: distances from `point` along the tangent and the
// bitangent (normal x tangent), divided by uv_scale (textures repeat).
// An infinite plane cannot emit (it has infinite power): scene validation
// refuses an emitting material on one.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "geometry/float_util.h"
#include "geometry/shape_base.h"

namespace pt {

struct InfinitePlane {
  Vec3f point;
  Vec3f normal{0, 1, 0};   // unit; the side the plane faces
  Vec3f tangent{1, 0, 0};  // unit, in the plane: the direction of u
  float uv_scale = 1.0f;   // world length of one texture repeat
};

// A plane as a scene file gives it: the normal scaled to unit length, the
// tangent (zero: the deterministic frame's first axis, fp::axis_frame) made
// perpendicular to it and unit. Zero or parallel vectors are kept for check().
inline InfinitePlane make_plane(Vec3f point, Vec3f normal, Vec3f tangent, float uv_scale) {
  const float ln = length(normal);
  if (!(ln > 0.0f) || !std::isfinite(ln)) return {point, normal, tangent, uv_scale};
  const Vec3f n = normal / ln;
  if (length(tangent) == 0.0f) {
    Vec3f e0, e1;
    fp::axis_frame(n, e0, e1);
    return {point, n, e0, uv_scale};
  }
  const Vec3f t = tangent - n * dot(tangent, n);
  const float lt = length(t);
  return {point, n, lt > 0.0f ? t / lt : Vec3f(0.0f), uv_scale};
}

namespace plane_detail {

// The ray parameter where the ray meets the plane through `point` with unit
// normal `n` (in double: exact inputs, one rounding of t), or NaN if parallel.
inline double plane_t(Vec3f point, Vec3f n, const Ray& ray) {
  const double denom = static_cast<double>(ray.dir.x) * n.x + static_cast<double>(ray.dir.y) * n.y +
                       static_cast<double>(ray.dir.z) * n.z;
  const double num = (static_cast<double>(point.x) - ray.origin.x) * n.x +
                     (static_cast<double>(point.y) - ray.origin.y) * n.y +
                     (static_cast<double>(point.z) - ray.origin.z) * n.z;
  return denom != 0.0 ? num / denom : std::nan("");
}

// Ray point at t, moved onto the plane along its normal.
inline Vec3f project(Vec3f point, Vec3f n, Vec3f p) { return p - n * dot(p - point, n); }

}  // namespace plane_detail

// No primitive in the backends' sense; an empty box (extending by it changes nothing).
inline Bounds3f bounds(const InfinitePlane&) { return Bounds3f{}; }
inline Bounds3f bounds(const InfinitePlane&, uint32_t) { return Bounds3f{}; }
// uv are distances along tangent and normal x tangent, in units of uv_scale.
inline UvDerivatives uv_derivatives(const InfinitePlane& pl, const SurfaceGeometry&) {
  return {pl.tangent * pl.uv_scale, cross(pl.normal, pl.tangent) * pl.uv_scale};
}

inline uint32_t primitive_count(const InfinitePlane&) { return 0; }

// Addressed like a shape of primitives (prim is ignored), so that neither
// backend takes it for a whole shape to put in its tree.
inline bool intersect(const InfinitePlane& pl, uint32_t /*prim*/, const Ray& ray, PrimHit& hit) {
  const float t = static_cast<float>(plane_detail::plane_t(pl.point, pl.normal, ray));
  if (!(t > ray.tmin && t < ray.tmax) || !is_finite(ray.origin)) return false;
  hit.t = t;
  hit.uv = {0.0f, 0.0f};
  return true;
}

inline SurfaceGeometry surface(const InfinitePlane& pl, uint32_t /*prim*/, const Ray& ray, const PrimHit& hit) {
  SurfaceGeometry sg;
  sg.p = plane_detail::project(pl.point, pl.normal, ray.at(hit.t));
  sg.ng = pl.normal;
  sg.ns = pl.normal;
  const Vec3f q = sg.p - pl.point;
  const float inv = 1.0f / pl.uv_scale;
  sg.uv = {dot(q, pl.tangent) * inv, dot(q, cross(pl.normal, pl.tangent)) * inv};
  sg.p_error = fp::gamma(8) * (abs(sg.p) + abs(pl.point));
  return sg;
}

inline void check(const InfinitePlane& pl, ShapeChecker& c) {
  if (!is_finite(pl.point) || !is_finite(pl.normal) || !is_finite(pl.tangent) || !std::isfinite(pl.uv_scale))
    c.unusable("", "plane has a non-finite point, normal, tangent or uv_scale");
  if (length(pl.normal) == 0.0f) c.unusable("normal", "plane normal must not be zero");
  else if (length(pl.tangent) == 0.0f) c.error("tangent", "plane tangent must not be parallel to its normal");
  if (!(pl.uv_scale > 0.0f)) c.error("uv_scale", "uv_scale must be > 0, got " + format_number(pl.uv_scale));
}

// Nothing to sample (an infinite plane cannot emit; validation refuses it).
struct PlaneAreaSampler {
  Vec3f point, normal;
  float area = 0.0f;
  void sample(Vec2f /*u*/, Vec3f& q, Vec3f& n) const {
    q = point;
    n = normal;
  }
};

inline PlaneAreaSampler make_area_sampler(const InfinitePlane& pl) { return {pl.point, pl.normal, 0.0f}; }

}  // namespace pt
