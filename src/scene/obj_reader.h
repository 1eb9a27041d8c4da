// Wavefront OBJ, read as a stream: the file goes through a fixed buffer, one
// line at a time, straight into the triangle meshes the renderer uses (no
// copy of the file, no per-corner vertex arrays): each (v, vt, vn) index
// triple a face names becomes one vertex of its mesh, found again through a
// flat hash table, so a vertex shared by faces is stored once
// (docs/importing.md, "OBJ"; docs/bench/scale.md for the memory it takes).
//
// The file's structure is Assimp 5.2's reading of it, which this reader
// replaced: an object per `o` (and per `g`), a mesh per run of faces with one
// material inside an object (`usemtl`), faces before any `o`/`g` in an object
// "defaultobject", the materials listed as [DefaultMaterial, the MTL files'
// materials in the order they are defined, usemtl names no MTL file defines].
// Polygons become triangles: a quad is split from its concave corner, if it
// has one (as Assimp), larger polygons as a fan from their first corner.
// Points and lines are counted and left out. uvs are flipped (v measured from
// the image's top, as our textures).
//
// Every problem carries its place in the file: malformed statements are
// errors at line:col (the read stops there); statements we do not read are
// warnings, each keyword once per file at its first line with the number of
// statements.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "geometry/shapes/mesh.h"

namespace pt {

inline constexpr const char* kObjDefaultMaterial = "DefaultMaterial";  // Assimp's AI_DEFAULT_MATERIAL_NAME
inline constexpr const char* kObjDefaultObject = "defaultobject";

// One run of faces with one material (normals and uvs: one per vertex, or
// none when no face of the run names any; a corner without one gets zero).
struct ObjMesh {
  std::string name;  // its object's name, or the material's when a usemtl started it
  int material = 0;  // index into ObjModel::materials
  TriangleMesh mesh;
};

struct ObjObject {
  std::string name;
  std::vector<int> meshes;  // indices into ObjModel::meshes, in file order (empty ones included)
};

struct ObjModel {
  std::vector<ObjObject> objects;
  std::vector<ObjMesh> meshes;
  std::vector<std::string> materials;  // [0] is kObjDefaultMaterial
  std::vector<bool> material_used;     // per material: some face has it
  uint64_t points = 0, lines = 0;      // left out (p, l, and faces of one or two corners)
};

// For each `mtllib` statement (`name`: the rest of its line, as written):
// the names of the materials the library defines, in order (empty if it
// cannot be read; the handler reports that). Without a handler, mtllib
// statements are skipped.
using ObjMtlLibHandler = std::function<std::vector<std::string>(const std::string& name, const SourceLocation& where)>;

struct ObjReadOptions {
  ObjMtlLibHandler mtllib;
  // All faces into meshes[0] (objects not recorded; materials still listed):
  // what a {"type": "mesh"} reads, without a second copy to merge the runs.
  // Its normals (uvs) are dropped unless every run of faces has some.
  bool one_mesh = false;
  std::uintmax_t max_bytes = std::uintmax_t{2} << 30;  // larger files are refused before they are read
};

// Reads the OBJ file `path`. False after reporting an error to `diag` (at its
// line and column in the file, or at the file when it cannot be read); `out`
// is then unspecified.
bool read_obj(const std::string& path, const ObjReadOptions& options, ObjModel& out, Diagnostics& diag);

}  // namespace pt
