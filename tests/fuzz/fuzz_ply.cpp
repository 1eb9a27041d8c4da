#include <cmath>
#include <string>

#include "fuzz_check.h"
#include "fuzz_targets.h"
#include "scene/ply.h"

namespace pt::fuzz {

int ply_one_input(const uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  TriangleMesh mesh;
  PlyError error;
  if (!parse_ply(bytes, mesh, error)) {
    require(!error.message.empty(), "a refused PLY file says why");
    require(error.line >= 0, "PLY error lines are 1-based or 0");
    return 0;
  }
  require(error.message.empty(), "an accepted PLY file has no error");
  require(mesh.indices.size() % 3 == 0, "PLY indices come in triangles");
  for (uint32_t i : mesh.indices) require(i < mesh.positions.size(), "PLY indices are within the vertex array");
  for (const Vec3f& p : mesh.positions) require(is_finite(p), "PLY positions are finite");
  require(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size(), "one PLY normal per vertex, or none");
  require(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size(), "one PLY uv per vertex, or none");
  for (const Vec3f& n : mesh.normals) require(is_finite(n), "PLY normals are finite");
  for (const Vec2f& uv : mesh.uvs) require(std::isfinite(uv.x) && std::isfinite(uv.y), "PLY uvs are finite");
  // Nothing bigger than the file can explain: a triangle needs at least one
  // index byte, fan triangulation at most triples the indices of a polygon.
  require(mesh.positions.size() <= size, "no more vertices than bytes");
  require(mesh.indices.size() <= 3 * size, "no more indices than the bytes can describe");
  return 0;
}

}  // namespace pt::fuzz
