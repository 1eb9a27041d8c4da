// build_render_scene: conversion, resolution, textures decoded only when used,
// errors reported at their source location.
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/parallel.h"
#include "io/image_io.h"
#include "test_scenes.h"

namespace pt {
namespace {

using test::add_material;
using test::add_sphere;
using test::add_z_square;

namespace fs = std::filesystem;

class RenderSceneBuild : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pt_render_scene_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    file_ = std::make_shared<SourceFile>(SourceFile{"scene.json", "{\n  \"texture\": \"wood.png\"\n}\n"});
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write_png(const std::string& name) {
    const std::string path = (dir_ / name).string();
    Image image(2, 1);  // red, green (through the image module, as any PNG we write)
    image.pixels = {RGB(1.0f, 0.0f, 0.0f), RGB(0.0f, 1.0f, 0.0f)};
    std::string error;
    EXPECT_TRUE(write_image(path, image, DisplaySettings{}, error)) << error;
    return path;
  }

  TextureDesc texture(const std::string& written, const std::string& resolved) {
    TextureDesc t;
    t.where = SourceLocation{file_, 2, 15};
    t.written = written;
    t.resolved = resolved;
    return t;
  }

  WorkerPool pool_{1};
  fs::path dir_;
  std::shared_ptr<SourceFile> file_;
};

TEST_F(RenderSceneBuild, ConvertsShapesMaterialsAndLights) {
  SceneDescription d = test::empty_scene(20, 10, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  d.render.background = RGB(0.1f, 0.2f, 0.3f);
  add_material(d, test::diffuse_material(RGB(1, 0, 0)));
  const int blue = add_material(d, test::diffuse_material(RGB(0, 0, 1)));
  add_sphere(d, {0, 0, 0}, 1.0f, blue);
  test::add_shape(d, make_triangle(Vec3f(5, 0, 0), Vec3f(6, 0, 0), Vec3f(5, 1, 0)), 0);
  test::add_point_light(d, {1, 2, 3}, RGB(4), RGB(5));
  auto scene = test::build(d, pool_);
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->width, 20);
  EXPECT_EQ(scene->height, 10);
  EXPECT_EQ(scene->background, RGB(0.1f, 0.2f, 0.3f));
  ASSERT_EQ(scene->geometry.shapes.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<Sphere>(scene->geometry.shapes[0]));
  ASSERT_TRUE(std::holds_alternative<TriangleMesh>(scene->geometry.shapes[1]));
  EXPECT_EQ(std::get<TriangleMesh>(scene->geometry.shapes[1]).triangle_count(), 1u);
  // The point light and the background as a uniform environment, each once.
  ASSERT_EQ(scene->lights.size(), 2u);
  ASSERT_EQ(scene->lights.delta_lights().size(), 1u);
  ASSERT_TRUE(std::holds_alternative<PointLight>(scene->lights[0]));
  EXPECT_EQ(std::get<PointLight>(scene->lights[0]).specular_intensity, RGB(5));
  ASSERT_TRUE(std::holds_alternative<UniformEnvironment>(scene->lights[1]));
  EXPECT_EQ(scene->lights.environment(), 1);
  EXPECT_EQ(scene->escaped_radiance(Vec3f(0, 1, 0)), RGB(0.1f, 0.2f, 0.3f));

  Intersection isect;
  ASSERT_TRUE(scene->intersect(Ray{{0, 0, 5}, {0, 0, -1}}, isect));
  EXPECT_EQ(isect.hit.shape, 0u);
  EXPECT_NEAR(isect.hit.t, 4.0f, 1e-5f);
  EXPECT_NEAR(isect.geo.p.z, 1.0f, 1e-5f);
  ASSERT_NE(isect.material, nullptr);
  EXPECT_EQ(isect.material->diffuse, RGB(0, 0, 1));
  EXPECT_FALSE(scene->intersect(Ray{{0, 3, 5}, {0, 0, 1}}, isect));
  EXPECT_TRUE(scene->occluded(Ray{{5.2f, 0.2f, 1}, {0, 0, -1}}));
}

// The light set's order (delta before not, finite before infinite, the
// description's order within a kind) fixes the light choice and the classic
// integrator's sum, whatever order the description lists its lights in.
TEST_F(RenderSceneBuild, LightsAreOrderedByKindEachStoredOnce) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  MaterialDesc glow = test::diffuse_material(RGB(1));
  glow.emission = RGB(2);
  add_sphere(d, {0, 0, 0}, 1.0f, add_material(d, glow));
  DirectionalLightDesc sun;
  sun.direction = Vec3f(0, -1, 0);
  sun.irradiance = RGB(1);
  d.lights.emplace_back(sun);
  test::add_point_light(d, {1, 2, 3}, RGB(4), RGB(4));
  test::add_point_light(d, {3, 2, 1}, RGB(6), RGB(6));
  d.render.background = RGB(0.5f);
  auto scene = test::build(d, pool_);
  ASSERT_TRUE(scene);
  const LightSet& lights = scene->lights;
  ASSERT_EQ(lights.size(), 5u);
  EXPECT_EQ(lights.delta_lights().size(), 3u);
  ASSERT_TRUE(std::holds_alternative<PointLight>(lights[0]));
  EXPECT_EQ(std::get<PointLight>(lights[0]).intensity, RGB(4));
  ASSERT_TRUE(std::holds_alternative<PointLight>(lights[1]));
  EXPECT_EQ(std::get<PointLight>(lights[1]).intensity, RGB(6));
  EXPECT_TRUE(std::holds_alternative<DirectionalLight>(lights[2]));
  EXPECT_TRUE(std::holds_alternative<ShapeLight>(lights[3]));
  EXPECT_EQ(lights.shape_light(0), 3);
  EXPECT_TRUE(std::holds_alternative<UniformEnvironment>(lights[4]));
  EXPECT_EQ(lights.environment(), 4);
  // Every light answers the one interface; delta lights have no density.
  LightSample s;
  ASSERT_TRUE(sample_light(lights[2], Vec3f(0, 3, 0), Vec2f(0.5f, 0.5f), s));
  EXPECT_TRUE(s.delta && s.infinite);
  EXPECT_EQ(light_pdf(lights[2], Vec3f(0, 3, 0), s.wi, Vec3f(), Vec3f()), 0.0f);
  ASSERT_TRUE(sample_light(lights[4], Vec3f(0, 3, 0), Vec2f(0.5f, 0.5f), s));
  EXPECT_TRUE(!s.delta && s.infinite);
  EXPECT_EQ(light_pdf(lights[4], Vec3f(0, 3, 0), s.wi, Vec3f(), Vec3f()), s.pdf);
}

TEST_F(RenderSceneBuild, ResolutionOverrides) {
  SceneDescription d = test::empty_scene(800, 400, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  auto size = [&](int w, int h) {
    BuildOptions o;
    o.width_override = w;
    o.height_override = h;
    auto s = test::build(d, pool_, o);
    return s ? std::pair{s->width, s->height} : std::pair{-1, -1};
  };
  EXPECT_EQ(size(0, 0), (std::pair{800, 400}));
  EXPECT_EQ(size(160, 120), (std::pair{160, 120}));
  EXPECT_EQ(size(160, 0), (std::pair{160, 80}));   // keeps the aspect ratio
  EXPECT_EQ(size(0, 100), (std::pair{200, 100}));
}

TEST_F(RenderSceneBuild, UsedTexturesAreDecodedOnceUnusedOnesNever) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  d.textures.push_back(texture("missing.png", (dir_ / "missing.png").string()));  // never used
  d.textures.push_back(texture("wood.png", write_png("wood.png")));
  MaterialDesc m = test::diffuse_material(RGB(1));
  m.texture = 1;
  add_material(d, m);
  add_material(d, m);
  add_z_square(d, 0, 1, 0);
  add_z_square(d, -1, 1, 1);
  auto scene = test::build(d, pool_);
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->textures[0], nullptr);
  ASSERT_NE(scene->textures[1], nullptr);
  EXPECT_EQ(scene->materials[0].texture, scene->textures[1].get());
  EXPECT_EQ(scene->materials[1].texture, scene->textures[1].get());
  EXPECT_EQ(scene->materials[0].diffuse_at(Vec2f(0.25f, 0.5f)), RGB(1, 0, 0));
}

TEST_F(RenderSceneBuild, TextureThatFailsToDecodeIsReportedWhereItWasWritten) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  const std::string bad = (dir_ / "wood.png").string();
  { std::FILE* f = std::fopen(bad.c_str(), "wb"); std::fputs("garbage", f); std::fclose(f); }
  d.textures.push_back(texture("wood.png", bad));
  MaterialDesc m = test::diffuse_material(RGB(1));
  m.texture = 0;
  add_z_square(d, 0, 1, add_material(d, m));
  Diagnostics diag;
  EXPECT_EQ(build_render_scene(d, {}, pool_, diag), nullptr);
  ASSERT_EQ(diag.error_count(), 1);
  const Diagnostic& e = diag.all()[0];
  EXPECT_EQ(e.where.to_string(), "scene.json:2:15");
  EXPECT_NE(e.message.find("wood.png"), std::string::npos) << e.message;
}

TEST_F(RenderSceneBuild, BadMaterialIndexIsAnError) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  add_material(d, test::diffuse_material(RGB(1)));
  add_z_square(d, 0, 1, 3);
  d.shapes.back().where = SourceLocation{file_, 1, 1};
  Diagnostics diag;
  EXPECT_EQ(build_render_scene(d, {}, pool_, diag), nullptr);
  ASSERT_TRUE(diag.has_errors());
  EXPECT_EQ(diag.all()[0].where.to_string(), "scene.json:1:1");
}

// A description built in code is refused, with a message per shape, where its
// geometry would break the accelerators (the shapes' rules, geometry/shapes/*.h,
// run by scene validation), whichever the backend.
TEST_F(RenderSceneBuild, UnusableGeometryIsReportedNotBuilt) {
  for (const AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
    BuildOptions options;
    options.accel = kind;
    {
      SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
      TriangleMesh mesh;
      mesh.positions = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)};
      mesh.indices = {0, 1, 3};
      test::add_sphere(d, {0, 0, 0}, 1.0f, 0);
      test::add_shape(d, mesh, 0);
      test::add_shape(d, Cylinder{{0, 0, 0}, {0, kInfinity, 0}, 1.0f}, 0);
      Diagnostics diag;
      EXPECT_EQ(build_render_scene(d, options, pool_, diag), nullptr);
      ASSERT_EQ(diag.error_count(), 2) << diag.format();
      EXPECT_EQ(diag.all()[0].message,
                "shape 1: mesh: 1 vertex indices are out of range (e.g. 3; the mesh has 3 vertices)");
      EXPECT_EQ(diag.all()[1].message, "shape 2: cylinder has a non-finite end point or radius");
    }
    {
      SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
      TriangleMesh mesh;
      mesh.positions = {{0, 0, 0}, {1, 0, 0}};
      mesh.indices = {0, 1};
      test::add_shape(d, mesh, 0);
      test::add_sphere(d, {std::numeric_limits<float>::quiet_NaN(), 0, 0}, 1.0f, 0);
      Diagnostics diag;
      EXPECT_EQ(build_render_scene(d, options, pool_, diag), nullptr);
      ASSERT_EQ(diag.error_count(), 2) << diag.format();
      EXPECT_EQ(diag.all()[0].message, "shape 0: mesh has 2 indices, not a multiple of 3");
      EXPECT_EQ(diag.all()[1].message, "shape 1: sphere has a non-finite centre or radius");
    }
  }
}

// The material's kind is decided once, when the scene is built: every
// dielectric is Glass (a refractive Phong too, but not a refractive Lambert or
// mirror, whose type says what they are), and the physical types carry their
// classic meaning in the course fields.
TEST(MakeMaterial, DecidesTheKindOnce) {
  MaterialDesc d;
  d.refractive = true;
  d.ior = 1.3f;
  Material m = make_material(d);
  EXPECT_TRUE(m.glass());
  EXPECT_EQ(m.albedo_at(Vec2f()), RGB(1.0f));
  d.type = MaterialType::Lambert;
  d.kd = 0.5f;
  d.diffuse = RGB(0.2f, 0.4f, 0.6f);
  m = make_material(d);
  EXPECT_FALSE(m.glass());
  EXPECT_EQ(m.ks, 0.0f);
  EXPECT_EQ(m.albedo_at(Vec2f()), RGB(0.2f, 0.4f, 0.6f) * 0.5f);
  d.type = MaterialType::Mirror;
  d.specular = RGB(0.9f, 0.8f, 0.7f);
  m = make_material(d);
  EXPECT_FALSE(m.glass());
  EXPECT_EQ(m.reflectivity, 1.0f);
  EXPECT_EQ(m.kd, 0.0f);
  EXPECT_EQ(m.albedo_at(Vec2f()), RGB(0.9f, 0.8f, 0.7f));
  d.type = MaterialType::Glass;
  d.refractive = false;
  EXPECT_TRUE(make_material(d).glass());
}

}  // namespace
}  // namespace pt
