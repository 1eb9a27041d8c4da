// Fresnel reflectance of conductors (render/materials/conductor.h): the exact
// unpolarised reflectance of a complex index eta + i k, and Schlick's
// approximation from the normal-incidence reflectance F0. The dielectric's is
// fresnel_dielectric (dielectric.h).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/color.h"

namespace pt {

// Reflectance at incidence cos_i in [0, 1] from a medium of index 1 onto a
// conductor of complex index eta + i k (one channel). The closed form of
// Lagarde's "Memo on Fresnel equations" (2013), as pbrt-v4's FrComplex.
inline float fresnel_conductor(float cos_i, float eta, float k) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float cos2 = cos_i * cos_i, sin2 = 1.0f - cos2;
  const float eta2 = eta * eta, k2 = k * k;
  const float t0 = eta2 - k2 - sin2;
  const float a2b2 = std::sqrt(std::max(0.0f, t0 * t0 + 4.0f * eta2 * k2));
  const float a = std::sqrt(std::max(0.0f, 0.5f * (a2b2 + t0)));
  const float t1 = a2b2 + cos2, t2 = 2.0f * cos_i * a;
  const float rs = (t1 - t2) / (t1 + t2);
  const float t3 = cos2 * a2b2 + sin2 * sin2, t4 = t2 * sin2;
  const float rp = rs * (t3 - t4) / (t3 + t4);
  const float f = 0.5f * (rs + rp);
  return std::isfinite(f) ? std::clamp(f, 0.0f, 1.0f) : 1.0f;
}

inline RGB fresnel_conductor(float cos_i, RGB eta, RGB k) {
  return {fresnel_conductor(cos_i, eta.r, k.r), fresnel_conductor(cos_i, eta.g, k.g),
          fresnel_conductor(cos_i, eta.b, k.b)};
}

// Schlick: F0 + (1 - F0) (1 - cos_i)^5; exactly 1 when F0 is 1.
inline RGB fresnel_schlick(float cos_i, RGB f0) {
  const float m = 1.0f - std::clamp(cos_i, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (RGB(1.0f) - f0) * (m2 * m2 * m);
}

}  // namespace pt
