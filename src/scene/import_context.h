// State shared by the three importers while they fill a SceneDescription, and
// the helpers they have in common: texture registration (each file once),
// mesh files, and the default material.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "scene/json_reader.h"
#include "scene/loader.h"
#include "scene/scene_description.h"

namespace pt {

// A camera an imported model file brought (import_asset.cpp), for a scene
// without a camera of its own.
struct ImportedCamera {
  CameraDesc camera;
  float aspect = 0;  // the file's width / height; 0 if it gives none
  std::string file, name;
};

struct ImportContext {
  ReadContext read;
  const LoadOptions& options;
  SceneDescription& scene;
  std::map<std::string, int> texture_ids;  // canonical path (+ raw mark) -> index in scene.textures
  std::optional<int> default_material;     // index, once a shape needed it
  std::optional<ImportedCamera> imported_camera;  // the first import's camera, if it brought one

  Diagnostics& diag() { return read.diag; }
  const JsonDocument& doc() { return read.doc; }
};

// Resolves a path written in the file (see resolve_scene_path); a missing
// file is reported at the path's location as "<what> 'x' not found; looked
// in ..." and gives std::nullopt.
std::optional<std::string> find_scene_file(ImportContext& ctx, const Sourced<std::string>& written,
                                           const std::string& what);

// Resolves a texture path written in the file (see resolve_scene_path) and
// returns its index in scene.textures, adding it the first time (a file read
// `raw`, without sRGB decoding, is an entry of its own). A missing file is
// reported (saying where it was looked for) and gives std::nullopt.
std::optional<int> add_texture(ImportContext& ctx, const Sourced<std::string>& written, bool raw = false);

// Resolves and reads a mesh file into shape.geometry (a TriangleMesh) and
// records the file in shape.file and shape.fields ("file"): OBJ for a .obj
// extension (any case), PLY otherwise. Problems are reported at the path's location.
bool load_mesh_file(ImportContext& ctx, const Sourced<std::string>& written, ShapeDesc& shape);

// The index of the material used by shapes that name none (added on first use).
int default_material(ImportContext& ctx);

// "looked in '<scene dir>/x' and '<cwd>/x'" for messages about missing files.
std::string describe_search(const std::string& scene_path, const std::string& written);

}  // namespace pt
