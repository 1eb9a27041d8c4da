// The spherical camera ("spherical"): a 360 x 180 degree equirectangular
// (latitude-longitude) image around the camera position, in the layout the
// environment map reads (render/lights/environment.h), so that a render can
// serve as one. Column u = x / width in [0, 1) is the azimuth
// phi = 2 pi (u - 1/2) from the view direction towards `right`: the centre
// column looks along forward, u = 3/4 along right, u = 0 and 1 behind. Row
// v = y / height is the polar angle theta = pi v from `up`: the top row is the
// zenith. So a camera looking down -z with +y up renders exactly the map an
// "environment" with up [0, 1, 0] and rotation 0 reads (tests/render/
// test_camera.cpp). The field of view is always the full sphere.
// Depth (the Z AOV) is the distance from the camera position, |p - position|
// (there is no view axis). There is no worldToNDC (the projection is not
// linear): EXR files get worldToCamera only.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "core/sampling.h"
#include "render/camera/camera_basis.h"

namespace pt {

struct SphericalCamera {
  CameraBasis basis;

  SphericalCamera() = default;
  explicit SphericalCamera(const CameraBasis& b) : basis(b) {}

  static constexpr bool has_lens() { return false; }

  Ray generate_ray(Vec2f film_px) const {
    const float phi = 2.0f * kPi * (film_px.x / static_cast<float>(basis.width) - 0.5f);
    const float theta = kPi * (film_px.y / static_cast<float>(basis.height));
    const float sin_theta = std::sin(theta);
    Ray ray;
    ray.origin = basis.origin;
    ray.dir = normalize(basis.forward * (sin_theta * std::cos(phi)) + basis.right * (sin_theta * std::sin(phi)) +
                        basis.up * std::cos(theta));
    return ray;
  }
  Ray generate_ray(Vec2f film_px, Vec2f) const { return generate_ray(film_px); }

  // Every point but the camera position itself projects.
  bool project(Vec3f world, Vec2f& film_px) const {
    const Vec3f d = world - basis.origin;
    if (!(length_squared(d) > 0.0f)) return false;
    film_px = film_position(Ray{basis.origin, normalize(d)});
    return true;
  }

  Vec2f film_position(const Ray& camera_ray) const {
    const Vec3f d = camera_ray.dir;
    const float theta = std::acos(std::clamp(dot(d, basis.up), -1.0f, 1.0f));
    const float phi = std::atan2(dot(d, basis.right), dot(d, basis.forward));
    return {(0.5f + phi * kInv2Pi) * static_cast<float>(basis.width),
            theta * kInvPi * static_cast<float>(basis.height)};
  }

  float depth(Vec3f p) const { return length(p - basis.origin); }

  std::array<float, 16> world_to_camera() const {
    return world_to_camera_matrix(basis.origin, basis.right, basis.up, basis.forward);
  }
  std::optional<std::array<float, 16>> world_to_ndc() const { return std::nullopt; }
};

}  // namespace pt
