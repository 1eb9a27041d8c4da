// The classic recursive (Whitted-style) integrator of the course scene files:
// Blinn-Phong direct lighting from point lights with hard shadows, mirror
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

// The classic shading of each delta light at one surface point: ambient-free
// Blinn-Phong with hard shadows, added to `result`. Lights that are not delta
// (area lights, the environment) are not shaded: the integrator's rays see
// them (a material's emission, the escaped radiance).
// `n` is the shading normal facing the viewer, `wo` the unit direction to the viewer.
struct ClassicShading {
  const RenderScene& scene;
  const Material& m;
  const SurfaceGeometry& geo;
  Vec3f n, wo;
  RGB& result;

  void operator()(const PointLight& light) const {
    const Vec3f to_light = light.position - geo.p;
    const float r2 = length_squared(to_light);
    if (!(r2 > 0.0f)) return;
    const Vec3f l = to_light / std::sqrt(r2);
    const float cos_theta = dot(n, l);
    if (cos_theta <= 0.0f) return;
    if (scene.occluded(spawn_ray_to(geo, light.position))) return;
    const float falloff = light.falloff(r2);
    result += m.kd * cos_theta * falloff * (m.diffuse_at(geo.uv) * light.intensity);
    if (m.ks > 0.0f) {
      const Vec3f h = normalize(l + wo);
      const float spec = std::pow(std::max(0.0f, dot(n, h)), m.exponent);
      result += m.ks * spec * falloff * (m.specular * light.specular_intensity);
    }
  }

  // Directional lights deliver irradiance E; in the classic units above (where a
  // point light's I / r^2 is irradiance / pi) that is E / pi.
  void operator()(const DirectionalLight& light) const {
    const Vec3f l = -light.direction;
    const float cos_theta = dot(n, l);
    if (cos_theta <= 0.0f) return;
    if (scene.occluded(spawn_ray(geo, l))) return;
    const RGB e = light.irradiance * kInvPi;
    result += m.kd * cos_theta * (m.diffuse_at(geo.uv) * e);
    if (m.ks > 0.0f) {
      const float spec = std::pow(std::max(0.0f, dot(n, normalize(l + wo))), m.exponent);
      result += m.ks * spec * (m.specular * e);
    }
  }

  // Not reached: direct_lighting() visits only the delta lights.
  template <class L>
    requires(!L::delta)
  void operator()(const L&) const {}
};

// Direct light from every delta light (the light set keeps point lights
// before directional ones: the sum's order is fixed).
RGB direct_lighting(const RenderScene& scene, const Intersection& isect, Vec3f n, Vec3f wo) {
  RGB result;
  const ClassicShading shade{scene, *isect.material, isect.geo, n, wo, result};
  for (const Light& light : scene.lights.delta_lights()) std::visit(shade, light);
  return result;
}

// Refraction direction of unit `d` through a surface with unit normal `n`
// facing the incoming ray (dot(d, n) < 0); eta = eta_i / eta_t; cos_t > 0.
Vec3f refract_dir(Vec3f d, Vec3f n, float eta, float cos_i, float cos_t) {
  return normalize(d * eta + n * (eta * cos_i - cos_t));
}

class Whitted {
 public:
  Whitted(const RenderScene& scene, int max_depth) : scene_(scene), max_depth_(max_depth) {}

  RGB trace(const Ray& ray, int depth) const {
    Intersection isect;
    if (!scene_.intersect(ray, isect))
      return depth == 0 ? scene_.camera_ray_escaped(ray) : scene_.escaped_radiance(ray.dir);
    const Material& m = *isect.material;
    if (m.glass()) return dielectric(ray, isect, depth);

    // Both normals flipped to the viewer's side of the surface.
    const Vec3f wo = -ray.dir;
    Vec3f n = isect.geo.ns;
    if (dot(isect.geo.ng, wo) < 0.0f) n = -n;

    RGB local = m.emission + direct_lighting(scene_, isect, n, wo);
    if (m.reflectivity <= 0.0f) return local;
    RGB mirrored;  // beyond the depth limit a ray carries nothing
    if (depth < max_depth_) mirrored = trace(spawn_ray(isect.geo, reflect(wo, n)), depth + 1);
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
      result += trace(spawn_ray(isect.geo, t), depth + 1) * (1.0f - F);
    }
    return result;
  }

  const RenderScene& scene_;
  int max_depth_;
};

class WhittedIntegrator final : public Integrator {
 public:
  explicit WhittedIntegrator(const IntegratorSettings& settings) : settings_(settings) {}

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    const Whitted whitted(scene, settings_.max_depth);
    render_pixels(scene, film, pool, settings_, [&](const Ray& ray) { return whitted.trace(ray, 0); });
  }

 private:
  IntegratorSettings settings_;
};

}  // namespace

RGB whitted_radiance(const RenderScene& scene, const Ray& ray, int max_depth) {
  return Whitted(scene, max_depth).trace(ray, 0);
}

std::unique_ptr<Integrator> make_whitted_integrator(const IntegratorSettings& settings) {
  return std::make_unique<WhittedIntegrator>(settings);
}

}  // namespace pt
