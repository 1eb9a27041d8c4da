#include "render/camera/camera.h"

#include <cmath>

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

CameraKind make_kind(const CameraDesc& desc, const CameraBasis& basis) {
  switch (desc.type) {
    case CameraType::Orthographic: return OrthographicCamera(desc, basis);
    case CameraType::Spherical: return SphericalCamera(basis);
    case CameraType::Pinhole:
    case CameraType::ThinLens: break;
  }
  return PerspectiveCamera(desc, basis);
}

}  // namespace

CameraBasis CameraBasis::from(const CameraDesc& desc, int width, int height) {
  CameraBasis b;
  b.width = std::max(width, 1);
  b.height = std::max(height, 1);
  b.film_offset = desc.film_offset;
  b.origin = desc.position;
  const Vec3f forward = desc.look_at.value - desc.position.value;
  b.forward = length(forward) > 0 ? normalize(forward) : Vec3f(0, 0, -1);
  b.up = image_up(b.forward, desc.up);
  // Right-handed: right = forward x up. Left-handed (CGR): right = up x forward.
  b.right = normalize(desc.left_handed ? cross(b.up, b.forward) : cross(b.forward, b.up));
  return b;
}

PerspectiveCamera::PerspectiveCamera(const CameraDesc& desc, const CameraBasis& b) : basis(b) {
  const float tan_half = std::tan(0.5f * desc.fov_y_deg.value * kPi / 180.0f);
  right_ = basis.right * (tan_half * basis.aspect());
  up_ = basis.up * tan_half;
  if (desc.type == CameraType::ThinLens && desc.lens_radius.value > 0.0f && desc.focus_distance.value > 0.0f) {
    lens_radius_ = desc.lens_radius;
    focus_distance_ = desc.focus_distance;
  }
}

OrthographicCamera::OrthographicCamera(const CameraDesc& desc, const CameraBasis& b) : basis(b) {
  // One of the two extents is given (view_width 0: not given); the other follows from the aspect ratio.
  if (desc.view_width.value > 0.0f) {
    half_width = 0.5f * desc.view_width.value;
    half_height = half_width / basis.aspect();
  } else {
    half_height = 0.5f * desc.view_height.value;
    half_width = half_height * basis.aspect();
  }
}

Camera::Camera(const CameraDesc& desc, int width, int height)
    : kind_(make_kind(desc, CameraBasis::from(desc, width, height))) {}

}  // namespace pt
