// What the spatially aware light sampler (light_bvh.h) knows of a bounded
// light, or of a group of them: where it is, how strongly it emits, and in
// which directions (the idea of pbrt-v4's LightBounds; docs/path-tracing.md,
// "Choosing a light").
//
// `intensity` is a bound on the light's radiant intensity (W/sr, the mean of
// the RGB channels), not its power: then importance(p, n) is an estimate of
// the irradiance the light sends to p (W/m^2), in the same units as the
// estimates of the infinite lights it is weighed against (LightSet).
//
// The emission directions are a cone: every emitting surface normal (or a
// spot's axis) lies within theta_o of `axis`, and light leaves each normal
// within theta_e of it (pi/2 for surfaces, a spot's falloff band for spots).
// Both are kept as cosines.
#pragma once

#include "core/math.h"

namespace pt {

// A cone of directions: every direction within angle theta of `w` (cos_theta = -1: all of them).
struct DirectionCone {
  Vec3f w{0, 0, 1};
  float cos_theta = -1.0f;
  bool empty = true;

  static DirectionCone all() { return {Vec3f(0, 0, 1), -1.0f, false}; }
  static DirectionCone around(Vec3f w) { return {w, 1.0f, false}; }
  bool entire() const { return !empty && cos_theta <= -1.0f; }
};

// The smallest cone (of this construction) holding both.
DirectionCone cone_union(const DirectionCone& a, const DirectionCone& b);

struct LightBounds {
  Bounds3f bounds;
  float intensity = 0.0f;     // W/sr (see above); 0: nothing to choose
  DirectionCone normals;      // theta_o about the axis
  float cos_theta_e = 0.0f;   // cos(theta_e)
  bool two_sided = false;     // emits on both sides of each normal

  // An estimate of the irradiance the bounded lights send to p on a surface
  // with normal n (n = 0: any orientation). It is 0 only where none of them
  // can send anything: p outside every emission cone, or n turned edge-on to
  // all of them.
  float importance(Vec3f p, Vec3f n) const;  // ImportanceBounds(*this).importance(p, n)
};

LightBounds bounds_union(const LightBounds& a, const LightBounds& b);

// LightBounds as importance() reads it, computed once (the light BVH's nodes):
// the same value with a third of the square roots.
struct ImportanceBounds {
  Vec3f centre;
  float r2 = 0.0f, r = 0.0f;  // the bounding sphere's radius, squared and not
  Vec3f axis{0, 0, 1};
  float cos_o = -1.0f, sin_o = 0.0f, cos_e = 0.0f;
  float intensity = 0.0f;
  bool two_sided = false;

  ImportanceBounds() = default;
  explicit ImportanceBounds(const LightBounds& b);
  float importance(Vec3f p, Vec3f n) const;
};

// Four ImportanceBounds side by side (a light BVH node's children), evaluated
// at once: importance(p, n, out) writes what each lane's
// ImportanceBounds::importance(p, n) returns, bit for bit (the same operations
// in the same order, four lanes at a time where SSE2 is available). An unset
// lane has intensity 0 and importance 0.
struct ImportanceBounds4 {
  alignas(16) float cx[4]{}, cy[4]{}, cz[4]{};
  alignas(16) float r2[4]{}, r[4]{};
  alignas(16) float ax[4]{}, ay[4]{}, az[4]{};
  alignas(16) float cos_o[4]{}, sin_o[4]{}, cos_e[4]{};
  alignas(16) float intensity[4]{};
  alignas(16) float two_sided[4]{};  // 1 or 0

  void set(int lane, const ImportanceBounds& b);
  ImportanceBounds get(int lane) const;
  void importance(Vec3f p, Vec3f n, float out[4]) const;
};

}  // namespace pt
