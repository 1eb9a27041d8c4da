// The OBJ mesh reader (src/scene/mesh_obj.cpp), which the acceleration
// benchmark and native scenes use for OBJ meshes: triangulation, merging of
// parts, normals and texture coordinates, errors, and a scene that names an
// OBJ file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "scene/loader.h"
#include "scene/mesh_obj.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

class ObjFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pt_obj_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  fs::path dir_;
};

// A unit square as one quad and a triangle beside it, in two groups, with
// normals and texture coordinates throughout.
constexpr const char* kTwoParts = R"(# test
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
g square
f 1/1/1 2/2/1 3/3/1 4/4/1
g triangle
f 2/1/1 5/2/1 3/3/1
)";

TEST_F(ObjFiles, TriangulatesAndMergesParts) {
  TriangleMesh m;
  std::string error;
  ASSERT_TRUE(load_obj(write("a.obj", kTwoParts), m, error)) << error;
  EXPECT_EQ(m.indices.size(), 9u);  // the quad as 2 triangles, and 1
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
  for (const Vec3f& n : m.normals) EXPECT_EQ(n, Vec3f(0, 0, 1));
  // Every triangle faces +z (counter-clockwise seen from +z) and the areas add up.
  float area = 0;
  for (std::size_t k = 0; k < m.indices.size(); k += 3) {
    const Vec3f a = m.positions[m.indices[k]], b = m.positions[m.indices[k + 1]], c = m.positions[m.indices[k + 2]];
    const Vec3f n = cross(b - a, c - a);
    EXPECT_GT(n.z, 0.0f);
    area += 0.5f * n.z;
  }
  EXPECT_FLOAT_EQ(area, 1.5f);
  // Texture coordinates travel with their corners, v measured from the
  // image's top (OBJ's vt 1 1 is the top-right corner).
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    if (m.positions[v] == Vec3f(1, 1, 0)) {
      EXPECT_EQ(m.uvs[v], Vec2f(1, 0));
    }
  }
}

TEST_F(ObjFiles, DropsNormalsAndUvsThatOnlySomePartsHave) {
  TriangleMesh m;
  std::string error;
  ASSERT_TRUE(load_obj(write("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\n"
                                      "g a\nf 1//1 2//1 3//1\ng b\nf 2 4 3\n"),
                       m, error))
      << error;
  EXPECT_EQ(m.indices.size(), 6u);
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.uvs.empty());
}

TEST_F(ObjFiles, ReportsWhatIsWrong) {
  TriangleMesh m;
  std::string error;
  EXPECT_FALSE(load_obj((dir_ / "missing.obj").string(), m, error));
  EXPECT_NE(error.find("cannot read"), std::string::npos) << error;
  EXPECT_FALSE(load_obj(write("points.obj", "v 0 0 0\nv 1 0 0\np 1\nl 1 2\n"), m, error));
  EXPECT_NE(error.find("no triangles"), std::string::npos) << error;
  EXPECT_FALSE(load_obj(write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), m, error));
  EXPECT_FALSE(error.empty());
}

TEST_F(ObjFiles, NativeSceneReadsAnObjMesh) {
  write("part.obj", kTwoParts);
  const std::string scene = write("scene.json", R"({
  "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40 },
  "film": { "width": 8, "height": 8 },
  "shapes": [ { "type": "mesh", "file": "part.OBJ" } ]
})");
  fs::rename(dir_ / "part.obj", dir_ / "part.OBJ");  // the extension in any case
  Diagnostics diag;
  const auto desc = load_scene(scene, LoadOptions{}, diag);
  ASSERT_TRUE(desc.has_value()) << diag.format();
  ASSERT_EQ(desc->shapes.size(), 1u);
  const auto& mesh = std::get<TriangleMesh>(desc->shapes[0].geometry);
  EXPECT_EQ(mesh.indices.size(), 9u);
  EXPECT_EQ(desc->shapes[0].file, "part.OBJ");

  write("broken.obj", "# only points and lines\nv 0 0 0\nv 1 0 0\np 1\nl 1 2\n");
  const std::string bad = write("bad.json", R"({
  "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40 },
  "film": { "width": 8, "height": 8 },
  "shapes": [ { "type": "mesh", "file": "broken.obj" } ]
})");
  Diagnostics bad_diag;
  EXPECT_FALSE(load_scene(bad, LoadOptions{}, bad_diag).has_value() && !bad_diag.has_errors());
  ASSERT_TRUE(bad_diag.has_errors());
  EXPECT_NE(bad_diag.format().find("cannot read mesh 'broken.obj': the file holds no triangles"), std::string::npos)
      << bad_diag.format();
  EXPECT_NE(bad_diag.format().find("bad.json:5:"), std::string::npos) << bad_diag.format();
}

TEST(ObjAssets, StanfordBunny) {
  const fs::path bunny = fs::path(PT_SHARED_DIR) / "assets" / "meshes" / "stanford-bunny.obj";
  if (!fs::exists(bunny)) GTEST_SKIP() << bunny << " is not available";
  TriangleMesh m;
  std::string error;
  ASSERT_TRUE(load_obj(bunny.string(), m, error)) << error;
  EXPECT_EQ(m.indices.size(), 3u * 69451u);
  EXPECT_LE(m.positions.size(), 35947u);  // the file's vertices that faces use
  EXPECT_GT(m.positions.size(), 34000u);
}

}  // namespace
}  // namespace pt
