// The normalised Blinn-Phong specular lobe of exponent e (>= 0):
//
//   f(wo, wi) = (e + 1) / (8 pi) * cos^e(theta_h) / ((wo . h) max(cos theta_o, cos theta_i))
//
// with h = normalize(wo + wi): the isotropic case of Ashikhmin and Shirley's
// Phong BRDF ("An Anisotropic Phong BRDF Model", 2000) without its Fresnel
// factor. It is sampled through the half vector, h with density
// (e + 1)/(2 pi) cos^e(theta_h), wi = reflect(wo, h), so
//
//   pdf(wi) = (e + 1)/(2 pi) cos^e(theta_h) / (4 (wo . h))   and
//   f cos(theta_i) / pdf = cos(theta_i) / max(cos theta_o, cos theta_i) <= 1:
//
// every sample's weight is at most 1, so the lobe never reflects more energy
// than it receives (its albedo is at most 1 for every wo and e; the tests
// check it), and it is reciprocal. Local frame, reflection only.
#pragma once

#include "render/materials/bsdf_sample.h"

namespace pt {

struct BlinnPhongLobe {
  float exponent = 1.0f;

  // The scalar lobe value f(wo, wi) (the material multiplies it by its colour).
  float f(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  // Samples wi; s.weight is the scalar f cos / pdf in every channel.
  bool sample(Vec3f wo, Vec2f u, BsdfSample& s) const;
};

}  // namespace pt
