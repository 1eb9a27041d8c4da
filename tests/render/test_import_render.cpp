// Imported model files rendered (docs/importing.md): one image test per
// importer (statistical, small, few samples) on the assets of
// tests/data/assets, and the memory of a glTF mesh placed 1000 times.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "path_test_util.h"
#include "scene/loader.h"

namespace pt {
namespace {

namespace fs = std::filesystem;
const std::string kAssets = std::string(PT_TEST_DATA_DIR) + "/data/assets/";

SceneDescription load(const std::string& path) {
  Diagnostics diag;
  std::optional<SceneDescription> s = load_scene(path, {}, diag);
  EXPECT_TRUE(s) << diag.format();
  return s ? std::move(*s) : SceneDescription{};
}

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pt-import-render-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The mean of the 3x3 pixels around where `world` projects.
RGB around(const Image& img, const RenderScene& scene, Vec3f world) {
  Vec2f px;
  EXPECT_TRUE(scene.camera.project(world, px));
  RGB sum;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      sum += img.at(std::clamp(static_cast<int>(px.x) + dx, 0, img.width - 1),
                    std::clamp(static_cast<int>(px.y) + dy, 0, img.height - 1));
  return sum / 9.0f;
}

Image render(const SceneDescription& d, const std::string& integrator, int spp, WorkerPool& pool,
             std::unique_ptr<RenderScene>& scene) {
  scene = test::build(d, pool);
  if (!scene) return {};
  std::string error;
  auto in = make_integrator(integrator, test::path_settings(spp, 8), error);
  Film film(scene->width, scene->height);
  in->render(*scene, film, pool);
  return film.image();
}

// Two quads under a white sky: a red Lambert one (radiance = its albedo, with
// no variance) and one textured top red, bottom blue, a green column at u < 1/8.
TEST(ImportRender, ObjMaterialsAndTextureOrientation) {
  const fs::path dir = temp_dir("obj");
  std::ofstream(dir / "s.json") << R"({ "format": "pathtracer-scene", "version": 1,
    "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 30 },
    "film": { "width": 96, "height": 48 }, "render": { "background": [1, 1, 1] },
    "shapes": [ { "type": "import", "file": ")" + kAssets + R"(obj/two_materials.obj" } ] })";
  const SceneDescription d = load((dir / "s.json").string());
  WorkerPool pool(2);
  std::unique_ptr<RenderScene> scene;
  const Image img = render(d, "path", 16, pool, scene);
  ASSERT_TRUE(scene);
  const RGB left = around(img, *scene, {-1, 0, 0});
  EXPECT_NEAR(left.r, 0.8f, 0.02f);
  EXPECT_NEAR(left.g, 0.1f, 0.02f);
  EXPECT_NEAR(left.b, 0.1f, 0.02f);
  const RGB top = around(img, *scene, {1.2f, 0.5f, 0}), bottom = around(img, *scene, {1.2f, -0.5f, 0});
  const RGB strip = around(img, *scene, {0.1f, 0.5f, 0});
  EXPECT_GT(top.r, 0.5f);
  EXPECT_LT(top.b, 0.3f);
  EXPECT_GT(bottom.b, 0.5f);
  EXPECT_LT(bottom.r, 0.3f);
  EXPECT_GT(strip.g, 2.0f * strip.r);
}

// The .gltf (external image) and .glb (embedded image) files hold the same
// scene, and render the same image: the embedded image is written to the
// render scene's scratch folder and read through the texture cache, filtered
// over the footprint exactly as the external file (docs/importing.md).
TEST(ImportRender, GltfAndGlbGiveTheSameTexturedImage) {
  WorkerPool pool(2);
  std::unique_ptr<RenderScene> a, b;
  SceneDescription da = load(kAssets + "gltf/hierarchy.gltf"), db = load(kAssets + "gltf/hierarchy.glb");
  for (SceneDescription* d : {&da, &db}) {
    d->film.width = 72;
    d->film.height = 48;
  }
  const Image ia = render(da, "path", 4, pool, a), ib = render(db, "path", 4, pool, b);
  ASSERT_TRUE(a && b);
  const std::string scratch = b->embedded_images.path();
  EXPECT_FALSE(scratch.empty());
  int red = 0, blue = 0;
  double luminance = 0, difference = 0;
  for (int y = 0; y < ia.height; ++y)
    for (int x = 0; x < ia.width; ++x) {
      const RGB c = ia.at(x, y), d = ib.at(x, y);
      difference += std::abs(c.luminance() - d.luminance());
      red += c.r > 2.0f * (c.g + c.b) ? 1 : 0;
      blue += c.b > 2.0f * (c.r + c.g) ? 1 : 0;
      luminance += c.luminance();
    }
  const int n = ia.width * ia.height;
  EXPECT_GT(red, n / 30);
  EXPECT_GT(blue, n / 30);
  EXPECT_GT(luminance / n, 0.05);
  EXPECT_LT(difference / n, 1e-6 * luminance / n);  // the same lookups: the same image
  b.reset();
  EXPECT_FALSE(fs::exists(scratch));  // the scratch folder goes with the render scene
}

// tests/data/assets/obj/features.obj: six quads in a row (centres x = -5, -3,
// ..., 5) under a dim sky (0.2) and a sun from +x+z (irradiance 2, 45 degrees
// from the quads' normal), each showing one MTL mapping (docs/importing.md).
TEST(ImportRender, MtlCutoutBumpMirrorGlassMetalAndNormalMap) {
  const fs::path dir = temp_dir("features");
  std::ofstream(dir / "s.json") << R"({ "format": "pathtracer-scene", "version": 1,
    "camera": { "position": [0, 0, 14], "look_at": [0, 0, 0], "fov": 30 },
    "film": { "width": 192, "height": 48 }, "render": { "background": [0.2, 0.2, 0.2] },
    "lights": [ { "type": "directional", "direction": [-1, 0, -1], "irradiance": [2, 2, 2] } ],
    "shapes": [ { "type": "import", "file": ")" + kAssets + R"(obj/features.obj" } ] })";
  const SceneDescription d = load((dir / "s.json").string());
  WorkerPool pool(2);
  std::unique_ptr<RenderScene> scene;
  const Image img = render(d, "path", 16, pool, scene);
  ASSERT_TRUE(scene);
  // A flat white-ish Lambert (0.8): 0.8 x 0.2 from the sky + 0.8 / pi x 2 cos 45 from the sun.
  const float flat = 0.8f * 0.2f + 0.8f / 3.14159265f * 2.0f * 0.70710678f;
  const RGB kept = around(img, *scene, {-5.45f, 0, 0}), cut = around(img, *scene, {-4.55f, 0, 0});
  EXPECT_NEAR(kept.g, flat, 0.03f);    // map_d white: the surface
  EXPECT_NEAR(cut.g, 0.2f, 0.01f);     // map_d black: the sky behind
  // bump -bm 0.05 on vertical stripes: the ridges' slopes face the sun or turn from it.
  float lo = 1e9f, hi = 0;
  for (float x = -3.8f; x <= -2.2f; x += 0.05f) {
    const float v = around(img, *scene, {x, 0, 0}).g;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GT(hi - lo, 0.25f * flat);
  // illum 3, Kd 0, Ks (0.9, 0.6, 0.3): a mirror of F0 Ks showing the sky.
  const RGB mirror = around(img, *scene, {-1, 0, 0});
  EXPECT_NEAR(mirror.r / 0.2f, 0.9f, 0.05f);
  EXPECT_NEAR(mirror.g / 0.2f, 0.6f, 0.05f);
  EXPECT_NEAR(mirror.b / 0.2f, 0.3f, 0.05f);
  // illum 7, d 0.5: clear glass, grey, neither black nor opaque-lit.
  const RGB glass = around(img, *scene, {1, 0, 0});
  EXPECT_NEAR(glass.r, glass.b, 0.02f);
  EXPECT_GT(glass.g, 0.02f);
  EXPECT_LT(glass.g, 0.2f);
  // The rough metal tinted by map_Ks (255, 200, 120): red above green above blue.
  const RGB metal = around(img, *scene, {3, 0, 0});
  EXPECT_GT(metal.r, 1.3f * metal.g);
  EXPECT_GT(metal.g, 1.3f * metal.b);
  // norm tilts the normal 30 degrees towards +x (the sun): brighter than flat.
  const RGB tilted = around(img, *scene, {5, 0, 0});
  EXPECT_GT(tilted.g, 1.12f * flat);
}

// tests/data/assets/gltf/pbr.gltf and .glb as the scene (a white sky, a
// framed camera): MASK cuts the base colour texture's transparent half, BLEND
// at alpha 0.3 lets 70% of the rays through the whole quad (stochastic
// opacity), metallic-roughness shows its base colour as a metal's F0 and
// under a coating, and both files give the same image.
TEST(ImportRender, GltfMaskBlendAndMetallicRoughness) {
  WorkerPool pool(2);
  std::unique_ptr<RenderScene> a, b;
  SceneDescription da = load(kAssets + "gltf/pbr.gltf"), db = load(kAssets + "gltf/pbr.glb");
  for (SceneDescription* d : {&da, &db}) {
    d->film.width = 240;
    d->film.height = 120;  // the framed camera fits the model's bounding sphere in the height: 12 pixels a unit
  }
  const Image ia = render(da, "path", 8, pool, a), ib = render(db, "path", 8, pool, b);
  ASSERT_TRUE(a && b);
  const RGB opaque = around(ia, *a, {-4.45f, 0, 0}), masked = around(ia, *a, {-3.55f, 0, 0});
  EXPECT_GT(opaque.g, 2.0f * opaque.r);  // the green base colour
  EXPECT_NEAR(masked.r, 1.0f, 0.02f);    // the sky through the cut half
  EXPECT_NEAR(masked.g, 1.0f, 0.02f);
  // BLEND, alpha 0.3: the red quad stops 30% of the rays, 70% see the white sky through it.
  const RGB blend = around(ia, *a, {4, 0, 0});
  EXPECT_NEAR(blend.g, 0.7f, 0.06f);       // 0.7 sky + 0.3 x the coating's reflection
  EXPECT_GT(blend.r, blend.g + 0.15f);     // + 0.3 x the red base
  EXPECT_LT(blend.r, 1.0f);
  const RGB metal = around(ia, *a, {-2, 0, 0}), plastic = around(ia, *a, {0, 0, 0});
  EXPECT_GT(metal.r, 1.3f * metal.b);     // F0 (0.9, 0.6, 0.3)
  EXPECT_GT(plastic.b, 1.5f * plastic.r);  // base (0.2, 0.4, 0.8) under a white coating
  double difference = 0;
  for (int y = 0; y < ia.height; ++y)
    for (int x = 0; x < ia.width; ++x) difference += std::abs(ia.at(x, y).luminance() - ib.at(x, y).luminance());
  EXPECT_LT(difference, 1e-6);
}

// Two red panels (one mesh, two nodes) on a grey ground, lit by the file's
// point light and seen through the file's camera.
TEST(ImportRender, ColladaPanelsOnTheGround) {
  SceneDescription d = load(kAssets + "dae/scene.dae");
  d.film.width = 72;
  d.film.height = 48;
  WorkerPool pool(2);
  std::unique_ptr<RenderScene> scene;
  const Image img = render(d, "path", 16, pool, scene);
  ASSERT_TRUE(scene);
  for (const Vec3f panel : {Vec3f(-1, 0.5f, 0), Vec3f(1, 0.5f, 0)}) {
    const RGB c = around(img, *scene, panel);
    EXPECT_GT(c.r, 2.0f * c.g) << panel.x;
    EXPECT_GT(c.r, 0.05f) << panel.x;
  }
  const RGB ground = around(img, *scene, {0, 0, 2.5f});
  EXPECT_GT(ground.g, 0.05f);
  EXPECT_NEAR(ground.r / ground.g, 1.0f, 0.1f);
}

// Cryptomatte's names (RenderScene::names) of an imported file: its nodes, as
// Blender names their objects, and its materials.
TEST(ImportRender, NodesAndMaterialsHaveCryptomatteNames) {
  const SceneDescription d = load(kAssets + "dae/scene.dae");
  WorkerPool pool(2);
  const std::unique_ptr<RenderScene> scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  const SceneNames& n = scene->names;
  const auto has = [](const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  for (const char* node : {"ground", "panel_left", "panel_right"}) EXPECT_TRUE(has(n.objects, node)) << node;
  // The panels (one object, placed twice) are the last two instances (the
  // transformed ground is one before them), each with its node's name.
  ASSERT_EQ(n.instance_object.size(), 3u);
  EXPECT_EQ(n.objects[n.instance_object[1]], "panel_left");
  EXPECT_EQ(n.objects[n.instance_object[2]], "panel_right");
  EXPECT_TRUE(has(n.materials, "scene.dae:red"));
  EXPECT_TRUE(has(n.materials, "scene.dae:grey"));
  EXPECT_EQ(n.object_ids.size(), n.objects.size());
}

// One 12-triangle box, 1000 nodes: one stored copy, 1000 instances.
std::string write_reused_box(const fs::path& dir) {
  const std::vector<float> p = {-0.5f, -0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, -0.5f, -0.5f, 0.5f, -0.5f,
                                -0.5f, -0.5f, 0.5f,  0.5f, -0.5f, 0.5f,  0.5f, 0.5f, 0.5f,  -0.5f, 0.5f, 0.5f};
  const std::vector<uint16_t> idx = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                     3, 6, 2, 3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
  std::ofstream bin(dir / "box.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(p.data()), static_cast<std::streamsize>(p.size() * 4));
  bin.write(reinterpret_cast<const char*>(idx.data()), static_cast<std::streamsize>(idx.size() * 2));
  std::string nodes, list;
  for (int i = 0; i < 1000; ++i) {
    // Built by append: GCC 12 warns (-Wrestrict) on "," + string, wrongly.
    if (i > 0) {
      nodes += ",";
      list += ",";
    }
    nodes += R"({"mesh":0,"translation":[)";
    nodes += std::to_string(i % 10 * 2);
    nodes += ",";
    nodes += std::to_string(i / 10 % 10 * 2);
    nodes += ",";
    nodes += std::to_string(i / 100 * 2);
    nodes += "]}";
    list += std::to_string(i);
  }
  const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + list +
                           R"(]}],"nodes":[)" + nodes +
                           R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "buffers":[{"uri":"box.bin","byteLength":168}],
    "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":72}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[-0.5,-0.5,-0.5],"max":[0.5,0.5,0.5]},
                 {"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}]})";
  std::ofstream(dir / "reused.gltf") << gltf;
  return (dir / "reused.gltf").string();
}

std::size_t triangles_stored(const SceneGeometry& g) {
  std::size_t n = 0;
  for (const Shape& s : g.shapes)
    if (const auto* m = std::get_if<TriangleMesh>(&s)) n += m->triangle_count();
  return n;
}

TEST(ImportRender, AMeshReusedAThousandTimesIsStoredOnce) {
  const fs::path dir = temp_dir("reuse");
  const SceneDescription d = load(write_reused_box(dir));
  ASSERT_EQ(d.objects.size(), 1u);
  ASSERT_EQ(d.instances.size(), 1000u);
  // The same 12000 triangles baked into world space, for comparison.
  SceneDescription flat = d;
  flat.objects.clear();
  flat.instances.clear();
  for (const InstanceDesc& inst : d.instances) {
    ShapeDesc s = d.objects[0].shapes[0];
    TriangleMesh& m = std::get<TriangleMesh>(s.geometry);
    for (Vec3f& v : m.positions) v = inst.transform->value.point(v);
    s.material = d.objects[0].shapes[0].material;
    flat.shapes.push_back(std::move(s));
  }
  WorkerPool pool(2);
  for (AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
    BuildOptions options;
    options.accel = kind;
    Diagnostics diag;
    const auto instanced = build_render_scene(d, options, pool, diag);
    const auto baked = build_render_scene(flat, options, pool, diag);
    ASSERT_TRUE(instanced && baked) << diag.format();
    EXPECT_EQ(triangles_stored(instanced->geometry), 12u);
    EXPECT_EQ(triangles_stored(baked->geometry), 12000u);
    EXPECT_EQ(instanced->geometry.instances.size(), 1000u);
    const std::size_t a = instanced->accel->stats().memory_bytes, b = baked->accel->stats().memory_bytes;
    EXPECT_LT(a, b / 2) << instanced->accel->stats().backend << ": " << a << " bytes instanced, " << b << " baked";
  }
}

}  // namespace
}  // namespace pt
