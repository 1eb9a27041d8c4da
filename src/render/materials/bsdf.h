// The BSDF at one surface point, assembled from the material and the local
// geometry, in world space. Built on the stack per hit: no allocation, no
// virtual calls. Two kinds:
//
//  - Reflective (Phong, Lambert, Mirror): a mixture of a Lambert lobe, a
//    normalised Blinn-Phong lobe and a perfect mirror lobe,
//        f = (1 - rho) (kd' Cd / pi + ks' Cs f_bp) + rho * mirror(tint),
//    where rho is the mirror weight and kd', ks' are kd, ks scaled down by
//    max(1, max channel of kd Cd + ks Cs) so the sum never exceeds 1 (a course
//    file may say kd + ks > 1). One lobe is sampled, chosen with probability
//    proportional to its mean weight; the density of a direction is the
//    mixture of the non-delta lobes' densities. Reflection happens on the side
//    the ray arrives from (every surface is two-sided).
//  - Glass: a smooth dielectric (render/materials/dielectric.h).
//
// Shading normals: the frame is the shading normal flipped to the viewer's side
// (the geometric normal if the viewer is below the shading hemisphere), and
// reflection needs wo and wi on the same side of the geometric normal, so
// interpolated normals cannot leak light through a surface.
#pragma once

#include "core/sampling.h"
#include "geometry/shapes.h"
#include "render/materials/blinn_phong.h"
#include "render/materials/dielectric.h"
#include "render/materials/lambert.h"
#include "render/materials/material.h"
#include "render/materials/mirror.h"

namespace pt {

class Bsdf {
 public:
  // The BSDF of `m` at `geo`, seen from direction `wo` (unit, pointing away from the surface).
  Bsdf(const Material& m, const SurfaceGeometry& geo, Vec3f wo);

  // Glass (Material::glass(), decided when the scene was built) is a
  // dielectric; the facts below are per hit for reflective materials, because
  // the lobes present at a hit depend on it: a texture can make the diffuse
  // lobe black at one texel (and the kd Cd + ks Cs scaling depends on the
  // texel). Deciding them per material would spend a sample dimension where
  // the hit has no choice (or none where it has) and change images.

  // True if every lobe is a delta lobe (mirror, glass): f() and pdf() are 0
  // everywhere and next-event estimation is pointless.
  bool delta_only() const { return p_diffuse_ + p_glossy_ == 0.0f; }
  // True if the surface scatters nothing (a black material: paths end here).
  bool black() const { return !glass_ && p_diffuse_ + p_glossy_ + p_mirror_ == 0.0f; }

  // True if sample() chooses between lobes (glass between reflection and
  // transmission, a reflective material between the lobes with weight at this
  // hit): otherwise its `u_lobe` is not read and the caller need not spend a
  // sample dimension on it.
  bool needs_lobe_choice() const {
    return glass_ || (p_diffuse_ > 0.0f) + (p_glossy_ > 0.0f) + (p_mirror_ > 0.0f) > 1;
  }

  // The non-delta part of f(wo, wi) for unit world directions.
  RGB f(Vec3f wo, Vec3f wi) const;
  // The solid-angle density with which sample() produces wi through a non-delta lobe.
  float pdf(Vec3f wo, Vec3f wi) const;
  // Samples wi (world space): `u_lobe` picks the lobe (read only if
  // needs_lobe_choice()), `u` the direction.
  bool sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const;

  // The shading normal the BSDF uses (on wo's side for reflective materials):
  // |dot(wi, n)| is the cosine factor.
  Vec3f shading_normal() const { return frame_.n; }

 private:
  Frame frame_;
  Vec3f ng_;  // geometric normal: on wo's side for reflection, the shape's own for glass
  bool glass_ = false;
  LambertBrdf diffuse_;
  RGB glossy_weight_;
  BlinnPhongLobe glossy_;
  MirrorBrdf mirror_;
  DielectricBsdf dielectric_;
  // Lobe selection probabilities (sum 1, or all 0 for a black surface).
  float p_diffuse_ = 0.0f, p_glossy_ = 0.0f, p_mirror_ = 0.0f;
};

}  // namespace pt
