#include "scene/gltf_json.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>

#include "scene/json.h"

namespace pt {
namespace {

constexpr std::uintmax_t kMaxJsonBytes = std::uintmax_t{256} << 20;

// Extensions read somewhere (by Assimp or here): not reported.
bool known_extension(const std::string& name) {
  static const char* const kKnown[] = {"KHR_lights_punctual",       "KHR_materials_emissive_strength",
                                       "KHR_materials_transmission", "KHR_materials_ior",
                                       "KHR_materials_unlit",        "KHR_texture_transform",
                                       "KHR_mesh_quantization"};
  for (const char* k : kKnown)
    if (name == k) return true;
  return false;
}

std::optional<std::string> read_text(const std::string& path, bool binary) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxJsonBytes) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  if (!binary) {
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
  }
  // .glb: a 12-byte header, then the JSON chunk (length, type "JSON", data).
  std::array<uint32_t, 5> header{};
  if (!in.read(reinterpret_cast<char*>(header.data()), sizeof(header))) return std::nullopt;
  if (header[0] != 0x46546C67u || header[4] != 0x4E4F534Au || header[3] > size - sizeof(header)) return std::nullopt;
  std::string text(header[3], '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(text.size()))) return std::nullopt;
  return text;
}

std::optional<float> number_at(const JsonValue* object, const char* key) {
  const JsonValue* v = object && object->is_object() ? object->find(key) : nullptr;
  if (v && v->is_number()) return static_cast<float>(v->as_number());
  return std::nullopt;
}

// The first KHR_texture_transform under `v` (a material: its texture infos).
const JsonValue* find_texture_transform(const JsonValue& v, int depth = 0) {
  if (depth > 4 || !v.is_object()) return nullptr;
  for (const JsonMember& m : v.as_object()) {
    if (m.key == "KHR_texture_transform") return &m.value;
    if (const JsonValue* found = find_texture_transform(m.value, depth + 1)) return found;
  }
  return nullptr;
}

GltfMaterialInfo read_material(const JsonDocument& doc, const JsonValue& m) {
  GltfMaterialInfo info;
  info.where = doc.location(m);
  if (!m.is_object()) return info;
  if (const JsonValue* name = m.find("name"); name && name->is_string()) info.name = name->as_string();
  if (const JsonValue* t = find_texture_transform(m)) info.texture_transform = doc.location(*t);
  info.normal_scale = number_at(m.find("normalTexture"), "scale");
  const JsonValue* ext = m.find("extensions");
  if (!ext || !ext->is_object()) return info;
  for (const JsonMember& e : ext->as_object()) {
    if (e.key == "KHR_materials_emissive_strength") {
      info.emissive_strength = number_at(&e.value, "emissiveStrength");
    } else if (e.key == "KHR_materials_transmission") {
      info.transmission = number_at(&e.value, "transmissionFactor").value_or(0.0f);
    } else if (e.key == "KHR_materials_ior") {
      info.ior = number_at(&e.value, "ior").value_or(1.5f);
    } else if (e.key == "KHR_materials_unlit") {
      info.unlit = true;
    } else if (!known_extension(e.key)) {
      info.unsupported.emplace_back(e.key, doc.location(e.key_offset));
    }
  }
  return info;
}

}  // namespace

bool read_gltf_info(const std::string& path, bool binary, GltfInfo& out) {
  std::optional<std::string> text = read_text(path, binary);
  if (!text) return false;
  const std::string label = binary ? path + " (JSON chunk)" : path;
  Diagnostics ignored;  // Assimp reports what is wrong with the file
  const std::optional<JsonDocument> doc =
      parse_json(std::make_shared<const SourceFile>(SourceFile{label, std::move(*text)}), ignored);
  if (!doc || !doc->root().is_object()) return false;
  const JsonValue& root = doc->root();
  if (const JsonValue* materials = root.find("materials"); materials && materials->is_array()) {
    for (const JsonValue& m : materials->as_array()) out.materials.push_back(read_material(*doc, m));
  }
  if (const JsonValue* images = root.find("images"); images && images->is_array()) {
    for (const JsonValue& image : images->as_array()) {
      const JsonValue* uri = image.is_object() ? image.find("uri") : nullptr;
      if (uri && uri->is_string() && uri->as_string().rfind("data:", 0) != 0)
        out.image_uris.emplace(uri->as_string(), doc->location(*uri));
    }
  }
  if (const JsonValue* used = root.find("extensionsUsed"); used && used->is_array()) {
    for (const JsonValue& e : used->as_array()) {
      if (!e.is_string() || known_extension(e.as_string()) || e.as_string().rfind("KHR_materials_", 0) == 0) continue;
      out.unsupported.emplace_back(e.as_string(), doc->location(e));
    }
  }
  return true;
}

}  // namespace pt
