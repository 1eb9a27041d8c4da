// Debug view "depth": grey level 1 - t / R for a hit at distance t along the
// (unit) camera ray, where R is the distance from the camera to the farthest
// corner of the scene bounds, so the nearest surfaces are bright, the farthest
// possible point is black, and every value lies in [0, 1]; misses are black.
#include <algorithm>
#include <cmath>

#include "render/integrators/builtin.h"
#include "render/integrators/render_loop.h"
#include "render/render_scene.h"

namespace pt {

namespace {

class DepthIntegrator final : public Integrator {
 public:
  explicit DepthIntegrator(const IntegratorSettings& settings) : settings_(settings) {}

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    const float inv_range = 1.0f / depth_view_range(scene.accel->bounds(), scene.camera.position());
    render_pixels(scene, film, pool, settings_, [&](const Ray& ray) {
      Intersection isect;
      if (!scene.intersect(ray, isect)) return CameraEstimate{};
      return CameraEstimate{RGB(std::clamp(1.0f - isect.hit.t * inv_range, 0.0f, 1.0f)), true};
    });
  }

 private:
  IntegratorSettings settings_;
};

}  // namespace

float depth_view_range(const Bounds3f& b, Vec3f eye) {
  if (b.empty()) return 1.0f;
  float range = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const Vec3f corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
    range = std::max(range, length(corner - eye));
  }
  return (range > 0.0f && std::isfinite(range)) ? range : 1.0f;
}

std::unique_ptr<Integrator> make_depth_integrator(const IntegratorSettings& settings) {
  return std::make_unique<DepthIntegrator>(settings);
}

}  // namespace pt
