// load_scene / load_scene_from_string / resolve_scene_path: the native format's
// keys and defaults, path resolution, textures listed once, strictness, limits
// and how problems are printed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scene_test_util.h"

namespace pt {
namespace {

namespace fs = std::filesystem;
using test::geometry_of;
using test::near;
using test::point_light;
using test::ScopedCwd;
using test::TempDir;

const char* kNativeHeader = R"("format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 1, 5], "look_at": [0, 1, 0] })";

std::string native(const std::string& body) { return "{\n  " + std::string(kNativeHeader) + body + "\n}\n"; }

std::optional<SceneDescription> load_text(const std::string& path, const std::string& text, Diagnostics& diag,
                                          LoadOptions options = {}) {
  return load_scene_from_string(path, text, options, diag);
}

// ---------------------------------------------------------------- the native format

TEST(NativeFormat, DefaultsForEverythingOptional) {
  Diagnostics diag;
  const auto s = load_text("mem.json", native(R"(, "shapes": [{ "type": "sphere", "center": [0, 0, 0], "radius": 1 }])"), diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.all().size(), 0u) << diag.format();
  EXPECT_EQ(s->format, SceneFormat::Native);
  EXPECT_EQ(s->film.width.value, 640);
  EXPECT_EQ(s->film.height.value, 480);
  EXPECT_EQ(s->film.display.value, DisplayTransform::Srgb);
  EXPECT_EQ(s->film.exposure.value, 0.0f);
  EXPECT_EQ(s->render.integrator.value, "whitted");
  EXPECT_EQ(s->render.max_depth.value, 5);
  EXPECT_EQ(s->render.spp.value, 1);
  EXPECT_EQ(s->camera.type, CameraType::Pinhole);
  EXPECT_TRUE(near(s->camera.up, Vec3f(0, 1, 0)));
  EXPECT_EQ(s->camera.fov_y_deg.value, 45.0f);
  EXPECT_FALSE(s->camera.left_handed.value);
  // A shape without a material gets the default one.
  ASSERT_EQ(s->materials.size(), 1u);
  EXPECT_EQ(s->shapes[0].material, 0);
  EXPECT_TRUE(near(s->materials[0].diffuse, RGB(0.8f)));
}

TEST(NativeFormat, EveryKeyIsRead) {
  Diagnostics diag;
  const auto s = load_text("mem.json", R"({
  "format": "pathtracer-scene", "version": 1,
  "camera": { "type": "thin_lens", "position": [1, 2, 3], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 30,
              "handedness": "left", "lens_radius": 0.05, "focus_distance": 3.5 },
  "film": { "width": 320, "height": 200, "display": "cgr", "exposure": -1.5 },
  "render": { "integrator": "binary", "max_depth": 2, "spp": 16, "background": [0.1, 0.2, 0.3] },
  "materials": {
    "m": { "diffuse": [0.1, 0.2, 0.3], "kd": 0.5, "specular": [0.9, 0.8, 0.7], "ks": 0.25, "exponent": 12,
           "reflectivity": 0.4, "refractive": true, "ior": 1.33, "emission": [1, 2, 3] }
  },
  "lights": [
    { "type": "point", "position": [0, 5, 0], "intensity": [4, 5, 6] },
    { "type": "point", "position": [1, 5, 0], "intensity": [1, 1, 1], "specular_intensity": [2, 2, 2],
      "falloff": "none" }
  ],
  "shapes": [
    { "type": "sphere", "name": "ball", "material": "m", "center": [0, 1, 0], "radius": 0.5, "pole": [0, 0, 1] },
    { "type": "quad", "material": "m", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]] },
    { "type": "triangle", "material": "m", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]] },
    { "type": "cylinder", "material": "m", "p0": [0, 0, 0], "p1": [0, 2, 0], "radius": 0.25 },
    { "type": "mesh", "material": "m", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]],
      "indices": [[0, 1, 2], [2, 1, 3]], "normals": [[0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1]],
      "uvs": [[0, 0], [1, 0], [0, 1], [1, 1]] }
  ]
})", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.all().size(), 0u) << diag.format();
  EXPECT_EQ(s->camera.type, CameraType::ThinLens);
  EXPECT_TRUE(near(s->camera.position, Vec3f(1, 2, 3)));
  EXPECT_TRUE(near(s->camera.up, Vec3f(0, 0, 1)));
  EXPECT_TRUE(s->camera.left_handed.value);
  EXPECT_EQ(s->camera.lens_radius.value, 0.05f);
  EXPECT_EQ(s->camera.focus_distance.value, 3.5f);
  EXPECT_EQ(s->film.display.value, DisplayTransform::CgrCourse);
  EXPECT_EQ(s->film.exposure.value, -1.5f);
  EXPECT_EQ(s->render.integrator.value, "binary");
  EXPECT_EQ(s->render.spp.value, 16);
  ASSERT_EQ(s->materials.size(), 1u);
  const MaterialDesc& m = s->materials[0];
  EXPECT_EQ(m.name, "m");
  EXPECT_EQ(m.kd.value, 0.5f);
  EXPECT_EQ(m.ks.value, 0.25f);
  EXPECT_EQ(m.exponent.value, 12.0f);
  EXPECT_EQ(m.reflectivity.value, 0.4f);
  EXPECT_TRUE(m.refractive.value);
  EXPECT_EQ(m.ior.value, 1.33f);
  EXPECT_TRUE(near(m.specular, RGB(0.9f, 0.8f, 0.7f)));
  EXPECT_TRUE(near(m.emission, RGB(1, 2, 3)));
  ASSERT_EQ(s->lights.size(), 2u);
  EXPECT_TRUE(near(point_light(*s, 0).specular_intensity, RGB(4, 5, 6)));  // defaults to intensity
  EXPECT_TRUE(point_light(*s, 0).inverse_square.value);
  EXPECT_TRUE(near(point_light(*s, 1).specular_intensity, RGB(2)));
  EXPECT_FALSE(point_light(*s, 1).inverse_square.value);
  ASSERT_EQ(s->shapes.size(), 5u);
  EXPECT_EQ(s->shapes[0].name, "ball");
  EXPECT_TRUE(near(geometry_of<Sphere>(*s, 0).pole, Vec3f(0, 0, 1)));
  EXPECT_TRUE(near(geometry_of<Quad>(*s, 1).v[2], Vec3f(1, 1, 0)));
  EXPECT_TRUE(near(geometry_of<Cylinder>(*s, 3).p1, Vec3f(0, 2, 0)));
  const TriangleMesh& mesh = geometry_of<TriangleMesh>(*s, 4);
  EXPECT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(mesh.normals.size(), 4u);
  ASSERT_EQ(mesh.uvs.size(), 4u);
  EXPECT_EQ(mesh.uvs[3], Vec2f(1, 1));
  EXPECT_TRUE(s->shapes[4].file.empty());
}

TEST(NativeFormat, ValuesRememberWhereTheyWereWritten) {
  Diagnostics diag;
  const auto s = load_text("mem.json", native(R"(,
  "shapes": [
    { "type": "sphere", "center": [0, 0, 0], "radius": 2 }
  ])"), diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->shapes[0].at("radius").to_string(), "mem.json:5:56");
  EXPECT_EQ(s->shapes[0].where.to_string(), "mem.json:5:5");
  EXPECT_EQ(s->camera.look_at.where.to_string(), "mem.json:3:49");
}

TEST(NativeFormat, TexturesAreListedOnceAndOnlyWhenUsed) {
  TempDir dir;
  dir.write("tex/a.png", "not really a png; the loader only checks that it exists");
  dir.write("tex/b.png", "x");
  const std::string path = dir.write("scene.json", native(R"(,
  "materials": {
    "one":    { "texture": "tex/a.png" },
    "two":    { "texture": "./tex/../tex/a.png", "kd": 0.5 },
    "unused": { "texture": "tex/b.png" },
    "broken": { "texture": "tex/missing.png" }
  },
  "shapes": [
    { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "one" },
    { "type": "sphere", "center": [2, 0, 0], "radius": 1, "material": "two" }
  ])"));
  Diagnostics diag;
  const auto s = load_scene(path, LoadOptions{}, diag);
  ASSERT_TRUE(s) << diag.format();
  ASSERT_EQ(s->textures.size(), 1u);  // one file, two spellings; b.png is not used
  EXPECT_EQ(s->textures[0].written, "tex/a.png");
  EXPECT_TRUE(fs::equivalent(s->textures[0].resolved, dir.path() / "tex/a.png"));
  ASSERT_EQ(s->materials.size(), 2u);  // unused materials are dropped (with a warning)
  EXPECT_EQ(s->materials[0].texture, std::optional<int>(0));
  EXPECT_EQ(s->materials[1].texture, std::optional<int>(0));
  EXPECT_EQ(s->shapes[1].material, 1);
  EXPECT_EQ(diag.warning_count(), 2) << diag.format();  // 'unused' and 'broken' are not used
  EXPECT_EQ(diag.error_count(), 0);                     // so the missing file is never looked for
}

// Named textures, inline texture objects and image paths, their keys and
// defaults; "alpha" as a number or a texture reference.
TEST(NativeFormat, TexturesByNameInlineAndPath) {
  TempDir dir;
  dir.write("leaf.png", "the loader only checks that it exists");
  const std::string path = dir.write("scene.json", native(R"(,
  "textures": {
    "tiles": { "type": "checker", "color0": [0.1, 0.1, 0.1], "scale": [8, 4], "mapping": "uv" },
    "marble": { "type": "noise", "mapping": "object", "scale": 3, "octaves": 4, "roughness": 0.6,
                "transform": [ { "translate": [1, 0, 0] } ] },
    "photo": { "type": "image", "file": "leaf.png", "filter": "trilinear", "wrap": "clamp", "encoding": "linear" }
  },
  "materials": {
    "floor": { "texture": "tiles", "alpha": "photo" },
    "stone": { "texture": "marble", "alpha": 0 },
    "leaf":  { "texture": "leaf.png", "alpha": { "type": "checker", "scale": 2 } }
  },
  "shapes": [
    { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "floor" },
    { "type": "sphere", "center": [2, 0, 0], "radius": 1, "material": "stone" },
    { "type": "sphere", "center": [4, 0, 0], "radius": 1, "material": "leaf" }
  ])"));
  Diagnostics diag;
  const auto s = load_scene(path, LoadOptions{}, diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.all().size(), 0u) << diag.format();
  ASSERT_EQ(s->materials.size(), 3u);
  const auto texture = [&](const std::optional<int>& i) -> const TextureDesc& {
    return s->textures.at(static_cast<std::size_t>(i.value()));
  };
  const TextureDesc& tiles = texture(s->materials[0].texture);
  EXPECT_EQ(tiles.type, TextureType::Checker);
  EXPECT_EQ(tiles.name, "tiles");
  EXPECT_EQ(tiles.color0.value, RGB(0.1f));
  EXPECT_EQ(tiles.color1.value, RGB(1.0f));  // default
  EXPECT_EQ(tiles.scale.value, Vec3f(8, 4, 1));
  const TextureDesc& photo = texture(s->materials[0].alpha_texture);
  EXPECT_EQ(photo.type, TextureType::Image);
  EXPECT_EQ(photo.filter.value, TextureFilter::Trilinear);
  EXPECT_EQ(photo.wrap.value, TextureWrap::Clamp);
  EXPECT_TRUE(photo.raw);
  EXPECT_TRUE(fs::equivalent(photo.resolved, dir.path() / "leaf.png"));
  const TextureDesc& marble = texture(s->materials[1].texture);
  EXPECT_EQ(marble.type, TextureType::Noise);
  EXPECT_TRUE(marble.object_mapping.value);
  EXPECT_EQ(marble.octaves.value, 4);
  EXPECT_EQ(marble.roughness.value, 0.6f);
  ASSERT_TRUE(marble.transform);
  EXPECT_EQ(marble.transform->value.point(Vec3f(0.0f)), Vec3f(1, 0, 0));
  EXPECT_EQ(s->materials[1].alpha.value, 0.0f);
  EXPECT_FALSE(s->materials[1].alpha_texture);
  // A path: an image with every default (anisotropic, repeat, sRGB); an inline object its own texture.
  const TextureDesc& leaf = texture(s->materials[2].texture);
  EXPECT_EQ(leaf.type, TextureType::Image);
  EXPECT_EQ(leaf.filter.value, TextureFilter::Anisotropic);
  EXPECT_FALSE(leaf.raw);
  EXPECT_EQ(texture(s->materials[2].alpha_texture).type, TextureType::Checker);
  EXPECT_EQ(s->textures.size(), 5u);  // tiles, photo, marble, leaf.png, the inline checker
}

// ---------------------------------------------------------------- path resolution

TEST(ResolveScenePath, SceneDirectoryFirstThenWorkingDirectory) {
  TempDir dir;
  const std::string scene = dir.write("scenes/s.json", "{}");
  dir.write("scenes/both.png", "scene dir");
  dir.write("both.png", "cwd");
  dir.write("only-cwd.png", "cwd");
  dir.write("scenes/only-scene.png", "scene dir");
  ScopedCwd cwd(dir.path());
  EXPECT_EQ(resolve_scene_path(scene, "both.png"), (dir.path() / "scenes/both.png").string());
  EXPECT_EQ(resolve_scene_path(scene, "only-scene.png"), (dir.path() / "scenes/only-scene.png").string());
  EXPECT_EQ(resolve_scene_path(scene, "only-cwd.png"), std::optional<std::string>("only-cwd.png"));
  EXPECT_EQ(resolve_scene_path(scene, "missing.png"), std::nullopt);
  EXPECT_EQ(resolve_scene_path(scene, ""), std::nullopt);
  EXPECT_EQ(resolve_scene_path(scene, "."), std::nullopt);  // a directory is not a file
  // Relative scene paths work too (the scene's folder relative to the working directory).
  EXPECT_EQ(resolve_scene_path("scenes/s.json", "only-scene.png"), std::optional<std::string>("scenes/only-scene.png"));
  // Absolute paths are taken as they are.
  const std::string abs = (dir.path() / "only-cwd.png").string();
  EXPECT_EQ(resolve_scene_path(scene, abs), abs);
  EXPECT_EQ(resolve_scene_path(scene, abs + ".nope"), std::nullopt);
}

TEST(ResolveScenePath, MissingFilesSayWhereTheyWereLookedFor) {
  TempDir dir;
  const std::string path = dir.write("s.json", native(R"(,
  "materials": { "m": { "texture": "t.png" } },
  "shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ])"));
  Diagnostics diag;
  EXPECT_FALSE(load_scene(path, LoadOptions{}, diag));
  ASSERT_EQ(diag.error_count(), 1);
  const std::string& message = diag.all()[0].message;
  EXPECT_NE(message.find("texture file 't.png' not found"), std::string::npos) << message;
  EXPECT_NE(message.find((dir.path() / "t.png").string()), std::string::npos) << message;
  EXPECT_NE(message.find((fs::current_path() / "t.png").string()), std::string::npos) << message;
}

// ---------------------------------------------------------------- course formats through the loader

TEST(CourseFormats, PathOfLightTrimeshInlineAndFromPly) {
  TempDir dir;
  dir.write("meshes/tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string path = dir.write("pol.json", R"({
  "camera": { "type": "pinhole", "width": 8, "height": 8, "fov": 40,
              "position": [0, -5, 1], "lookat": [0, 1, 0], "up": [0, 0, 1] },
  "scene": { "lightsources": [ { "type": "pointlight", "position": [0, 0, 3], "id": [1, 1, 1], "is": [1, 1, 1] } ],
             "shapes": [
    { "type": "trimesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], "faces": [[0, 1, 2], [2, 1, 3]] },
    { "type": "trimesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2] },
    { "type": "trimesh", "mPath": "meshes/tri.ply" },
    { "type": "trimesh", "plyPath": "meshes/tri.ply" },
    { "type": "trimesh", "filename": "meshes/tri.ply" }
  ] }
})");
  Diagnostics diag;
  const auto s = load_scene(path, LoadOptions{}, diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.all().size(), 0u) << diag.format();
  EXPECT_EQ(s->format, SceneFormat::PathOfLight);
  ASSERT_EQ(s->shapes.size(), 5u);
  EXPECT_EQ(geometry_of<TriangleMesh>(*s, 0).indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(geometry_of<TriangleMesh>(*s, 1).indices, (std::vector<uint32_t>{0, 1, 2}));
  for (std::size_t i = 2; i < 5; ++i) {
    const TriangleMesh& m = geometry_of<TriangleMesh>(*s, i);
    EXPECT_EQ(s->shapes[i].file, "meshes/tri.ply");
    EXPECT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.indices.size(), 3u);
  }
  EXPECT_EQ(s->materials.size(), 1u);  // all five use the default material
}

TEST(CourseFormats, PathOfLightThinLensUsesOurKeys) {
  Diagnostics diag;
  const auto s = load_text("pol.json", R"({
  "camera": { "type": "thinlens", "width": 8, "height": 8, "fov": 40, "position": [0, -5, 1],
              "lookat": [0, 1, 0], "up": [0, 0, 1], "lensradius": 0.1, "focusdistance": 5 },
  "scene": { "shapes": [] }
})", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.all().size(), 0u) << diag.format();
  EXPECT_EQ(s->camera.type, CameraType::ThinLens);
  EXPECT_EQ(s->camera.lens_radius.value, 0.1f);
  EXPECT_EQ(s->camera.focus_distance.value, 5.0f);
  EXPECT_TRUE(near(s->camera.look_at, Vec3f(0, -4, 1)));
  // A pinhole camera does not take lens keys: they are unknown (a warning in course files).
  Diagnostics pinhole;
  EXPECT_TRUE(load_text("pol.json", R"({
  "camera": { "type": "pinhole", "width": 8, "height": 8, "fov": 40, "position": [0, -5, 1],
              "lookat": [0, 1, 0], "up": [0, 0, 1], "lensradius": 0.1 },
  "scene": { "shapes": [] }
})", pinhole));
  EXPECT_EQ(pinhole.warning_count(), 1);
}

TEST(CourseFormats, UnknownLegacyKeysAreWarningsUnlessStrict) {
  const std::string text = R"({
  "rendermode": "phong", "accelerator": "bvh",
  "camera": { "type": "pinhole", "width": 8, "height": 8, "position": [0, 0, 0], "lookAt": [0, 0, 1],
              "upVector": [0, 1, 0], "fov": 45 },
  "scene": { "shapes": [] }
})";
  Diagnostics relaxed;
  EXPECT_TRUE(load_text("cgr.json", text, relaxed));
  EXPECT_EQ(relaxed.warning_count(), 1);
  EXPECT_EQ(relaxed.error_count(), 0);
  LoadOptions strict;
  strict.strict = true;
  Diagnostics strict_diag;
  EXPECT_FALSE(load_text("cgr.json", text, strict_diag, strict));
  ASSERT_EQ(strict_diag.error_count(), 1);
  EXPECT_EQ(strict_diag.all()[0].where.to_string(), "cgr.json:2:26");
  EXPECT_NE(strict_diag.all()[0].message.find("'accelerator'"), std::string::npos);
}

TEST(CourseFormats, DetectionNeedsAnExplicitMarker) {
  Diagnostics diag;
  EXPECT_FALSE(load_text("x.json", R"({"format": "other", "version": 1})", diag));
  ASSERT_EQ(diag.error_count(), 1);
  EXPECT_NE(diag.all()[0].message.find("pathtracer-scene"), std::string::npos);
  // CGR is recognised by its camera keys even without "rendermode".
  Diagnostics cgr;
  const auto s = load_text("c.json", R"({"camera": {"type": "pinhole", "width": 4, "height": 4, "position": [0, 0, 0],
      "lookAt": [0, 0, 1], "upVector": [0, 1, 0], "fov": 45}, "scene": {"shapes": []}})", cgr);
  ASSERT_TRUE(s) << cgr.format();
  EXPECT_EQ(s->format, SceneFormat::Cgr);
  EXPECT_EQ(s->render.integrator.value, "whitted");  // no rendermode: the classic integrator
}

// ---------------------------------------------------------------- limits and reporting

TEST(Loader, MissingFilesAndFolders) {
  Diagnostics diag;
  EXPECT_FALSE(load_scene("/no/such/scene.json", LoadOptions{}, diag));
  ASSERT_EQ(diag.error_count(), 1);
  EXPECT_EQ(format_diagnostic(diag.all()[0]), "/no/such/scene.json: error: scene file not found\n");
  TempDir dir;
  Diagnostics folder;
  EXPECT_FALSE(load_scene(dir.str(), LoadOptions{}, folder));
  EXPECT_EQ(folder.error_count(), 1);
}

TEST(Loader, HugeFilesAreRefusedBeforeReading) {
  TempDir dir;
  const fs::path big = dir.path() / "big.json";
  std::ofstream(big) << "{";
  fs::resize_file(big, 300ull << 20);  // sparse: nothing is written to disk
  Diagnostics diag;
  EXPECT_FALSE(load_scene(big.string(), LoadOptions{}, diag));
  ASSERT_EQ(diag.error_count(), 1);
  EXPECT_NE(diag.all()[0].message.find("larger than 256 MiB"), std::string::npos) << diag.all()[0].message;
}

TEST(Loader, ResolutionLimitComesFromTheOptions) {
  const std::string text = native(R"(, "film": { "width": 2000, "height": 1000 })");
  Diagnostics ok;
  EXPECT_TRUE(load_text("m.json", text, ok));
  LoadOptions small;
  small.limits.max_resolution = 1024;
  Diagnostics diag;
  EXPECT_FALSE(load_text("m.json", text, diag, small));
  ASSERT_EQ(diag.error_count(), 1);
  EXPECT_EQ(diag.all()[0].message, "width must be between 1 and 1024, got 2000");
}

TEST(Loader, ProblemsArePrintedWithTheLineAndACaret) {
  Diagnostics diag;
  EXPECT_FALSE(load_text("scenes/bad.json", native(R"(,
  "shapes": [
    { "type": "sphere",
      "center": [0, 0, 0],
      "radius": -1 }
  ])"), diag));
  EXPECT_EQ(diag.format(),
            "scenes/bad.json:7:17: error: radius must be > 0, got -1\n"
            " 7 |       \"radius\": -1 }\n"
            "   |                 ^\n"
            "1 error, 0 warnings\n");
}

TEST(Loader, AllProblemsOfAFileAreReportedInOneRun) {
  Diagnostics diag;
  EXPECT_FALSE(load_text("m.json", native(R"(,
  "film": { "width": 0 },
  "shapes": [
    { "type": "sphere", "center": [0, 0, 0], "radius": -1 },
    { "type": "sphere", "center": [0, 0], "radius": 1 },
    { "type": "cube" },
    { "type": "sphere", "center": [0, 0, 0], "radius": 1, "matrial": "x" }
  ])"), diag));
  EXPECT_EQ(diag.error_count(), 5) << diag.format();
}

// ---------------------------------------------------------------- the scenes shipped in scenes/

TEST(ShippedScenes, AllLoadWithoutProblems) {  // scenes/*.json and scenes/gallery/*.json
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(PT_SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    Diagnostics diag;
    const auto s = load_scene(entry.path().string(), LoadOptions{}, diag);
    EXPECT_TRUE(s) << entry.path() << "\n" << diag.format();
    EXPECT_EQ(diag.all().size(), 0u) << entry.path() << "\n" << diag.format();
  }
  EXPECT_GE(count, 3);
}

TEST(ShippedScenes, ClassicSceneExercisesEveryClassicShapeAndItsAssets) {
  Diagnostics diag;
  const auto s = load_scene(std::string(PT_SCENES_DIR) + "/classic.json", LoadOptions{}, diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_GE(s->film.width.value, 1024);
  EXPECT_GE(s->lights.size(), 2u);
  EXPECT_EQ(s->textures.size(), 2u);
  int spheres = 0, quads = 0, triangles = 0, cylinders = 0, meshes = 0, refractive = 0, mirrors = 0;
  for (const ShapeDesc& shape : s->shapes) {
    spheres += std::holds_alternative<Sphere>(shape.geometry);
    quads += std::holds_alternative<Quad>(shape.geometry);
    triangles += shape.type == "triangle";  // a one-triangle mesh
    cylinders += std::holds_alternative<Cylinder>(shape.geometry);
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape.geometry); mesh && shape.type == "mesh") {
      ++meshes;
      EXPECT_GE(mesh->indices.size() / 3, 20000u);
      EXPECT_EQ(mesh->normals.size(), mesh->positions.size());
      EXPECT_EQ(mesh->uvs.size(), mesh->positions.size());
    }
  }
  for (const MaterialDesc& m : s->materials) {
    refractive += m.refractive.value;
    mirrors += m.reflectivity.value > 0.8f;
  }
  EXPECT_GE(spheres, 3);
  EXPECT_GE(quads, 1);
  EXPECT_GE(triangles, 1);
  EXPECT_GE(cylinders, 1);
  EXPECT_EQ(meshes, 1);
  EXPECT_GE(refractive, 1);
  EXPECT_GE(mirrors, 1);
}

// The README's first command renders scenes/showcase.json: it must show what a
// path tracer is for (issue 21): the path integrator, an area light, glass, a
// metal, a textured mesh, an HDR environment map and depth of field.
TEST(ShippedScenes, ShowcaseShowsWhatThePathTracerIsFor) {
  Diagnostics diag;
  const auto s = load_scene(std::string(PT_SCENES_DIR) + "/showcase.json", LoadOptions{}, diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->render.integrator.value, "path");
  EXPECT_EQ(s->camera.type, CameraType::ThinLens);
  int coated = 0;
  for (const MaterialDesc& m : s->materials) coated += m.type.value == MaterialType::CoatedDiffuse;
  EXPECT_GE(coated, 1);
  ASSERT_TRUE(s->environment.has_value());
  EXPECT_NE(s->environment->resolved.find("scenes/assets/"), std::string::npos) << "the map ships with the repository";
  int glass = 0, metals = 0, emitters = 0;
  for (const MaterialDesc& m : s->materials) {
    glass += m.type.value == MaterialType::Glass;
    metals += m.type.value == MaterialType::Conductor && m.uroughness.value.value > 0.0f;  // a rough metal
    emitters += m.emission.value.max_component() > 0.0f;
  }
  EXPECT_GE(glass, 1);
  EXPECT_GE(metals, 1);
  EXPECT_GE(emitters, 1);
  int textured_meshes = 0;
  for (const ShapeDesc& shape : s->shapes) {
    const auto* mesh = std::get_if<TriangleMesh>(&shape.geometry);
    const MaterialDesc& m = s->materials[static_cast<std::size_t>(shape.material)];
    textured_meshes += mesh != nullptr && !mesh->uvs.empty() && m.texture.has_value();
  }
  EXPECT_GE(textured_meshes, 1);
}

}  // namespace
}  // namespace pt
