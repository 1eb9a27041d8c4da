// The native format's materials (docs/scene-format.md, "materials"): the
// types, the keys each reads, textured parameters, conductor presets, and the
// textures of the materials shapes use.
#include <algorithm>
#include <string>
#include <vector>

#include "scene/material_kinds.h"
#include "scene/metal_presets.h"
#include "scene/native_shapes.h"
#include "scene/suggest.h"

namespace pt {
namespace {

struct TypeName {
  const char* name;
  MaterialType type;
};
// pbrt-v4's names for the microfacet materials.
constexpr TypeName kTypes[] = {{"phong", MaterialType::Phong},
                               {"lambert", MaterialType::Lambert},
                               {"mirror", MaterialType::Mirror},
                               {"glass", MaterialType::Glass},
                               {"conductor", MaterialType::Conductor},
                               {"dielectric", MaterialType::Dielectric},
                               {"coateddiffuse", MaterialType::CoatedDiffuse},
                               {"metallicroughness", MaterialType::MetallicRoughness}};

// The keys each material type reads besides "type" (docs/scene-format.md); a
// key the type does not read is an error rather than silently ignored.
const std::vector<std::string>& material_keys(MaterialType type) {
  static const std::vector<std::string> kPhong = {
      "diffuse", "kd",        "ka",            "specular", "ks",        "exponent",    "reflectivity", "refractive",
      "ior",     "emission",  "two_sided",     "light_samples", "texture", "normalmap", "displacement", "alpha", "alpha_mode"};
  static const std::vector<std::string> kLambert = {"diffuse",   "kd",        "ka",           "texture",
                                                    "emission",  "two_sided", "light_samples", "normalmap",
                                                    "displacement", "alpha", "alpha_mode"};
  static const std::vector<std::string> kMirror = {"specular",      "emission",  "two_sided",
                                                   "light_samples", "normalmap", "displacement", "alpha", "alpha_mode"};
  static const std::vector<std::string> kGlass = {"ior",       "transmittance", "emission",     "two_sided", "light_samples",
                                                  "normalmap", "displacement",  "alpha",        "alpha_mode"};
  static const std::vector<std::string> kConductor = {
      "metal",    "eta",       "k",         "reflectance",   "roughness", "uroughness",  "vroughness",
      "remaproughness", "emission", "two_sided", "light_samples", "normalmap", "displacement", "alpha", "alpha_mode"};
  static const std::vector<std::string> kDielectric = {
      "ior",           "transmittance", "roughness", "uroughness", "vroughness", "remaproughness", "emission",
      "two_sided",     "light_samples", "normalmap", "displacement", "alpha",     "alpha_mode"};
  static const std::vector<std::string> kCoated = {"reflectance",   "ior",       "roughness", "uroughness",
                                                   "vroughness",    "remaproughness", "emission", "two_sided",
                                                   "light_samples", "normalmap", "displacement", "alpha", "alpha_mode"};
  static const std::vector<std::string> kMetallicRoughness = {
      "reflectance", "metallic",       "ior",      "roughness", "uroughness",    "vroughness",   "remaproughness",
      "emission",    "two_sided",      "light_samples", "normalmap", "displacement", "alpha", "alpha_mode"};
  switch (type) {
    case MaterialType::MetallicRoughness: return kMetallicRoughness;
    case MaterialType::Lambert: return kLambert;
    case MaterialType::Mirror: return kMirror;
    case MaterialType::Glass: return kGlass;
    case MaterialType::Conductor: return kConductor;
    case MaterialType::Dielectric: return kDielectric;
    case MaterialType::CoatedDiffuse: return kCoated;
    case MaterialType::Phong: break;
  }
  return kPhong;
}

// Every key some type reads.
std::vector<std::string> all_material_keys() {
  std::vector<std::string> all;
  for (const TypeName& t : kTypes)
    for (const std::string& k : material_keys(t.type))
      if (std::find(all.begin(), all.end(), k) == all.end()) all.push_back(k);
  return all;
}

void check_material_keys(ImportContext& ctx, ObjectReader& r, const JsonValue& object, MaterialType type,
                         const std::string& type_name) {
  const std::vector<std::string>& allowed = material_keys(type);
  static const std::vector<std::string> all = all_material_keys();
  for (const JsonMember& member : object.as_object()) {
    if (member.duplicate || std::find(all.begin(), all.end(), member.key) == all.end()) continue;
    if (std::find(allowed.begin(), allowed.end(), member.key) != allowed.end()) continue;
    std::string list;
    for (const std::string& k : allowed) list += (list.empty() ? "" : ", ") + k;
    ctx.diag().error(ctx.doc().location(member.key_offset),
                     "'" + member.key + "' does not apply to a " + type_name + " material (it reads: " + list + ")");
    r.fail();
  }
}

// The scale of a textured parameter: a number, or for colours also an RGB.
bool read_scale(ReadContext& ctx, const JsonValue& v, Sourced<float>& out) { return read_value(ctx, v, "scale", out); }
bool read_scale(ReadContext& ctx, const JsonValue& v, Sourced<RGB>& out) {
  if (!v.is_number()) return read_value(ctx, v, "scale", out);
  Sourced<float> s;
  if (!read_value(ctx, v, "scale", s)) return false;
  out = Sourced<RGB>(RGB(s.value), s.where);
  return true;
}

// A textured parameter (docs/scene-format.md, "Textured parameters"): a
// constant, or {"texture": reference, "scale": s} (s: 1 by default; the
// reference as native_textures.h reads it). It is resolved later, if the
// material is used; `data` reads an image file without sRGB decoding.
template <class T>
void read_textured(ImportContext& ctx, ObjectReader& r, const char* key, TexturedParam<T>& out, NativeMaterial& nm,
                   MaterialTexture slot, bool data) {
  const JsonValue* v = r.get(key);
  if (!v) return;
  if (!v->is_object()) {
    if (!read_value(ctx.read, *v, key, out.value)) r.fail();
    return;
  }
  ObjectReader t(ctx.read, *v, std::string("'") + key + "' of " + r.what());
  if (const JsonValue* ref = t.require("texture")) nm.textures.push_back(PendingTexture{ref, key, slot, data});
  out.value = Sourced<T>(T(1.0f), ctx.read.at(*v));
  if (const JsonValue* s = t.get("scale"); s && !read_scale(ctx.read, *s, out.value)) t.fail();
  t.finish();
  if (!t.ok()) r.fail();
}

// "roughness" sets both directions; "uroughness" and "vroughness" one each
// (given together, they replace "roughness", which is then an error).
void read_roughness(ImportContext& ctx, ObjectReader& r, NativeMaterial& nm) {
  MaterialDesc& m = nm.desc;
  const bool has_u = r.get("uroughness") != nullptr, has_v = r.get("vroughness") != nullptr;
  if (const JsonValue* v = r.get("roughness"); v && (has_u || has_v)) {
    ctx.diag().error(ctx.read.at(*v), "give 'roughness' or 'uroughness' and 'vroughness', not both");
    r.fail();
  }
  if (has_u != has_v) {
    ctx.diag().error(r.where(), std::string("'") + (has_u ? "uroughness" : "vroughness") + "' needs '" +
                                    (has_u ? "vroughness" : "uroughness") + "' (or give 'roughness' for both)");
    r.fail();
  }
  read_textured(ctx, r, "roughness", m.uroughness, nm, MaterialTexture::URoughness, true);
  if (r.get("roughness")) {
    m.vroughness = m.uroughness;
    for (std::size_t i = 0, n = nm.textures.size(); i < n; ++i)
      if (nm.textures[i].slot == MaterialTexture::URoughness)
        nm.textures.push_back(PendingTexture{nm.textures[i].ref, "roughness", MaterialTexture::VRoughness, true});
  }
  read_textured(ctx, r, "uroughness", m.uroughness, nm, MaterialTexture::URoughness, true);
  read_textured(ctx, r, "vroughness", m.vroughness, nm, MaterialTexture::VRoughness, true);
  r.read("remaproughness", m.remap_roughness);
}

// Conductor: "metal" (a preset), "eta" and "k", or "reflectance" (Schlick).
void read_conductor(ImportContext& ctx, ObjectReader& r, NativeMaterial& nm) {
  MaterialDesc& m = nm.desc;
  const JsonValue* metal = r.get("metal");
  const JsonValue* reflectance = r.get("reflectance");
  const bool has_index = r.get("eta") != nullptr || r.get("k") != nullptr;
  if ((metal != nullptr) + has_index + (reflectance != nullptr) > 1) {
    ctx.diag().error(r.where(), "a conductor takes one of 'metal', 'eta' and 'k', or 'reflectance'");
    r.fail();
  }
  SourceLocation metal_at;
  const std::vector<std::string> names = metal_preset_names();
  const int preset = read_choice(r, "metal", names, &metal_at);
  if (preset >= 0) {
    const std::optional<MetalPreset> p = find_metal_preset(names[static_cast<std::size_t>(preset)]);
    m.eta.value = Sourced<RGB>(p->eta, metal_at);
    m.k.value = Sourced<RGB>(p->k, metal_at);
  }
  if (has_index && !(r.get("eta") && r.get("k"))) {
    ctx.diag().error(r.where(), "a conductor's complex index needs both 'eta' and 'k'");
    r.fail();
  }
  read_textured(ctx, r, "eta", m.eta, nm, MaterialTexture::Eta, true);
  read_textured(ctx, r, "k", m.k, nm, MaterialTexture::K, true);
  if (reflectance) {
    m.schlick = true;
    read_textured(ctx, r, "reflectance", m.reflectance, nm, MaterialTexture::Reflectance, false);
  }
}

// The keys of the microfacet types, normal and bump maps (any type).
void read_physical_keys(ImportContext& ctx, ObjectReader& r, NativeMaterial& nm) {
  MaterialDesc& m = nm.desc;
  const MaterialType type = m.type;
  const bool coated = has_coated_diffuse(type);
  if (is_microfacet(type)) read_roughness(ctx, r, nm);
  if (type == MaterialType::Conductor) read_conductor(ctx, r, nm);
  if (coated) read_textured(ctx, r, "reflectance", m.reflectance, nm, MaterialTexture::Reflectance, false);
  if (type == MaterialType::MetallicRoughness)
    read_textured(ctx, r, "metallic", m.metallic, nm, MaterialTexture::Metallic, true);
  if (type == MaterialType::Glass || type == MaterialType::Dielectric) r.read("transmittance", m.transmittance);
  // pbrt-v4's default index for its dielectric and coating (glTF's for metallic-roughness).
  if ((type == MaterialType::Dielectric || coated) && !r.get("ior")) m.ior = 1.5f;
  if (const JsonValue* normal_map = r.get("normalmap"))
    nm.textures.push_back(PendingTexture{normal_map, "normalmap", MaterialTexture::NormalMap, true});
  if (r.get("displacement")) {
    m.displacement.emplace();
    read_textured(ctx, r, "displacement", *m.displacement, nm, MaterialTexture::Displacement, true);
    if (!m.displacement->texture && std::none_of(nm.textures.begin(), nm.textures.end(), [](const PendingTexture& t) {
          return t.slot == MaterialTexture::Displacement;
        })) {
      ctx.diag().error(m.displacement->value.where, "'displacement' must be a texture ({\"texture\": reference})");
      r.fail();
    }
  }
}

// "emission": an rgb, or a textured rgb ({"texture": reference, "scale": rgb}:
// the texture's colour times the scale, e.g. the emission strength).
void read_emission(ImportContext& ctx, ObjectReader& r, NativeMaterial& nm) {
  TexturedParam<RGB> e{nm.desc.emission, {}};
  read_textured(ctx, r, "emission", e, nm, MaterialTexture::Emission, false);
  nm.desc.emission = e.value;
}

NativeMaterial read_material(ImportContext& ctx, const JsonMember& member) {
  NativeMaterial out;
  out.desc.name = member.key;
  out.desc.where = ctx.doc().location(member.key_offset);
  if (!expect_object(ctx.read, member.value, "material '" + member.key + "'")) {
    out.ok = false;
    return out;
  }
  ObjectReader r(ctx.read, member.value, "material '" + member.key + "'");
  MaterialDesc& m = out.desc;
  SourceLocation type_at;
  std::vector<std::string> names;
  for (const TypeName& t : kTypes) names.emplace_back(t.name);
  const int type = read_choice(r, "type", names, &type_at);
  if (type >= 0) {
    m.type = Sourced<MaterialType>(kTypes[type].type, type_at);
    check_material_keys(ctx, r, member.value, m.type, names[static_cast<std::size_t>(type)]);
  }
  r.read("diffuse", m.diffuse);
  r.read("kd", m.kd);
  if (Sourced<float> ka; r.get("ka") && r.read("ka", ka)) m.ka = ka;
  r.read("specular", m.specular);
  r.read("ks", m.ks);
  r.read("exponent", m.exponent);
  r.read("reflectivity", m.reflectivity);
  r.read("refractive", m.refractive);
  r.read("ior", m.ior);
  read_emission(ctx, r, out);
  r.read("two_sided", m.two_sided);
  if (r.get("light_samples") && r.read("light_samples", m.light_samples) && m.light_samples.value < 1) {
    ctx.diag().error(m.light_samples.where, "'light_samples' must be at least 1");
    r.fail();
  }
  if (const JsonValue* texture = r.get("texture"))
    out.textures.push_back(PendingTexture{texture, "texture", MaterialTexture::Diffuse, false});
  out.alpha = r.get("alpha");  // resolved with the textures
  SourceLocation mode_at;
  if (read_choice(r, "alpha_mode", {"cutout", "blend"}, &mode_at) == 1) m.alpha_blend = Sourced<bool>(true, mode_at);
  read_physical_keys(ctx, r, out);
  r.finish();
  out.ok = r.ok();
  return out;
}

std::optional<int>& texture_slot(MaterialDesc& m, MaterialTexture slot) {
  switch (slot) {
    case MaterialTexture::URoughness: return m.uroughness.texture;
    case MaterialTexture::VRoughness: return m.vroughness.texture;
    case MaterialTexture::Eta: return m.eta.texture;
    case MaterialTexture::K: return m.k.texture;
    case MaterialTexture::Reflectance: return m.reflectance.texture;
    case MaterialTexture::Metallic: return m.metallic.texture;
    case MaterialTexture::Emission: return m.emission_texture;
    case MaterialTexture::NormalMap: return m.normal_map;
    case MaterialTexture::Displacement: return m.displacement->texture;
    case MaterialTexture::Diffuse: break;
  }
  return m.texture;
}

// "alpha": a number from 0 to 1, or a texture reference. Cutouts are binary
// (present where alpha >= 0.5), which a constant strictly between 0 and 1 is
// warned about, unless "alpha_mode" is "blend" (an opacity).
void resolve_alpha(ImportContext& ctx, NativeTextures& textures, const JsonValue& v, MaterialDesc& m) {
  if (!v.is_number()) {
    m.alpha_texture = resolve_texture_ref(ctx, textures, v, "alpha");
    return;
  }
  if (!read_value(ctx.read, v, "alpha", m.alpha)) return;
  const float a = m.alpha.value;
  if (!(a >= 0.0f && a <= 1.0f)) {
    ctx.diag().error(m.alpha.where, "'alpha' must be from 0 to 1");
  } else if (a > 0.0f && a < 1.0f && !m.alpha_blend.value) {
    ctx.diag().warning(m.alpha.where, std::string("alpha cutouts are binary (the surface is there where alpha >= 0.5): ") +
                                          (a >= 0.5f ? "this makes it fully opaque" : "this makes it invisible"));
  }
}

}  // namespace

std::vector<NativeMaterial> read_materials(ImportContext& ctx, const JsonValue& v) {
  std::vector<NativeMaterial> materials;
  if (!expect_object(ctx.read, v, "materials")) return materials;
  for (const JsonMember& member : v.as_object())
    if (!member.duplicate) materials.push_back(read_material(ctx, member));
  return materials;
}

void resolve_material_textures(ImportContext& ctx, NativeTextures& textures, NativeMaterial& m) {
  for (std::size_t i = 0; i < m.textures.size(); ++i) {
    const PendingTexture& t = m.textures[i];
    // "roughness" gives one reference for both directions: resolve (and report) it once.
    const auto first = m.textures.begin() + static_cast<std::ptrdiff_t>(i);
    const auto same = std::find_if(m.textures.begin(), first, [&](const PendingTexture& o) { return o.ref == t.ref; });
    texture_slot(m.desc, t.slot) = same != first ? texture_slot(m.desc, same->slot)
                                                 : resolve_texture_ref(ctx, textures, *t.ref, t.key, t.data);
  }
  if (m.alpha) resolve_alpha(ctx, textures, *m.alpha, m.desc);
}

}  // namespace pt
