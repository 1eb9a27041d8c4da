// Debug view "signature": every object in a colour of its own, a hash of its
// object id (stable across runs, thread counts and platforms); misses are black.
#include "core/rng.h"
#include "render/integrators/builtin.h"
#include "render/integrators/render_loop.h"
#include "render/render_scene.h"

namespace pt {

namespace {

class SignatureIntegrator final : public Integrator {
 public:
  explicit SignatureIntegrator(const IntegratorSettings& settings) : settings_(settings) {}

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    render_pixels(scene, film, pool, settings_, [&](const Ray& ray) {
      Hit hit;
      const bool found = scene.accel->intersect(ray, hit);
      return CameraEstimate{found ? signature_colour(hit.shape) : RGB(), found};
    });
  }

 private:
  IntegratorSettings settings_;
};

}  // namespace

RGB signature_colour(uint32_t id) {
  const uint64_t h = mix64(static_cast<uint64_t>(id) + 0x5151'5151ULL);
  auto channel = [&](int shift) { return 0.15f + 0.85f * static_cast<float>((h >> shift) & 0xffff) / 65535.0f; };
  return {channel(0), channel(16), channel(32)};
}

std::unique_ptr<Integrator> make_signature_integrator(const IntegratorSettings& settings) {
  return std::make_unique<SignatureIntegrator>(settings);
}

}  // namespace pt
