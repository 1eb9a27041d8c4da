// "path": unidirectional path tracing with next-event estimation and multiple
// importance sampling (docs/path-tracing.md).
//
// At every vertex: emission found by the ray is added with its MIS weight;
// one light, chosen for the vertex (LightSet::choose), is sampled (next-event estimation), or,
// where the lights are a few infinite ones (a sun and a sky, LightSet::each_lights), each of them
// is, and combined with BSDF sampling by the power heuristic, except delta lights (only NEE can
// find them) and delta lobes (only BSDF sampling can); then the BSDF picks the
// next direction (or, with render.path_guiding, a mixture of the BSDF and the
// learned path guide, render/guiding/path_guide.h). Russian roulette starts after `roulette_depth` bounces, with
// survival probability min(1, max channel of the throughput / threshold), and
// divides by it, so it is unbiased. `max_depth` bounds the number of bounces: a path sees
// emitters and lights across at most max_depth scattering events.
#include <algorithm>
#include <cmath>
#include <memory>
#include <span>

#include "core/sampling.h"
#include "geometry/shapes.h"
#include "render/guiding/light_guide.h"
#include "render/guiding/path_guide.h"
#include "render/integrators/builtin.h"
#include "render/integrators/path_aov.h"
#include "render/integrators/render_loop.h"
#include "render/materials/bsdf.h"
#include "render/render_scene.h"

namespace pt {

namespace {

// The lights that next-event estimation samples each at every vertex (none:
// it chooses one light per vertex).
std::span<const int> lights_estimated_each(const RenderScene& scene, const IntegratorSettings& settings) {
  return settings.estimate_each_light ? scene.lights.each_lights() : std::span<const int>();
}

class PathTracer {
 public:
  PathTracer(const RenderScene& scene, const IntegratorSettings& settings, const LightGuide& guide,
             const PathGuide& path_guide)
      : scene_(scene),
        lights_(scene.lights),
        guide_(guide),
        path_guide_(path_guide),
        max_depth_(std::max(0, settings.max_depth)),
        clamp_(settings.clamp),
        strategy_(settings.light_strategy),
        each_(lights_estimated_each(scene, settings)),
        roulette_depth_(std::max(1, settings.roulette_depth)),
        inv_roulette_threshold_(settings.roulette_threshold > 0.0f ? 1.0f / settings.roulette_threshold : 1.0f) {}

  // `aov`, when not null, receives the lighting split (path_aov.h).
  CameraEstimate radiance(const CameraRay& camera_ray, Sampler& sampler, AovSample* aov = nullptr) const {
    Ray ray = camera_ray;
    PathAovRecorder rec(aov);
    bool camera_hit = false;
    RGB L, beta(1.0f);
    bool specular = true;  // the camera ray, or a delta lobe: no light sampling could have found this
    float prev_pdf = 0.0f;
    LightGuide::Site prev_site;  // the previous vertex: where the light choice a BSDF ray competes with was made
    Vec3f prev_n;
    float eta2 = 1.0f;  // product of the refraction radiance scales along the path
    for (int depth = 0;; ++depth) {
      Intersection isect;
      if (!scene_.intersect(ray, isect, depth == 0 ? camera_ray.differential_or_null() : nullptr)) {
        const RGB le = depth == 0 ? scene_.camera_ray_escaped(ray) : scene_.escaped_radiance(ray.dir);
        if (!le.is_black()) {
          const RGB term = beta * le * escape_weight(ray.dir, specular, prev_pdf, prev_site, prev_n);
          L += term;
          if (rec.active()) rec.found(depth, term);
        }
        break;
      }
      camera_hit = camera_hit || depth == 0;
      const Material& m = *isect.material;
      const Vec3f wo = -ray.dir;
      if (m.emits()) {
        const RGB le = m.emitted(isect.geo.ng, wo, tex_coord(isect.geo));
        if (!le.is_black()) {
          const RGB term = beta * le * emitter_weight(isect, ray.dir, specular, prev_pdf, prev_site, prev_n);
          L += term;
          if (rec.active()) rec.found(depth, term);
        }
      }
      if (depth >= max_depth_) break;

      const Bsdf bsdf(m, isect.geo, wo);
      if (bsdf.black()) break;
      if (rec.active() && depth == 0) rec.first_vertex(bsdf);
      const LightGuide::Site site = guide_.site(isect.geo.p, LightGuide::sky_normal(bsdf, wo));
      const PathGuide::Leaf* region = bsdf.delta_only() ? nullptr : path_guide_.leaf(isect.geo.p, bsdf.shading_normal());
      if (!bsdf.delta_only()) L += next_event(isect, site, region, bsdf, wo, beta, depth, sampler, rec);

      BsdfSample bs;
      // A BSDF with one lobe has nothing to choose: no sample dimension for it.
      const float u_lobe = bsdf.needs_lobe_choice() ? sampler.get_1d() : 0.0f;
      if (!PathGuide::sample_bounce(bsdf, region, wo, u_lobe, sampler.get_2d(), bs)) break;
      if (rec.active() && depth == 0) rec.first_bounce(wo, bs);
      beta *= bs.weight;
      eta2 *= bs.eta2;
      if (beta.is_black()) break;
      specular = bs.delta;
      prev_pdf = bs.pdf;
      prev_site = site;
      prev_n = isect.geo.ng;
      ray = spawn_ray(isect.geo, bs.wi);

      if (depth + 1 >= roulette_depth_) {
        const float survive = (beta * eta2).max_component() * inv_roulette_threshold_;
        if (survive < 1.0f) {
          if (sampler.get_1d() >= survive) break;
          beta *= 1.0f / survive;
        }
      }
    }
    if (clamp_ > 0.0f) {
      const float peak = L.max_component();
      if (peak > clamp_) {
        L *= clamp_ / peak;
        if (rec.active()) rec.scale(clamp_ / peak);
      }
    }
    return {L, camera_hit};
  }

 private:
  // The MIS weight of the sky sampled with density `a` against the other
  // strategy's `b`, at the vertex `at`: where the light guide weighs the sky's
  // bins by the normal (site(p, n)), the balance heuristic, else the power
  // heuristic. Both strategies of a vertex ask with the same site, so the
  // weights still sum to one. (On Sponza under its sky the balance heuristic
  // had 0.92x the variance of the power heuristic; docs/bench/sponza-s17.md.)
  static float sky_weight(const LightGuide::Site& at, float a, float b) {
    return at.environment == nullptr ? power_heuristic(a, b) : balance_heuristic(a, b);
  }

  // MIS weight of an environment seen through a BSDF-sampled direction.
  // The light choice's probability is the one at the previous vertex (prev_p, prev_n).
  float escape_weight(Vec3f dir, bool specular, float prev_pdf, const LightGuide::Site& prev, Vec3f prev_n) const {
    const int env = lights_.environment();
    if (specular || env < 0 || strategy_ == LightStrategy::BsdfOnly) return 1.0f;
    if (strategy_ == LightStrategy::LightOnly) return 0.0f;
    // An infinite light reads only the direction.
    const Vec3f none;
    const float pdf = choice_pmf(prev, prev_n, env) * guide_.pdf(env, prev, dir, none, none);
    return sky_weight(prev, prev_pdf, pdf);
  }

  // MIS weight of an emitter hit through a BSDF-sampled direction.
  float emitter_weight(const Intersection& isect, Vec3f dir, bool specular, float prev_pdf,
                       const LightGuide::Site& prev, Vec3f prev_n) const {
    const int index = lights_.shape_light(isect.hit.shape, isect.hit.instance);
    if (specular || index < 0 || strategy_ == LightStrategy::BsdfOnly) return 1.0f;
    if (strategy_ == LightStrategy::LightOnly) return 0.0f;
    const Light& light = lights_[static_cast<std::size_t>(index)];
    const float pdf = choice_pmf(prev, prev_n, index) * light_pdf(light, prev.p, dir, isect.geo.p, isect.geo.ng);
    return power_heuristic(prev_pdf, pdf);
  }

  // Next-event estimation at a vertex reached with throughput beta: its
  // contribution (each term also given to the AOV split).
  RGB next_event(const Intersection& isect, const LightGuide::Site& site, const PathGuide::Leaf* region,
                 const Bsdf& bsdf, Vec3f wo, RGB beta, int depth, Sampler& sampler, PathAovRecorder& rec) const {
    // One light's estimate, weighted by beta and given to the AOV split.
    const auto term = [&](RGB estimate, Vec3f wi_light) {
      const RGB t = beta * estimate;
      if (rec.active() && !t.is_black()) rec.light(depth, t, wo, wi_light);
      return t;
    };
    Vec3f wi_light;
    if (each_.empty()) {
      if (lights_.empty()) return {};
      const RGB estimate = direct_light(isect, site, region, bsdf, wo, sampler, &wi_light);
      return term(estimate, wi_light);
    }
    RGB sum;
    for (const int index : each_) {  // every light, each with its own sample and shadow ray
      const Vec2f u = sampler.get_2d();
      const RGB estimate = sample_one(isect, site, region, bsdf, wo, index, 1.0f, u, &wi_light);
      sum += term(estimate, wi_light);
    }
    return sum;
  }

  // The probability that next-event estimation at `at` samples `light`:
  // 1 where every light is sampled at every vertex, else that of its choice.
  float choice_pmf(const LightGuide::Site& at, Vec3f n, int light) const {
    return each_.empty() ? guide_.pmf(at, n, light) : 1.0f;
  }

  // Next-event estimation: one light, chosen for this point and normal,
  // sampled at one point; or, where each_ is not empty, each of those lights.
  // `wi_out`, when not null, receives the sampled light direction (for the AOV split).
  RGB direct_light(const Intersection& isect, const LightGuide::Site& site, const PathGuide::Leaf* region,
                   const Bsdf& bsdf, Vec3f wo, Sampler& sampler, Vec3f* wi_out = nullptr) const {
    // Where there is nothing to choose (one light that can be picked), no
    // sample dimension is spent on the choice.
    const float u_light = lights_.needs_choice() ? sampler.get_1d() : 0.0f;
    const Vec2f u = sampler.get_2d();
    float pmf = 0.0f;
    const int index = guide_.choose(site, isect.geo.ng, u_light, pmf);
    if (index < 0 || !(pmf > 0.0f)) return {};
    return sample_one(isect, site, region, bsdf, wo, index, pmf, u, wi_out);
  }

  // The light `index`, sampled with u and weighed as chosen with probability pmf.
  RGB sample_one(const Intersection& isect, const LightGuide::Site& site, const PathGuide::Leaf* region,
                 const Bsdf& bsdf, Vec3f wo, int index, float pmf, Vec2f u, Vec3f* wi_out) const {
    LightSample ls;
    if (!guide_.sample(index, site, u, ls)) return {};
    if (ls.L.is_black() || !(ls.pdf > 0.0f)) return {};
    if (!ls.delta && strategy_ == LightStrategy::BsdfOnly) return {};
    if (wi_out != nullptr) *wi_out = ls.wi;
    const RGB f = bsdf.f(wo, ls.wi);
    if (f.is_black()) return {};
    if (scene_.occluded(light_shadow_ray(isect.geo, ls))) return {};
    const float light_pdf = pmf * ls.pdf;
    float w = 1.0f;
    if (!ls.delta && strategy_ != LightStrategy::LightOnly) {
      const float bounce_pdf = PathGuide::bounce_pdf(bsdf, region, wo, ls.wi);
      w = index == lights_.environment() ? sky_weight(site, light_pdf, bounce_pdf) : power_heuristic(light_pdf, bounce_pdf);
    }
    const float cos_i = std::fabs(dot(ls.wi, bsdf.shading_normal()));
    return f * ls.L * (cos_i * w / light_pdf);
  }

  const RenderScene& scene_;
  const LightSet& lights_;
  const LightGuide& guide_;  // the light choice and sampling (LightSet's own when guiding is off)
  const PathGuide& path_guide_;  // the bounces' guide (inactive when path guiding is off)
  int max_depth_;
  float clamp_;
  LightStrategy strategy_;
  // The lights estimated each at every vertex (LightSet::each_lights), or
  // none: one is chosen per vertex.
  std::span<const int> each_;
  int roulette_depth_;
  float inv_roulette_threshold_;
};

class PathIntegrator final : public Integrator {
 public:
  explicit PathIntegrator(const IntegratorSettings& settings) : settings_(settings), filter_(settings.filter) {}

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    const std::shared_ptr<const Guides> guides = learned(scene, pool);
    const PathTracer tracer(scene, settings_, guides->light, guides->path);
    render_samples(scene, film, pool, settings_, make_sampler(settings_.sampler, settings_.spp, settings_.seed),
                   filter_,
                   [&](const CameraRay& ray, Sampler& sampler, AovSample* aov) { return tracer.radiance(ray, sampler, aov); });
  }

 private:
  // Learned before the samples and frozen (render.light_guiding, light_guide.h;
  // render.path_guiding, path_guide.h): once per render where the settings
  // carry a RenderCache, else for this call.
  struct Guides {
    LightGuide light;
    PathGuide path;
  };
  std::shared_ptr<const Guides> learned(const RenderScene& scene, WorkerPool& pool) const {
    if (settings_.cache != nullptr && settings_.cache->slot)
      return std::static_pointer_cast<const Guides>(settings_.cache->slot);
    const IntegratorSettings& s = settings_;
    auto guides = std::make_shared<const Guides>(Guides{
        s.light_guiding > 0 ? LightGuide::learn(scene, pool, s.light_guiding, s.max_depth, s.seed,
                                                lights_estimated_each(scene, s).empty())
                            : LightGuide(scene.lights),
        s.path_guiding > 0 ? PathGuide::learn(scene, pool, s.path_guiding, s.max_depth, s.seed) : PathGuide()});
    if (settings_.cache != nullptr) settings_.cache->slot = guides;
    return guides;
  }

  IntegratorSettings settings_;
  PixelFilter filter_;
};

}  // namespace

std::unique_ptr<Integrator> make_path_integrator(const IntegratorSettings& settings) {
  return std::make_unique<PathIntegrator>(settings);
}

}  // namespace pt
