#include "scene/import_materials.h"

#include <algorithm>
#include <cmath>

namespace pt {
namespace {

float max_of(RGB c) { return std::max(c.r, std::max(c.g, c.b)); }

// Colours as validation accepts them (finite, not negative); true if one had to change.
bool clamp_colour(Sourced<RGB>& c) {
  const RGB v = c.value;
  auto fix = [](float x) { return std::isfinite(x) ? std::max(x, 0.0f) : 0.0f; };
  c.value = RGB(fix(v.r), fix(v.g), fix(v.b));
  return !(c.value == v);
}

float unit(float x) { return std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 0.0f; }

// Reads the texture of `ref` at `slot` if the file has it (found or embedded).
class Textures {
 public:
  // `uv_set`: the set the mesh's texture coordinates are (the diffuse or base colour texture's).
  Textures(const std::vector<AssetTexture>& all, int uv_set, MappedMaterial& out)
      : all_(all), uv_set_(uv_set), out_(out) {}
  bool usable(const AssetTextureRef& ref) const {
    return ref && static_cast<std::size_t>(ref.texture) < all_.size() &&
           !all_[static_cast<std::size_t>(ref.texture)].missing;
  }
  bool use(TextureSlot slot, const AssetTextureRef& ref, bool data) {
    if (!usable(ref)) return false;
    out_.textures.push_back({slot, ref.texture, data});
    if (ref.transformed)
      out_.notes.push_back(
          {"texture coordinate transforms (MTL -o/-s, KHR_texture_transform) are not supported: ignored", ref.where});
    if (ref.uv_set != uv_set_)
      out_.notes.push_back({"textures reading a texture-coordinate set other than the base colour's read the base "
                            "colour's set",
                            ref.where});
    return true;
  }

 private:
  const std::vector<AssetTexture>& all_;
  int uv_set_;
  MappedMaterial& out_;
};

// GGX roughness given as alpha (remaproughness false), isotropic.
void set_alpha(MaterialDesc& d, float alpha) {
  d.remap_roughness = false;
  d.uroughness.value = d.vroughness.value = unit(alpha);
}

// Alpha cutouts, normal and bump maps: the same for both models.
void map_surface(const AssetMaterial& m, bool glass, float length_scale, Textures& tex, MappedMaterial& out) {
  MaterialDesc& d = out.desc;
  if (m.model == AssetMaterial::Model::Phong && !glass) {
    // MTL: alpha = d x map_d; the surface is there where it is at least 0.5,
    // or, for a partial dissolve (d strictly between 0 and 1), with probability alpha.
    const float opacity = unit(m.opacity);
    d.alpha = opacity;
    d.alpha_blend = opacity > 0.0f && opacity < 1.0f;
    if (tex.use(TextureSlot::Alpha, m.opacity_map, true) && opacity > 0.0f && !d.alpha_blend.value)
      d.alpha_cutoff = 0.5f / opacity;
  } else if (m.model == AssetMaterial::Model::MetallicRoughness && m.alpha_mode != AlphaMode::Opaque) {
    // glTF: alpha = baseColorFactor.a x the base colour texture's alpha, against
    // alphaCutoff (MASK), or an opacity (BLEND: the surface is there with probability alpha).
    const float factor = unit(m.opacity);
    d.alpha = factor;
    d.alpha_cutoff = m.alpha_cutoff;
    d.alpha_blend = m.alpha_mode == AlphaMode::Blend;
    if (tex.use(TextureSlot::Alpha, m.base_color_map, false) && !d.alpha_blend.value)
      d.alpha_cutoff = factor > 0.0f ? m.alpha_cutoff / factor : 2.0f;
  }
  if (tex.use(TextureSlot::NormalMap, m.normal_map, true)) d.normal_scale = m.normal_map.scale;
  if (tex.use(TextureSlot::Displacement, m.bump_map, true)) {
    TexturedParam<float> h;
    h.value = m.bump_map.scale * length_scale;
    d.displacement = h;
  }
  if (m.occlusion_map)
    out.notes.push_back({"occlusion maps are not used (the path tracer computes occlusion itself)", m.occlusion_map.where,
                         false});
  for (const auto& [name, where] : m.unsupported)
    out.notes.push_back({"material extension '" + name + "' is not supported: what it adds is left out", where});
}

// Emission: the colour (Ke, emissiveFactor x KHR_materials_emissive_strength)
// times the emission texture (map_Ke, emissiveTexture; sRGB colour). glTF
// multiplies the two as its specification says (a texture with the default
// factor 0 emits nothing); an MTL map_Ke with no Ke (or Ke 0) emits the
// texture itself (Ke 1), as Blender's OBJ importer and most tools read it, and
// so does a COLLADA emission texture (COLLADA gives a colour or a texture).
void map_emission(const AssetMaterial& m, Textures& tex, MappedMaterial& out) {
  MaterialDesc& d = out.desc;
  RGB factor = m.emission;
  const bool phong = m.model == AssetMaterial::Model::Phong;
  if (tex.usable(m.emission_map) && (phong || !factor.is_black())) {
    tex.use(TextureSlot::Emission, m.emission_map, false);
    if (phong && factor.is_black()) factor = RGB(1.0f);
  }
  d.emission = d.emission.value + factor;
}

// MTL's illumination model, or the one a COLLADA material implies.
int illum_of(const AssetMaterial& m) {
  if (m.illum >= 0) return m.illum;
  return m.lambert_only || m.specular.is_black() ? 1 : (m.reflectivity > 0.0f ? 3 : 2);
}

// A metal: Schlick's Fresnel with F0 = Ks (x map_Ks), roughness from Ns (x map_Ns).
void map_mtl_conductor(const AssetMaterial& m, Textures& tex, MappedMaterial& out) {
  MaterialDesc& d = out.desc;
  d.type = MaterialType::Conductor;
  d.schlick = true;
  d.reflectance.value = m.specular.is_black() ? RGB(1.0f) : m.specular;  // black Ks: a white mirror (map_Ks colours it)
  tex.use(TextureSlot::Reflectance, m.specular_map, false);
  set_alpha(d, m.shininess > 0.0f ? alpha_for_exponent(m.shininess) : 0.0f);  // no Ns: the spec's ideal mirror
  if (tex.use(TextureSlot::Roughness, m.shininess_map, true)) {
    // map_Ns: a roughness texture as Blender writes and reads it (alpha = t^2); Ns is not used.
    d.uroughness.value = d.vroughness.value = 1.0f;
    d.uroughness.squared = d.vroughness.squared = true;
  }
}

// MTL and COLLADA: the illumination model chooses the type (docs/importing.md).
void map_phong(const AssetMaterial& m, float length_scale, MappedMaterial& out, Textures& tex) {
  MaterialDesc& d = out.desc;
  const int illum = illum_of(m);
  const bool glassy = illum == 4 || illum == 6 || illum == 7 || illum == 9;
  const bool glass = glassy && (m.opacity < 1.0f || !(m.transmission_filter == RGB(1.0f)));
  const bool no_diffuse = m.diffuse.is_black() && !tex.usable(m.diffuse_map);
  const bool metal = illum == 5 || illum == 8 || ((illum == 3 || glassy) && !glass && no_diffuse);
  d.diffuse = m.diffuse;
  if (glass) {
    d.type = MaterialType::Dielectric;  // roughness 0: exactly glass (the MTL's ray-traced refraction)
    d.ior = m.ior && *m.ior > 0.0f ? *m.ior : 1.5f;
    const RGB tf = m.transmission_filter;
    d.transmittance = RGB(unit(tf.r), unit(tf.g), unit(tf.b));  // Tf: the tint of every crossing
  } else if (metal) {
    map_mtl_conductor(m, tex, out);
    if ((illum == 5 || illum == 8) && !no_diffuse)
      out.notes.push_back({"the diffuse colour of illum 5 and 8 (mirrors) is not used", m.where});
  } else if (illum <= 1 || (m.specular.is_black() && !tex.usable(m.specular_map))) {
    d.type = MaterialType::Lambert;
    tex.use(TextureSlot::Diffuse, m.diffuse_map, false);
  } else {
    d.type = MaterialType::Phong;  // Kd Lambert + Ks normalised Blinn-Phong of exponent Ns (+ Ks mirror for illum 3)
    d.ks = 1.0f;
    d.specular = m.specular;
    d.exponent = std::isfinite(m.shininess) ? std::max(m.shininess, 1.0f) : 1.0f;
    if (illum == 3 || glassy) d.reflectivity = std::clamp(std::max(m.reflectivity, max_of(m.specular)), 0.0f, 1.0f);
    tex.use(TextureSlot::Diffuse, m.diffuse_map, false);
    if (tex.usable(m.specular_map))
      out.notes.push_back({"specular textures (map_Ks) of Blinn-Phong materials (illum 2, or 3 with a diffuse colour) "
                           "are not supported: Ks used",
                           m.specular_map.where});
    if (tex.usable(m.shininess_map))
      out.notes.push_back({"specular exponent textures (map_Ns) of Blinn-Phong materials (illum 2, or 3 with a diffuse "
                           "colour) are not supported: Ns used",
                           m.shininess_map.where});
  }
  if (illum == 0 || illum == 10)
    out.notes.push_back({"illumination models 0 (constant colour) and 10 (shadow matte) are rendered as lit surfaces",
                         m.where});
  map_surface(m, glass, length_scale, tex, out);
}

// glTF roughness r (x the green channel of metallicRoughnessTexture): GGX alpha = r^2.
void gltf_roughness(const AssetMaterial& m, Textures& tex, MaterialDesc& d) {
  const float r = unit(m.roughness);
  set_alpha(d, r * r);
  if (tex.use(TextureSlot::Roughness, m.metallic_roughness_map, true)) {
    d.uroughness.channel = d.vroughness.channel = 1;
    d.uroughness.squared = d.vroughness.squared = true;
  }
}

// glTF's metallic-roughness (docs/importing.md): the `metallicroughness`
// material, glTF's blend of a Schlick conductor of F0 = base colour and a coated
// diffuse of index 1.5 (F0 0.04) by metallic = metallicFactor x the blue channel
// of metallicRoughnessTexture; transmission rough dielectrics; all with GGX
// alpha = roughness^2.
void map_metallic_roughness(const AssetMaterial& m, float length_scale, MappedMaterial& out, Textures& tex) {
  MaterialDesc& d = out.desc;
  if (m.unlit) {
    d.type = MaterialType::Lambert;
    d.diffuse = RGB(0.0f);
    d.emission = m.base_color;
    out.notes.push_back({"unlit materials (KHR_materials_unlit) emit their base colour (and light the scene)", m.where});
  } else if (m.transmission > 0.0f) {
    d.type = MaterialType::Dielectric;
    d.ior = m.ior && *m.ior > 0.0f ? *m.ior : 1.5f;
    gltf_roughness(m, tex, d);
    if (m.transmission < 1.0f || !(m.base_color == RGB(1.0f)) || tex.usable(m.base_color_map))
      out.notes.push_back({"partial or tinted transmission (KHR_materials_transmission below 1, a base colour) is "
                           "rendered as clear, fully transmissive glass",
                           m.where});
  } else {
    d.type = MaterialType::MetallicRoughness;
    d.ior = m.ior && *m.ior > 0.0f ? *m.ior : 1.5f;
    d.reflectance.value = m.base_color;
    tex.use(TextureSlot::Reflectance, m.base_color_map, false);
    d.metallic.value = unit(m.metallic);
    if (tex.use(TextureSlot::Metallic, m.metallic_roughness_map, true)) d.metallic.channel = 2;
    gltf_roughness(m, tex, d);
  }
  map_surface(m, d.type == MaterialType::Dielectric, length_scale, tex, out);
}

}  // namespace

float alpha_for_exponent(float exponent) {
  if (!std::isfinite(exponent)) return exponent > 0.0f ? 0.0f : 1.0f;
  return std::sqrt(2.0f / (std::max(exponent, 0.0f) + 2.0f));
}

void set_texture(MaterialDesc& d, TextureSlot slot, int index) {
  switch (slot) {
    case TextureSlot::Diffuse: d.texture = index; break;
    case TextureSlot::Reflectance: d.reflectance.texture = index; break;
    case TextureSlot::Roughness: d.uroughness.texture = d.vroughness.texture = index; break;
    case TextureSlot::Metallic: d.metallic.texture = index; break;
    case TextureSlot::Emission: d.emission_texture = index; break;
    case TextureSlot::Alpha: d.alpha_texture = index; break;
    case TextureSlot::NormalMap: d.normal_map = index; break;
    case TextureSlot::Displacement:
      if (d.displacement) d.displacement->texture = index;
      break;
  }
}

MappedMaterial map_asset_material(const AssetMaterial& m, const std::vector<AssetTexture>& textures,
                                  float length_scale) {
  MappedMaterial out;
  MaterialDesc& d = out.desc;
  d.name = m.name;
  d.where = m.where;
  const AssetTextureRef& base = m.model == AssetMaterial::Model::Phong ? m.diffuse_map : m.base_color_map;
  Textures tex(textures, base ? base.uv_set : 0, out);
  if (m.model == AssetMaterial::Model::Phong) {
    map_phong(m, length_scale, out, tex);
  } else {
    map_metallic_roughness(m, length_scale, out, tex);
  }
  map_emission(m, tex, out);
  d.two_sided = m.double_sided;
  bool clamped = false;
  for (Sourced<RGB>* c : {&d.diffuse, &d.specular, &d.emission}) clamped = clamp_colour(*c) || clamped;
  RGB r = d.reflectance.value.value;
  Sourced<RGB> reflectance(RGB(unit(r.r), unit(r.g), unit(r.b)));
  clamped = clamped || !(reflectance.value == r);
  d.reflectance.value = reflectance;
  if (clamped) out.notes.push_back({"negative, non-finite or (reflectance) above 1 colours clamped", m.where});
  return out;
}

}  // namespace pt
