#include "render/materials/bsdf.h"

#include <type_traits>

namespace pt {

static_assert(BsdfKindType<ClassicLobes> && BsdfKindType<DielectricBsdf> && BsdfKindType<ConductorBsdf> &&
              BsdfKindType<RoughDielectricBsdf> && BsdfKindType<CoatedDiffuseBsdf> &&
              BsdfKindType<MetallicRoughnessBsdf>);

void Bsdf::set_kind(const Material& m, const TexCoord& tc, Vec3f wo) {
  switch (m.type) {
    case MaterialType::Glass:
      // DielectricBsdf{...}, not emplace's (m.ior, ...): an aggregate, which clang 14 (the fuzz and
      // sanitizer builds) cannot initialise from parentheses.
      emplace<DielectricBsdf>(DielectricBsdf{m.ior, m.transmittance});
      return;
    case MaterialType::Dielectric: {
      const Vec2f a = m.alpha_at(tc);
      // Index 1 passes light straight through however rough the interface is.
      if (TrowbridgeReitz::smooth(a.x, a.y) || m.ior == 1.0f) {
        emplace<DielectricBsdf>(DielectricBsdf{m.ior, m.transmittance});
      } else {
        emplace<RoughDielectricBsdf>(m.ior, a.x, a.y, m.transmittance);
      }
      return;
    }
    case MaterialType::Conductor: {
      const Vec2f a = m.alpha_at(tc);
      ConductorFresnel fresnel;
      fresnel.schlick = m.schlick;
      if (m.schlick) {
        fresnel.f0 = m.reflectance.at(tc);
      } else {
        fresnel.eta = m.eta.at(tc);
        fresnel.k = m.k.at(tc);
      }
      emplace<ConductorBsdf>(a.x, a.y, fresnel);
      return;
    }
    case MaterialType::CoatedDiffuse: {
      if (!m.coating) break;  // a material made without its tables: its classic meaning
      const Vec2f a = m.alpha_at(tc);
      emplace<CoatedDiffuseBsdf>(m.reflectance.at(tc), a.x, a.y, *m.coating, frame_.to_local(wo));
      return;
    }
    case MaterialType::MetallicRoughness: {
      if (!m.coating) break;
      const Vec2f a = m.alpha_at(tc);
      const RGB base = m.reflectance.at(tc);
      const float metal = m.metallic.at(tc);
      // The ends are the two materials themselves, bit for bit (metallic_roughness.h).
      if (!(metal > 0.0f)) {
        emplace<CoatedDiffuseBsdf>(base, a.x, a.y, *m.coating, frame_.to_local(wo));
      } else if (metal >= 1.0f) {
        ConductorFresnel fresnel;
        fresnel.schlick = true;
        fresnel.f0 = base;
        emplace<ConductorBsdf>(a.x, a.y, fresnel);
      } else {
        emplace<MetallicRoughnessBsdf>(base, metal, a.x, a.y, *m.coating, frame_.to_local(wo));
      }
      return;
    }
    case MaterialType::Phong:
    case MaterialType::Lambert:
    case MaterialType::Mirror:
      break;
  }
  emplace<ClassicLobes>(m, tc);
}

Bsdf::Bsdf(const Material& m, const SurfaceGeometry& geo, Vec3f wo) : smooth_(geo.smooth.mesh != nullptr) {
  const bool above = dot(geo.ng, wo) > 0.0f;
  if (m.glass()) {
    // Transmissive kinds keep the shape's orientation (+z = outside).
    ng_ = geo.ng;
    frame_ = Frame::from_normal((dot(geo.ns, wo) > 0.0f) == above ? geo.ns : geo.ng);
  } else {
    ng_ = above ? geo.ng : -geo.ng;
    Vec3f n = above ? geo.ns : -geo.ns;
    if (!(dot(n, wo) > 0.0f)) n = ng_;  // viewer below the shading hemisphere
    frame_ = Frame::from_normal(n);
  }
  // The kind's type decides the frame rule above: a refracting material's kind transmits.
  const MaterialType t = m.type;
  if (t == MaterialType::Lambert || t == MaterialType::Phong || t == MaterialType::Mirror) [[likely]] {
    emplace<ClassicLobes>(m, tex_coord(geo));  // inline: the course materials' common path
  } else {
    set_kind(m, tex_coord(geo), wo);
  }
}

RGB Bsdf::f(Vec3f wo, Vec3f wi) const {
  return visit_kind(
      [&](const auto& k) -> RGB {
        using K = std::decay_t<decltype(k)>;
        if (delta_only_) return {};
        if constexpr (!K::kTransmits) {
          if (!reflects_to(wi)) return {};
        }
        const Vec3f lo = frame_.to_local(wo), li = frame_.to_local(wi);
        if constexpr (K::kTransmits) {
          if (!sides_agree(wo, wi, lo, li)) return {};
        }
        return k.f(lo, li);
      });
}

float Bsdf::pdf(Vec3f wo, Vec3f wi) const {
  return visit_kind(
      [&](const auto& k) -> float {
        using K = std::decay_t<decltype(k)>;
        if (delta_only_) return 0.0f;
        if constexpr (!K::kTransmits) {
          if (!reflects_to(wi)) return 0.0f;
        }
        const Vec3f lo = frame_.to_local(wo), li = frame_.to_local(wi);
        if constexpr (K::kTransmits) {
          if (!sides_agree(wo, wi, lo, li)) return 0.0f;
        }
        return k.pdf(lo, li);
      });
}

RGB Bsdf::f_diffuse(Vec3f wo, Vec3f wi) const {
  return visit_kind(
      [&](const auto& k) -> RGB {
        using K = std::decay_t<decltype(k)>;
        if constexpr (K::kTransmits) {
          return {};  // no transmissive kind has a diffuse part
        } else {
          if (!reflects_to(wi)) return {};
          return k.f_diffuse(frame_.to_local(wo), frame_.to_local(wi));
        }
      });
}

bool Bsdf::sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const {
  return visit_kind(
      [&](const auto& k) -> bool {
        using K = std::decay_t<decltype(k)>;
        const Vec3f lo = frame_.to_local(wo);
        if (!k.sample(lo, u_lobe, u, s)) return false;
        const Vec3f li = s.wi;
        s.wi = frame_.from_local(li);
        if constexpr (K::kTransmits) {
          return s.delta || sides_agree(wo, s.wi, lo, li);
        } else {
          return reflects_to(s.wi);
        }
      });
}

}  // namespace pt
