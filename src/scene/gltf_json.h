// A glTF file's JSON, read once more beside Assimp (with our JSON reader, so
// with file:line:col) for what Assimp 5.2 drops or does not say: material
// names (lost in .glb files), KHR_materials_emissive_strength, transmission,
// ior and unlit, KHR_texture_transform, the extensions a file uses that we
// do not read, and where each material and image is written. For a .glb
// file the locations are in its JSON chunk. docs/importing.md.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnostics.h"

namespace pt {

struct GltfMaterialInfo {
  std::string name;
  SourceLocation where;
  std::optional<float> emissive_strength, transmission, ior;
  std::optional<float> normal_scale;  // normalTexture.scale
  bool unlit = false;
  std::optional<SourceLocation> texture_transform;  // the first KHR_texture_transform in it
  std::vector<std::pair<std::string, SourceLocation>> unsupported;  // extensions we do not read
};

struct GltfInfo {
  std::vector<GltfMaterialInfo> materials;  // in the file's order (Assimp's, too)
  std::map<std::string, SourceLocation> image_uris;
  // Extensions the file uses that we read nowhere, outside materials (a
  // material's are in its `unsupported`).
  std::vector<std::pair<std::string, SourceLocation>> unsupported;
};

// Reads the JSON of `path` (a .gltf file, or a .glb file's JSON chunk when
// `binary`). False if it cannot be read or parsed (Assimp then reports what is
// wrong with the file; the import goes on without these details).
bool read_gltf_info(const std::string& path, bool binary, GltfInfo& out);

}  // namespace pt
