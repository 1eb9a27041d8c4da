#include "render/materials/rough_dielectric.h"

#include <cmath>

#include "render/materials/dielectric.h"

namespace pt {

bool RoughDielectricBsdf::half_vector(Vec3f wo, Vec3f wi, Vec3f& m, float& etap) const {
  if (wo.z == 0.0f || wi.z == 0.0f) return false;
  const bool reflection = wo.z * wi.z > 0.0f;
  etap = reflection ? 1.0f : (wo.z > 0.0f ? ior_ : 1.0f / ior_);
  const Vec3f h = wi * etap + wo;
  const float len = length(h);
  if (!(len > 0.0f) || !std::isfinite(len)) return false;
  m = h / len;
  if (m.z < 0.0f) m = -m;
  // Microfacets seen from behind by wo or wi scatter nothing.
  return dot(m, wi) * wi.z > 0.0f && dot(m, wo) * wo.z > 0.0f;
}

float RoughDielectricBsdf::fresnel(Vec3f wo, Vec3f m) const {
  const bool outside = wo.z > 0.0f;
  return fresnel_dielectric(std::fabs(dot(wo, m)), outside ? 1.0f : ior_, outside ? ior_ : 1.0f);
}

RGB RoughDielectricBsdf::f(Vec3f wo, Vec3f wi) const {
  Vec3f m;
  float etap;
  if (!half_vector(wo, wi, m, etap)) return {};
  const float F = fresnel(wo, m);
  const float DG = distribution_.D(m) * distribution_.G(wo, wi);
  const float cos_oi = std::fabs(wo.z * wi.z);
  if (wo.z * wi.z > 0.0f) return RGB(F * DG / (4.0f * cos_oi));  // reflection
  const float wim = dot(wi, m), wom = dot(wo, m);
  const float denom = wim + wom / etap;
  const float ft = (1.0f - F) * DG * std::fabs(wim * wom / (cos_oi * denom * denom));
  return tint_ * (ft / (etap * etap));
}

float RoughDielectricBsdf::pdf(Vec3f wo, Vec3f wi) const {
  Vec3f m;
  float etap;
  if (!half_vector(wo, wi, m, etap)) return 0.0f;
  const float F = fresnel(wo, m);
  const float wom = dot(wo, m);
  const float visible = distribution_.visible_D(wo, m);
  if (wo.z * wi.z > 0.0f) return visible / (4.0f * std::fabs(wom)) * F;
  const float wim = dot(wi, m);
  const float denom = wim + wom / etap;
  return visible * std::fabs(wim) / (denom * denom) * (1.0f - F);
}

bool RoughDielectricBsdf::sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const {
  if (wo.z == 0.0f || !std::isfinite(wo.z)) return false;
  const Vec3f m = distribution_.sample_visible(wo, u);  // on wo's side
  const float cos_i = dot(wo, m);
  if (!(cos_i > 0.0f)) return false;
  const float F = fresnel(wo, m);
  if (u_lobe < F) {
    s.wi = reflect(wo, m);
    if (!(wo.z * s.wi.z > 0.0f)) return false;
    s.eta2 = 1.0f;
  } else {
    // Refraction through m: eta_rel = eta_i / eta_t from wo's side.
    const float eta_rel = wo.z > 0.0f ? 1.0f / ior_ : ior_;
    const float sin2_t = eta_rel * eta_rel * std::max(0.0f, 1.0f - cos_i * cos_i);
    if (sin2_t >= 1.0f) return false;  // total internal reflection (F = 1: not chosen)
    const float cos_t = std::sqrt(1.0f - sin2_t);
    s.wi = normalize(-wo * eta_rel + m * (eta_rel * cos_i - cos_t));
    if (!(wo.z * s.wi.z < 0.0f)) return false;
    s.eta2 = 1.0f / (eta_rel * eta_rel);
  }
  // f and pdf of the direction found, from the same definitions as f() and pdf().
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return false;
  s.weight = f(wo, s.wi) * (std::fabs(s.wi.z) / s.pdf);
  s.delta = false;
  return true;
}

}  // namespace pt
