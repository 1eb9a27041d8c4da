// Internal to import_asset*.cpp: the import entry as read, and the steps of
// placing a model file in the scene.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/transform.h"
#include "scene/asset.h"
#include "scene/import_asset.h"

namespace pt {

// One {"type": "import"} entry (or a model file given as the scene).
struct ImportRequest {
  SourceLocation where;           // the entry
  Sourced<std::string> file;      // as written
  std::string resolved;           // the existing file
  Affine transform;               // the entry's "transform" (identity if none)
  int material = -1;              // "material": index into the native materials, or -1 (the file's)
  bool use_camera = true;         // "camera": false
  std::string camera_name;        // "camera": "name" (empty: the first)
  SourceLocation camera_where;
  bool use_lights = true;         // "lights": false
};

// The native importer's tables the placed shapes and objects join.
struct NativeTables {
  std::vector<NativeMaterial>& materials;
  std::vector<int>& shape_material;
  std::vector<std::vector<int>>& object_material;
};

// Reads the entry's keys and finds its file; false after reporting a problem.
bool read_import_request(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials,
                         ImportRequest& req);
// Shapes, objects and instances of the file's placements (import_asset.cpp).
void place_meshes(ImportContext& ctx, ImportedAsset& asset, const ImportRequest& req, const std::vector<int>& material,
                  NativeTables& tables, ImportCounts& counts);
// The file's lights and its camera (import_asset_view.cpp).
void place_camera_and_lights(ImportContext& ctx, const ImportedAsset& asset, const ImportRequest& req,
                             ImportCounts& counts);

}  // namespace pt
