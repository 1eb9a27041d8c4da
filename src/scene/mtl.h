// Wavefront MTL files: our own small reader (Assimp reads them too, but does
// not say on which line a statement was), so that every statement we do not
// support is reported once, at its first line, and every material and texture
// carries its place in the file. docs/importing.md has the mapping.
#pragma once

#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene/asset.h"
#include "scene/asset_internal.h"

namespace pt {

// MTL files larger than this are refused (an MTL file is a few kilobytes).
inline constexpr std::size_t kMaxMtlFileBytes = std::size_t{64} << 20;

// Reads the MTL file `path` and appends its materials (model Phong) to
// `materials`, their textures (resolved beside the MTL file) to `textures`.
// Statements we do not read, malformed values and texture options are
// warnings, each kind once per file at its first occurrence with the number
// of statements. Returns false (nothing appended) if the file cannot be read;
// `error` says why.
bool read_mtl(const std::string& path, std::vector<AssetMaterial>& materials, AssetTextureTable& textures,
              Diagnostics& diag, std::string& error);

}  // namespace pt
