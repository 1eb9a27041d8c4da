// Debug view "normal": the surface's outward shading normal n as the colour
// n * 0.5 + 0.5 (not flipped towards the viewer, so back faces show their
// orientation); black where the camera ray misses.
#include "render/integrators/builtin.h"
#include "render/integrators/render_loop.h"
#include "render/render_scene.h"

namespace pt {

namespace {

class NormalIntegrator final : public Integrator {
 public:
  explicit NormalIntegrator(const IntegratorSettings& settings) : settings_(settings) {}

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    render_pixels(scene, film, pool, settings_, [&](const Ray& ray) {
      Intersection isect;
      if (!scene.intersect(ray, isect)) return CameraEstimate{};
      const Vec3f c = isect.geo.ns * 0.5f + Vec3f(0.5f);
      return CameraEstimate{RGB(c.x, c.y, c.z), true};
    });
  }

 private:
  IntegratorSettings settings_;
};

}  // namespace

std::unique_ptr<Integrator> make_normal_integrator(const IntegratorSettings& settings) {
  return std::make_unique<NormalIntegrator>(settings);
}

}  // namespace pt
