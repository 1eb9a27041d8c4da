// The self-intersection policy (docs/geometry.md): offset the origin of a ray
// leaving a surface along the geometric normal by the error bound of the hit
// point, to the side the ray leaves on, and round the result away from the
// surface; tmin stays 0.
#include <bit>
#include <cmath>
#include <cstdint>

#include "geometry/float_util.h"
#include "geometry/shapes.h"
#include "geometry/terminator.h"

namespace pt {

namespace {

// fp::next_float_up(v) if step > 0, fp::next_float_down(v) if step < 0, else v,
// in integer selects. Which side a ray leaves on, and so the signs here, is a
// coin toss for the branch predictor; selects cost less than its misses.
float step_away(float v, float step) {
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  const uint32_t negative = bits >> 31;
  const bool zero = (bits & 0x7fffffffu) == 0u;
  uint32_t up = bits + 1u - 2u * negative;    // away from zero for v > 0, towards it for v < 0
  up = zero ? 0x00000001u : up;               // +-0 -> the smallest positive denormal
  up = bits == 0x7f800000u ? bits : up;       // +inf stays
  uint32_t down = bits - 1u + 2u * negative;
  down = zero ? 0x80000001u : down;           // +-0 -> the smallest negative denormal
  down = bits == 0xff800000u ? bits : down;   // -inf stays
  // The choice by step's bits, as masks: `move` unless step is +-0 or NaN,
  // `down` where step is negative.
  const uint32_t s = std::bit_cast<uint32_t>(step);
  const uint32_t move = 0u - static_cast<uint32_t>(((s & 0x7fffffffu) - 1u) < 0x7f800000u);
  const uint32_t towards_down = 0u - (s >> 31);
  const uint32_t chosen = up ^ ((up ^ down) & towards_down);
  return std::bit_cast<float>(bits ^ ((chosen ^ bits) & move));
}

}  // namespace

Vec3f offset_ray_origin(Vec3f p, Vec3f p_error, Vec3f ng, Vec3f dir) {
  const float d = dot(abs(ng), p_error);
  // The offset goes to the side of ng that dir leaves on (sign flipped by a mask).
  const uint32_t flip = dot(dir, ng) < 0.0f ? 0x80000000u : 0u;
  const Vec3f offset = ng * std::bit_cast<float>(std::bit_cast<uint32_t>(d) ^ flip);
  const Vec3f po = p + offset;
  return {step_away(po.x, offset.x), step_away(po.y, offset.y), step_away(po.z, offset.z)};
}

Vec3f offset_ray_origin(Vec3f p, Vec3f ng, Vec3f dir) {
  // Without the shape's own bound, assume p came from a computation whose
  // operands were about as large as p itself.
  return offset_ray_origin(p, Vec3f(fp::gamma(16) * max_component(abs(p))), ng, dir);
}

namespace {

// The origin of a ray leaving a point of a smooth-shaded mesh towards `dir`
// (geometry/terminator.h): the point moved towards the smooth surface on the
// side of the shading normal that dir leaves on, by the part of Hanika's
// offset that terminator_amount gives, then offset as every origin is, to the
// side of the triangle's plane the shading normal is on for dir. So a
// direction below the triangle but above the shading normal (the terminator)
// starts above the triangle, and meets the triangle if it crosses it: light
// never comes through the surface, it reaches the smooth surface or nothing.
// The error bound grows by the rounding of the sum and of the offset (the
// offset itself only moves the point away from the plane, never through it).
[[gnu::noinline]] Vec3f smooth_origin(const SurfaceGeometry& sg, Vec3f dir) {
  const float cos_n = dot(dir, sg.ns);
  const bool outer = cos_n >= 0.0f;
  const Vec3f leaves = outer ? sg.ns : -sg.ns;
  Vec3f p = sg.p;
  Vec3f error = sg.p_error;
  const float len = length(dir);
  if (len > 0.0f) {
    const float cos_g = dot(outer ? sg.ng : -sg.ng, dir) / len;
    const float amount = terminator_amount(std::fabs(cos_n) / len, cos_g, sg.smooth.cutoff);
    if (amount > 0.0f) {
      const Vec3f offset = terminator_offset(sg.smooth, outer) * amount;
      p = sg.p + offset;
      error = sg.p_error + fp::gamma(2) * abs(p) + fp::gamma(4) * abs(offset);
    }
  }
  return offset_ray_origin(p, error, sg.ng, leaves);
}

Vec3f leaving_origin(const SurfaceGeometry& sg, Vec3f dir) {
  if (sg.smooth.mesh != nullptr) [[unlikely]] return smooth_origin(sg, dir);
  return offset_ray_origin(sg.p, sg.p_error, sg.ng, dir);
}

}  // namespace

Ray spawn_ray(const SurfaceGeometry& sg, Vec3f dir) { return Ray{leaving_origin(sg, dir), dir, 0.0f, kInfinity}; }

Ray spawn_ray_to(const SurfaceGeometry& sg, Vec3f target) {
  const Vec3f o = leaving_origin(sg, target - sg.p);
  return Ray{o, target - o, 0.0f, 1.0f - kShadowEpsilon};
}

}  // namespace pt
