#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_check.h"
#include "fuzz_targets.h"
#include "scene/mesh_obj.h"

namespace pt::fuzz {

int obj_one_input(const uint8_t* data, std::size_t size) {
  // load_obj reads a file (the streaming reader never holds it whole): one private
  // file per process, rewritten for every input.
  static const std::string path = (std::filesystem::temp_directory_path() /
                                   ("pt_fuzz_obj_" + std::to_string(::getpid()) + ".obj")).string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    require(static_cast<bool>(out), "the fuzz input can be written to a temporary file");
  }
  TriangleMesh mesh;
  std::string error;
  const bool ok = load_obj(path, mesh, error);
  std::remove(path.c_str());
  if (!ok) {
    require(!error.empty(), "a refused OBJ file says why");
    return 0;
  }
  require(mesh.indices.size() % 3 == 0, "OBJ indices come in triangles");
  for (uint32_t i : mesh.indices) require(i < mesh.positions.size(), "OBJ indices are within the vertex array");
  for (const Vec3f& p : mesh.positions) require(is_finite(p), "OBJ positions are finite");
  require(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size(), "one OBJ normal per vertex, or none");
  require(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size(), "one OBJ uv per vertex, or none");
  return 0;
}

}  // namespace pt::fuzz
