// The lights of a render scene as the path integrator sees them: point and
// directional lights, area lights (every emissive shape), and the environment
// (an image map, or the background colour as a uniform environment when it is
// not black). One light is chosen per next-event estimate, in proportion to
// its power (an estimate for infinite lights, from the scene's bounding
// sphere; docs/path-tracing.md).
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "core/sampling.h"
#include "render/lights/environment.h"
#include "render/lights/light.h"
#include "render/lights/shape_light.h"

namespace pt {

using Light = std::variant<PointLight, DirectionalLight, ShapeLight, EnvironmentLight, UniformEnvironment>;

// Samples light `light` from point p.
bool sample_light(const Light& light, Vec3f p, Vec2f u, LightSample& s);

class LightSet {
 public:
  LightSet() = default;
  // `shape_count`: the number of shapes (for the shape -> light table).
  LightSet(std::vector<Light> lights, std::size_t shape_count, float scene_radius);

  bool empty() const { return lights_.empty(); }
  std::size_t size() const { return lights_.size(); }
  const Light& operator[](std::size_t i) const { return lights_[i]; }

  // Picks a light with probability proportional to its power; -1 if there is none.
  int choose(float u, float& pmf) const;
  // False when choose() does not depend on u: one light, or one light with
  // positive power among lights that can never be picked. The integrator then
  // spends no sample dimension on the choice (so adding a powerless light to
  // a scene leaves its image bit for bit as it was).
  bool needs_choice() const { return lights_.size() > 1 && only_ < 0; }
  float pmf(int light) const {
    if (light < 0) return 0.0f;
    if (only_ >= 0) return light == only_ ? 1.0f : 0.0f;
    return lights_.size() == 1 ? 1.0f : selection_.pmf(static_cast<std::size_t>(light));
  }

  // The area light of shape i, or -1.
  int shape_light(uint32_t shape) const {
    return shape < shape_light_.size() ? shape_light_[shape] : -1;
  }
  // The environment's light index (map or uniform), or -1.
  int environment() const { return environment_; }

 private:
  std::vector<Light> lights_;
  Distribution1D selection_;
  std::vector<int> shape_light_;  // empty when no shape emits
  int environment_ = -1;
  int only_ = -1;  // the one light with positive power when exactly one has it, else -1
};

}  // namespace pt
