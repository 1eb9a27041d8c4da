// What the BSDF tests share: a surface at the origin with normal +z (world =
// shading frame) and directions given by their angles from that normal.
#pragma once

#include <cmath>

#include "render/materials/bsdf.h"

namespace pt::test {

inline SurfaceGeometry flat_surface() {
  SurfaceGeometry g;
  g.ng = g.ns = Vec3f(0, 0, 1);
  return g;
}

// The direction at polar angle theta and azimuth phi (degrees) about +z.
inline Vec3f direction_at(float theta_deg, float phi_deg = 0.0f) {
  const float t = theta_deg * kPi / 180.0f, p = phi_deg * kPi / 180.0f;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

}  // namespace pt::test
