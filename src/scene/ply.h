// PLY mesh reader: ASCII and binary (little and big endian), triangles and
// polygons (fan-triangulated), optional per-vertex normals (nx,ny,nz) and
// texture coordinates (u,v | s,t | texture_u,texture_v). Counts in the header
// are checked against the file size before anything is allocated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/shapes/mesh.h"

namespace pt {

struct PlyError {
  std::string message;  // what is wrong
  int line = 0;         // 1-based header line for header errors, 0 otherwise
};

// Fills a TriangleMesh (positions, 3 indices per triangle, normals and uvs each
// empty or one per vertex). Returns true on success. On failure fills `error`
// and leaves `out` unspecified.
bool load_ply(const std::string& path, TriangleMesh& out, PlyError& error);
bool parse_ply(const std::string& bytes, TriangleMesh& out, PlyError& error);

}  // namespace pt
