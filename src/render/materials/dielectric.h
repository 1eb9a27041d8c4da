// A smooth dielectric interface (glass): exact Fresnel reflection and
// refraction, total internal reflection, both directions delta lobes.
//
// Local frame: +z is the side of the surface's geometric normal ng, outside
// the medium (index 1); the medium of index `ior` is on the -z side. A wo with
// z > 0 therefore arrives from outside (the ray enters), z < 0 from inside
// (it leaves): the same rule as the classic integrator (docs/rendering.md).
// Sampling picks reflection with probability F and refraction with 1 - F, so
// both weights are 1 apart from the radiance scale 1/eta^2 of refraction
// (eta = eta_t / eta_i): radiance is compressed into a denser medium's
// narrower cone. With ior = 1, F = 0 and the ray passes straight through
// with weight 1 (times the tint: MTL's transmission filter Tf, white by default).
#pragma once

#include "render/materials/bsdf_sample.h"

namespace pt {

// Fresnel reflectance of an unpolarised wave going from index eta_i into
// eta_t, cos_i = cos(angle of incidence) in [0, 1]. 1 for total internal reflection.
float fresnel_dielectric(float cos_i, float eta_i, float eta_t);

// A BSDF kind of render/materials/bsdf.h (the smooth limit of the rough
// dielectric, rough_dielectric.h): delta lobes only.
struct DielectricBsdf {
  static constexpr bool kTransmits = true;
  float ior = 1.5f;
  RGB tint{1.0f, 1.0f, 1.0f};  // multiplies the refracted weight (Material::transmittance, MTL's Tf)

  bool delta_only() const { return true; }
  bool black() const { return false; }
  bool needs_lobe_choice() const { return true; }  // reflection or refraction
  RGB f(Vec3f, Vec3f) const { return {}; }
  float pdf(Vec3f, Vec3f) const { return 0.0f; }
  RGB f_diffuse(Vec3f, Vec3f) const { return {}; }
  bool sample(Vec3f wo, float u_lobe, Vec2f /*u*/, BsdfSample& s) const { return sample(wo, u_lobe, s); }
  // `u` picks reflection or refraction.
  bool sample(Vec3f wo, float u, BsdfSample& s) const;
  // The probability that sample() reflects (the Fresnel reflectance for wo).
  float reflectance(Vec3f wo) const;
};

}  // namespace pt
