#include "scene/mesh_obj.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <system_error>

#include "core/file_access.h"

namespace pt {

namespace {

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The file can be read and is not larger than kMaxObjFileBytes.
bool check_obj_file(const std::string& path, std::string& error) {
  if (const std::string why = why_unreadable(path); !why.empty()) {
    error = "cannot read the file: " + why;
    return false;
  }
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) {
    error = "cannot read the file: " + ec.message();
    return false;
  }
  if (size > kMaxObjFileBytes) {
    error = "the file is " + std::to_string(size) + " bytes; OBJ files over " + std::to_string(kMaxObjFileBytes) +
            " bytes are refused";
    return false;
  }
  return true;
}

}  // namespace

bool load_obj(const std::string& path, TriangleMesh& out, std::string& error, ObjInfo* info) {
  if (!check_obj_file(path, error)) return false;

  Assimp::Importer importer;
  // SortByPType splits points and lines into meshes of their own, skipped below.
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                         aiProcess_ValidateDataStructure | aiProcess_FlipUVs;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (scene == nullptr) {
    error = importer.GetErrorString();
    if (error.empty()) error = "Assimp could not read the file";
    return false;
  }

  // Normals and uvs are kept only if every part has them (one per vertex or none).
  std::size_t vertices = 0, triangles = 0;
  bool normals = true, uvs = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    vertices += mesh->mNumVertices;
    triangles += mesh->mNumFaces;
    normals = normals && mesh->HasNormals();
    uvs = uvs && mesh->HasTextureCoords(0);
  }
  if (triangles == 0) {
    error = "the file holds no triangles or polygons";
    return false;
  }
  if (vertices > std::numeric_limits<uint32_t>::max() || triangles > std::numeric_limits<uint32_t>::max() / 3) {
    error = std::to_string(vertices) + " vertices and " + std::to_string(triangles) +
            " triangles exceed what a mesh can index (2^32 - 1 vertices, 2^32 / 3 triangles)";
    return false;
  }

  if (info) {
    std::vector<bool> named(scene->mNumMaterials, false);
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const unsigned k = scene->mMeshes[m]->mMaterialIndex;
      aiString name;
      if (k < named.size() && scene->mMaterials[k]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS &&
          std::string(name.C_Str()) != AI_DEFAULT_MATERIAL_NAME)
        named[k] = true;
    }
    info->materials = static_cast<int>(std::count(named.begin(), named.end(), true));
  }
  out = TriangleMesh{};
  out.positions.reserve(vertices + 1);  // one spare: the Embree backend can share the buffer
  out.indices.reserve(3 * triangles);
  if (normals) out.normals.reserve(vertices);
  if (uvs) out.uvs.reserve(vertices);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const auto base = static_cast<uint32_t>(out.positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      if (!finite(p)) {
        error = "vertex " + std::to_string(base + v) + " has a non-finite position";
        return false;
      }
      out.positions.emplace_back(p.x, p.y, p.z);
      if (normals) {
        const aiVector3D& n = mesh->mNormals[v];
        out.normals.push_back(finite(n) ? Vec3f(n.x, n.y, n.z) : Vec3f(0.0f));  // zero: falls back to ng
      }
      if (uvs) {
        const aiVector3D& t = mesh->mTextureCoords[0][v];
        out.uvs.push_back(std::isfinite(t.x) && std::isfinite(t.y) ? Vec2f(t.x, t.y) : Vec2f());
      }
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // triangulated: only stray points/lines remain
      for (int k = 0; k < 3; ++k) out.indices.push_back(base + face.mIndices[k]);
    }
  }
  return true;
}

}  // namespace pt
