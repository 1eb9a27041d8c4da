// Internal to read_asset (asset_reader.h): the pieces its source files share.
// Only asset_reader.cpp and asset_assimp*.cpp include Assimp's headers (glTF,
// COLLADA; OBJ is read by asset_obj.cpp); the rest of the renderer sees the
// neutral record of asset.h.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene/asset.h"
#include "scene/asset_reader.h"

struct aiScene;

namespace pt {

// The textures of one asset, each once: files resolved beside the model (as
// written, with '\' read as '/', URL escapes decoded, then by file name
// alone), or images embedded in it.
class AssetTextureTable {
 public:
  AssetTextureTable(ImportedAsset& asset, std::string model_dir) : asset_(asset), dir_(std::move(model_dir)) {}

  // The index of the file `name` (relative to `dir`, the model's directory
  // if empty), adding it the first time; a file not found is added with
  // `missing` set (read_asset reports it).
  int file(const std::string& name, const SourceLocation& where, const std::string& dir = {});
  // The index of an embedded image (encoded bytes), adding it the first time.
  int embedded(const std::string& key, const std::string& name,
               std::shared_ptr<const std::vector<unsigned char>> bytes, const std::string& hint,
               const SourceLocation& where);

 private:
  ImportedAsset& asset_;
  std::string dir_;
  std::map<std::string, int> ids_;
};

// Where the texture file `name` written in a model in `dir` is: as written,
// with '\' as '/', URL escapes decoded ("%20"), then its file name alone in
// `dir`. Empty if none exists.
std::string find_asset_file(const std::string& dir, const std::string& name);

// ---------------------------------------------------------------- asset_obj.cpp
// An OBJ file (out.path; out.format set) and its MTL files, by our own
// readers (no Assimp). Problems inside the files are reported at their
// lines; false after an error (the reader's, then one at `where` naming
// `written`). Appends the model and the MTL files read to `files_opened`.
bool read_obj_asset(const SourceLocation& where, const std::string& written, ImportedAsset& out, Diagnostics& diag,
                    std::vector<std::string>& files_opened);

// ---------------------------------------------------------------- asset_assimp.cpp
// Every triangle mesh of the scene (points and lines are counted and left
// out), with the texture-coordinate set `uv_set[material]` (0 where the
// material has no texture). False after reporting a mesh whose data cannot
// be used (non-finite positions, too many vertices) at `where`.
bool convert_meshes(const aiScene& scene, const std::vector<int>& uv_set, ImportedAsset& out, Diagnostics& diag,
                    const SourceLocation& where);
// The nodes that place meshes, with their transforms to the file's world space.
void convert_placements(const aiScene& scene, ImportedAsset& out);
// Cameras and lights, in the file's world space; lights in our units.
void convert_cameras(const aiScene& scene, ImportedAsset& out);
void convert_lights(const aiScene& scene, ImportedAsset& out);

// ---------------------------------------------------------------- asset_assimp_materials.cpp
// The materials of a glTF or COLLADA file as Assimp reads them, their
// textures added to `textures`.
void convert_materials(const aiScene& scene, ImportedAsset& out, AssetTextureTable& textures);
// The texture-coordinate set each material's diffuse (base colour) texture reads.
std::vector<int> diffuse_uv_sets(const aiScene& scene);
// The names of the scene's materials, in order (Assimp's "DefaultMaterial" included).
std::vector<std::string> material_names(const aiScene& scene);

}  // namespace pt
