// A rough dielectric interface (Walter, Marschner, Li and Torrance 2007,
// "Microfacet Models for Refraction through Rough Surfaces"), on the GGX
// distribution with visible-normal sampling, as pbrt-v4's DielectricBxDF.
//
// Local frame as the smooth dielectric's (dielectric.h): +z is outside (index
// 1), the medium of index `ior` below. With eta' = eta_t / eta_i the ratio of
// the indices on wi's and wo's sides (1 for a reflection) and the generalised
// half vector m = normalize(eta' wi + wo), turned to +z:
//
//   reflection:    f = F(wo . m) D(m) G(wo, wi) / (4 |cos_o cos_i|)
//   transmission:  f = (1 - F(wo . m)) D(m) G(wo, wi) |wi . m| |wo . m|
//                      / (|cos_o cos_i| (wi . m + wo . m / eta')^2) / eta'^2
//
// where the last 1/eta'^2 is the radiance scaling of refraction, as the smooth
// glass's weight (eta_i / eta_t)^2. Microfacets that face away from wo or wi
// scatter nothing. Sampling draws m from the visible normals seen from wo and
// reflects with probability F(wo . m), refracts otherwise; the density of wi
// is D_wo(m) times the Jacobian of m -> wi (1 / (4 |wo . m|) for a reflection,
// |wi . m| / (wi . m + wo . m / eta')^2 for a refraction) times that
// probability. Below kSmoothAlpha the material is the smooth DielectricBsdf
// (bsdf.cpp chooses), so roughness 0 is exactly the glass. A tint (MTL's Tf)
// multiplies the transmission (f and the weight; not the density).
// A BSDF kind of render/materials/bsdf.h.
#pragma once

#include "render/materials/bsdf_sample.h"
#include "render/materials/microfacet.h"

namespace pt {

class RoughDielectricBsdf {
 public:
  static constexpr bool kTransmits = true;

  // `tint`: what transmission is multiplied by (Material::transmittance; white: clear).
  RoughDielectricBsdf(float ior, float alpha_x, float alpha_y, RGB tint = RGB(1.0f)) noexcept
      : ior_(ior), distribution_(alpha_x, alpha_y), tint_(tint) {}

  bool delta_only() const { return false; }
  bool black() const { return false; }
  bool needs_lobe_choice() const { return true; }  // reflection or refraction
  RGB f_diffuse(Vec3f, Vec3f) const { return {}; }

  RGB f(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  bool sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const;

 private:
  // The generalised half vector of (wo, wi) turned to +z, and eta' (eta_t /
  // eta_i; 1 for a reflection). False where nothing scatters.
  bool half_vector(Vec3f wo, Vec3f wi, Vec3f& m, float& etap) const;
  // Fresnel reflectance at a microfacet, wo on its +z or -z side.
  float fresnel(Vec3f wo, Vec3f m) const;

  float ior_;
  TrowbridgeReitz distribution_;
  RGB tint_;
};

}  // namespace pt
