// The orthographic camera ("orthographic"): parallel rays along the view
// direction, leaving the plane through the camera position perpendicular to
// it. The film covers a view_width x view_height rectangle of that plane
// (scene units; give one, the other follows from the image's aspect ratio;
// view_height 2 by default, pbrt-v4's default screen window for a landscape
// image). Rays start on that plane, so nothing behind it is seen.
// Depth (the Z AOV) is the distance along the view axis, dot(p - position,
// forward), which is also the camera ray's length.
#pragma once

#include <array>
#include <optional>

#include "render/camera/camera_basis.h"

namespace pt {

struct OrthographicCamera {
  CameraBasis basis;
  float half_width = 1.0f, half_height = 1.0f;  // of the visible rectangle, scene units

  OrthographicCamera() = default;
  OrthographicCamera(const CameraDesc& desc, const CameraBasis& b);

  static constexpr bool has_lens() { return false; }

  Ray generate_ray(Vec2f film_px) const {
    const Vec2f p = basis.ndc(film_px);
    Ray ray;
    ray.origin = basis.origin + basis.right * (p.x * half_width) + basis.up * (p.y * half_height);
    ray.dir = basis.forward;
    return ray;
  }
  Ray generate_ray(Vec2f film_px, Vec2f) const { return generate_ray(film_px); }

  // False if the point is behind the plane the rays start from.
  bool project(Vec3f world, Vec2f& film_px) const {
    const Vec3f d = world - basis.origin;
    if (!(dot(d, basis.forward) >= 0.0f)) return false;
    film_px = film_position(Ray{world, basis.forward});
    return true;
  }

  Vec2f film_position(const Ray& camera_ray) const {
    const Vec3f d = camera_ray.origin - basis.origin;
    return basis.film_px(dot(d, basis.right) / half_width, dot(d, basis.up) / half_height);
  }

  float depth(Vec3f p) const { return dot(p - basis.origin, basis.forward); }

  std::array<float, 16> world_to_camera() const {
    return world_to_camera_matrix(basis.origin, basis.right, basis.up, basis.forward);
  }
  // x' = x / half_width, y' = y / half_height, z' = -z (the depth), w' = 1.
  std::optional<std::array<float, 16>> world_to_ndc() const {
    const std::array<float, 16> c = world_to_camera();
    std::array<float, 16> m{};
    for (int row = 0; row < 4; ++row) {
      m[row * 4 + 0] = c[row * 4 + 0] / half_width;
      m[row * 4 + 1] = c[row * 4 + 1] / half_height;
      m[row * 4 + 2] = -c[row * 4 + 2];
      m[row * 4 + 3] = row == 3 ? 1.0f : 0.0f;
    }
    return m;
  }
};

}  // namespace pt
