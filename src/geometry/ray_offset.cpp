// The self-intersection policy (docs/geometry.md): offset the origin of a ray
// leaving a surface along the geometric normal by the error bound of the hit
// point, to the side the ray leaves on, and round the result away from the
// surface; tmin stays 0.
#include <cmath>

#include "geometry/float_util.h"
#include "geometry/shapes.h"

namespace pt {

Vec3f offset_ray_origin(Vec3f p, Vec3f p_error, Vec3f ng, Vec3f dir) {
  const float d = dot(abs(ng), p_error);
  Vec3f offset = ng * d;
  if (dot(dir, ng) < 0.0f) offset = -offset;
  Vec3f po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0f) {
      po[i] = fp::next_float_up(po[i]);
    } else if (offset[i] < 0.0f) {
      po[i] = fp::next_float_down(po[i]);
    }
  }
  return po;
}

Vec3f offset_ray_origin(Vec3f p, Vec3f ng, Vec3f dir) {
  // Without the shape's own bound, assume p came from a computation whose
  // operands were about as large as p itself.
  return offset_ray_origin(p, Vec3f(fp::gamma(16) * max_component(abs(p))), ng, dir);
}

Ray spawn_ray(const SurfaceGeometry& sg, Vec3f dir) {
  return Ray{offset_ray_origin(sg.p, sg.p_error, sg.ng, dir), dir, 0.0f, kInfinity};
}

Ray spawn_ray_to(const SurfaceGeometry& sg, Vec3f target) {
  const Vec3f o = offset_ray_origin(sg.p, sg.p_error, sg.ng, target - sg.p);
  return Ray{o, target - o, 0.0f, 1.0f - kShadowEpsilon};
}

}  // namespace pt
