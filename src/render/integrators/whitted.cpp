// The classic recursive (Whitted-style) integrator of the course scene files:
// Blinn-Phong direct lighting from point lights with hard shadows and from
// area lights (emissive shapes) with soft shadows, mirror
// reflection blended by the material's reflectivity, and Fresnel-weighted
// reflection/refraction for dielectrics. Equations: docs/rendering.md.
#include <algorithm>
#include <cmath>

#include "geometry/shapes.h"
#include "render/integrators/builtin.h"
#include "render/integrators/render_loop.h"
#include "render/materials/dielectric.h"
#include "render/render_scene.h"

namespace pt {

namespace {

// The diffuse and specular parts of the direct light, kept apart only for the
// AOVs (their sum in shading order is the beauty's term).
struct DirectParts {
  RGB diffuse, specular;
};

// The classic shading of each delta light at one surface point: Blinn-Phong
// with hard shadows, added to `result` (and, when `parts` is set, to its
// diffuse or specular part); area lights through shade_area(). The
// environment is not shaded: the integrator's rays see it (the escaped
// radiance). The ambient term is the caller's.
// `n` is the shading normal facing the viewer, `wo` the unit direction to the viewer.
struct ClassicShading {
  const RenderScene& scene;
  const Material& m;
  const SurfaceGeometry& geo;
  Vec3f n, wo;
  RGB& result;
  DirectParts* parts;

  void add(RGB term, bool diffuse) const {
    result += term;
    if (parts != nullptr) (diffuse ? parts->diffuse : parts->specular) += term;
  }

  void operator()(const PointLight& light) const {
    shade_from(light.position, light.intensity, light.specular_intensity,
               [&](float r2, Vec3f) { return light.falloff(r2); });
  }

  // A spot light: a point light times its classic cone factor (render/lights/spot_light.h).
  void operator()(const SpotLight& light) const {
    shade_from(light.position, light.intensity, light.specular_intensity, [&](float r2, Vec3f l) {
      const float cone = light.classic_factor(dot(-l, light.axis));
      return cone > 0.0f ? cone / r2 : 0.0f;
    });
  }

  // A light at `position`; falloff(r2, l) is the factor on both intensities
  // (0: nothing arrives, no shadow ray).
  template <class Falloff>
  void shade_from(Vec3f position, const RGB& intensity, const RGB& specular_intensity, Falloff falloff_of) const {
    const Vec3f to_light = position - geo.p;
    const float r2 = length_squared(to_light);
    if (!(r2 > 0.0f)) return;
    const Vec3f l = to_light / std::sqrt(r2);
    const float cos_theta = dot(n, l);
    if (cos_theta <= 0.0f) return;
    const float falloff = falloff_of(r2, l);
    if (falloff == 0.0f) return;
    if (scene.occluded(spawn_ray_to(geo, position))) return;
    shade_lobes(l, cos_theta, falloff, intensity, specular_intensity);
  }

  // The Blinn-Phong lobes of light arriving from unit direction l (cos_theta =
  // dot(n, l) > 0, unoccluded), each intensity times `falloff`.
  void shade_lobes(Vec3f l, float cos_theta, float falloff, const RGB& intensity, const RGB& specular_intensity) const {
    add(m.kd * cos_theta * falloff * (m.diffuse_at(tex_coord(geo)) * intensity), true);
    if (m.ks > 0.0f) {
      const Vec3f h = normalize(l + wo);
      const float spec = std::pow(std::max(0.0f, dot(n, h)), m.exponent);
      add(m.ks * spec * falloff * (m.specular * specular_intensity), false);
    }
  }

  // An area light (an emissive shape), sampled at `count` points by its own
  // sample() (the path integrator's), stratified on a k x k grid when count is
  // k^2, soft shadows from one shadow ray each. Each sample acts as a point
  // light at the sampled point with I / r^2 = L / (pi count pdf), pdf the
  // sample's solid-angle density: then the diffuse term kd Cd (1/count) sum
  // L cos / (pi pdf) estimates kd Cd E / pi, E the light's irradiance, the
  // classic units of the point lights above (docs/rendering.md).
  void shade_area(const Light& light, int count, Sampler& sampler) const {
    const int k = grid_side(count);
    const float inv_k = k > 0 ? 1.0f / static_cast<float>(k) : 1.0f;
    const float weight = kInvPi / static_cast<float>(count);
    for (int i = 0; i < count; ++i) {
      Vec2f u = sampler.get_2d();
      if (k > 0) u = Vec2f((static_cast<float>(i % k) + u.x) * inv_k, (static_cast<float>(i / k) + u.y) * inv_k);
      LightSample s;
      if (!sample_light(light, geo.p, u, s) || s.L.is_black() || !(s.pdf > 0.0f)) continue;
      const float cos_theta = dot(n, s.wi);
      if (cos_theta <= 0.0f) continue;
      if (scene.occluded(spawn_ray_to(geo, offset_ray_origin(s.p_light, s.n_light, -s.wi)))) continue;
      shade_lobes(s.wi, cos_theta, weight / s.pdf, s.L, s.L);
    }
  }

  // k if count = k^2 (k > 1), else 0.
  static int grid_side(int count) {
    int k = 1;
    while ((k + 1) * (k + 1) <= count) ++k;
    return k > 1 && k * k == count ? k : 0;
  }

  // Directional lights deliver irradiance E; in the classic units above (where a
  // point light's I / r^2 is irradiance / pi) that is E / pi.
  void operator()(const DirectionalLight& light) const {
    const Vec3f l = -light.direction;
    const float cos_theta = dot(n, l);
    if (cos_theta <= 0.0f) return;
    if (scene.occluded(spawn_ray(geo, l))) return;
    const RGB e = light.irradiance * kInvPi;
    add(m.kd * cos_theta * (m.diffuse_at(tex_coord(geo)) * e), true);
    if (m.ks > 0.0f) {
      const float spec = std::pow(std::max(0.0f, dot(n, normalize(l + wo))), m.exponent);
      add(m.ks * spec * (m.specular * e), false);
    }
  }

  // Not reached: direct_lighting() visits only the delta lights.
  template <class L>
    requires(!L::delta)
  void operator()(const L&) const {}
};

// Direct light from every delta light (the light set keeps point and spot
// lights before directional ones: the sum's order is fixed).
RGB direct_lighting(const RenderScene& scene, const Intersection& isect, Vec3f n, Vec3f wo, DirectParts* parts) {
  RGB result;
  const ClassicShading shade{scene, *isect.material, isect.geo, n, wo, result, parts};
  for (const Light& light : scene.lights.delta_lights()) std::visit(shade, light);
  return result;
}

// The classic integrator's samples per shading point of an area light whose
// material does not say (a Path of Light area light's "samples" does).
constexpr int kDefaultAreaLightSamples = 16;

// Direct light from every area light (emissive shape), added to `direct` (and
// `parts`) after the delta lights' (the set keeps area lights after them).
void area_lighting(const RenderScene& scene, const Intersection& isect, Vec3f n, Vec3f wo, Sampler& sampler,
                   RGB& direct, DirectParts* parts) {
  const ClassicShading shade{scene, *isect.material, isect.geo, n, wo, direct, parts};
  for (std::size_t i = scene.lights.delta_lights().size(); i < scene.lights.size(); ++i) {
    const ShapeLight* area = std::get_if<ShapeLight>(&scene.lights[i]);
    if (area == nullptr) continue;
    const int count = area->material().light_samples;
    shade.shade_area(scene.lights[i], count > 0 ? count : kDefaultAreaLightSamples, sampler);
  }
}

// Refraction direction of unit `d` through a surface with unit normal `n`
// facing the incoming ray (dot(d, n) < 0); eta = eta_i / eta_t; cos_t > 0.
Vec3f refract_dir(Vec3f d, Vec3f n, float eta, float cos_i, float cos_t) {
  return normalize(d * eta + n * (eta * cos_i - cos_t));
}

class Whitted {
 public:
  // `sampler` gives the area lights' sample points (render_loop.h: reproducible per pixel and sample).
  Whitted(const RenderScene& scene, int max_depth, Sampler& sampler)
      : scene_(scene), max_depth_(max_depth), sampler_(sampler) {}

  // `aov` (the camera ray's only, else null) receives the terms of the
  // result: emission (the surface's own, or what the ray sees leaving the
  // scene), ambient, diffuse and specular direct light at the first hit, and
  // specular_indirect (what its mirror reflection or refraction brings).
  // `differential`: the camera ray's (depth 0), or null. `hit` (the camera
  // ray's only) is set when the ray hits a surface.
  RGB trace(const Ray& ray, int depth, AovSample* aov = nullptr, const RayDifferential* differential = nullptr,
            bool* hit = nullptr) const {
    Intersection isect;
    const bool found = scene_.intersect(ray, isect, differential);
    if (hit != nullptr) *hit = found;
    if (!found) {
      const RGB seen = depth == 0 ? scene_.camera_ray_escaped(ray) : scene_.escaped_radiance(ray.dir);
      if (aov != nullptr) aov->emission += seen;
      return seen;
    }
    const Material& m = *isect.material;
    if (m.glass()) {
      const RGB through = dielectric(ray, isect, depth);
      if (aov != nullptr) aov->specular_indirect += through;
      return through;
    }

    // Both normals flipped to the viewer's side of the surface.
    const Vec3f wo = -ray.dir;
    Vec3f n = isect.geo.ns;
    if (dot(isect.geo.ng, wo) < 0.0f) n = -n;

    DirectParts parts;
    RGB direct = direct_lighting(scene_, isect, n, wo, aov != nullptr ? &parts : nullptr);
    area_lighting(scene_, isect, n, wo, sampler_, direct, aov != nullptr ? &parts : nullptr);
    RGB ambient;
    RGB local;
    const RGB emission = m.emission_texture ? m.emission_at(tex_coord(isect.geo)) : m.emission;
    if (scene_.ambient.is_black()) {
      local = emission + direct;
    } else {
      ambient = m.ka * (m.diffuse_at(tex_coord(isect.geo)) * scene_.ambient);
      local = emission + ambient + direct;
    }
    if (m.reflectivity <= 0.0f) {
      if (aov != nullptr) record(*aov, emission, ambient, parts, 1.0f);
      return local;
    }
    RGB mirrored;  // beyond the depth limit a ray carries nothing
    if (depth < max_depth_) mirrored = trace(spawn_ray(isect.geo, reflect(wo, n)), depth + 1);
    if (aov != nullptr) {
      record(*aov, emission, ambient, parts, 1.0f - m.reflectivity);
      aov->specular_indirect += mirrored * m.reflectivity;
    }
    return local * (1.0f - m.reflectivity) + mirrored * m.reflectivity;
  }

 private:
  // Smooth dielectric: F * reflected + (1 - F) * transmitted, F exact Fresnel.
  // The side is decided by the geometric normal: the ray enters when dot(dir, ng) < 0.
  RGB dielectric(const Ray& ray, const Intersection& isect, int depth) const {
    if (depth >= max_depth_) return RGB();
    const Material& m = *isect.material;
    const bool entering = dot(ray.dir, isect.geo.ng) < 0.0f;
    const Vec3f n = entering ? isect.geo.ns : -isect.geo.ns;  // faces the incoming ray
    const float eta_i = entering ? 1.0f : m.ior;
    const float eta_t = entering ? m.ior : 1.0f;
    const float cos_i = std::clamp(-dot(ray.dir, n), 0.0f, 1.0f);
    const float F = fresnel_dielectric(cos_i, eta_i, eta_t);

    RGB result = trace(spawn_ray(isect.geo, reflect(-ray.dir, n)), depth + 1) * F;
    if (F < 1.0f) {
      const float eta = eta_i / eta_t;
      const float sin2_t = eta * eta * std::max(0.0f, 1.0f - cos_i * cos_i);
      const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
      const Vec3f t = refract_dir(ray.dir, n, eta, cos_i, cos_t);
      result += trace(spawn_ray(isect.geo, t), depth + 1) * (m.transmittance * (1.0f - F));
    }
    return result;
  }

  static void record(AovSample& aov, RGB emission, RGB ambient, const DirectParts& parts, float weight) {
    aov.emission += emission * weight;
    aov.ambient += ambient * weight;
    aov.diffuse_direct += parts.diffuse * weight;
    aov.specular_direct += parts.specular * weight;
  }

  const RenderScene& scene_;
  int max_depth_;
  Sampler& sampler_;
};

class WhittedIntegrator final : public Integrator {
 public:
  explicit WhittedIntegrator(const IntegratorSettings& settings) : settings_(settings) {}

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    render_pixels_with_split(scene, film, pool, settings_, [&](const CameraRay& ray, Sampler& sampler, AovSample* aov) {
      CameraEstimate e;
      e.radiance = Whitted(scene, settings_.max_depth, sampler).trace(ray, 0, aov, ray.differential_or_null(), &e.hit);
      return e;
    });
  }

 private:
  IntegratorSettings settings_;
};

}  // namespace

RGB whitted_radiance(const RenderScene& scene, const Ray& ray, int max_depth) {
  Sampler sampler = StratifiedPixelSampler(1, 0, 1);
  sampler.start_pixel_sample(0, 0, 0);
  return Whitted(scene, max_depth, sampler).trace(ray, 0);
}

std::unique_ptr<Integrator> make_whitted_integrator(const IntegratorSettings& settings) {
  return std::make_unique<WhittedIntegrator>(settings);
}

}  // namespace pt
