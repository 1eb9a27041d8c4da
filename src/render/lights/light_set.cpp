#include "render/lights/light_set.h"

#include <utility>

namespace pt {

bool sample_light(const Light& light, Vec3f p, Vec2f u, LightSample& s) {
  switch (light.index()) {
    case 0: return std::get<PointLight>(light).sample(p, s);
    case 1: return std::get<DirectionalLight>(light).sample(s);
    case 2: return std::get<ShapeLight>(light).sample(p, u, s);
    case 3: return std::get<EnvironmentLight>(light).map->sample(u, s);
    default: return std::get<UniformEnvironment>(light).sample(u, s);
  }
}

LightSet::LightSet(std::vector<Light> lights, std::size_t shape_count, float scene_radius)
    : lights_(std::move(lights)) {
  std::vector<float> power(lights_.size());
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    const Light& l = lights_[i];
    if (const auto* p = std::get_if<PointLight>(&l)) {
      power[i] = p->power();
    } else if (const auto* d = std::get_if<DirectionalLight>(&l)) {
      power[i] = d->power(scene_radius);
    } else if (const auto* a = std::get_if<ShapeLight>(&l)) {
      power[i] = a->power();
      if (shape_light_.empty()) shape_light_.assign(shape_count, -1);
      if (a->shape_id() < shape_count) shape_light_[a->shape_id()] = static_cast<int>(i);
    } else if (const auto* e = std::get_if<EnvironmentLight>(&l)) {
      power[i] = e->map->power(scene_radius);
      environment_ = static_cast<int>(i);
    } else {
      power[i] = std::get<UniformEnvironment>(l).power(scene_radius);
      environment_ = static_cast<int>(i);
    }
  }
  selection_ = Distribution1D(power);
  int positive = 0;
  for (std::size_t i = 0; i < power.size(); ++i) {
    if (power[i] > 0.0f) {
      ++positive;
      only_ = static_cast<int>(i);
    }
  }
  if (positive != 1) only_ = -1;
}

int LightSet::choose(float u, float& pmf) const {
  if (lights_.size() <= 1) {  // the common case of one light: no search
    pmf = lights_.empty() ? 0.0f : 1.0f;
    return lights_.empty() ? -1 : 0;
  }
  if (only_ >= 0) {  // the others can never be picked
    pmf = 1.0f;
    return only_;
  }
  return static_cast<int>(selection_.sample_discrete(u, &pmf));
}

}  // namespace pt
