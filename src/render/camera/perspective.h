// The perspective camera: a pinhole, or a thin lens when lens_radius > 0
// ("pinhole"/"perspective" and "thin_lens"/"thinlens" in the scene file).
//
// Rays leave the eye (pinhole) through the image plane at distance 1, whose
// half extents are tan(fov/2) * aspect by tan(fov/2). A thin lens moves the
// origin to a point of the lens disk and aims it at the point where the
// pinhole ray meets the plane in focus (perpendicular to the view direction,
// at focus_distance), so that plane is sharp and everything else is blurred.
// Depth (the Z AOV) is the distance along the view axis, dot(p - eye, forward).
#pragma once

#include <array>
#include <optional>

#include "core/sampling.h"
#include "render/camera/camera_basis.h"

namespace pt {

struct PerspectiveCamera {
  CameraBasis basis;
  Vec3f right_, up_;  // basis.right / basis.up scaled to the image-plane half extents at distance 1
  float lens_radius_ = 0.0f;
  float focus_distance_ = 1.0f;

  PerspectiveCamera() = default;
  PerspectiveCamera(const CameraDesc& desc, const CameraBasis& b);

  bool has_lens() const { return lens_radius_ > 0.0f; }

  Ray generate_ray(Vec2f film_px) const {
    const Vec2f p = basis.ndc(film_px);
    Ray ray;
    ray.origin = basis.origin;
    ray.dir = normalize(basis.forward + right_ * p.x + up_ * p.y);
    return ray;
  }

  Ray generate_ray(Vec2f film_px, Vec2f lens_sample) const {
    Ray ray = generate_ray(film_px);
    if (!has_lens()) return ray;
    // The pinhole ray meets the plane in focus at distance focus_distance_ along forward.
    const Vec3f focus = ray.origin + ray.dir * (focus_distance_ / dot(ray.dir, basis.forward));
    const Vec2f disk = sample_uniform_disk_concentric(lens_sample);
    const Vec3f lens = basis.origin + (normalize(right_) * disk.x + normalize(up_) * disk.y) * lens_radius_;
    ray.origin = lens;
    ray.dir = normalize(focus - lens);
    return ray;
  }

  // Through the lens centre; false if the point is not in front of the eye.
  bool project(Vec3f world, Vec2f& film_px) const {
    const Vec3f d = world - basis.origin;
    const float z = dot(d, basis.forward);
    if (!(z > 0.0f)) return false;
    // right_ and up_ are scaled by the half extents s, so dot(d, right_) / s^2 = (d . r_unit) / s.
    const float x = dot(d, right_) / (z * length_squared(right_));
    const float y = dot(d, up_) / (z * length_squared(up_));
    film_px = basis.film_px(x, y);
    return true;
  }

  // The film position a camera ray was generated for: where the point it
  // aims at (on the plane in focus for a thin lens) projects.
  Vec2f film_position(const Ray& camera_ray) const {
    const float along = has_lens() ? focus_distance_ / dot(camera_ray.dir, basis.forward) : 1.0f;
    Vec2f px{0.0f, 0.0f};
    project(camera_ray.origin + camera_ray.dir * along, px);
    return px;
  }

  float depth(Vec3f p) const { return dot(p - basis.origin, basis.forward); }

  std::array<float, 16> world_to_camera() const {
    return world_to_camera_matrix(basis.origin, normalize(right_), normalize(up_), basis.forward);
  }
  // Camera space to clip space: x' = x / |right_|, y' = y / |up_|, z' = 1,
  // w' = -z; after the divide, NDC z = 1 / depth.
  std::optional<std::array<float, 16>> world_to_ndc() const {
    const std::array<float, 16> c = world_to_camera();
    const float sx = 1.0f / length(right_), sy = 1.0f / length(up_);
    std::array<float, 16> m{};
    for (int row = 0; row < 4; ++row) {
      m[row * 4 + 0] = c[row * 4 + 0] * sx;
      m[row * 4 + 1] = c[row * 4 + 1] * sy;
      m[row * 4 + 2] = row == 3 ? 1.0f : 0.0f;
      m[row * 4 + 3] = -c[row * 4 + 2];
    }
    return m;
  }
};

}  // namespace pt
