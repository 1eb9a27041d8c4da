#include "render/materials/blinn_phong.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace pt {

namespace {

// Density of the half vector h (local z = normal): (e + 1)/(2 pi) cos^e.
float half_vector_pdf(float cos_h, float e) {
  return cos_h > 0.0f ? (e + 1.0f) * kInv2Pi * std::pow(cos_h, e) : 0.0f;
}

}  // namespace

float BlinnPhongLobe::f(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
  const Vec3f sum = wo + wi;
  const float len = length(sum);
  if (!(len > 0.0f)) return 0.0f;
  const Vec3f h = sum / len;
  const float wo_h = dot(wo, h);
  if (!(wo_h > 0.0f)) return 0.0f;
  return (exponent + 1.0f) * (0.125f * kInvPi) * std::pow(std::max(h.z, 0.0f), exponent) /
         (wo_h * std::max(wo.z, wi.z));
}

float BlinnPhongLobe::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
  const Vec3f sum = wo + wi;
  const float len = length(sum);
  if (!(len > 0.0f)) return 0.0f;
  const Vec3f h = sum / len;
  const float wo_h = dot(wo, h);
  if (!(wo_h > 0.0f)) return 0.0f;
  return half_vector_pdf(h.z, exponent) / (4.0f * wo_h);
}

bool BlinnPhongLobe::sample(Vec3f wo, Vec2f u, BsdfSample& s) const {
  if (!(wo.z > 0.0f)) return false;
  // cos(theta_h) = u^(1/(e+1)) has the density above; computed through exp/log1p-free pow.
  const float cos_h = std::pow(u.x, 1.0f / (exponent + 1.0f));
  const float sin_h = std::sqrt(std::max(0.0f, 1.0f - cos_h * cos_h));
  const float phi = 2.0f * kPi * u.y;
  const Vec3f h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
  const float wo_h = dot(wo, h);
  if (!(wo_h > 0.0f)) return false;
  s.wi = h * (2.0f * wo_h) - wo;
  if (!(s.wi.z > 0.0f)) return false;  // below the surface: the lobe's mass there is lost
  s.pdf = half_vector_pdf(cos_h, exponent) / (4.0f * wo_h);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return false;
  s.weight = RGB(s.wi.z / std::max(wo.z, s.wi.z));
  s.delta = false;
  return true;
}

}  // namespace pt
