// Lambertian (ideal diffuse) reflection: f = albedo / pi, sampled
// cosine-weighted, so each sample's weight is exactly the albedo.
// Local shading frame: reflection only, wo.z > 0 and wi.z > 0.
#pragma once

#include "core/sampling.h"
#include "render/materials/bsdf_sample.h"

namespace pt {

struct LambertBrdf {
  RGB albedo;

  RGB f(Vec3f wo, Vec3f wi) const {
    return (wo.z > 0.0f && wi.z > 0.0f) ? albedo * kInvPi : RGB();
  }
  float pdf(Vec3f wo, Vec3f wi) const { return wo.z > 0.0f ? cosine_hemisphere_pdf(wi.z) : 0.0f; }
  bool sample(Vec3f wo, Vec2f u, BsdfSample& s) const {
    if (!(wo.z > 0.0f)) return false;
    s.wi = sample_cosine_hemisphere(u);
    s.pdf = cosine_hemisphere_pdf(s.wi.z);
    if (!(s.pdf > 0.0f)) return false;
    s.weight = albedo;  // (albedo / pi) cos / (cos / pi)
    s.delta = false;
    return true;
  }
};

}  // namespace pt
