// The native format's textures (docs/scene-format.md, "Textures").
#include <algorithm>
#include <iterator>
#include <string>
#include <utility>

#include "scene/import_transform.h"
#include "scene/native_textures.h"
#include "scene/suggest.h"

namespace pt {
namespace {

// The keys each texture type reads besides "type" and the mapping's
// ("mapping", "scale", "transform").
const std::vector<std::string>& texture_keys(TextureType type) {
  static const std::vector<std::string> kImage = {"file", "filter", "wrap", "encoding"};
  static const std::vector<std::string> kChecker = {"color0", "color1"};
  static const std::vector<std::string> kNoise = {"color0", "color1", "octaves", "roughness"};
  switch (type) {
    case TextureType::Checker: return kChecker;
    case TextureType::Noise: return kNoise;
    case TextureType::Image: break;
  }
  return kImage;
}

// A key another texture type reads is an error here, naming what this one reads.
void check_texture_keys(ImportContext& ctx, ObjectReader& r, const JsonValue& object, TextureType type,
                        const std::string& type_name) {
  const std::vector<std::string>& allowed = texture_keys(type);
  for (const JsonMember& member : object.as_object()) {
    if (member.duplicate || std::find(allowed.begin(), allowed.end(), member.key) != allowed.end()) continue;
    bool other = false;
    for (TextureType t : {TextureType::Image, TextureType::Checker, TextureType::Noise}) {
      const std::vector<std::string>& keys = texture_keys(t);
      other = other || std::find(keys.begin(), keys.end(), member.key) != keys.end();
    }
    if (!other) continue;
    r.get(member.key);  // reported here, not again as unknown by finish()
    std::string list;
    for (const std::string& k : allowed) list += k + ", ";
    ctx.diag().error(ctx.doc().location(member.key_offset), "'" + member.key + "' does not apply to a " + type_name +
                                                                " texture (it reads: " + list + "mapping, scale, transform)");
    r.fail();
  }
}

// "scale": a number, [su, sv] or [sx, sy, sz]; no component zero.
void read_scale(ImportContext& ctx, ObjectReader& r, TextureDesc& t) {
  const JsonValue* v = r.get("scale");
  if (!v) return;
  bool ok = false;
  if (v->is_number()) {
    Sourced<float> s;
    ok = read_value(ctx.read, *v, "scale", s);
    t.scale = Sourced<Vec3f>(Vec3f(s.value), s.where);
  } else if (v->is_array() && v->as_array().size() == 2) {
    Sourced<Vec2f> s;
    ok = read_value(ctx.read, *v, "scale", s);
    t.scale = Sourced<Vec3f>(Vec3f(s.value.x, s.value.y, 1.0f), s.where);
  } else {
    Sourced<Vec3f> s;
    ok = read_value(ctx.read, *v, "scale", s);
    t.scale = s;
  }
  if (!ok) {
    r.fail();
    return;
  }
  const Vec3f s = t.scale.value;
  if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) {
    ctx.diag().error(t.scale.where, "a texture's 'scale' must not be zero");
    r.fail();
  }
}

template <class Enum, std::size_t N>
void read_enum(ObjectReader& r, const char* key, const char* const (&names)[N], Sourced<Enum>& out) {
  SourceLocation at;
  const int i = read_choice(r, key, {std::begin(names), std::end(names)}, &at);
  if (i >= 0) out = Sourced<Enum>(static_cast<Enum>(i), at);
}

void read_image_keys(ImportContext& ctx, ObjectReader& r, TextureDesc& t) {
  Sourced<std::string> file;
  if (r.read_required("file", file)) {
    t.written = file.value;
    if (const std::optional<std::string> resolved = find_scene_file(ctx, file, "texture file")) {
      t.resolved = *resolved;
    } else {
      r.fail();
    }
  }
  read_enum(r, "filter", kTextureFilterNames, t.filter);
  read_enum(r, "wrap", kTextureWrapNames, t.wrap);
  const int encoding = read_choice(r, "encoding", {"srgb", "linear"});
  t.raw = encoding == 1;
}

void read_procedural_keys(ImportContext& ctx, ObjectReader& r, TextureDesc& t) {
  r.read("color0", t.color0);
  r.read("color1", t.color1);
  if (t.type != TextureType::Noise) return;
  if (r.read("octaves", t.octaves) && (t.octaves.value < 1 || t.octaves.value > 16)) {
    ctx.diag().error(t.octaves.where, "'octaves' must be from 1 to 16");
    r.fail();
  }
  if (r.read("roughness", t.roughness) && !(t.roughness.value >= 0.0f && t.roughness.value <= 1.0f)) {
    ctx.diag().error(t.roughness.where, "'roughness' must be from 0 to 1");
    r.fail();
  }
}

// A texture object (named or inline); false after reporting a problem.
bool read_texture_object(ImportContext& ctx, const JsonValue& v, const std::string& label, TextureDesc& t) {
  if (!expect_object(ctx.read, v, label)) return false;
  ObjectReader r(ctx.read, v, label);
  t.where = r.where();
  SourceLocation type_at;
  const int type = read_choice(r, "type", {std::begin(kTextureTypeNames), std::end(kTextureTypeNames)}, &type_at);
  if (type == -1) r.require("type");
  if (type < 0) return false;
  t.type = static_cast<TextureType>(type);
  check_texture_keys(ctx, r, v, t.type, kTextureTypeNames[type]);
  SourceLocation mapping_at;
  const int mapping = read_choice(r, "mapping", {"uv", "object"}, &mapping_at);
  if (mapping >= 0) t.object_mapping = Sourced<bool>(mapping == 1, mapping_at);
  read_scale(ctx, r, t);
  if (const JsonValue* tr = r.get("transform"); tr && !read_transform(ctx.read, *tr, t.transform)) r.fail();
  if (t.type == TextureType::Image) {
    read_image_keys(ctx, r, t);
  } else {
    read_procedural_keys(ctx, r, t);
  }
  r.finish();
  return r.ok();
}

bool has_key(const JsonValue& v, std::string_view key) {
  if (!v.is_object()) return false;
  const auto& members = v.as_object();
  return std::any_of(members.begin(), members.end(), [&](const JsonMember& m) { return m.key == key; });
}

int add_desc(ImportContext& ctx, TextureDesc desc) {
  ctx.scene.textures.push_back(std::move(desc));
  return static_cast<int>(ctx.scene.textures.size()) - 1;
}

}  // namespace

NativeTextures read_native_textures(ImportContext& ctx, const JsonValue& v) {
  NativeTextures out;
  if (!expect_object(ctx.read, v, "textures")) return out;
  for (const JsonMember& member : v.as_object()) {
    if (member.duplicate) continue;
    NativeTextures::Named named;
    named.desc.name = member.key;
    named.ok = read_texture_object(ctx, member.value, "texture '" + member.key + "'", named.desc);
    named.desc.where = ctx.doc().location(member.key_offset);
    named.encoding_given = has_key(member.value, "encoding");
    out.by_name.emplace(member.key, out.named.size());
    out.named.push_back(std::move(named));
  }
  return out;
}

std::optional<int> resolve_texture_ref(ImportContext& ctx, NativeTextures& textures, const JsonValue& v,
                                       std::string_view key, bool data) {
  if (v.is_object()) {
    TextureDesc desc;
    if (!read_texture_object(ctx, v, std::string(key), desc)) return std::nullopt;
    desc.raw = desc.raw || (data && !has_key(v, "encoding"));
    return add_desc(ctx, std::move(desc));
  }
  Sourced<std::string> text;
  if (!v.is_string()) {
    ctx.diag().error(ctx.read.at(v), "expected a texture for '" + std::string(key) +
                                         "': the name of one in \"textures\", an image file or a texture object");
    return std::nullopt;
  }
  if (!read_value(ctx.read, v, key, text)) return std::nullopt;
  if (const auto it = textures.by_name.find(text.value); it != textures.by_name.end()) {
    NativeTextures::Named& named = textures.named[it->second];
    if (!named.ok) return std::nullopt;  // already reported
    if (data && !named.encoding_given && !named.desc.raw) {
      if (!named.data_index) {
        TextureDesc raw = named.desc;
        raw.raw = true;
        named.data_index = add_desc(ctx, std::move(raw));
      }
      return named.data_index;
    }
    if (!named.index) named.index = add_desc(ctx, named.desc);
    return named.index;
  }
  // Not a name: an image file. A word close to a name and no such file is a misspelt name.
  std::vector<std::string> names;
  for (const auto& [name, i] : textures.by_name) names.push_back(name);
  if (const std::string close = closest_match(text.value, names);
      !close.empty() && !resolve_scene_path(ctx.scene.source_path, text.value)) {
    ctx.diag().error(text.where, "unknown texture '" + text.value + "'; did you mean '" + close + "'?");
    return std::nullopt;
  }
  return add_texture(ctx, text, data);
}

void warn_unused_textures(ImportContext& ctx, const NativeTextures& textures) {
  for (const NativeTextures::Named& named : textures.named) {
    if (named.ok && !named.index && !named.data_index)
      ctx.diag().warning(named.desc.where, "texture '" + named.desc.name + "' is not used by any material");
  }
}

}  // namespace pt
