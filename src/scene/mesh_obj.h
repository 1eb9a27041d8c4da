// Wavefront OBJ as one mesh (the streaming reader, obj_reader.h). Every run
// of faces (objects, groups, material switches) goes into one triangle mesh:
// positions, and per-vertex normals and texture coordinates where every run
// of the file has them (v measured from the image's top, as our textures:
// OBJ's v is flipped). Polygons are triangulated, each run's (v, vt, vn)
// triples stored once; points and lines are dropped.
// Materials (MTL) are not read here (a model file's materials come in through
// {"type": "import"}, asset_reader.h); `info` says how many the file names.
// Fills the same struct as the PLY reader.
#pragma once

#include <cstdint>
#include <string>

#include "core/diagnostics.h"
#include "geometry/shapes/mesh.h"

namespace pt {

// Files larger than this are refused before they are read.
inline constexpr std::uintmax_t kMaxObjFileBytes = std::uintmax_t{2} << 30;  // 2 GiB

struct ObjInfo {
  int materials = 0;  // materials (usemtl) the faces name
};

// Returns true on success. On failure `error` says what is wrong (without the
// path, which the caller adds, as for load_ply; with the line and column for a
// problem inside the file) and `out` is unspecified. With `diag`, problems
// inside the file (the error, and warnings about statements left out) are
// also reported there at their place in the file.
bool load_obj(const std::string& path, TriangleMesh& out, std::string& error, ObjInfo* info = nullptr,
              Diagnostics* diag = nullptr);

}  // namespace pt
