// The path integrator's lighting split (docs/output.md): every term added to a
// path's radiance goes to exactly one of emission, diffuse/specular x
// direct/indirect, so their sum is the beauty.
//  - emission: emitters and the environment seen by the camera ray itself;
//  - direct: light arriving at the first surface hit (next-event estimation
//    there, or an emitter or the environment found by its BSDF sample);
//  - indirect: everything that scattered more than once.
// Diffuse vs specular is decided at the first hit: its BSDF's diffuse part's
// share of f (Bsdf::f_diffuse, per channel) is diffuse, the rest (Blinn-Phong,
// mirror, glass, microfacet lobes) specular.
// Inactive (no cost beyond a branch) when the film asks for no lighting AOV.
#pragma once

#include <algorithm>

#include "core/color.h"
#include "render/film/aov.h"
#include "render/materials/bsdf.h"

namespace pt {

class PathAovRecorder {
 public:
  explicit PathAovRecorder(AovSample* out) : out_(out) {}
  bool active() const { return out_ != nullptr; }

  // Terms found at path depth `depth` (0 = by the camera ray) by a ray that hit an emitter or escaped.
  void found(int depth, RGB term) {
    if (depth == 0) {
      out_->emission += term;
    } else {
      split(term, continuation_, depth == 1);
    }
  }
  // Next-event estimation at vertex `depth` (0 = the first hit) towards `wi`.
  void light(int depth, RGB term, Vec3f wo, Vec3f wi) {
    if (depth == 0) {
      split(term, diffuse_share(wo, wi), true);
    } else {
      split(term, continuation_, false);
    }
  }
  // The BSDF of the first hit: the diffuse share of f is its f_diffuse / f.
  void first_vertex(const Bsdf& bsdf) { bsdf_ = &bsdf; }
  // The first bounce: the sampled direction (delta lobes are specular).
  void first_bounce(Vec3f wo, const BsdfSample& bs) {
    continuation_ = bs.delta ? RGB() : diffuse_share(wo, bs.wi);
  }
  void scale(float k) {
    for (RGB* c : {&out_->emission, &out_->diffuse_direct, &out_->diffuse_indirect, &out_->specular_direct,
                   &out_->specular_indirect})  // (path has no ambient term)
      *c *= k;
  }

 private:
  RGB diffuse_share(Vec3f wo, Vec3f wi) const {
    const RGB f = bsdf_->f(wo, wi), fd = bsdf_->f_diffuse(wo, wi);
    const auto ratio = [](float d, float t) { return t > 0.0f ? std::clamp(d / t, 0.0f, 1.0f) : 0.0f; };
    return {ratio(fd.r, f.r), ratio(fd.g, f.g), ratio(fd.b, f.b)};
  }
  void split(RGB term, RGB share, bool direct) {
    const RGB d = term * share, s = term - d;
    (direct ? out_->diffuse_direct : out_->diffuse_indirect) += d;
    (direct ? out_->specular_direct : out_->specular_indirect) += s;
  }

  AovSample* out_;
  const Bsdf* bsdf_ = nullptr;
  RGB continuation_;  // the first bounce's diffuse share
};

}  // namespace pt
