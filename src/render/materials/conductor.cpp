#include "render/materials/conductor.h"

namespace pt {

namespace {

// The half vector of a reflection (wo, wi above the surface), or false.
bool half_vector(Vec3f wo, Vec3f wi, Vec3f& h) {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return false;
  const Vec3f s = wo + wi;
  const float len = length(s);
  if (!(len > 0.0f)) return false;
  h = s / len;
  return true;
}

}  // namespace

RGB ConductorBsdf::f(Vec3f wo, Vec3f wi) const {
  Vec3f h;
  if (smooth_ || !half_vector(wo, wi, h)) return {};
  const float value = distribution_.D(h) * distribution_.G(wo, wi) / (4.0f * wo.z * wi.z);
  return fresnel_(dot(wo, h)) * value;
}

float ConductorBsdf::pdf(Vec3f wo, Vec3f wi) const {
  Vec3f h;
  if (smooth_ || !half_vector(wo, wi, h)) return 0.0f;
  const float c = dot(wo, h);
  return c > 0.0f ? distribution_.visible_D(wo, h) / (4.0f * c) : 0.0f;
}

bool ConductorBsdf::sample(Vec3f wo, float /*u_lobe*/, Vec2f u, BsdfSample& s) const {
  if (!(wo.z > 0.0f)) return false;
  if (smooth_) {
    s.wi = {-wo.x, -wo.y, wo.z};
    s.weight = fresnel_(wo.z);
    s.pdf = 1.0f;
    s.delta = true;
    return true;
  }
  const Vec3f h = distribution_.sample_visible(wo, u);
  const float c = dot(wo, h);
  if (!(c > 0.0f)) return false;
  s.wi = reflect(wo, h);
  if (!(s.wi.z > 0.0f)) return false;
  s.pdf = distribution_.visible_D(wo, h) / (4.0f * c);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return false;
  // f cos_i / pdf = F G / G1(wo).
  s.weight = fresnel_(c) * (distribution_.G(wo, s.wi) / distribution_.G1(wo));
  s.delta = false;
  return true;
}

}  // namespace pt
