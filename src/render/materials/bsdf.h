// The BSDF at one surface point, assembled from the material and the local
// geometry, in world space. Built on the stack per hit: no allocation, no
// virtual calls. It is one of several BSDF kinds (a std::variant, visited like
// the lights), each defined in local shading coordinates in a header of its own:
//
//  - ClassicLobes (classic_lobes.h): Phong, Lambert and Mirror, a mixture of
//    a Lambert, a normalised Blinn-Phong and a perfect mirror lobe;
//  - DielectricBsdf (dielectric.h): glass, and a dielectric of roughness 0;
//  - ConductorBsdf (conductor.h): rough (GGX) or smooth conductor;
//  - RoughDielectricBsdf (rough_dielectric.h): rough dielectric (GGX, Walter et al.);
//  - CoatedDiffuseBsdf (coated_diffuse.h): a Lambert base under a rough or
//    smooth dielectric coating;
//  - MetallicRoughnessBsdf (metallic_roughness.h): glTF's blend of a Schlick
//    conductor and a coated diffuse.
//
// Every kind has the same members, checked by the BsdfKindType concept below:
// kTransmits (whether wi may lie on the other side of the surface), delta_only,
// black, needs_lobe_choice, f, pdf, sample and f_diffuse (the part of f the
// diffuse AOVs count), all in the local frame.
//
// Shading normals never let light through a surface. Reflective kinds: the
// frame is the shading normal flipped to the viewer's side (the geometric
// normal if the viewer is below the shading hemisphere), and f, pdf and sample
// need wo and wi on the same side of the geometric normal, except on a
// smooth-shaded mesh with the shadow-terminator offset on (reflects_to).
// Transmissive kinds:
// the frame keeps the shape's orientation (+z = the side of the geometric
// normal, outside), with the geometric normal in place of a shading normal
// that disagrees with it about the viewer's side; a non-delta direction counts
// only if the shading frame and the geometric normal agree on whether it is
// reflected or transmitted.
#pragma once

#include <concepts>
#include <utility>
#include <variant>

#include "core/sampling.h"
#include "geometry/shapes.h"
#include "render/materials/classic_lobes.h"
#include "render/materials/coated_diffuse.h"
#include "render/materials/conductor.h"
#include "render/materials/dielectric.h"
#include "render/materials/material.h"
#include "render/materials/metallic_roughness.h"
#include "render/materials/rough_dielectric.h"

namespace pt {

template <class K>
concept BsdfKindType = requires(const K& k, Vec3f w, Vec2f u, BsdfSample& s) {
  { K::kTransmits } -> std::convertible_to<bool>;
  { k.delta_only() } -> std::same_as<bool>;
  { k.black() } -> std::same_as<bool>;
  { k.needs_lobe_choice() } -> std::same_as<bool>;
  { k.f(w, w) } -> std::same_as<RGB>;
  { k.pdf(w, w) } -> std::same_as<float>;
  { k.f_diffuse(w, w) } -> std::same_as<RGB>;
  { k.sample(w, 0.0f, u, s) } -> std::same_as<bool>;
};

// DielectricBsdf first: the cheapest to construct before the kind is emplaced.
using BsdfKind = std::variant<DielectricBsdf, ClassicLobes, ConductorBsdf, RoughDielectricBsdf, CoatedDiffuseBsdf,
                              MetallicRoughnessBsdf>;

class Bsdf {
 public:
  // The BSDF of `m` at `geo`, seen from direction `wo` (unit, pointing away from the surface).
  Bsdf(const Material& m, const SurfaceGeometry& geo, Vec3f wo);

  // The facts below are per hit, because the lobes present at a hit depend on
  // it: a texture can make the diffuse lobe black at one texel (and the kd Cd
  // + ks Cs scaling depends on the texel). Deciding them per material would
  // spend a sample dimension where the hit has no choice (or none where it
  // has) and change images.

  // True if every lobe is a delta lobe (mirror, glass): f() and pdf() are 0
  // everywhere and next-event estimation is pointless. (The three facts are
  // the kind's, read once when the BSDF is built.)
  bool delta_only() const { return delta_only_; }
  // True if the surface scatters nothing (a black material: paths end here).
  bool black() const { return black_; }
  // True if sample() chooses between lobes (glass between reflection and
  // transmission, a reflective material between the lobes with weight at this
  // hit): otherwise its `u_lobe` is not read and the caller need not spend a
  // sample dimension on it.
  bool needs_lobe_choice() const { return needs_lobe_choice_; }
  // True if wi may lie on the other side of the surface (glass); false for
  // the reflective kinds, whose f and pdf are 0 below shading_normal().
  bool transmits() const { return transmits_; }

  // The non-delta part of f(wo, wi) for unit world directions.
  RGB f(Vec3f wo, Vec3f wi) const;
  // The solid-angle density with which sample() produces wi through a non-delta lobe.
  float pdf(Vec3f wo, Vec3f wi) const;
  // Samples wi (world space): `u_lobe` picks the lobe (read only if
  // needs_lobe_choice()), `u` the direction.
  bool sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const;
  // The diffuse part of f(wo, wi) (Lambert lobes), for the lighting AOVs.
  RGB f_diffuse(Vec3f wo, Vec3f wi) const;

  // The shading normal the BSDF uses (on wo's side for reflective materials):
  // |dot(wi, n)| is the cosine factor.
  Vec3f shading_normal() const { return frame_.n; }

 private:
  // The material's BSDF kind at texture coordinates `tc`, seen from `wo`
  // (its type was decided when the render scene was built: make_material).
  void set_kind(const Material& m, const TexCoord& tc, Vec3f wo);
  // Builds kind K in place and reads its facts.
  template <class K, class... Args>
  void emplace(Args&&... args) {
    const K& k = kind_.emplace<K>(std::forward<Args>(args)...);
    delta_only_ = k.delta_only();
    black_ = k.black();
    needs_lobe_choice_ = k.needs_lobe_choice();
    transmits_ = K::kTransmits;
  }

  // std::visit, with the classic lobes (every course material, the Cornell
  // box's every vertex) tested first so that their path is inlined rather
  // than an indirect call (measured: docs/path-tracing.md, "Performance").
  template <class F>
  decltype(auto) visit_kind(F&& f) const {
    if (const auto* c = std::get_if<ClassicLobes>(&kind_)) [[likely]]
      return f(*c);
    return std::visit(std::forward<F>(f), kind_);
  }

  // For transmissive kinds: whether the shading frame (lo, li) and the
  // geometric normal agree on whether (wo, wi) is a reflection or a transmission.
  bool sides_agree(Vec3f wo, Vec3f wi, Vec3f lo, Vec3f li) const {
    const bool geometric_reflection = (dot(wo, ng_) > 0.0f) == (dot(wi, ng_) > 0.0f);
    return li.z != 0.0f && geometric_reflection == (lo.z * li.z > 0.0f);
  }

  // Reflective kinds: whether light may arrive from (or leave towards) wi at
  // all. Above the geometric normal; or, at a point of a smooth-shaded mesh
  // whose rays leave from the smooth surface (`smooth_`: the shadow-terminator
  // offset, geometry/terminator.h), wherever the kind's shading frame allows:
  // there a direction below the triangle but above the shading normal is
  // traced from above the triangle, so it cannot pass through the surface.
  bool reflects_to(Vec3f wi) const { return smooth_ || dot(wi, ng_) > 0.0f; }

  Frame frame_;
  Vec3f ng_;  // geometric normal: on wo's side for reflective kinds, the shape's own for transmissive ones
  BsdfKind kind_;
  bool delta_only_ = false, black_ = false, needs_lobe_choice_ = false, transmits_ = false;
  bool smooth_ = false;
};

}  // namespace pt
