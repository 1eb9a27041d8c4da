// The GGX (Trowbridge-Reitz) microfacet distribution, anisotropic, with
// Smith's height-correlated masking-shadowing and sampling of the visible
// normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
// The definitions are pbrt-v4's (TrowbridgeReitzDistribution) and Walter et
// al. 2007's; docs/path-tracing.md, "Microfacet materials", writes them out.
//
// Local frame: z is the macro-surface normal; alpha_x and alpha_y are the
// roughnesses along x and y (the shading frame's s and t axes).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "core/sampling.h"

namespace pt {

// Below this alpha (in both directions) a surface is smooth: the BSDFs use
// their delta (mirror, glass) forms, as pbrt-v4 does (EffectivelySmooth).
inline constexpr float kSmoothAlpha = 1e-3f;
// A rough surface's alpha is at least this (an anisotropic one may be smooth
// in one direction only): D stays finite.
inline constexpr float kMinAlpha = 1e-4f;

// alpha from the scene's roughness: sqrt(roughness) with remaproughness (the
// default, as pbrt-v4's RoughnessToAlpha), the roughness itself without.
inline float roughness_to_alpha(float roughness, bool remap) {
  roughness = std::max(roughness, 0.0f);
  return remap ? std::sqrt(roughness) : roughness;
}

struct TrowbridgeReitz {
  float alpha_x = 0.0f, alpha_y = 0.0f;

  TrowbridgeReitz() = default;
  TrowbridgeReitz(float ax, float ay) : alpha_x(std::max(ax, kMinAlpha)), alpha_y(std::max(ay, kMinAlpha)) {}

  static bool smooth(float ax, float ay) { return std::max(ax, ay) < kSmoothAlpha; }

  // The distribution of normals D(m) (per unit projected area), m.z > 0:
  //   D(m) = 1 / (pi ax ay (m.x^2/ax^2 + m.y^2/ay^2 + m.z^2)^2).
  float D(Vec3f m) const {
    if (!(m.z > 0.0f)) return 0.0f;
    const float x = m.x / alpha_x, y = m.y / alpha_y;
    const float d = x * x + y * y + m.z * m.z;
    return 1.0f / (kPi * alpha_x * alpha_y * d * d);
  }
  // Smith's Lambda(w) = (sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2) - 1) / 2.
  float lambda(Vec3f w) const {
    const float z2 = w.z * w.z;
    const float a2t2 = (alpha_x * alpha_x * w.x * w.x + alpha_y * alpha_y * w.y * w.y) / z2;
    if (!std::isfinite(a2t2)) return INFINITY;  // grazing: fully masked
    return 0.5f * (std::sqrt(1.0f + a2t2) - 1.0f);
  }
  float G1(Vec3f w) const { return 1.0f / (1.0f + lambda(w)); }
  // Height-correlated masking and shadowing.
  float G(Vec3f wo, Vec3f wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

  // The density of visible normals seen from w (w.z != 0), for a normal m
  // with m.z > 0 (for w below the surface, the facet -m faces w):
  //   D_w(m) = G1(w) max(0, w . m sign(w.z)) D(m) / |w.z|.
  float visible_D(Vec3f w, Vec3f m) const {
    const float c = w.z < 0.0f ? -dot(w, m) : dot(w, m);
    if (!(c > 0.0f)) return 0.0f;
    return G1(w) * c * D(m) / std::fabs(w.z);
  }
  // A normal drawn from D_w (w on either side; the normal is on w's side).
  Vec3f sample_visible(Vec3f w, Vec2f u) const {
    const bool flip = w.z < 0.0f;
    const Vec3f m = sample_visible_upper(flip ? -w : w, u);
    return flip ? -m : m;
  }

 private:
  // Heitz 2018 for w.z >= 0: stretch w to the hemisphere configuration, sample
  // its projected area (a disk whose far half is squashed by the
  // hemisphere's tilt), lift the point onto the hemisphere, unstretch.
  Vec3f sample_visible_upper(Vec3f w, Vec2f u) const {
    const Vec3f wh = normalize(Vec3f(alpha_x * w.x, alpha_y * w.y, w.z));
    const float len2 = wh.x * wh.x + wh.y * wh.y;
    const Vec3f t1 = len2 > 0.0f ? Vec3f(-wh.y, wh.x, 0.0f) / std::sqrt(len2) : Vec3f(1.0f, 0.0f, 0.0f);
    const Vec3f t2 = cross(wh, t1);
    const Vec2f d = sample_uniform_disk_concentric(u);
    const float s = 0.5f * (1.0f + wh.z);
    const float h = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x));
    const float p2 = (1.0f - s) * h + s * d.y;
    const Vec3f nh = t1 * d.x + t2 * p2 + wh * std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - p2 * p2));
    return normalize(Vec3f(alpha_x * nh.x, alpha_y * nh.y, std::max(1e-6f, nh.z)));
  }
};

}  // namespace pt
