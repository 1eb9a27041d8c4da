// Cameras. A camera maps a point on the film (in pixels, (0,0) = top-left
// corner of the top-left pixel, y down) to a world-space ray. Built from
// CameraDesc + film resolution; knows nothing of JSON.
//
// One struct per kind, each in its own header with the same members
// (generate_ray with and without a lens sample, has_lens, project,
// film_position, depth, world_to_camera, world_to_ndc):
//   perspective.h  — pinhole and thin lens;
//   orthographic.h — parallel rays over a view_width x view_height rectangle;
//   spherical.h    — 360-degree equirectangular, the environment map's layout.
// The kind is chosen once, when the camera is built; every call is a
// std::visit over the variant (a jump, no virtual call, no allocation).
// A new kind: its header, its place in CameraKind, its CameraType and its
// construction in camera.cpp, the native importer, schema and docs.
#pragma once

#include <array>
#include <optional>
#include <variant>

#include "core/math.h"
#include "render/camera/orthographic.h"
#include "render/camera/ray_differential.h"
#include "render/camera/perspective.h"
#include "render/camera/spherical.h"
#include "scene/scene_description.h"

namespace pt {

using CameraKind = std::variant<PerspectiveCamera, OrthographicCamera, SphericalCamera>;

class Camera {
 public:
  Camera() = default;
  Camera(const CameraDesc& desc, int width, int height);

  // Ray through film position (px, py) in pixel units from the lens centre
  // (the pinhole ray). Direction is unit length.
  Ray generate_ray(Vec2f film_px) const {
    return std::visit([&](const auto& c) { return c.generate_ray(film_px); }, kind_);
  }
  // Same, leaving the lens at `lens_sample` in [0,1)^2 (mapped onto the lens
  // disk); a camera without a lens ignores the sample.
  Ray generate_ray(Vec2f film_px, Vec2f lens_sample) const {
    return std::visit([&](const auto& c) { return c.generate_ray(film_px, lens_sample); }, kind_);
  }
  // The differential of the ray generate_ray(film_px, lens_sample) makes: the
  // rays one pixel right and one pixel down, same lens sample (every kind, as
  // pbrt-v4's CameraBase::GenerateRayDifferential does by default).
  RayDifferential differential(Vec2f film_px, Vec2f lens_sample) const {
    const Ray rx = generate_ray(film_px + Vec2f(1.0f, 0.0f), lens_sample);
    const Ray ry = generate_ray(film_px + Vec2f(0.0f, 1.0f), lens_sample);
    return {rx.origin, rx.dir, ry.origin, ry.dir};
  }
  // True for a thin lens with a non-zero aperture (rays depend on the lens sample).
  bool has_lens() const {
    return std::visit([](const auto& c) { return c.has_lens(); }, kind_);
  }

  // Projects a world point to film pixel coordinates (through the lens
  // centre); false if the camera cannot see it (behind a perspective or
  // orthographic camera; the spherical camera's own position).
  bool project(Vec3f world, Vec2f& film_px) const {
    return std::visit([&](const auto& c) { return c.project(world, film_px); }, kind_);
  }
  // The film position (pixels, possibly outside the frame) of a ray this
  // camera generated: what a screen-space background image is looked up by.
  Vec2f film_position(const Ray& camera_ray) const {
    return std::visit([&](const auto& c) { return c.film_position(camera_ray); }, kind_);
  }
  // The Z AOV of a point (docs/output.md): the distance along the view axis
  // (perspective, orthographic) or from the camera position (spherical).
  float depth(Vec3f p) const {
    return std::visit([&](const auto& c) { return c.depth(p); }, kind_);
  }

  // OpenEXR's worldToCamera and worldToNDC (docs/output.md): 4x4 matrices for
  // row vectors (p' = (x, y, z, 1) * M, translation in the last row), stored
  // row-major. Camera space: x right, y up, the camera looking down -z. NDC
  // after dividing by w: x in [-1, 1] left to right and y in [-1, 1] bottom to
  // top across the full frame, i.e. pixel ((x + 1) / 2 * width,
  // (1 - y) / 2 * height), as project() computes; z = 1 / depth (perspective)
  // or depth (orthographic). The spherical camera has no worldToNDC.
  std::array<float, 16> world_to_camera() const {
    return std::visit([](const auto& c) { return c.world_to_camera(); }, kind_);
  }
  std::optional<std::array<float, 16>> world_to_ndc() const {
    return std::visit([](const auto& c) { return c.world_to_ndc(); }, kind_);
  }

  Vec3f position() const { return basis().origin; }
  Vec3f forward() const { return basis().forward; }
  const CameraKind& kind() const { return kind_; }

 private:
  const CameraBasis& basis() const {
    return std::visit([](const auto& c) -> const CameraBasis& { return c.basis; }, kind_);
  }

  CameraKind kind_;
};

}  // namespace pt
