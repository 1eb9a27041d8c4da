// What every camera kind shares: where it is and which way it looks, and the
// OpenEXR worldToCamera matrix built from that (docs/output.md).
#pragma once

#include <array>

#include "core/math.h"
#include "scene/scene_description.h"

namespace pt {

// The camera's position and unit axes: `forward` towards look_at, `up` the
// description's up made perpendicular to forward, `right` = forward x up
// (up x forward for a left-handed, CGR, camera).
struct CameraBasis {
  Vec3f origin, forward, right, up;
  int width = 1, height = 1;  // the film, in pixels
  Vec2f film_offset;          // CameraDesc::film_offset

  static CameraBasis from(const CameraDesc& desc, int width, int height);

  float aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
  // Film pixel -> normalised device coordinates: x in [-1, 1] left to right,
  // y in [-1, 1] bottom to top.
  Vec2f ndc(Vec2f film_px) const {
    const Vec2f p(film_px.x + film_offset.x, film_px.y + film_offset.y);  // exact when the offset is 0
    return {2.0f * p.x / static_cast<float>(width) - 1.0f, 1.0f - 2.0f * p.y / static_cast<float>(height)};
  }
  // The inverse of ndc().
  Vec2f film_px(float x, float y) const {
    return {0.5f * (x + 1.0f) * static_cast<float>(width) - film_offset.x,
            0.5f * (1.0f - y) * static_cast<float>(height) - film_offset.y};
  }
};

// OpenEXR's worldToCamera for a camera at `origin` with unit axes r, u, f:
// row vectors, translation in the last row, stored row-major; camera space is
// x right, y up, looking down -z.
inline std::array<float, 16> world_to_camera_matrix(Vec3f origin, Vec3f r, Vec3f u, Vec3f f) {
  return {r.x, u.x, -f.x, 0.0f,  //
          r.y, u.y, -f.y, 0.0f,  //
          r.z, u.z, -f.z, 0.0f,  //
          -dot(origin, r), -dot(origin, u), dot(origin, f), 1.0f};
}

}  // namespace pt
