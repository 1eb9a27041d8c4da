#include "scene/import_materials.h"

#include <algorithm>
#include <cmath>

namespace pt {
namespace {

// Notes shared by both models: what no material of ours can show yet.
void note_common(const AssetMaterial& m, bool glass, std::vector<MaterialNote>& notes) {
  const bool alpha = m.opacity_map || m.alpha_mode != AlphaMode::Opaque ||
                     (m.opacity < 1.0f && !glass && m.model == AssetMaterial::Model::Phong);
  if (alpha)
    notes.push_back({"alpha (map_d, d/Tr, glTF alphaMode MASK/BLEND) is not supported yet: the surfaces render opaque",
                     m.opacity_map ? m.opacity_map.where : (m.opacity_where.file ? m.opacity_where : m.where)});
  if (m.normal_map) notes.push_back({"normal maps (norm, glTF normalTexture) are not supported yet: ignored", m.normal_map.where});
  if (m.bump_map) notes.push_back({"bump maps (map_bump, bump) are not supported yet: ignored", m.bump_map.where});
  if (m.emission_map && !m.emission.is_black())
    notes.push_back({"emission textures (map_Ke, emissiveTexture) are not supported yet: those surfaces do not emit "
                     "(an untextured emission colour would make the whole surface a light)",
                     m.emission_map.where});
  if (m.occlusion_map)
    notes.push_back({"occlusion maps are not used (the path tracer computes occlusion itself)", m.occlusion_map.where,
                     false});
  for (const auto& [name, where] : m.unsupported)
    notes.push_back({"material extension '" + name + "' is not supported: what it adds is left out", where});
}

float max_of(RGB c) { return std::max(c.r, std::max(c.g, c.b)); }

// Colours as validation accepts them (finite, not negative); true if one had to change.
bool clamp_colour(Sourced<RGB>& c) {
  const RGB v = c.value;
  auto fix = [](float x) { return std::isfinite(x) ? std::max(x, 0.0f) : 0.0f; };
  c.value = RGB(fix(v.r), fix(v.g), fix(v.b));
  return !(c.value == v);
}

// MTL and COLLADA: the illumination model chooses the type (docs/importing.md).
void map_phong(const AssetMaterial& m, MappedMaterial& out) {
  MaterialDesc& d = out.desc;
  int illum = m.illum;
  if (illum < 0) illum = m.lambert_only || m.specular.is_black() ? 1 : (m.reflectivity > 0.0f ? 3 : 2);
  const bool glassy = illum == 4 || illum == 6 || illum == 7 || illum == 9;
  const bool glass = glassy && (m.opacity < 1.0f || !(m.transmission_filter == RGB(1.0f)));
  d.diffuse = m.diffuse;
  if (glass) {
    d.type = MaterialType::Glass;
    d.ior = m.ior && *m.ior > 0.0f ? *m.ior : 1.5f;
    if (!(m.transmission_filter == RGB(1.0f)))
      out.notes.push_back({"tinted glass (Tf) is not supported: clear glass", m.where});
  } else if (illum == 5 || illum == 8) {
    d.type = MaterialType::Mirror;
    d.specular = m.specular.is_black() ? RGB(1.0f) : m.specular;
    if (illum == 5) out.notes.push_back({"Fresnel reflection (illum 5) approximated by a mirror tinted Ks", m.where});
  } else if (illum <= 1 || m.specular.is_black()) {
    d.type = MaterialType::Lambert;
    out.texture = m.diffuse_map.texture;
  } else {
    d.type = MaterialType::Phong;
    d.ks = 1.0f;
    d.specular = m.specular;
    d.exponent = std::isfinite(m.shininess) ? std::max(m.shininess, 1.0f) : 1.0f;
    if (illum == 3 || glassy) d.reflectivity = std::clamp(std::max(m.reflectivity, max_of(m.specular)), 0.0f, 1.0f);
    out.texture = m.diffuse_map.texture;
  }
  if (illum == 0 || illum == 10)
    out.notes.push_back({"illumination models 0 (constant colour) and 10 (shadow matte) are rendered as lit surfaces",
                         m.where});
  if (m.specular_map && d.type == MaterialType::Phong)
    out.notes.push_back({"specular textures (map_Ks) are not supported yet: Ks used", m.specular_map.where});
  if (m.shininess_map && d.type == MaterialType::Phong)
    out.notes.push_back({"specular exponent textures (map_Ns) are not supported yet: Ns used", m.shininess_map.where});
  note_common(m, glass, out.notes);
}

// glTF's metallic-roughness onto today's materials: the nearest, noted.
void map_metallic_roughness(const AssetMaterial& m, MappedMaterial& out) {
  MaterialDesc& d = out.desc;
  const bool metal = m.metallic >= 0.5f;
  if (m.unlit) {
    d.type = MaterialType::Lambert;
    d.diffuse = RGB(0.0f);
    d.emission = m.base_color;
    out.notes.push_back({"unlit materials (KHR_materials_unlit) emit their base colour (and light the scene)", m.where});
  } else if (m.transmission > 0.0f) {
    d.type = MaterialType::Glass;
    d.ior = m.ior && *m.ior > 0.0f ? *m.ior : 1.5f;
    if (m.roughness > 0.1f || m.transmission < 1.0f || !(m.base_color == RGB(1.0f)))
      out.notes.push_back({"transmission approximated by smooth, clear, fully transmissive glass", m.where});
  } else if (metal && m.roughness <= 0.1f) {
    d.type = MaterialType::Mirror;
    d.specular = m.base_color;
    if (m.roughness > 0.0f) out.notes.push_back({"metals of roughness up to 0.1 approximated by a perfect mirror", m.where});
  } else if (metal) {
    d.type = MaterialType::Phong;
    d.kd = 0.0f;
    d.ks = 1.0f;
    d.specular = m.base_color;
    d.exponent = blinn_exponent_for_roughness(m.roughness);
    out.notes.push_back({"rough metals approximated by normalised Blinn-Phong (exponent 2/alpha^2 - 2, alpha = roughness^2)",
                         m.where});
  } else {
    d.type = MaterialType::Phong;
    d.diffuse = m.base_color;
    d.kd = 0.96f;  // what a dielectric of F0 = 0.04 leaves to its diffuse base
    d.ks = 0.04f;
    d.specular = RGB(1.0f);
    d.exponent = blinn_exponent_for_roughness(m.roughness);
    out.texture = m.base_color_map.texture;
    out.notes.push_back({"dielectric metallic-roughness materials approximated by Lambert base colour (kd 0.96) plus "
                         "normalised Blinn-Phong (ks 0.04, exponent from roughness)",
                         m.where});
  }
  if (m.metallic > 0.0f && m.metallic < 1.0f)
    out.notes.push_back({"metallic factors between 0 and 1 rounded to dielectric (< 0.5) or metal", m.where});
  if (m.metallic_roughness_map)
    out.notes.push_back({"metallic-roughness textures are not supported yet: the factors are used",
                         m.metallic_roughness_map.where});
  if (m.base_color_map && out.texture < 0)
    out.notes.push_back({"base colour textures of metals, glass and unlit materials are not supported yet: the "
                         "factor is used",
                         m.base_color_map.where});
  note_common(m, d.type == MaterialType::Glass, out.notes);
}

}  // namespace

float blinn_exponent_for_roughness(float roughness) {
  const float alpha = std::max(roughness * roughness, 1e-4f);
  return std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 10000.0f);
}

MappedMaterial map_asset_material(const AssetMaterial& m, const std::vector<AssetTexture>& textures) {
  MappedMaterial out;
  MaterialDesc& d = out.desc;
  d.name = m.name;
  d.where = m.where;
  if (m.model == AssetMaterial::Model::Phong) {
    map_phong(m, out);
  } else {
    map_metallic_roughness(m, out);
  }
  if (!(m.emission_map && !m.emission.is_black())) d.emission = d.emission.value + m.emission;
  d.two_sided = m.double_sided;
  bool clamped = false;
  for (Sourced<RGB>* c : {&d.diffuse, &d.specular, &d.emission}) clamped = clamp_colour(*c) || clamped;
  if (clamped) out.notes.push_back({"negative or non-finite colours set to 0", m.where});
  // A texture that was not found is reported by read_asset; the material keeps its colour.
  if (out.texture >= 0 && (static_cast<std::size_t>(out.texture) >= textures.size() ||
                           textures[static_cast<std::size_t>(out.texture)].missing))
    out.texture = -1;
  const AssetTextureRef& used = m.model == AssetMaterial::Model::Phong ? m.diffuse_map : m.base_color_map;
  if (out.texture >= 0 && used.transformed)
    out.notes.push_back({"texture coordinate transforms (MTL -o/-s, KHR_texture_transform) are not supported: ignored",
                         used.where});
  return out;
}

}  // namespace pt
