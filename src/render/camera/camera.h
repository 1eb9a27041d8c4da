// Cameras. A camera maps a point on the film (in pixels, (0,0) = top-left
// corner of the top-left pixel, y down) to a world-space ray. Built from
// CameraDesc + film resolution; knows nothing of JSON.
#pragma once

#include "core/math.h"
#include "scene/scene_description.h"

namespace pt {

class Camera {
 public:
  Camera() = default;
  Camera(const CameraDesc& desc, int width, int height);

  // Ray through film position (px, py) in pixel units. Direction is unit length.
  Ray generate_ray(Vec2f film_px) const;

  // Projects a world point to film pixel coordinates; false if behind the camera.
  bool project(Vec3f world, Vec2f& film_px) const;

  Vec3f position() const { return origin_; }
  Vec3f forward() const { return forward_; }

 private:
  Vec3f origin_, forward_, right_, up_;  // right_/up_ scaled to the image-plane half extents at distance 1
  int width_ = 1, height_ = 1;
};

}  // namespace pt
