// Cameras. A camera maps a point on the film (in pixels, (0,0) = top-left
// corner of the top-left pixel, y down) to a world-space ray. Built from
// CameraDesc + film resolution; knows nothing of JSON.
//
// Pinhole, or thin lens (CameraType::ThinLens with lens_radius > 0): rays leave
// a point of the lens disk and pass through the point where the pinhole ray
// meets the plane in focus (perpendicular to the view direction, at
// focus_distance), so that plane is sharp and everything else is blurred.
#pragma once

#include <array>

#include "core/math.h"
#include "scene/scene_description.h"

namespace pt {

class Camera {
 public:
  Camera() = default;
  Camera(const CameraDesc& desc, int width, int height);

  // Ray through film position (px, py) in pixel units from the lens centre
  // (the pinhole ray). Direction is unit length.
  Ray generate_ray(Vec2f film_px) const;
  // Same, leaving the lens at `lens_sample` in [0,1)^2 (mapped onto the lens
  // disk); a pinhole camera ignores the sample.
  Ray generate_ray(Vec2f film_px, Vec2f lens_sample) const;
  // True for a thin lens with a non-zero aperture (rays depend on the lens sample).
  bool has_lens() const { return lens_radius_ > 0.0f; }

  // Projects a world point to film pixel coordinates (through the lens
  // centre); false if behind the camera.
  bool project(Vec3f world, Vec2f& film_px) const;

  // OpenEXR's worldToCamera and worldToNDC (docs/output.md): 4x4 matrices for
  // row vectors (p' = (x, y, z, 1) * M, translation in the last row), stored
  // row-major. Camera space: x right, y up, the camera looking down -z. NDC
  // after dividing by w: x in [-1, 1] left to right and y in [-1, 1] bottom to
  // top across the full frame, z = 1 / depth; i.e. pixel
  // ((x + 1) / 2 * width, (1 - y) / 2 * height), as project() computes.
  std::array<float, 16> world_to_camera() const;
  std::array<float, 16> world_to_ndc() const;

  Vec3f position() const { return origin_; }
  Vec3f forward() const { return forward_; }

 private:
  Vec3f origin_, forward_, right_, up_;  // right_/up_ scaled to the image-plane half extents at distance 1
  int width_ = 1, height_ = 1;
  float lens_radius_ = 0.0f;
  float focus_distance_ = 1.0f;
};

}  // namespace pt
