// Ray differentials (pbrt-v4): the camera rays through the film positions one
// pixel to the right and one pixel down of a camera ray, with the same lens
// sample. Carried to the camera ray's first hit, where they give the footprint
// of a pixel on the surface and so the width texture lookups filter over
// (render/textures/footprint.h, docs/textures.md).
#pragma once

#include "core/math.h"

namespace pt {

struct RayDifferential {
  Vec3f dx_origin, dx_dir;  // through film x + 1
  Vec3f dy_origin, dy_dir;  // through film y + 1
};

// A camera ray and, in a scene whose textures filter, its differential
// (render_samples fills it only there).
struct CameraRay : Ray {
  RayDifferential differential;
  bool has_differential = false;

  CameraRay() = default;
  explicit CameraRay(const Ray& r) : Ray(r) {}
  const RayDifferential* differential_or_null() const { return has_differential ? &differential : nullptr; }
};

}  // namespace pt
