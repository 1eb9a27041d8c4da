// {"type": "import"}: a model file's meshes, materials and textures placed in
// the scene (docs/importing.md). Cameras, lights and framing are in
// import_asset_view.cpp.
#include "scene/import_asset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "core/stopwatch.h"
#include "scene/asset_reader.h"
#include "scene/import_asset_internal.h"
#include "scene/import_materials.h"
#include "scene/import_transform.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

// The scene's index of an asset texture (each file or embedded image once
// as colour, once as data).
int register_texture(ImportContext& ctx, const ImportedAsset& asset, int index, bool data) {
  const AssetTexture& t = asset.textures[static_cast<std::size_t>(index)];
  std::error_code ec;
  const std::string key = (data ? "data:" : "") + (t.embedded ? "embedded:" + asset.path + "#" + t.name
                                                             : fs::weakly_canonical(t.resolved, ec).string());
  if (const auto it = ctx.texture_ids.find(key); it != ctx.texture_ids.end()) return it->second;
  TextureDesc desc;
  desc.where = t.where;
  desc.written = t.name;
  desc.resolved = t.resolved;
  desc.raw = data;
  desc.embedded = t.embedded;
  desc.embedded_format = t.format_hint;
  const int id = static_cast<int>(ctx.scene.textures.size());
  ctx.scene.textures.push_back(std::move(desc));
  ctx.texture_ids.emplace(key, id);
  return id;
}

// Scene units per unit of the file: the cube root of the import transform's
// volume scale (bump heights are in the file's units).
float length_scale(const Affine& a) {
  const double s = std::cbrt(std::abs(a.determinant()));
  return std::isfinite(s) && s > 0.0 ? static_cast<float>(s) : 1.0f;
}

// One warning per kind of note, at its first place, naming the materials.
void report_notes(ImportContext& ctx, const std::vector<std::pair<MaterialNote, std::string>>& notes) {
  std::vector<std::string> kinds;
  for (const auto& [note, material] : notes)
    if (std::find(kinds.begin(), kinds.end(), note.kind) == kinds.end()) kinds.push_back(note.kind);
  for (const std::string& kind : kinds) {
    std::vector<std::string> names;
    const MaterialNote* first = nullptr;
    for (const auto& [note, material] : notes) {
      if (note.kind != kind) continue;
      if (!first) first = &note;
      if (std::find(names.begin(), names.end(), material) == names.end()) names.push_back(material);
    }
    std::string list;
    for (std::size_t i = 0; i < names.size() && i < 4; ++i) list += (i ? ", '" : "'") + names[i] + "'";
    if (names.size() > 4) list += " and " + std::to_string(names.size() - 4) + " more";
    const std::string message = kind + " (material" + (names.size() > 1 ? "s " : " ") + list + ")";
    if (first->warning) ctx.diag().warning(first->where, message);
    else ctx.diag().note(first->where, message);
  }
}

// The native material index of each asset material a placed mesh uses (-1
// for the others): mapped (import_materials.h), textures registered.
std::vector<int> place_materials(ImportContext& ctx, const ImportedAsset& asset, const ImportRequest& req,
                                 std::vector<NativeMaterial>& materials, ImportCounts& counts) {
  std::vector<int> index(asset.materials.size(), -1);
  std::vector<bool> used(asset.materials.size(), false);
  for (const AssetPlacement& p : asset.placements)
    for (int m : p.meshes) used[static_cast<std::size_t>(asset.meshes[static_cast<std::size_t>(m)].material)] = true;
  const auto n_used = static_cast<uint64_t>(std::count(used.begin(), used.end(), true));
  if (req.material >= 0) {
    counts.skipped_n("materials (replaced by the import's \"material\")", n_used);
    return std::vector<int>(asset.materials.size(), req.material);
  }
  std::vector<std::pair<MaterialNote, std::string>> notes;
  std::vector<int> textures;
  for (std::size_t i = 0; i < asset.materials.size(); ++i) {
    if (!used[i]) continue;
    MappedMaterial mapped = map_asset_material(asset.materials[i], asset.textures, length_scale(req.transform));
    for (MaterialNote& n : mapped.notes) notes.emplace_back(std::move(n), asset.materials[i].name);
    for (const TextureUse& use : mapped.textures) {
      set_texture(mapped.desc, use.slot, register_texture(ctx, asset, use.texture, use.data));
      if (std::find(textures.begin(), textures.end(), use.texture) == textures.end()) textures.push_back(use.texture);
    }
    // "file.gltf:name": unique across imports, and Cryptomatte's material name.
    mapped.desc.name = fs::path(req.file.value).filename().string() + ":" + mapped.desc.name;
    NativeMaterial m;
    m.desc = std::move(mapped.desc);
    m.used = true;
    index[i] = static_cast<int>(materials.size());
    materials.push_back(std::move(m));
  }
  report_notes(ctx, notes);
  counts.imported_n("materials", n_used);
  counts.imported_n("textures used", textures.size());
  return index;
}

ShapeDesc make_shape(const ImportRequest& req, const std::string& name, TriangleMesh mesh) {
  ShapeDesc s;
  s.where = req.where;
  s.name = name;
  s.type = "mesh";
  s.file = req.file.value;
  s.fields.push_back({"file", req.file.where});
  s.geometry = std::move(mesh);
  return s;
}

// The transform of a placement in the scene: the import's, after the node's.
std::optional<Affine> placement_transform(const ImportRequest& req, const AssetPlacement& p) {
  const Affine a = req.transform * p.to_world;
  if (!a.finite() || !a.invertible()) return std::nullopt;
  return a;
}

std::optional<Sourced<Transform>> sourced(const Affine& a, const SourceLocation& where) {
  if (a.is_identity()) return std::nullopt;
  return Sourced<Transform>(Transform(a), where);
}

}  // namespace

bool is_import(const JsonValue& v) {
  const JsonValue* type = v.is_object() ? v.find("type") : nullptr;
  return type && type->is_string() && type->as_string() == "import";
}

namespace {

// The meshes of the file grouped by the list a node places, in file order;
// how many groups use each mesh (one: it is moved into its shape, else copied).
struct Groups {
  std::vector<std::pair<std::vector<int>, std::vector<std::size_t>>> list;  // meshes, placements
  std::vector<int> uses;

  explicit Groups(const ImportedAsset& asset) : uses(asset.meshes.size(), 0) {
    std::map<std::vector<int>, std::size_t> index;
    for (std::size_t i = 0; i < asset.placements.size(); ++i) {
      const std::vector<int>& meshes = asset.placements[i].meshes;
      auto [it, added] = index.emplace(meshes, list.size());
      if (added) {
        list.push_back({meshes, {}});
        for (int m : meshes) ++uses[static_cast<std::size_t>(m)];
      }
      list[it->second].second.push_back(i);
    }
  }
  TriangleMesh take(ImportedAsset& asset, int m) {
    TriangleMesh& mesh = asset.meshes[static_cast<std::size_t>(m)].mesh;
    if (--uses[static_cast<std::size_t>(m)] == 0) return std::move(mesh);
    return mesh;
  }
};

int material_of(const ImportedAsset& asset, const std::vector<int>& material, int mesh) {
  return material[static_cast<std::size_t>(asset.meshes[static_cast<std::size_t>(mesh)].material)];
}

// A group placed more than once: one object, one instance per placement.
void place_object(ImportContext& ctx, ImportedAsset& asset, const ImportRequest& req, const std::vector<int>& material,
                  Groups& groups, std::size_t g, NativeTables& tables, ImportCounts& counts) {
  const auto& [meshes, placements] = groups.list[g];
  ObjectDesc object;
  object.where = req.where;
  object.name = fs::path(req.file.value).filename().string() + "#" + std::to_string(ctx.scene.objects.size());
  std::vector<int> object_material;
  for (int m : meshes) {
    object_material.push_back(material_of(asset, material, m));
    object.shapes.push_back(make_shape(req, asset.meshes[static_cast<std::size_t>(m)].name, groups.take(asset, m)));
  }
  for (std::size_t p : placements) {
    const std::optional<Affine> t = placement_transform(req, asset.placements[p]);
    if (!t) {
      counts.skipped_n("placements with a singular transform", 1);
      continue;
    }
    InstanceDesc inst;
    inst.where = req.where;
    inst.name = asset.placements[p].node;  // Cryptomatte's object name, as Blender names the node's object
    inst.object = static_cast<int>(ctx.scene.objects.size());
    inst.transform = sourced(*t, req.where);
    ctx.scene.instances.push_back(std::move(inst));
    counts.imported_n("instances", 1);
  }
  counts.imported_n("objects (meshes placed more than once)", 1);
  ctx.scene.objects.push_back(std::move(object));
  tables.object_material.push_back(std::move(object_material));
}

}  // namespace

void place_meshes(ImportContext& ctx, ImportedAsset& asset, const ImportRequest& req, const std::vector<int>& material,
                  NativeTables& tables, ImportCounts& counts) {
  Groups groups(asset);
  for (std::size_t g = 0; g < groups.list.size(); ++g) {
    const auto& [meshes, placements] = groups.list[g];
    if (placements.size() > 1) {
      place_object(ctx, asset, req, material, groups, g, tables, counts);
      continue;
    }
    const AssetPlacement& p = asset.placements[placements.front()];
    const std::optional<Affine> t = placement_transform(req, p);
    if (!t) {
      counts.skipped_n("placements with a singular transform", 1);
      continue;
    }
    for (int m : meshes) {
      // Named by its node, as Blender names the node's object (Cryptomatte's object name).
      const std::string& name = p.node.empty() ? asset.meshes[static_cast<std::size_t>(m)].name : p.node;
      ShapeDesc s = make_shape(req, name, groups.take(asset, m));
      s.transform = sourced(*t, req.where);
      tables.shape_material.push_back(material_of(asset, material, m));
      ctx.scene.shapes.push_back(std::move(s));
    }
    counts.imported_n("shapes", meshes.size());
  }
}

void read_native_import(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials,
                        std::vector<int>& shape_material, std::vector<std::vector<int>>& object_material) {
  ImportRequest req;
  if (!read_import_request(ctx, v, materials, req)) return;
  const auto start = Clock::now();
  ImportedAsset asset;
  if (!read_asset(req.resolved, req.file.value, req.file.where, asset, ctx.diag())) return;
  ImportCounts counts = std::move(asset.counts);
  NativeTables tables{materials, shape_material, object_material};
  const std::vector<int> material = place_materials(ctx, asset, req, materials, counts);
  place_meshes(ctx, asset, req, material, tables, counts);
  place_camera_and_lights(ctx, asset, req, counts);
  ImportSummary summary;
  summary.file = req.file.value;
  summary.format = asset_format_name(asset.format);
  summary.seconds = seconds_since(start);
  summary.imported = std::move(counts.imported);
  summary.skipped = std::move(counts.skipped);
  summary.files_read = std::move(asset.files_read);
  ctx.scene.mesh_load_seconds += summary.seconds;
  ctx.scene.imports.push_back(std::move(summary));
}

}  // namespace pt
