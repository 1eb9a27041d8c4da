// The lights of a render scene, each stored once: point and directional
// lights, spot lights, area lights (every emissive shape), and the environment (an image
// map, or the background colour as a uniform environment when it is not
// black). The path integrator chooses one light per next-event estimate
// (docs/path-tracing.md, "Choosing a light"; where the lights are a few
// infinite ones it samples each, each_lights()): by default by its importance at
// the shading point (the bounded lights through a light BVH, light_bvh.h,
// weighed against the infinite ones' irradiance estimates), or, with
// render.light_sampler "power", in proportion to its power (an estimate for
// infinite lights, from the scene's bounding sphere). The classic integrator
// shades the delta lights and samples every area light (docs/rendering.md).
#pragma once

#include <concepts>
#include <cstdint>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include "core/sampling.h"
#include "scene/scene_description.h"
#include "render/lights/environment.h"
#include "render/lights/light.h"
#include "render/lights/light_bvh.h"
#include "render/lights/shape_light.h"
#include "render/lights/spot_light.h"

namespace pt {

// The members every light kind has (render/lights/light.h).
template <class L>
concept LightKind = requires(const L& light, Vec3f v, Vec2f u, LightSample& s, float r) {
  { L::delta } -> std::convertible_to<bool>;
  { L::infinite } -> std::convertible_to<bool>;
  { light.sample(v, u, s) } -> std::same_as<bool>;
  { light.pdf(v, v, v, v) } -> std::same_as<float>;
  { light.power(r) } -> std::same_as<float>;
} && (L::delta || (L::infinite ? requires(const L& light, Vec3f d) { { light.radiance(d) } -> std::same_as<RGB>; }
                                : requires(const L& light) { { light.shape_id() } -> std::same_as<uint32_t>; }))
  && (L::infinite || requires(const L& light, LightBounds& b) { { light.bounds(b) } -> std::same_as<bool>; });

// Every light kind. Adding one: its struct (with the members above), this
// list, and where it comes from (RenderScene's build, from a LightDesc).
template <LightKind... Kinds>
using LightVariant = std::variant<Kinds...>;
using Light = LightVariant<PointLight, SpotLight, DirectionalLight, ShapeLight, EnvironmentLight, UniformEnvironment>;

// Samples `light` from point p (and sets s.delta, s.infinite from its kind).
bool sample_light(const Light& light, Vec3f p, Vec2f u, LightSample& s);
// The density with which sample_light(light, p, ...) produces wi, reaching the light at q with normal n.
float light_pdf(const Light& light, Vec3f p, Vec3f wi, Vec3f q, Vec3f n);

class LightSet {
 public:
  LightSet() = default;
  // `shape_count`: the number of shapes (for the shape -> light table).
  // The lights are kept in the order delta before not, finite before infinite
  // (point and spot, directional, area, environment), each in the order given:
  // the choice among them and the classic integrator's sum over them follow
  // this order, and images depend on it bit for bit.
  // `sampler` chooses how the path integrator picks a light (see above).
  LightSet(std::vector<Light> lights, std::size_t shape_count, float scene_radius,
           LightSamplerType sampler = LightSamplerType::Bvh);

  bool empty() const { return lights_.empty(); }
  std::size_t size() const { return lights_.size(); }
  const Light& operator[](std::size_t i) const { return lights_[i]; }
  auto begin() const { return lights_.begin(); }
  auto end() const { return lights_.end(); }
  // The delta lights (point and spot, then directional): the first ones of the set.
  std::span<const Light> delta_lights() const { return {lights_.data(), delta_count_}; }

  // Picks a light for the shading point p with geometric normal n (n = 0: any
  // orientation), with its probability; -1 (pmf 0) if there is none, or if
  // no light can send p anything. With the power sampler p and n are not read.
  int choose(Vec3f p, Vec3f n, float u, float& pmf) const;
  // False when choose() does not depend on u: one light, or one light with
  // positive power among lights that can never be picked. The integrator then
  // spends no sample dimension on the choice (so adding a powerless light to
  // a scene leaves its image bit for bit as it was).
  bool needs_choice() const { return lights_.size() > 1 && only_ < 0; }
  // The lights the path integrator estimates each with its own sample at
  // every vertex, instead of choosing one (docs/path-tracing.md, "Every
  // infinite light at every vertex"): every light with positive power, when
  // there are 2 to kMaxEachLights of them and all are infinite (a sun and a
  // sky); else empty, and the integrator chooses one light per vertex.
  static constexpr std::size_t kMaxEachLights = 4;
  std::span<const int> each_lights() const { return each_; }
  // The probability that choose(p, n, ...) returns `light`: what a light found
  // by a BSDF ray from p is weighed with (multiple importance sampling).
  float pmf(Vec3f p, Vec3f n, int light) const;
  LightSamplerType sampler() const { return sampler_; }
  // The light BVH (empty with the power sampler or without bounded lights).
  const LightBvh& bvh() const { return bvh_; }

  // The area light of shape i placed directly, or of shape i placed by
  // `instance` (Hit::instance), or -1.
  int shape_light(uint32_t shape, uint32_t instance = kNoInstance) const {
    if (instance != kNoInstance) return instance_light(shape, instance);
    return shape < shape_light_.size() ? shape_light_[shape] : -1;
  }
  // The environment's light index (the infinite light that is not delta), or -1.
  int environment() const { return environment_; }
  // Radiance arriving along a ray that leaves the scene in direction `dir`:
  // the environment's, or `none` if there is no environment.
  RGB escaped_radiance(Vec3f dir, RGB none) const;

 private:
  std::vector<Light> lights_;
  LightSamplerType sampler_ = LightSamplerType::Bvh;
  Distribution1D selection_;  // the power sampler's
  int instance_light(uint32_t shape, uint32_t instance) const;
  // The bvh sampler: the bounded lights in `bvh_`; the others (infinite
  // lights, point lights without falloff) by `unbounded_`, in proportion to
  // their irradiance estimates, which sum to `unbounded_total_`.
  void build_bvh(const std::vector<float>& power, float scene_radius);
  // The share of the choice at (p, n) that goes to the unbounded lights
  // (against the light BVH's importance there); false if no light can send p
  // anything. choose() and pmf() both split by it.
  bool unbounded_share(Vec3f p, Vec3f n, float& share) const;
  LightBvh bvh_;
  Distribution1D unbounded_;
  float unbounded_total_ = 0.0f;
  std::vector<int> unbounded_light_;  // per entry of unbounded_: the light
  std::vector<int> unbounded_slot_;   // per light: its entry in unbounded_, or -1

  std::vector<int> shape_light_;  // empty when no shape emits
  // (instance << 32 | shape, light) for the area lights placed by instances, sorted.
  std::vector<std::pair<uint64_t, int>> instance_light_;
  int environment_ = -1;
  std::size_t delta_count_ = 0;
  int only_ = -1;  // the one light with positive power when exactly one has it, else -1
  std::vector<int> each_;  // see each_lights()
};

}  // namespace pt
