#include "render/camera/camera.h"

#include <cmath>

#include "core/sampling.h"

namespace pt {

namespace {

// A unit vector perpendicular to `forward` that points as much along `up` as
// possible; falls back to an arbitrary perpendicular if up is parallel to forward
// (the loader rejects that case, but the camera must never produce NaNs).
Vec3f image_up(Vec3f forward, Vec3f up) {
  const Vec3f perp = up - forward * dot(up, forward);
  const float len = length(perp);
  if (len > 1e-6f * std::max(1.0f, length(up))) return perp / len;
  Vec3f t, b;
  orthonormal_basis(forward, t, b);
  return b;
}

}  // namespace

Camera::Camera(const CameraDesc& desc, int width, int height)
    : width_(std::max(width, 1)), height_(std::max(height, 1)) {
  origin_ = desc.position;
  Vec3f forward = desc.look_at.value - desc.position.value;
  forward_ = length(forward) > 0 ? normalize(forward) : Vec3f(0, 0, -1);

  const Vec3f up = image_up(forward_, desc.up);
  // Right-handed: right = forward x up. Left-handed (CGR): right = up x forward.
  const Vec3f right = desc.left_handed ? cross(up, forward_) : cross(forward_, up);

  const float tan_half = std::tan(0.5f * desc.fov_y_deg.value * kPi / 180.0f);
  const float aspect = static_cast<float>(width_) / static_cast<float>(height_);
  right_ = normalize(right) * (tan_half * aspect);
  up_ = up * tan_half;

  if (desc.type == CameraType::ThinLens && desc.lens_radius.value > 0.0f && desc.focus_distance.value > 0.0f) {
    lens_radius_ = desc.lens_radius;
    focus_distance_ = desc.focus_distance;
  }
}

Ray Camera::generate_ray(Vec2f film_px, Vec2f lens_sample) const {
  Ray ray = generate_ray(film_px);
  if (!has_lens()) return ray;
  // The pinhole ray meets the plane in focus at distance focus_distance_ along forward.
  const Vec3f focus = ray.origin + ray.dir * (focus_distance_ / dot(ray.dir, forward_));
  const Vec2f disk = sample_uniform_disk_concentric(lens_sample);
  const Vec3f lens = origin_ + (normalize(right_) * disk.x + normalize(up_) * disk.y) * lens_radius_;
  ray.origin = lens;
  ray.dir = normalize(focus - lens);
  return ray;
}

Ray Camera::generate_ray(Vec2f film_px) const {
  // Normalised device coordinates: x in [-1, 1] left to right, y in [-1, 1] bottom to top.
  const float x = 2.0f * film_px.x / static_cast<float>(width_) - 1.0f;
  const float y = 1.0f - 2.0f * film_px.y / static_cast<float>(height_);
  Ray ray;
  ray.origin = origin_;
  ray.dir = normalize(forward_ + right_ * x + up_ * y);
  return ray;
}

bool Camera::project(Vec3f world, Vec2f& film_px) const {
  const Vec3f d = world - origin_;
  const float z = dot(d, forward_);
  if (!(z > 0.0f)) return false;
  // right_ and up_ are scaled by the half extents s, so dot(d, right_) / s^2 = (d . r_unit) / s.
  const float x = dot(d, right_) / (z * length_squared(right_));
  const float y = dot(d, up_) / (z * length_squared(up_));
  film_px = {0.5f * (x + 1.0f) * static_cast<float>(width_), 0.5f * (1.0f - y) * static_cast<float>(height_)};
  return true;
}

std::array<float, 16> Camera::world_to_camera() const {
  const Vec3f r = normalize(right_), u = normalize(up_), f = forward_;
  return {r.x, u.x, -f.x, 0.0f,  //
          r.y, u.y, -f.y, 0.0f,  //
          r.z, u.z, -f.z, 0.0f,  //
          -dot(origin_, r), -dot(origin_, u), dot(origin_, f), 1.0f};
}

std::array<float, 16> Camera::world_to_ndc() const {
  // Camera space to clip space: x' = x / |right_|, y' = y / |up_|, z' = 1, w' = -z.
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

}  // namespace pt
