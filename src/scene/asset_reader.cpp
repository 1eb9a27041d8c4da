// read_asset(): our OBJ and MTL readers (asset_obj.cpp) or Assimp (glTF,
// COLLADA; the glTF JSON adds what Assimp does not say); everything ends in
// the neutral ImportedAsset.
#include "scene/asset_reader.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "core/file_access.h"
#include "core/heap.h"
#include "scene/asset_internal.h"
#include "scene/gltf_json.h"
#include "scene/mtl.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Assimp's file system, recording the files Assimp opens (the model, glTF
// buffers, ...), which it does not otherwise tell.
class RecordingIOSystem : public Assimp::DefaultIOSystem {
 public:
  std::vector<std::string> opened;

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    Assimp::IOStream* s = Assimp::DefaultIOSystem::Open(file, mode);
    if (s != nullptr && std::find(opened.begin(), opened.end(), file) == opened.end()) opened.emplace_back(file);
    return s;
  }
};

std::string url_decoded(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// What the glTF JSON says and Assimp 5.2 does not (gltf_json.h).
void merge_gltf_info(ImportedAsset& out, Diagnostics& diag) {
  GltfInfo info;
  if (!read_gltf_info(out.path, out.format == AssetFormat::Glb, info)) return;
  for (std::size_t i = 0; i < info.materials.size() && i < out.materials.size(); ++i) {
    const GltfMaterialInfo& g = info.materials[i];
    AssetMaterial& m = out.materials[i];
    if (m.name.empty()) m.name = g.name;
    m.where = g.where;
    for (AssetTextureRef* ref : {&m.base_color_map, &m.metallic_roughness_map, &m.emission_map, &m.normal_map,
                                 &m.occlusion_map}) {
      if (*ref) ref->where = g.where;
      if (*ref && g.texture_transform) ref->transformed = true;
    }
    if (g.normal_scale) m.normal_map.scale = *g.normal_scale;
    if (g.emissive_strength) m.emission = m.emission * *g.emissive_strength;
    if (g.transmission) m.transmission = *g.transmission;
    if (g.ior) m.ior = *g.ior;
    m.unlit = m.unlit || g.unlit;
    m.unsupported.insert(m.unsupported.end(), g.unsupported.begin(), g.unsupported.end());
  }
  for (AssetTexture& t : out.textures) {
    if (const auto it = info.image_uris.find(t.name); it != info.image_uris.end()) t.where = it->second;
  }
  for (const auto& [name, where] : info.unsupported)
    diag.warning(where, "glTF extension '" + name + "' is not supported; what it adds is left out");
}

void count(ImportedAsset& out) {
  ImportCounts& c = out.counts;
  uint64_t triangles = 0, meshes = 0;
  for (const AssetMesh& m : out.meshes) {
    if (m.mesh.indices.empty()) continue;
    ++meshes;
    triangles += m.mesh.triangle_count();
  }
  c.imported.insert(c.imported.begin(), {{"triangles", triangles}, {"meshes", meshes},
                                         {"placements", out.placements.size()}});
  c.imported_n("cameras", out.cameras.size());
  c.imported_n("lights", out.lights.size());
  uint64_t missing = 0;
  for (const AssetTexture& t : out.textures) missing += t.missing ? 1 : 0;
  c.skipped_n("textures not found", missing);
}

bool convert(const aiScene& scene, const SourceLocation& where, ImportedAsset& out, Diagnostics& diag) {
  AssetTextureTable textures(out, fs::path(out.path).parent_path().string());
  convert_materials(scene, out, textures);
  const std::vector<int> uv_sets = diffuse_uv_sets(scene);
  if (out.format != AssetFormat::Collada) merge_gltf_info(out, diag);
  if (!convert_meshes(scene, uv_sets, out, diag, where)) return false;
  convert_placements(scene, out);
  convert_cameras(scene, out);
  convert_lights(scene, out);
  return true;
}

// Glb, glTF and COLLADA through Assimp; the files it opened in `opened`.
bool read_with_assimp(const std::string& written, const SourceLocation& where, ImportedAsset& out, Diagnostics& diag,
                      std::vector<std::string>& opened) {
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_USE_COLLADA_NAMES, true);
  auto* io = new RecordingIOSystem;  // owned by the importer
  importer.SetIOHandler(io);
  // The peak of an import is Assimp's scene beside the file's buffers (in
  // ReadFile), then beside our meshes (convert): the pages that start-up and
  // the importer's set-up touched, then those the reading ran, leave first.
  release_importer_pages();
  // Triangles only (points and lines sorted into meshes of their own and
  // counted); uvs with v downwards from the image's top, as our textures.
  // Identical vertices are joined for COLLADA, whose reader makes one vertex
  // per face corner; a glTF mesh is indexed already, and joining it took
  // 300 bytes a triangle of peak memory (docs/bench/scale.md).
  unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure | aiProcess_FlipUVs;
  if (out.format == AssetFormat::Collada) flags |= aiProcess_JoinIdenticalVertices;
  const aiScene* scene = importer.ReadFile(out.path, flags);
  if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || scene->mRootNode == nullptr) {
    std::string reason = scene == nullptr ? importer.GetErrorString() : "the file describes no complete scene";
    if (reason.empty()) reason = "Assimp could not read the file";
    diag.error(where, "cannot read '" + written + "' (" + asset_format_name(out.format) + "): " + reason);
    return false;
  }
  release_importer_pages();
  if (!convert(*scene, where, out, diag)) return false;
  opened = io->opened;
  return true;
}

// What every format ends with: the textures not found, the counts, the files read.
void finish(ImportedAsset& out, Diagnostics& diag, std::vector<std::string> opened) {
  for (const AssetTexture& t : out.textures) {
    if (t.missing)
      diag.warning(t.where, "texture '" + t.name + "' named by '" + fs::path(out.path).filename().string() +
                                "' not found; looked beside it in '" + fs::path(out.path).parent_path().string() +
                                "' (as written, and by its file name alone)");
  }
  count(out);
  out.files_read = std::move(opened);
  for (const AssetTexture& t : out.textures)
    if (!t.resolved.empty()) out.files_read.push_back(t.resolved);
}

}  // namespace

void release_importer_pages() { release_library_pages({"libassimp.so", "libdraco.so"}); }

SourceLocation file_location(const std::string& path) {
  SourceLocation loc;
  loc.file = std::make_shared<const SourceFile>(SourceFile{path, {}});
  return loc;
}

std::optional<AssetFormat> asset_format_of(const std::string& path) {
  const std::string ext = lower(fs::path(path).extension().string());
  if (ext == ".obj") return AssetFormat::Obj;
  if (ext == ".gltf") return AssetFormat::Gltf;
  if (ext == ".glb") return AssetFormat::Glb;
  if (ext == ".dae") return AssetFormat::Collada;
  return std::nullopt;
}

const char* asset_format_name(AssetFormat format) {
  switch (format) {
    case AssetFormat::Obj: return "OBJ";
    case AssetFormat::Gltf: return "glTF";
    case AssetFormat::Glb: return "glTF binary";
    case AssetFormat::Collada: return "COLLADA";
  }
  return "?";
}

std::string find_asset_file(const std::string& dir, const std::string& name) {
  std::string slashed = name;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  std::error_code ec;
  for (const std::string& candidate : {name, slashed, url_decoded(slashed), fs::path(slashed).filename().string()}) {
    if (candidate.empty()) continue;
    const fs::path p = fs::path(candidate).is_absolute() ? fs::path(candidate) : fs::path(dir) / candidate;
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  }
  return {};
}

int AssetTextureTable::file(const std::string& name, const SourceLocation& where, const std::string& dir) {
  const std::string resolved = find_asset_file(dir.empty() ? dir_ : dir, name);
  const std::string key = resolved.empty() ? "?" + name : resolved;
  if (const auto it = ids_.find(key); it != ids_.end()) return it->second;
  AssetTexture t;
  t.name = name;
  t.resolved = resolved;
  t.where = where;
  t.missing = resolved.empty();
  asset_.textures.push_back(std::move(t));
  return ids_[key] = static_cast<int>(asset_.textures.size() - 1);
}

int AssetTextureTable::embedded(const std::string& key, const std::string& name,
                                std::shared_ptr<const std::vector<unsigned char>> bytes, const std::string& hint,
                                const SourceLocation& where) {
  if (const auto it = ids_.find("*" + key); it != ids_.end()) return it->second;
  AssetTexture t;
  t.name = name;
  t.embedded = std::move(bytes);
  t.format_hint = hint;
  t.where = where;
  asset_.textures.push_back(std::move(t));
  return ids_["*" + key] = static_cast<int>(asset_.textures.size() - 1);
}

bool read_asset(const std::string& resolved, const std::string& written, const SourceLocation& where,
                ImportedAsset& out, Diagnostics& diag) {
  out = ImportedAsset{};
  out.path = resolved;
  const std::optional<AssetFormat> format = asset_format_of(resolved);
  const std::string error = format ? why_not_read(resolved, kMaxAssetFileBytes, "model") : std::string();
  if (!format || !error.empty()) {
    diag.error(where, "cannot read '" + written + "': " + (format ? error : "not a model file this build reads"));
    return false;
  }
  out.format = *format;
  std::vector<std::string> opened;
  const bool read = out.format == AssetFormat::Obj ? read_obj_asset(where, written, out, diag, opened)
                                                   : read_with_assimp(written, where, out, diag, opened);
  if (!read) return false;
  finish(out, diag, std::move(opened));
  if (out.placements.empty()) {
    diag.error(where, "cannot read '" + written + "': the file places no triangles (nothing to render)");
    return false;
  }
  return true;
}

}  // namespace pt
