#include "render/lights/light_set.h"

#include <algorithm>
#include <cmath>
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

LightSet::LightSet(std::vector<Light> lights, std::size_t shape_count, float scene_radius, LightSamplerType sampler)
    : lights_(std::move(lights)), sampler_(sampler) {
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
  if (sampler_ == LightSamplerType::Power) {
    selection_ = Distribution1D(power);
  } else {
    build_bvh(power, scene_radius);
  }
  // The lights with positive power: the one (only_), or a few infinite ones (each_).
  bool all_infinite = true;
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    if (!(power[i] > 0.0f)) continue;
    all_infinite = all_infinite && std::visit([](const auto& l) { return KindOf<decltype(l)>::infinite; }, lights_[i]);
    each_.push_back(static_cast<int>(i));
  }
  only_ = each_.size() == 1 ? each_.front() : -1;
  if (!all_infinite || each_.size() < 2 || each_.size() > kMaxEachLights) each_.clear();
}

int LightSet::instance_light(uint32_t shape, uint32_t instance) const {
  const std::pair<uint64_t, int> key{(uint64_t{instance} << 32) | shape, -1};
  const auto it = std::lower_bound(instance_light_.begin(), instance_light_.end(), key);
  return it != instance_light_.end() && it->first == key.first ? it->second : -1;
}

void LightSet::build_bvh(const std::vector<float>& power, float scene_radius) {
  std::vector<LightBvh::Entry> bounded;
  std::vector<float> irradiance;
  unbounded_slot_.assign(lights_.size(), -1);
  const float disc_area = kPi * scene_radius * scene_radius;
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    if (!(power[i] > 0.0f)) continue;  // never chosen
    LightBounds b;
    const bool is_bounded = std::visit(
        [&](const auto& l) {
          if constexpr (KindOf<decltype(l)>::infinite) {
            return false;
          } else {
            return l.bounds(b);
          }
        },
        lights_[i]);
    if (is_bounded) {
      bounded.push_back({static_cast<int>(i), b});
      continue;
    }
    // An irradiance estimate, comparable with LightBounds::importance: a
    // directional light's irradiance (its power is that over the scene's disc),
    // an environment's on a surface facing it, pi times its mean radiance (its
    // power is 4 pi^2 R^2 times that mean), a point light without falloff pi I.
    const float e = std::visit(
        [&](const auto& l) {
          using L = KindOf<decltype(l)>;
          if constexpr (L::infinite) {
            return L::delta ? power[i] / disc_area : power[i] / (4.0f * disc_area);
          } else {
            return power[i] / (4.0f * kPi);  // a point light's power is 4 pi^2 I
          }
        },
        lights_[i]);
    if (!(e > 0.0f) || !std::isfinite(e)) continue;
    unbounded_slot_[i] = static_cast<int>(unbounded_light_.size());
    unbounded_light_.push_back(static_cast<int>(i));
    irradiance.push_back(e);
    unbounded_total_ += e;
  }
  if (!irradiance.empty()) unbounded_ = Distribution1D(irradiance);
  bvh_ = LightBvh(std::move(bounded), lights_.size());
}

bool LightSet::unbounded_share(Vec3f p, Vec3f n, float& share) const {
  const float bounded = bvh_.importance(p, n);
  if (!(unbounded_total_ + bounded > 0.0f)) return false;
  share = unbounded_total_ / (unbounded_total_ + bounded);
  return true;
}

int LightSet::choose(Vec3f p, Vec3f n, float u, float& pmf) const {
  if (lights_.size() <= 1) {  // the common case of one light: no search
    pmf = lights_.empty() ? 0.0f : 1.0f;
    return lights_.empty() ? -1 : 0;
  }
  if (only_ >= 0) {  // the others can never be picked
    pmf = 1.0f;
    return only_;
  }
  if (sampler_ == LightSamplerType::Power) return static_cast<int>(selection_.sample_discrete(u, &pmf));
  pmf = 0.0f;
  float p_unbounded = 0.0f;
  if (!unbounded_share(p, n, p_unbounded)) return -1;
  float q = 0.0f;
  if (u < p_unbounded) {
    const std::size_t k = unbounded_.sample_discrete(std::min(u / p_unbounded, kOneMinusEpsilon), &q);
    pmf = p_unbounded * q;
    return unbounded_light_[k];
  }
  const int light = bvh_.choose(p, n, std::min((u - p_unbounded) / (1.0f - p_unbounded), kOneMinusEpsilon), q);
  pmf = (1.0f - p_unbounded) * q;
  return light;
}

float LightSet::pmf(Vec3f p, Vec3f n, int light) const {
  if (light < 0 || static_cast<std::size_t>(light) >= lights_.size()) return 0.0f;
  if (only_ >= 0) return light == only_ ? 1.0f : 0.0f;
  if (lights_.size() == 1) return 1.0f;
  if (sampler_ == LightSamplerType::Power) return selection_.pmf(static_cast<std::size_t>(light));
  float p_unbounded = 0.0f;
  if (!unbounded_share(p, n, p_unbounded)) return 0.0f;
  const int slot = unbounded_slot_[static_cast<std::size_t>(light)];
  if (slot >= 0) return p_unbounded * unbounded_.pmf(static_cast<std::size_t>(slot));
  return (1.0f - p_unbounded) * bvh_.pmf(p, n, light);
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
