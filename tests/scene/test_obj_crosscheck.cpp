// Our OBJ reader against Assimp 5.2's, which it replaced (with the flags the
// renderer used: Triangulate, JoinIdenticalVertices, SortByPType, FlipUVs):
// the same nodes, meshes, materials and triangles, corner by corner, for the
// test assets and, where ../shared has them, Sponza, the bunny and the
// Cornell box. Positions may differ in the last bit (Assimp's fast_atof is not
// correctly rounded; std::from_chars is).
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/asset_reader.h"
#include "scene/mesh_obj.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

struct Corner {
  Vec3f p, n;
  Vec2f uv;
  bool has_n = false, has_uv = false;
};
struct Part {  // one mesh placed by one node
  std::string node, material;
  std::vector<Corner> corners;  // 3 per triangle
  std::size_t vertices = 0;
};

std::vector<Part> with_assimp(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* s = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                 aiProcess_SortByPType | aiProcess_ValidateDataStructure |
                                                 aiProcess_FlipUVs);
  std::vector<Part> parts;
  if (s == nullptr) return parts;
  std::vector<const aiNode*> stack{s->mRootNode};
  while (!stack.empty()) {
    const aiNode* node = stack.back();
    stack.pop_back();
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh& m = *s->mMeshes[node->mMeshes[k]];
      if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      aiString name;
      s->mMaterials[m.mMaterialIndex]->Get(AI_MATKEY_NAME, name);
      Part part{node->mName.C_Str(), name.C_Str(), {}, m.mNumVertices};
      for (unsigned f = 0; f < m.mNumFaces; ++f) {
        if (m.mFaces[f].mNumIndices != 3) continue;
        for (int c = 0; c < 3; ++c) {
          const unsigned v = m.mFaces[f].mIndices[c];
          Corner corner;
          corner.p = Vec3f(m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z);
          if ((corner.has_n = m.HasNormals())) corner.n = Vec3f(m.mNormals[v].x, m.mNormals[v].y, m.mNormals[v].z);
          if ((corner.has_uv = m.HasTextureCoords(0)))
            corner.uv = Vec2f(m.mTextureCoords[0][v].x, m.mTextureCoords[0][v].y);
          part.corners.push_back(corner);
        }
      }
      parts.push_back(std::move(part));
    }
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.push_back(node->mChildren[c]);
  }
  return parts;
}

std::vector<Part> with_ours(const std::string& path, Diagnostics& diag) {
  ImportedAsset asset;
  std::vector<Part> parts;
  if (!read_asset(path, path, SourceLocation{}, asset, diag)) return parts;
  for (const AssetPlacement& p : asset.placements) {
    for (int k : p.meshes) {
      const AssetMesh& am = asset.meshes[static_cast<std::size_t>(k)];
      const TriangleMesh& m = am.mesh;
      Part part{p.node, asset.materials[static_cast<std::size_t>(am.material)].name, {}, m.positions.size()};
      for (uint32_t v : m.indices) {
        Corner c;
        c.p = m.positions[v];
        if ((c.has_n = !m.normals.empty())) c.n = m.normals[v];
        if ((c.has_uv = !m.uvs.empty())) c.uv = m.uvs[v];
        part.corners.push_back(c);
      }
      parts.push_back(std::move(part));
    }
  }
  return parts;
}

// Relative difference, in units of float's epsilon.
float ulps(float a, float b) {
  return std::abs(a - b) / (std::numeric_limits<float>::epsilon() * std::max({std::abs(a), std::abs(b), 1e-30f}));
}

void expect_same(const std::string& path) {
  Diagnostics diag;
  const std::vector<Part> theirs = with_assimp(path), ours = with_ours(path, diag);
  ASSERT_FALSE(theirs.empty()) << path;
  ASSERT_EQ(ours.size(), theirs.size()) << path << "\n" << diag.format();
  float worst = 0;
  std::size_t triangles = 0, our_vertices = 0, their_vertices = 0;
  for (std::size_t i = 0; i < ours.size(); ++i) {
    ASSERT_EQ(ours[i].node, theirs[i].node) << path << " part " << i;
    ASSERT_EQ(ours[i].material, theirs[i].material) << path << " part " << i;
    ASSERT_EQ(ours[i].corners.size(), theirs[i].corners.size()) << path << " part " << i;
    for (std::size_t c = 0; c < ours[i].corners.size(); ++c) {
      const Corner &a = ours[i].corners[c], &b = theirs[i].corners[c];
      ASSERT_EQ(a.has_n, b.has_n);
      ASSERT_EQ(a.has_uv, b.has_uv);
      for (int k = 0; k < 3; ++k) worst = std::max(worst, ulps(a.p[k], b.p[k]));
      for (int k = 0; k < 3 && a.has_n; ++k) worst = std::max(worst, ulps(a.n[k], b.n[k]));
      // v as the file writes it: 1 - v loses the relative precision of a v near 1.
      if (a.has_uv) worst = std::max({worst, ulps(a.uv.x, b.uv.x), ulps(1.0f - a.uv.y, 1.0f - b.uv.y)});
    }
    triangles += ours[i].corners.size() / 3;
    our_vertices += ours[i].vertices;
    their_vertices += theirs[i].vertices;
  }
  // Ours joins equal (v, vt, vn) triples, Assimp equal values: never fewer.
  EXPECT_GE(our_vertices, their_vertices) << path;
  // fast_atof against correct rounding: at most a unit or two in the last place.
  EXPECT_LE(worst, 2.0f) << path;
  std::printf("%s: %zu parts, %zu triangles, %zu vertices (Assimp %zu), largest difference %.2f ulp\n", path.c_str(),
              ours.size(), triangles, our_vertices, their_vertices, static_cast<double>(worst));
}

TEST(ObjCrosscheck, TestAssetsAsAssimpReadThem) {
  for (const char* name : {"features.obj", "two_materials.obj"})
    expect_same(std::string(PT_TEST_DATA_DIR) + "/data/assets/obj/" + name);
}

TEST(ObjCrosscheck, SharedModelsAsAssimpReadThem) {
  const fs::path assets = fs::path(PT_SHARED_DIR) / "assets";
  const fs::path files[] = {assets / "sponza" / "sponza.obj", assets / "meshes" / "stanford-bunny.obj",
                            assets / "cornell" / "cornell_box_original_tinyobjloader.obj"};
  int found = 0;
  for (const fs::path& f : files) {
    if (!fs::exists(f)) continue;
    ++found;
    expect_same(f.string());
  }
  if (found == 0) GTEST_SKIP() << "no OBJ files under " << assets;
}

}  // namespace
}  // namespace pt
