// An OBJ file with its MTL files -> the neutral ImportedAsset, without
// Assimp: the streaming reader (obj_reader.h) for the geometry and its
// structure, our MTL reader (mtl.h) for the materials. The result is what
// Assimp 5.2 made of the file (a node per object, a mesh per material run, the
// materials in Assimp's order), read in a fraction of its memory and time
// (docs/bench/scale.md).
#include <algorithm>
#include <filesystem>
#include <utility>

#include "core/file_access.h"
#include "scene/asset_internal.h"
#include "scene/mtl.h"
#include "scene/obj_reader.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

// The MTL files an OBJ file names, read as it names them (Assimp's search:
// the name beside the OBJ file, then the OBJ file's own name with .mtl).
class MtlLibraries {
 public:
  MtlLibraries(const std::string& obj_path, AssetTextureTable& textures, Diagnostics& diag)
      : obj_(obj_path), textures_(textures), diag_(diag) {}

  std::vector<std::string> read(const std::string& name, const SourceLocation& where) {
    std::string path = (fs::path(obj_).parent_path() / name).string();
    if (!why_unreadable(path).empty()) {
      diag_.warning(where, not_found(name, path));
      path = obj_.substr(0, obj_.size() - 3) + "mtl";  // Assimp's fallback
      if (!why_unreadable(path).empty()) {
        diag_.warning(where, not_found(fs::path(path).filename().string(), path));
        return {};
      }
    }
    const std::size_t before = defined.size();
    std::string error;
    if (!read_mtl(path, defined, textures_, diag_, error)) {
      diag_.warning(where, "cannot read material library '" + path + "': " + error);
      return {};
    }
    if (std::find(opened.begin(), opened.end(), path) == opened.end()) opened.push_back(path);
    std::vector<std::string> names;
    for (std::size_t i = before; i < defined.size(); ++i) names.push_back(defined[i].name);
    return names;
  }

  std::vector<AssetMaterial> defined;  // every definition, in the order read
  std::vector<std::string> opened;     // the MTL files read

 private:
  static std::string not_found(const std::string& name, const std::string& path) {
    return "material library '" + name + "' (mtllib) not found at '" + path + "'";
  }
  const std::string& obj_;
  AssetTextureTable& textures_;
  Diagnostics& diag_;
};

// The file's materials, in the reader's order: each from its last definition
// in the MTL files (as Assimp), or the defaults under its name.
void set_materials(const ObjModel& model, const std::vector<AssetMaterial>& defined, ImportedAsset& out,
                   Diagnostics& diag) {
  const SourceLocation file = file_location(out.path);
  out.materials.resize(model.materials.size());
  for (std::size_t i = 0; i < model.materials.size(); ++i) {
    const std::string& name = model.materials[i];
    const auto it = std::find_if(defined.rbegin(), defined.rend(), [&](const AssetMaterial& m) { return m.name == name; });
    if (it != defined.rend()) {
      out.materials[i] = *it;
      continue;
    }
    AssetMaterial& m = out.materials[i];
    m.name = name;
    m.where = file;
    if (model.material_used[i] && name != kObjDefaultMaterial)
      diag.warning(file, "material '" + name + "' (usemtl) is defined in no material library; its faces get "
                                               "the default material");
  }
}

// A node per object placing its meshes (Assimp's order: object by object).
void set_meshes(ObjModel& model, ImportedAsset& out) {
  for (const ObjObject& object : model.objects) {
    AssetPlacement p;
    p.node = object.name;
    for (int k : object.meshes) {
      ObjMesh& m = model.meshes[static_cast<std::size_t>(k)];
      if (m.mesh.indices.empty()) continue;
      p.meshes.push_back(static_cast<int>(out.meshes.size()));
      out.meshes.push_back(AssetMesh{m.name, std::move(m.mesh), {}, m.material});
    }
    if (!p.meshes.empty()) out.placements.push_back(std::move(p));
  }
  out.counts.skipped_n("point and line primitives", model.points + model.lines);
}

}  // namespace

bool read_obj_asset(const SourceLocation& where, const std::string& written, ImportedAsset& out, Diagnostics& diag,
                    std::vector<std::string>& files_opened) {
  AssetTextureTable textures(out, fs::path(out.path).parent_path().string());
  MtlLibraries libraries(out.path, textures, diag);
  ObjReadOptions options;
  options.max_bytes = kMaxAssetFileBytes;
  options.mtllib = [&](const std::string& name, const SourceLocation& at) { return libraries.read(name, at); };
  ObjModel model;
  if (!read_obj(out.path, options, model, diag)) {
    diag.error(where, "cannot read '" + written + "' (OBJ): the error above");
    return false;
  }
  set_materials(model, libraries.defined, out, diag);
  set_meshes(model, out);
  files_opened.push_back(out.path);
  files_opened.insert(files_opened.end(), libraries.opened.begin(), libraries.opened.end());
  return true;
}

}  // namespace pt
