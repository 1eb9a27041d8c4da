// The footprint of one pixel on a surface, for filtered texture lookups
// (docs/textures.md, "Filter widths"), as pbrt-v4 computes it:
//  - at a camera ray's first hit, from its ray differential: the offset rays
//    meet the hit's tangent plane at p + dpdx and p + dpdy;
//  - at any other hit (bounces, and rays whose offsets miss the plane), from
//    the camera's spread (pbrt-v4's Camera::Approximate_dp_dxy): the hit as a
//    camera ray from the camera position would see it, with the smallest
//    change a camera ray's origin and direction make across one pixel;
// then the change of (u, v) across the pixel, from dp/du and dp/dv by least
// squares (for a surface whose v is constant, u alone, and so on).
#pragma once

#include "core/math.h"
#include "render/camera/camera.h"
#include "render/camera/ray_differential.h"

namespace pt {

// How much a camera ray changes across one pixel: measured once, at the
// centre of the film, the smaller of the x and y steps of its origin and of
// its unit direction.
struct CameraSpread {
  Vec3f position;      // the camera's
  float origin = 0.0f;     // scene units per pixel (orthographic)
  float direction = 0.0f;  // radians per pixel, about (perspective, spherical)

  static CameraSpread of(const Camera& camera, int width, int height);
};

// dpdx, dpdy on the plane through p with normal n, where the differential's
// offset rays meet it; false if either misses it (parallel, or behind).
bool footprint_from_differential(const RayDifferential& d, Vec3f p, Vec3f n, Vec3f& dpdx, Vec3f& dpdy);
// The approximation for hits no differential reaches.
void footprint_from_camera(const CameraSpread& c, Vec3f p, Vec3f n, Vec3f& dpdx, Vec3f& dpdy);
// duv/dx and duv/dy from dp/dx and dp/dy, given dp/du and dp/dv; zero where
// neither partial has length.
void uv_footprint(Vec3f dpdu, Vec3f dpdv, Vec3f dpdx, Vec3f dpdy, Vec2f& duvdx, Vec2f& duvdy);

}  // namespace pt
