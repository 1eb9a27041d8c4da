// PLY mesh reader: ASCII and binary (little and big endian), triangles and
// polygons (fan-triangulated), optional per-vertex normals (nx,ny,nz) and
// texture coordinates (u,v | s,t | texture_u,texture_v). Counts in the header
// are checked against the file size before anything is allocated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace pt {

struct PlyMesh {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<Vec3f> normals;     // empty or one per vertex
  std::vector<Vec2f> uvs;         // empty or one per vertex
};

struct PlyError {
  std::string message;  // what is wrong
  int line = 0;         // 1-based header line for header errors, 0 otherwise
};

// Returns true on success. On failure fills `error` and leaves `out` unspecified.
bool load_ply(const std::string& path, PlyMesh& out, PlyError& error);
bool parse_ply(const std::string& bytes, PlyMesh& out, PlyError& error);

}  // namespace pt
