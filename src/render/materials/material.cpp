#include "render/materials/material.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "render/materials/fresnel.h"
#include "render/materials/microfacet.h"

namespace pt {

namespace {

// Fills `out` from a textured parameter of the description.
template <class Param, class T>
void resolve(Param& out, const TexturedParam<T>& in, const std::vector<const Texture*>& textures) {
  out.value = in.value.value;
  if constexpr (std::is_same_v<Param, FloatParam>) {
    out.channel = in.channel >= 0 && in.channel < 3 ? in.channel : -1;
    out.squared = in.squared;
  }
  if (in.texture && static_cast<std::size_t>(*in.texture) < textures.size())
    out.texture = textures[static_cast<std::size_t>(*in.texture)];
}

const Texture* texture_of(const std::optional<int>& index, const std::vector<const Texture*>& textures) {
  return index && static_cast<std::size_t>(*index) < textures.size() ? textures[static_cast<std::size_t>(*index)]
                                                                      : nullptr;
}

// The Blinn-Phong exponent with the same width as GGX of this alpha (Walter et
// al. 2007's e = 2 / alpha^2 - 2), for the classic integrator.
float phong_exponent(float alpha) { return std::max(0.0f, 2.0f / std::max(alpha * alpha, 1e-6f) - 2.0f); }

// The closest classic meaning of the microfacet types: the course fields the
// classic integrator reads (docs/path-tracing.md).
void give_classic_meaning(Material& m) {
  // The constants (a textured roughness's scale): the classic model has no textures but the diffuse one.
  const float ax = roughness_to_alpha(m.uroughness.value, m.remap_roughness);
  const float ay = roughness_to_alpha(m.vroughness.value, m.remap_roughness);
  const float alpha = std::sqrt(ax * ay);
  const bool smooth = TrowbridgeReitz::smooth(ax, ay);
  switch (m.type) {
    case MaterialType::Conductor: {
      const RGB f0 = m.schlick ? m.reflectance.value : fresnel_conductor(1.0f, m.eta.value, m.k.value);
      m.kd = 0.0f;
      m.ks = smooth ? 0.0f : 1.0f;
      m.specular = f0;
      m.exponent = phong_exponent(alpha);
      m.reflectivity = smooth ? 1.0f : 0.0f;
      break;
    }
    case MaterialType::CoatedDiffuse:
    case MaterialType::MetallicRoughness: {
      // The metallic-roughness blend: (1 - metallic) the coated diffuse, metallic a Schlick conductor of F0 = base.
      const float metal = m.type == MaterialType::MetallicRoughness ? std::clamp(m.metallic.value, 0.0f, 1.0f) : 0.0f;
      const float f0 = ((m.ior - 1.0f) / (m.ior + 1.0f)) * ((m.ior - 1.0f) / (m.ior + 1.0f));
      // (A coated diffuse: ks = F0 of a white specular colour, as it always was.)
      const RGB spec = metal > 0.0f ? RGB(f0 * (1.0f - metal)) + m.reflectance.value * metal : RGB(1.0f);
      const float ks = metal > 0.0f ? 1.0f : f0;
      m.kd = 1.0f - metal;
      m.diffuse = m.reflectance.value;
      m.texture = m.reflectance.texture;
      m.ks = smooth ? 0.0f : ks;
      m.specular = spec;
      m.exponent = phong_exponent(alpha);
      m.reflectivity = smooth ? f0 * (1.0f - metal) + metal : 0.0f;  // the conductor's is an untinted mirror
      break;
    }
    default:
      break;
  }
}

}  // namespace

float Material::roughness_alpha(float roughness) const { return roughness_to_alpha(roughness, remap_roughness); }

RGB Material::albedo_at(const TexCoord& tc) const {
  if (glass()) return RGB(1.0f);
  switch (type) {
    case MaterialType::Mirror: return specular;
    case MaterialType::Conductor:
      return schlick ? reflectance.at(tc) : fresnel_conductor(1.0f, eta.at(tc), k.at(tc));
    case MaterialType::CoatedDiffuse:
    case MaterialType::MetallicRoughness: return reflectance.at(tc);
    default: return diffuse_at(tc) * kd;
  }
}

Material make_material(const MaterialDesc& d, const std::vector<const Texture*>& textures,
                       const CoatingTable* coating) {
  Material m;
  m.kd = d.kd;
  m.ks = d.ks;
  m.diffuse = d.diffuse;
  m.specular = d.specular;
  m.exponent = d.exponent;
  m.reflectivity = std::clamp(d.reflectivity.value, 0.0f, 1.0f);
  m.ior = d.ior;
  m.emission = d.emission;
  m.emission_texture = texture_of(d.emission_texture, textures);
  m.transmittance = d.transmittance;
  m.two_sided = d.two_sided;
  m.light_samples = d.light_samples;
  m.type = d.type;
  m.texture = texture_of(d.texture, textures);
  resolve(m.uroughness, d.uroughness, textures);
  resolve(m.vroughness, d.vroughness, textures);
  m.remap_roughness = d.remap_roughness;
  resolve(m.eta, d.eta, textures);
  resolve(m.k, d.k, textures);
  resolve(m.reflectance, d.reflectance, textures);
  resolve(m.metallic, d.metallic, textures);
  m.schlick = d.schlick;
  m.coating = coating;
  m.normal_map = texture_of(d.normal_map, textures);
  m.normal_scale = d.normal_scale;
  if (d.displacement) resolve(m.displacement, *d.displacement, textures);
  // The classic integrator reads only the course fields: give the physical
  // types their closest classic meaning (docs/path-tracing.md).
  switch (m.type) {
    case MaterialType::Lambert:
      m.ks = 0.0f;
      m.reflectivity = 0.0f;
      break;
    case MaterialType::Mirror:
      m.kd = 0.0f;
      m.ks = 0.0f;
      m.reflectivity = 1.0f;
      break;
    case MaterialType::Glass:
    case MaterialType::Dielectric:
      break;
    case MaterialType::Conductor:
    case MaterialType::CoatedDiffuse:
    case MaterialType::MetallicRoughness:
      give_classic_meaning(m);
      break;
    case MaterialType::Phong:
      if (d.refractive) m.type = MaterialType::Glass;  // the course's dielectric
      break;
  }
  m.ka = d.ka ? d.ka->value : m.kd;  // after the classic meanings: a mirror has none
  return m;
}

}  // namespace pt
