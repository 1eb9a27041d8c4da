// read_asset(): a model file (OBJ + MTL, glTF 2.0 .gltf/.glb, COLLADA .dae)
// into the importer-neutral ImportedAsset (asset.h), through Assimp. The
// Assimp side lives in asset_assimp*.cpp; MTL files are read by our own
// reader (mtl.h) for their statements' lines, and a glTF file's JSON is read
// once more (gltf_json.h) for what Assimp 5.2 drops (extensions, names,
// locations). docs/importing.md.
#pragma once

#include <cstdint>
#include <string>

#include "core/diagnostics.h"
#include "scene/asset.h"

namespace pt {

// Model files larger than this are refused before they are read.
inline constexpr std::uintmax_t kMaxAssetFileBytes = std::uintmax_t{2} << 30;  // 2 GiB

// Reads `resolved` (the existing file; its extension chooses the format, see
// asset_format_of). Errors about the file as a whole (unreadable, too large,
// rejected by Assimp with its reason, nothing to render) are reported at
// `where` (the scene's reference to the file) naming `written`, and give
// false. Problems inside the file (an unsupported MTL statement, a texture
// that is named but not found, a mesh left out) are warnings at their own
// place in the model file where it is known, else at the file.
bool read_asset(const std::string& resolved, const std::string& written, const SourceLocation& where,
                ImportedAsset& out, Diagnostics& diag);

// Returns the pages of Assimp's code and constants (libassimp, libdraco) to
// the system (release_library_pages, core/heap.h). Every run touches about
// 2 MiB of them at start-up and a glTF import 3 MiB more; the scene loader
// calls this once loading is done (nothing after it runs them), and
// read_asset before Assimp reads a file and again before its scene is
// converted, so that they do not sit under the import's own peak either
// (docs/bench/scale.md).
void release_importer_pages();

// A location naming only `path` (for problems with no line in a binary file
// or one Assimp read).
SourceLocation file_location(const std::string& path);

}  // namespace pt
