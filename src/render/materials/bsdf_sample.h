// What sampling a BSDF lobe returns, in the lobe's local shading frame
// (z = the shading normal on the side the lobe is defined for).
#pragma once

#include "core/color.h"
#include "core/math.h"

namespace pt {

struct BsdfSample {
  Vec3f wi;            // unit incident direction (towards the light)
  RGB weight;          // f(wo, wi) |cos theta_i| / pdf: the throughput factor
  float pdf = 0.0f;    // solid-angle density of wi (for a delta lobe: the probability of choosing it)
  bool delta = false;  // a specular (Dirac) direction: no other strategy can produce it
  // For refraction, (eta_t / eta_i)^2: the radiance scale the weight divides
  // by; Russian roulette multiplies it back so it does not kill paths in glass.
  float eta2 = 1.0f;
};

}  // namespace pt
