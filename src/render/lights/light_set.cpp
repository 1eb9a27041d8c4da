#include "render/lights/light_set.h"

#include <algorithm>
#include <type_traits>
#include <utility>

namespace pt {

namespace {

template <class L>
using KindOf = std::decay_t<L>;

// The place of a light kind in the set's order (see the constructor).
int order(const Light& light) {
  return std::visit(
      [](const auto& l) {
        using L = KindOf<decltype(l)>;
        return (L::delta ? 0 : 2) + (L::infinite ? 1 : 0);
      },
      light);
}

}  // namespace

bool sample_light(const Light& light, Vec3f p, Vec2f u, LightSample& s) {
  return std::visit(
      [&](const auto& l) {
        using L = KindOf<decltype(l)>;
        s.delta = L::delta;
        s.infinite = L::infinite;
        return l.sample(p, u, s);
      },
      light);
}

float light_pdf(const Light& light, Vec3f p, Vec3f wi, Vec3f q, Vec3f n) {
  return std::visit([&](const auto& l) { return l.pdf(p, wi, q, n); }, light);
}

LightSet::LightSet(std::vector<Light> lights, std::size_t shape_count, float scene_radius)
    : lights_(std::move(lights)) {
  std::stable_sort(lights_.begin(), lights_.end(), [](const Light& a, const Light& b) { return order(a) < order(b); });
  std::vector<float> power(lights_.size());
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    power[i] = std::visit(
        [&](const auto& l) {
          using L = KindOf<decltype(l)>;
          if constexpr (L::delta) {
            ++delta_count_;
          } else if constexpr (L::infinite) {
            environment_ = static_cast<int>(i);
          } else {  // finite and not delta: an area light
            uint32_t instance = kNoInstance;
            if constexpr (requires { l.instance(); }) instance = l.instance();
            if (instance != kNoInstance) {
              instance_light_.push_back({(uint64_t{instance} << 32) | l.shape_id(), static_cast<int>(i)});
            } else {
              if (shape_light_.empty()) shape_light_.assign(shape_count, -1);
              if (l.shape_id() < shape_count) shape_light_[l.shape_id()] = static_cast<int>(i);
            }
          }
          return l.power(scene_radius);
        },
        lights_[i]);
  }
  std::sort(instance_light_.begin(), instance_light_.end());
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

int LightSet::instance_light(uint32_t shape, uint32_t instance) const {
  const std::pair<uint64_t, int> key{(uint64_t{instance} << 32) | shape, -1};
  const auto it = std::lower_bound(instance_light_.begin(), instance_light_.end(), key);
  return it != instance_light_.end() && it->first == key.first ? it->second : -1;
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

RGB LightSet::escaped_radiance(Vec3f dir, RGB none) const {
  if (environment_ < 0) return none;
  return std::visit(
      [&](const auto& l) -> RGB {
        using L = KindOf<decltype(l)>;
        if constexpr (!L::delta && L::infinite) {
          return l.radiance(dir);
        } else {
          return none;  // not reached: environment_ is such a light
        }
      },
      lights_[static_cast<std::size_t>(environment_)]);
}

}  // namespace pt
