// The CGR course's "binary" mode: pure red (1, 0, 0) where the camera ray hits
// anything, black elsewhere, whatever the background. The values are exactly
// 1 and 0, which every display transform maps to 255 and 0 (docs/rendering.md).
// One ray through each pixel centre whatever spp says: averaging samples would
// put intermediate values on the edges, and the mode promises pure pixels.
#include "render/integrators/builtin.h"
#include "render/integrators/render_loop.h"
#include "render/render_scene.h"

namespace pt {

namespace {

class BinaryIntegrator final : public Integrator {
 public:
  explicit BinaryIntegrator(const IntegratorSettings& settings) : settings_(settings) { settings_.spp = 1; }

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    render_pixels(scene, film, pool, settings_, [&](const Ray& ray) {
      const bool hit = scene.occluded(ray);
      return CameraEstimate{hit ? RGB(1, 0, 0) : RGB(0, 0, 0), hit};
    });
  }

 private:
  IntegratorSettings settings_;
};

}  // namespace

std::unique_ptr<Integrator> make_binary_integrator(const IntegratorSettings& settings) {
  return std::make_unique<BinaryIntegrator>(settings);
}

}  // namespace pt
