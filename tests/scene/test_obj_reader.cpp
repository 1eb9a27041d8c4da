// The streaming OBJ reader (src/scene/obj_reader.cpp): index forms and
// negative indices, polygons, missing vt/vn, CRLF and continued lines, the
// object/material structure Assimp gave, and errors at line:col.
#include <gtest/gtest.h>

#include <string>

#include "scene/obj_reader.h"
#include "scene_test_util.h"

namespace pt {
namespace {

struct Read {
  bool ok = false;
  ObjModel model;
  Diagnostics diag;
};

Read read_text(test::TempDir& dir, const std::string& text, bool one_mesh = false) {
  Read r;
  ObjReadOptions options;
  options.one_mesh = one_mesh;
  r.ok = read_obj(dir.write("m.obj", text), options, r.model, r.diag);
  return r;
}

// The corners of triangle t of `m` as positions.
std::array<Vec3f, 3> corners(const TriangleMesh& m, std::size_t t) {
  return {m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]], m.positions[m.indices[3 * t + 2]]};
}

TEST(ObjReader, NegativeIndicesCountBackFromTheLineAndTriplesAreStoredOnce) {
  test::TempDir dir;
  Read r = read_text(dir, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n"
                          "f -4/-2/-1 -3/-2/-1 -2/-1/-1\nf 1/1/1 3/2/1 4/2/1\n");
  ASSERT_TRUE(r.ok) << r.diag.format();
  ASSERT_EQ(r.model.meshes.size(), 1u);
  const TriangleMesh& m = r.model.meshes[0].mesh;
  ASSERT_EQ(m.indices.size(), 6u);
  EXPECT_EQ(corners(m, 0)[0], Vec3f(0, 0, 0));
  EXPECT_EQ(corners(m, 0)[2], Vec3f(1, 1, 0));
  // 1/1/1 is the same triple in both faces: one vertex; 3/2/1 likewise.
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.indices[0], m.indices[3]);
  EXPECT_EQ(m.indices[2], m.indices[4]);
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[m.indices[2]], Vec2f(1, 0));  // vt 1 1, v flipped to the image's top
  ASSERT_EQ(m.normals.size(), 4u);
  EXPECT_EQ(m.normals[0], Vec3f(0, 0, 1));
}

TEST(ObjReader, ConvexPolygonsFanAndAConcaveQuadSplitsAtItsConcaveCorner) {
  test::TempDir dir;
  // A convex pentagon, and an arrow-head quad whose corner 3 (1, 0.2) is concave.
  Read r = read_text(dir, "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n"
                          "v 0 0 1\nv 2 -1 1\nv 1 0.2 1\nv 2 1 1\nf 6 7 8 9\n");
  ASSERT_TRUE(r.ok) << r.diag.format();
  const TriangleMesh& m = r.model.meshes[0].mesh;
  ASSERT_EQ(m.indices.size(), 3u * 5u);
  for (std::size_t t = 0; t < 3; ++t) EXPECT_EQ(corners(m, t)[0], Vec3f(0, 0, 0));  // a fan from the first corner
  // The quad: both triangles share the concave corner, and both face +z.
  for (std::size_t t = 3; t < 5; ++t) {
    const auto c = corners(m, t);
    EXPECT_EQ(c[0], Vec3f(1, 0.2f, 1));
    EXPECT_GT(cross(c[1] - c[0], c[2] - c[0]).z, 0.0f);
  }
}

TEST(ObjReader, MissingTexCoordsAndNormalsAndTheVnOnlySlashForm) {
  test::TempDir dir;
  Read r = read_text(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n");
  ASSERT_TRUE(r.ok) << r.diag.format();
  const TriangleMesh& m = r.model.meshes[0].mesh;
  EXPECT_TRUE(m.uvs.empty());
  ASSERT_EQ(m.normals.size(), 6u);  // the second face's corners are other triples: zero normals (ng)
  EXPECT_EQ(m.normals[m.indices[3]], Vec3f(0.0f));
  // No vt in the file but some vn: "v/n" names the normal (as Assimp read it).
  Read slash = read_text(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -1\nf 1/1 2/1 3/1\n");
  ASSERT_TRUE(slash.ok) << slash.diag.format();
  EXPECT_EQ(slash.model.meshes[0].mesh.normals.at(0), Vec3f(0, 0, -1));
  // One mesh: normals only if every run of faces has them.
  Read merged = read_text(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\ng a\nf 1//1 2//1 3//1\ng b\nf 1 2 3\n", true);
  ASSERT_TRUE(merged.ok);
  EXPECT_TRUE(merged.model.meshes[0].mesh.normals.empty());
  EXPECT_EQ(merged.model.meshes[0].mesh.indices.size(), 6u);
}

TEST(ObjReader, CrlfContinuationCommentsHomogeneousAndColouredVertices) {
  test::TempDir dir;
  Read r = read_text(dir, "# comment\r\nv 0 0 0 1\r\nv 2 0 0 2\r\nv 0 1 0 0.5 0.5 0.5\r\n\r\n"
                          "v 0 0 0 0.1 0.2 0.3\r\nf 1 2 \\\r\n 3 # a comment\r\n");
  ASSERT_TRUE(r.ok) << r.diag.format();
  EXPECT_EQ(r.diag.all().size(), 0u) << r.diag.format();
  const TriangleMesh& m = r.model.meshes[0].mesh;
  ASSERT_EQ(m.indices.size(), 3u);
  EXPECT_EQ(corners(m, 0)[1], Vec3f(1, 0, 0));  // w = 2 divides
}

TEST(ObjReader, ObjectsGroupsAndMaterialRunsAsAssimpMadeThem) {
  test::TempDir dir;
  Read r = read_text(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                          "f 1 2 3\n"                        // defaultobject, default material
                          "o a\nusemtl red\nf 1 2 3\nusemtl blue\nf 1 2 3\nusemtl blue\nf 1 3 2\n"
                          "g b c\nf 1 2 3\n"                  // a group is an object; the material goes on
                          "o a\nf 1 2 3\n");                  // a named again: faces go on in the current mesh
  ASSERT_TRUE(r.ok) << r.diag.format();
  const ObjModel& m = r.model;
  ASSERT_EQ(m.objects.size(), 3u);
  EXPECT_EQ(m.objects[0].name, kObjDefaultObject);
  EXPECT_EQ(m.objects[1].name, "a");
  EXPECT_EQ(m.objects[2].name, "b c");
  ASSERT_EQ(m.materials, (std::vector<std::string>{kObjDefaultMaterial, "red", "blue"}));
  ASSERT_EQ(m.objects[1].meshes.size(), 2u);
  const ObjMesh& red = m.meshes[static_cast<std::size_t>(m.objects[1].meshes[0])];
  const ObjMesh& blue = m.meshes[static_cast<std::size_t>(m.objects[1].meshes[1])];
  EXPECT_EQ(red.material, 1);
  EXPECT_EQ(red.mesh.indices.size(), 3u);
  EXPECT_EQ(blue.material, 2);
  EXPECT_EQ(blue.mesh.indices.size(), 6u);
  const ObjMesh& group = m.meshes[static_cast<std::size_t>(m.objects[2].meshes[0])];
  EXPECT_EQ(group.material, 2);
  EXPECT_EQ(group.mesh.indices.size(), 6u);
  EXPECT_EQ(m.meshes[0].material, 0);
}

TEST(ObjReader, PointsAndLinesAreCountedAndUnsupportedStatementsWarnedOnce) {
  test::TempDir dir;
  Read r = read_text(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2\nl 1 2 3\nf 1 2\n"
                          "cstype bspline\ncstype bspline\nfoo 1\nf 1 2 3\n");
  ASSERT_TRUE(r.ok) << r.diag.format();
  EXPECT_EQ(r.model.points, 2u);
  EXPECT_EQ(r.model.lines, 3u);  // l 1 2 3 is two segments; f 1 2 one
  const std::string text = r.diag.format();
  EXPECT_NE(text.find("m.obj:7:1: warning: OBJ statement 'cstype' is not supported"), std::string::npos) << text;
  EXPECT_NE(text.find("2 statements"), std::string::npos) << text;
  EXPECT_NE(text.find("m.obj:9:1: warning: unknown OBJ statement 'foo'"), std::string::npos) << text;
  EXPECT_EQ(r.diag.warning_count(), 2);
}

TEST(ObjReader, MalformedStatementsAreErrorsAtTheirLineAndColumn) {
  test::TempDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {"v 0 0 0\nv 1 x 0\n", "m.obj:2:5: error: 'x' is not a number"},
      {"v 0 0\n", "m.obj:1:1: error: a vertex (v) has 3 numbers"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "m.obj:4:7: error: vertex 9 does not exist (3 defined before this line)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "m.obj:4:7: error: vertex -4 does not exist"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 3\n", "m.obj:4:5: error: vertex index 0: OBJ indices start at 1"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "m.obj:5:9: error: texture coordinate 2 does not exist"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", "m.obj:4:3: error: a face corner is v, v/vt, v//vn or v/vt/vn"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3a\n", "m.obj:4:7: error: '3a' is not an index"},
      {"v 1e999 0 0\n", "m.obj:1:3: error: '1e999' is not a number"},
      {"v 1 0 0 0\n", "m.obj:1:1: error: a vertex's w is 0"},
      {"vn 0 1\n", "m.obj:1:1: error: a normal (vn) has 3 numbers"},
  };
  for (const auto& [text, expected] : cases) {
    Read r = read_text(dir, text);
    EXPECT_FALSE(r.ok) << text;
    EXPECT_NE(r.diag.format().find(expected), std::string::npos) << text << "\n" << r.diag.format();
  }
}

TEST(ObjReader, MaterialLibrariesAreAskedForInFileOrder) {
  test::TempDir dir;
  std::vector<std::string> asked;
  ObjReadOptions options;
  options.mtllib = [&](const std::string& name, const SourceLocation& where) {
    asked.push_back(name + "@" + std::to_string(where.line) + ":" + std::to_string(where.col));
    return std::vector<std::string>{"b", "a"};
  };
  ObjModel model;
  Diagnostics diag;
  ASSERT_TRUE(read_obj(dir.write("m.obj", "usemtl c\nmtllib my lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"),
                       options, model, diag))
      << diag.format();
  EXPECT_EQ(asked, std::vector<std::string>{"my lib.mtl@2:8"});  // the rest of the line, as Assimp
  EXPECT_EQ(model.materials, (std::vector<std::string>{kObjDefaultMaterial, "c", "b", "a"}));
  EXPECT_EQ(model.meshes.at(0).material, 3);
  EXPECT_EQ(model.material_used, (std::vector<bool>{false, false, false, true}));
}


// The meshes leave the reader at their exact sizes (the doubling growth of
// reading would otherwise stay allocated under the build's peak,
// docs/bench/scale.md), positions with the one spare element the Embree
// backend needs to share the buffer (it reads 16 bytes from the last vertex).
TEST(ObjReader, MeshArraysLeaveAtTheirExactSizesWithOneSparePosition) {
  test::TempDir dir;
  std::string text;
  const int n = 37;  // (n + 1)^2 vertices, 2 n^2 triangles: sizes no doubling lands on
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) text += "v " + std::to_string(i) + " 0 " + std::to_string(j) + "\nvt 0 0\nvn 0 1 0\n";
  for (int pass = 0; pass < 2; ++pass) {
    text += pass == 0 ? "o first\n" : "o second\n";
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = j * (n + 1) + i + 1, b = a + 1, c = b + n + 1, d = a + n + 1;
        const auto corner = [](int k) { const std::string s = std::to_string(k); return s + "/" + s + "/" + s; };
        text += "f " + corner(a) + " " + corner(b) + " " + corner(c) + " " + corner(d) + "\n";
      }
  }
  for (const bool one_mesh : {false, true}) {
    Read r = read_text(dir, text, one_mesh);
    ASSERT_TRUE(r.ok) << r.diag.format();
    ASSERT_EQ(r.model.meshes.size(), one_mesh ? 1u : 2u);
    for (const ObjMesh& om : r.model.meshes) {
      const TriangleMesh& m = om.mesh;
      EXPECT_EQ(m.indices.size(), (one_mesh ? 12u : 6u) * n * n);
      EXPECT_EQ(m.positions.size(), static_cast<std::size_t>((n + 1) * (n + 1)) * (one_mesh ? 2u : 1u));
      EXPECT_EQ(m.positions.capacity(), m.positions.size() + 1);
      EXPECT_EQ(m.indices.capacity(), m.indices.size());
      EXPECT_EQ(m.normals.size(), m.positions.size());
      EXPECT_EQ(m.normals.capacity(), m.normals.size());
      EXPECT_EQ(m.uvs.size(), m.positions.size());
      EXPECT_EQ(m.uvs.capacity(), m.uvs.size());
    }
  }
}

}  // namespace
}  // namespace pt
