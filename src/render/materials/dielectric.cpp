#include "render/materials/dielectric.h"

#include <algorithm>
#include <cmath>

namespace pt {

float fresnel_dielectric(float cos_i, float eta_i, float eta_t) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float eta = eta_i / eta_t;
  // cos_t^2 = 1 - eta^2 sin_i^2 = 1 - eta^2 + eta^2 cos_i^2: for eta = 1 this
  // is cos_i^2 exactly, so equal indices reflect nothing (F = 0 exactly).
  const float cos2_t = std::fma(eta * eta, cos_i * cos_i, 1.0f - eta * eta);
  if (cos2_t <= 0.0f) return 1.0f;  // total internal reflection
  const float cos_t = std::sqrt(cos2_t);
  const float r_s = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  const float r_p = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return 0.5f * (r_s * r_s + r_p * r_p);
}

float DielectricBsdf::reflectance(Vec3f wo) const {
  const bool entering = wo.z > 0.0f;
  return fresnel_dielectric(std::fabs(wo.z), entering ? 1.0f : ior, entering ? ior : 1.0f);
}

bool DielectricBsdf::sample(Vec3f wo, float u, BsdfSample& s) const {
  if (wo.z == 0.0f || !std::isfinite(wo.z)) return false;
  const bool entering = wo.z > 0.0f;
  const float eta_i = entering ? 1.0f : ior, eta_t = entering ? ior : 1.0f;
  const float cos_i = std::min(std::fabs(wo.z), 1.0f);
  const float F = fresnel_dielectric(cos_i, eta_i, eta_t);
  s.delta = true;
  if (u < F) {
    s.wi = {-wo.x, -wo.y, wo.z};
    s.weight = RGB(1.0f);
    s.eta2 = 1.0f;
    s.pdf = F;
    return true;
  }
  // Refraction: t = -eta_rel wo + (eta_rel cos_i - cos_t) n, n on wo's side.
  const float eta_rel = eta_i / eta_t;
  // cos_t^2 = 1 - eta^2 (1 - cos_i^2), written so that eta = 1 gives cos_t = cos_i exactly.
  const float eta2 = eta_rel * eta_rel;
  const float cos_t = std::sqrt(std::max(0.0f, std::fma(eta2, cos_i * cos_i, 1.0f - eta2)));
  const float side = entering ? 1.0f : -1.0f;
  const Vec3f n(0.0f, 0.0f, side);
  s.wi = normalize(-wo * eta_rel + n * (eta_rel * cos_i - cos_t));
  s.weight = tint * (eta_rel * eta_rel);  // 1 / (eta_t / eta_i)^2
  s.eta2 = 1.0f / (eta_rel * eta_rel);
  s.pdf = 1.0f - F;
  return true;
}

}  // namespace pt
