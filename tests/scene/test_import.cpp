// Model files through {"type": "import"} and as the scene itself
// (docs/importing.md): OBJ + MTL, glTF (.gltf with its .bin, .glb with an
// embedded image) and COLLADA, on the small assets of tests/data/assets
// (written by tests/data/assets/make_assets.py; scene.dae by hand).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/import_materials.h"
#include "scene_test_util.h"

namespace pt {
namespace {

const std::string kAssets = std::string(PT_TEST_DATA_DIR) + "/data/assets/";
constexpr float kPiF = 3.14159265f;

std::string messages(const Diagnostics& diag) { return diag.format(); }

// A native scene (in a temporary folder) importing `file` with `extra` keys.
struct Loaded {
  std::optional<SceneDescription> scene;
  Diagnostics diag;
};

Loaded load_import(test::TempDir& dir, const std::string& file, const std::string& extra = "",
                   const std::string& top = "") {
  Loaded l;
  const std::string path = dir.write("scene.json", R"({ "format": "pathtracer-scene", "version": 1, )" + top +
                                                       R"( "shapes": [ { "type": "import", "file": ")" + file +
                                                       "\"" + extra + " } ] }");
  l.scene = load_scene(path, {}, l.diag);
  return l;
}

const MaterialDesc& material_named(const SceneDescription& s, const std::string& suffix) {
  for (const MaterialDesc& m : s.materials)
    if (m.name.size() >= suffix.size() && m.name.compare(m.name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return m;
  ADD_FAILURE() << "no material named *" << suffix;
  return s.materials.front();
}

uint64_t count_of(const std::vector<std::pair<std::string, uint64_t>>& list, const std::string& what) {
  for (const auto& [name, n] : list)
    if (name == what) return n;
  return 0;
}

TEST(ImportObj, TwoMaterialsMappedWithTheirStatementsReported) {
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(kAssets + "obj/two_materials.obj", {}, diag);
  ASSERT_TRUE(s) << messages(diag);
  ASSERT_EQ(s->shapes.size(), 2u);  // one per usemtl
  const MaterialDesc& red = material_named(*s, ":red");
  EXPECT_EQ(red.type.value, MaterialType::Lambert);
  EXPECT_TRUE(test::near(red.diffuse.value, RGB(0.8f, 0.1f, 0.1f)));
  const MaterialDesc& tex = material_named(*s, ":textured");
  EXPECT_EQ(tex.type.value, MaterialType::Phong);  // illum 2, Ks 0.1, Ns 50
  EXPECT_FLOAT_EQ(tex.ks.value, 1.0f);
  EXPECT_TRUE(test::near(tex.specular.value, RGB(0.1f)));
  EXPECT_FLOAT_EQ(tex.exponent.value, 50.0f);
  ASSERT_TRUE(tex.texture);
  EXPECT_EQ(s->textures[static_cast<std::size_t>(*tex.texture)].written, "halves.png");
  // The unused glass material is not mapped.
  for (const MaterialDesc& m : s->materials) EXPECT_EQ(m.name.find("unused_glass"), std::string::npos);
  // Unsupported statements once each, at their first line, with their count.
  const std::string text = messages(diag);
  EXPECT_NE(text.find("two_materials.mtl:3:1: warning: 'Ka' (ambient colour) is not supported; ignored (2 statements)"),
            std::string::npos) << text;
  EXPECT_NE(text.find("two_materials.mtl:15:1: warning: 'sharpness'"), std::string::npos) << text;
  EXPECT_NE(text.find("no camera"), std::string::npos) << text;  // framed, with a note
  // Counted: what was read and what was left out.
  ASSERT_EQ(s->imports.size(), 1u);
  EXPECT_EQ(s->imports[0].format, "OBJ");
  EXPECT_EQ(count_of(s->imports[0].imported, "triangles"), 4u);
  EXPECT_EQ(count_of(s->imports[0].imported, "materials"), 2u);
}

TEST(ImportObj, UvsMeasureVFromTheImagesTop) {
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(kAssets + "obj/two_materials.obj", {}, diag);
  ASSERT_TRUE(s);
  const TriangleMesh& m = test::geometry_of<TriangleMesh>(*s, 1);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    if (m.positions[v] == Vec3f(2, 1, 0)) {
      EXPECT_EQ(m.uvs[v], Vec2f(1, 0));  // vt 1 1: the image's top right
    }
    if (m.positions[v] == Vec3f(0, -1, 0)) {
      EXPECT_EQ(m.uvs[v], Vec2f(0, 1));  // vt 0 0: bottom left
    }
  }
}

// The glTF scene of make_assets.py: the box mesh placed by three nodes is one
// object with three instances, each at its node's full transform.
void expect_hierarchy(const SceneDescription& s) {
  ASSERT_EQ(s.objects.size(), 1u);
  ASSERT_EQ(s.objects[0].shapes.size(), 1u);
  EXPECT_EQ(std::get<TriangleMesh>(s.objects[0].shapes[0].geometry).triangle_count(), 12u);
  ASSERT_EQ(s.instances.size(), 3u);
  // box_a: root (translate y -1) . boxes (45 degrees about y) . (translate -1.5, 0.5, 0).
  const Transform& a = s.instances[0].transform->value;
  const float c = std::sqrt(0.5f);
  EXPECT_TRUE(test::near(a.point(Vec3f(0, 0, 0)), Vec3f(-1.5f * c, -0.5f, 1.5f * c), 1e-5f));
  // box_c is scaled by 0.5.
  EXPECT_NEAR(s.instances[2].transform->value.scale, 0.5f, 1e-6f);
  EXPECT_EQ(s.shapes.size(), 4u);  // ground, the lamp's two primitives, leaf
  // The ground's material reads TEXCOORD_1 (TEXCOORD_0 is constant 0.5).
  const TriangleMesh& ground = test::geometry_of<TriangleMesh>(s, 0);
  EXPECT_EQ(ground.uvs[0], Vec2f(0, 1));
  const MaterialDesc& tiles = material_named(s, ":tiles");
  EXPECT_EQ(tiles.type.value, MaterialType::MetallicRoughness);  // glTF's own, metallic 0: the coated diffuse
  EXPECT_FLOAT_EQ(tiles.metallic.value.value, 0.0f);
  ASSERT_TRUE(tiles.reflectance.texture);
  const MaterialDesc& gold = material_named(s, ":gold");  // metallic 1, roughness 0.02: alpha 0.0004
  EXPECT_EQ(gold.type.value, MaterialType::MetallicRoughness);  // metallic 1: the Schlick conductor of F0 = base
  EXPECT_FLOAT_EQ(gold.metallic.value.value, 1.0f);
  EXPECT_TRUE(test::near(gold.reflectance.value.value, RGB(1.0f, 0.77f, 0.33f)));
  EXPECT_NEAR(gold.uroughness.value.value, 0.0004f, 1e-7f);
  EXPECT_FALSE(gold.remap_roughness.value);
  // KHR_materials_emissive_strength (read from the JSON: Assimp 5.2 drops it).
  EXPECT_TRUE(test::near(material_named(s, ":glow").emission.value, RGB(8.0f, 7.2f, 6.4f), 1e-4f));
  // Lights: candela / pi, lux as irradiance; the sun points along the node's -z.
  ASSERT_EQ(s.lights.size(), 3u);
  const auto& sun = std::get<DirectionalLightDesc>(s.lights[0]);
  EXPECT_TRUE(test::near(normalize(sun.direction.value), Vec3f(0, -0.8660254f, -0.5f), 1e-5f));
  EXPECT_TRUE(test::near(sun.irradiance.value, RGB(2.0f, 2.0f, 1.8f)));
  const auto& bulb = std::get<PointLightDesc>(s.lights[1]);
  EXPECT_TRUE(test::near(bulb.position.value, Vec3f(2, 2, 2)));
  EXPECT_TRUE(test::near(bulb.intensity.value, RGB(20.0f, 16.0f, 12.0f) * (1.0f / kPiF), 1e-5f));
  const auto& spot = std::get<SpotLightDesc>(s.lights[2]);
  EXPECT_NEAR(spot.cone_angle.value, 0.5f * 180.0f / kPiF, 1e-3f);
  EXPECT_NEAR(spot.cone_delta.value, 0.2f * 180.0f / kPiF, 1e-3f);
  // The first camera: yfov 0.7 rad, at its node, looking down 12 degrees; the image takes its aspect ratio.
  EXPECT_EQ(s.camera.type, CameraType::Pinhole);
  EXPECT_NEAR(s.camera.fov_y_deg.value, 0.7f * 180.0f / kPiF, 1e-3f);
  EXPECT_TRUE(test::near(s.camera.position.value, Vec3f(0, 1.5f, 7)));
  const Vec3f forward = normalize(s.camera.look_at.value - s.camera.position.value);
  EXPECT_NEAR(forward.y, -std::sin(12.0f * kPiF / 180.0f), 1e-5f);
  EXPECT_EQ(s.film.height.value, 427);  // 640 / 1.5
}

TEST(ImportGltf, HierarchyInstancesCameraLightsAndMaterials) {
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(kAssets + "gltf/hierarchy.gltf", {}, diag);
  ASSERT_TRUE(s) << messages(diag);
  expect_hierarchy(*s);
  const std::string text = messages(diag);
  // The mapping is exact now: no approximation is reported for these materials.
  EXPECT_EQ(text.find("approximated"), std::string::npos) << text;
  EXPECT_EQ(text.find("not supported"), std::string::npos) << text;
  const ImportSummary& sum = s->imports.at(0);
  EXPECT_EQ(count_of(sum.imported, "instances"), 3u);
  EXPECT_EQ(count_of(sum.skipped, "mesh tangents (normal maps take tangents from the texture coordinates)"), 1u);
  EXPECT_EQ(count_of(sum.skipped, "cameras (not chosen)"), 1u);
}

TEST(ImportGltf, BinaryFileWithAnEmbeddedImage) {
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(kAssets + "gltf/hierarchy.glb", {}, diag);
  ASSERT_TRUE(s) << messages(diag);
  expect_hierarchy(*s);
  const MaterialDesc& tiles = material_named(*s, ":tiles");  // names come from the JSON chunk
  const TextureDesc& t = s->textures.at(static_cast<std::size_t>(*tiles.reflectance.texture));
  ASSERT_TRUE(t.embedded);
  EXPECT_EQ(t.embedded_format, "png");
  EXPECT_TRUE(t.resolved.empty());
}

TEST(ImportGltf, CameraByNameLightsOffTransformAndMaterialOverride) {
  test::TempDir dir;
  Loaded l = load_import(dir, kAssets + "gltf/hierarchy.gltf",
                         R"(, "camera": "top_view", "lights": false, "material": "white",
                            "transform": [ { "translate": [10, 0, 0] } ])",
                         R"("materials": { "white": { "type": "lambert", "diffuse": [0.9, 0.9, 0.9] } },)");
  ASSERT_TRUE(l.scene) << messages(l.diag);
  const SceneDescription& s = *l.scene;
  EXPECT_EQ(s.camera.type, CameraType::Orthographic);
  EXPECT_NEAR(s.camera.view_height.value, 6.0f, 1e-5f);  // 2 ymag
  EXPECT_TRUE(test::near(s.camera.position.value, Vec3f(10, 8, 0)));
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(s.materials.size(), 1u);  // the file's are replaced
  EXPECT_EQ(count_of(s.imports[0].skipped, "lights (\"lights\": false)"), 3u);
  EXPECT_TRUE(test::near(s.instances[0].transform->value.point(Vec3f(0, 0, 0)),
                         Vec3f(10 - 1.5f * std::sqrt(0.5f), -0.5f, 1.5f * std::sqrt(0.5f)), 1e-5f));
}

TEST(ImportGltf, TheScenesCameraWinsAndAFileWithoutOneIsFramed) {
  test::TempDir dir;
  Loaded own = load_import(dir, kAssets + "gltf/hierarchy.gltf", "",
                           R"("camera": { "position": [0, 0, 9], "look_at": [0, 0, 0] },)");
  ASSERT_TRUE(own.scene) << messages(own.diag);
  EXPECT_TRUE(test::near(own.scene->camera.position.value, Vec3f(0, 0, 9)));
  EXPECT_EQ(count_of(own.scene->imports[0].skipped, "cameras (the scene has its own)"), 1u);
  Loaded framed = load_import(dir, kAssets + "gltf/hierarchy.gltf", R"(, "camera": false)");
  ASSERT_TRUE(framed.scene) << messages(framed.diag);
  EXPECT_NE(messages(framed.diag).find("a camera framed on the scene's bounds"), std::string::npos);
  const CameraDesc& c = framed.scene->camera;
  EXPECT_GT(c.position.value.z, c.look_at.value.z);  // from the front (+z)
}

TEST(ImportCollada, ZUpHierarchyInstancesCameraAndLight) {
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(kAssets + "dae/scene.dae", {}, diag);
  ASSERT_TRUE(s) << messages(diag);
  ASSERT_EQ(s->objects.size(), 1u);  // the panel, placed twice
  EXPECT_EQ(s->instances.size(), 2u);
  EXPECT_EQ(s->shapes.size(), 1u);   // the ground
  // Z up becomes y up: the camera at (0, -6, 1.5) is at (0, 1.5, 6), looking along -z.
  EXPECT_TRUE(test::near(s->camera.position.value, Vec3f(0, 1.5f, 6), 1e-5f));
  EXPECT_TRUE(test::near(normalize(s->camera.look_at.value - s->camera.position.value), Vec3f(0, 0, -1), 1e-5f));
  EXPECT_NEAR(s->camera.fov_y_deg.value, 40.0f, 1e-3f);
  const PointLightDesc& lamp = test::point_light(*s, 0);
  EXPECT_TRUE(test::near(lamp.position.value, Vec3f(0, 3, 2), 1e-5f));
  EXPECT_TRUE(test::near(lamp.intensity.value, RGB(10.0f)));  // quadratic attenuation 1
  EXPECT_TRUE(lamp.inverse_square.value);
  EXPECT_EQ(material_named(*s, ":grey").type.value, MaterialType::Lambert);
  const MaterialDesc& red = material_named(*s, ":red");
  EXPECT_EQ(red.type.value, MaterialType::Phong);
  EXPECT_FLOAT_EQ(red.exponent.value, 40.0f);
}

TEST(ImportErrors, FormatsAndFilesAreNamed) {
  test::TempDir dir;
  dir.write("model.xyz", "x");
  Loaded xyz = load_import(dir, "model.xyz");
  EXPECT_FALSE(xyz.scene);
  EXPECT_NE(messages(xyz.diag).find("unsupported mesh format '.xyz' (supported: .obj, .gltf, .glb and .dae"),
            std::string::npos) << messages(xyz.diag);
  dir.write("broken.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ { \"primitives\": [ 7 ] } ] }");
  Loaded broken = load_import(dir, "broken.gltf");
  EXPECT_FALSE(broken.scene);
  EXPECT_NE(messages(broken.diag).find("cannot read 'broken.gltf' (glTF): "), std::string::npos)
      << messages(broken.diag);
  // A mesh reads PLY and OBJ only, and says so.
  const std::string mesh = dir.write("mesh.json", R"({ "format": "pathtracer-scene", "version": 1,
    "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0] },
    "shapes": [ { "type": "mesh", "file": "model.xyz" }, { "type": "mesh", "file": "broken.gltf" } ] })");
  Diagnostics diag;
  EXPECT_FALSE(load_scene(mesh, {}, diag));
  EXPECT_NE(messages(diag).find("unsupported mesh format '.xyz' (supported: .ply, .obj; .gltf, .glb and .dae"),
            std::string::npos) << messages(diag);
  EXPECT_NE(messages(diag).find("place a '.gltf' file with {\"type\": \"import\""), std::string::npos);
}

TEST(ImportErrors, MissingTextureNamesTheFileAndTheTexture) {
  test::TempDir dir;
  dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl a\nf 1/1 2/1 3/1\n");
  dir.write("m.mtl", "newmtl a\nKd 1 0 0\nmap_Kd textures/nowhere.png\n");
  Loaded l = load_import(dir, "m.obj");
  ASSERT_TRUE(l.scene) << messages(l.diag);  // a warning: the material keeps its colour
  const std::string text = messages(l.diag);
  EXPECT_NE(text.find("m.mtl:3:8: warning: texture 'textures/nowhere.png' named by 'm.obj' not found"),
            std::string::npos) << text;
  EXPECT_FALSE(l.scene->materials[0].texture);
  EXPECT_EQ(count_of(l.scene->imports[0].skipped, "textures not found"), 1u);
}

TEST(ImportErrors, AnObjectCannotImport) {
  test::TempDir dir;
  const std::string path = dir.write("s.json", R"({ "format": "pathtracer-scene", "version": 1,
    "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0] },
    "objects": [ { "name": "o", "shapes": [ { "type": "import", "file": "x.gltf" } ] } ] })");
  Diagnostics diag;
  EXPECT_FALSE(load_scene(path, {}, diag));
  EXPECT_NE(messages(diag).find("an object cannot import a model file"), std::string::npos) << messages(diag);
}

TEST(ImportMaterials, BlinnExponentToGgxAlpha) {
  EXPECT_FLOAT_EQ(alpha_for_exponent(0.0f), 1.0f);  // sqrt(2 / 2)
  EXPECT_NEAR(alpha_for_exponent(30.0f), 0.25f, 1e-6f);  // sqrt(2 / 32)
  EXPECT_NEAR(alpha_for_exponent(998.0f), std::sqrt(0.002f), 1e-6f);
  EXPECT_FLOAT_EQ(alpha_for_exponent(-5.0f), 1.0f);
}

}  // namespace
}  // namespace pt
