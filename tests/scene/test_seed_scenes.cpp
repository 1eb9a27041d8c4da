// The shared course scenes load without errors or warnings, and the importers
// apply each family's conventions (docs/scene-format.md).
#include <gtest/gtest.h>

#include <filesystem>

#include "scene_test_util.h"

namespace pt {
namespace {

using test::geometry_of;
using test::near;
using test::point_light;

std::optional<SceneDescription> load_seed(const std::string& relative, Diagnostics& diag) {
  LoadOptions options;
  options.strict = true;  // the official files have no unknown keys
  return load_scene(test::seed_dir() + "/" + relative, options, diag);
}

// Skips every test when the shared seed scenes are not there.
class SeedScenes : public ::testing::Test {
 protected:
  void SetUp() override {
    if (test::seed_dir().empty()) GTEST_SKIP() << "shared seed scenes not found at " PT_SHARED_DIR "/seed-scenes";
  }
};

TEST_F(SeedScenes, EveryFileLoadsCleanly) {
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test::seed_dir())) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    Diagnostics diag;
    const auto scene = load_scene(entry.path().string(), LoadOptions{}, diag);
    EXPECT_TRUE(scene.has_value()) << entry.path() << "\n" << diag.format();
    EXPECT_EQ(diag.all().size(), 0u) << entry.path() << "\n" << diag.format();
  }
  EXPECT_GE(count, 5);
}

TEST_F(SeedScenes, PathOfLightConventions) {
  Diagnostics diag;
  const auto s = load_seed("path-of-light/examples/example.json", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->format, SceneFormat::PathOfLight);
  // Camera: lookat is a direction, so the target is position + lookat; Z-up; right-handed.
  EXPECT_TRUE(near(s->camera.position, Vec3f(0, -3.5f, 2)));
  EXPECT_TRUE(near(s->camera.look_at, Vec3f(0, -2.5f, 1.9f)));
  EXPECT_TRUE(near(s->camera.up, Vec3f(0, 0, 0.5f)));
  EXPECT_FALSE(s->camera.left_handed.value);
  EXPECT_EQ(s->camera.fov_y_deg.value, 35.0f);
  EXPECT_EQ(s->camera.look_at.where.line, 9);  // reported at "lookat"
  EXPECT_EQ(s->film.width.value, 800);
  EXPECT_EQ(s->film.height.value, 800);
  EXPECT_EQ(s->film.display.value, DisplayTransform::Linear);
  EXPECT_EQ(s->render.max_depth.value, 3);
  EXPECT_EQ(s->render.integrator.value, "whitted");
  EXPECT_TRUE(near(s->render.background, RGB(0.01f)));
  // Point light: id/is with 1/(4 pi r^2) become intensities / (4 pi) with 1/r^2.
  ASSERT_EQ(s->lights.size(), 1u);
  const PointLightDesc& light = point_light(*s, 0);
  EXPECT_TRUE(near(light.intensity, RGB(100.0f / (4 * kPi))));
  EXPECT_TRUE(near(light.specular_intensity, RGB(100.0f / (4 * kPi))));
  EXPECT_TRUE(light.inverse_square.value);
  EXPECT_TRUE(near(light.position, Vec3f(0, 1, 1.5f)));
  // Shapes, in file order: textured sphere (pole +Z), back wall, floor, two triangles.
  ASSERT_EQ(s->shapes.size(), 5u);
  const Sphere& sphere = geometry_of<Sphere>(*s, 0);
  EXPECT_TRUE(near(sphere.center, Vec3f(0, 2.7f, 0.15f)));
  EXPECT_EQ(sphere.radius, 0.5f);
  EXPECT_TRUE(near(sphere.pole, Vec3f(0, 0, 1)));
  // "plane" corners are looked up by name, whatever the key order in the file.
  const Quad& back = geometry_of<Quad>(*s, 1);
  EXPECT_EQ(s->shapes[1].name, "back wall");
  EXPECT_TRUE(near(back.v[0], Vec3f(2, 8, 0)));
  EXPECT_TRUE(near(back.v[1], Vec3f(-2, 8, 0)));
  EXPECT_TRUE(near(back.v[2], Vec3f(-2, 8, 5)));
  EXPECT_TRUE(near(back.v[3], Vec3f(2, 8, 5)));
  const Quad& floor = geometry_of<Quad>(*s, 2);
  EXPECT_TRUE(near(floor.v[0], Vec3f(-2, 8, 0)));
  EXPECT_TRUE(near(floor.v[1], Vec3f(2, 8, 0)));
  EXPECT_TRUE(near(floor.v[2], Vec3f(2, 0, 0)));
  EXPECT_TRUE(near(floor.v[3], Vec3f(-2, 0, 0)));
  const TriangleMesh& left = geometry_of<TriangleMesh>(*s, 3);
  EXPECT_EQ(s->shapes[3].name, "left wall");
  ASSERT_EQ(left.positions.size(), 3u);
  EXPECT_TRUE(near(left.positions[1], Vec3f(-2, 8, 5)));
  // Materials: kr -> reflectivity; textures resolved from the scene's folder, each once.
  const MaterialDesc& floor_m = s->materials[static_cast<std::size_t>(s->shapes[2].material)];
  EXPECT_EQ(floor_m.reflectivity.value, 0.3f);
  EXPECT_EQ(floor_m.exponent.value, 10.0f);
  EXPECT_EQ(floor_m.ks.value, 0.0f);  // textured: no highlight (docs/rendering.md, the course reference images)
  EXPECT_EQ(floor_m.kd.value, 0.7f);
  const MaterialDesc& sphere_m = s->materials[static_cast<std::size_t>(s->shapes[0].material)];
  EXPECT_TRUE(near(sphere_m.diffuse, RGB(1.0f)));  // the texture replaces "diffusecolor" (0.4, 0.3, 0.4)
  EXPECT_EQ(sphere_m.ks.value, 0.0f);
  EXPECT_EQ(sphere_m.reflectivity.value, 0.0f);
  ASSERT_EQ(s->textures.size(), 2u);
  ASSERT_TRUE(sphere_m.texture && floor_m.texture);
  EXPECT_EQ(s->textures[static_cast<std::size_t>(*sphere_m.texture)].written, "../textures/sky-map.jpg");
  EXPECT_EQ(s->textures[static_cast<std::size_t>(*floor_m.texture)].written, "../textures/sicily.jpg");
  for (const TextureDesc& t : s->textures) {
    EXPECT_TRUE(std::filesystem::is_regular_file(t.resolved)) << t.resolved;
    EXPECT_TRUE(t.raw) << "the course's texels are used as stored";
  }
  const MaterialDesc& wall_m = s->materials[static_cast<std::size_t>(s->shapes[3].material)];
  EXPECT_FALSE(wall_m.texture.has_value());
}

TEST_F(SeedScenes, CgrConventions) {
  Diagnostics diag;
  const auto s = load_seed("cgr/scene.json", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->format, SceneFormat::Cgr);
  EXPECT_EQ(s->render.integrator.value, "binary");  // rendermode
  EXPECT_EQ(s->render.max_depth.value, 8);
  EXPECT_EQ(s->film.display.value, DisplayTransform::CgrCourse);
  EXPECT_EQ(s->film.width.value, 1200);
  EXPECT_EQ(s->film.height.value, 800);
  // lookAt is a target point; Y-up; left-handed image frame; vertical fov.
  EXPECT_TRUE(near(s->camera.position, Vec3f(0, 0.75f, -0.25f)));
  EXPECT_TRUE(near(s->camera.look_at, Vec3f(0, 0.35f, 1)));
  EXPECT_TRUE(near(s->camera.up, Vec3f(0, 1, 0)));
  EXPECT_TRUE(s->camera.left_handed.value);
  EXPECT_EQ(s->camera.fov_y_deg.value, 45.0f);
  EXPECT_EQ(s->camera.film_offset.x, -1.0f);  // the course samples one pixel to the left
  EXPECT_EQ(s->camera.film_offset.y, 0.0f);
  // Lights: one intensity for both lobes, no distance falloff; then the course's
  // ambient term, lit by the background colour.
  ASSERT_EQ(s->lights.size(), 3u);
  ASSERT_TRUE(std::holds_alternative<AmbientLightDesc>(s->lights[2]));
  EXPECT_TRUE(near(std::get<AmbientLightDesc>(s->lights[2]).intensity, RGB(0.25f)));
  EXPECT_TRUE(near(point_light(*s, 1).intensity, RGB(0.5f)));
  EXPECT_TRUE(near(point_light(*s, 1).specular_intensity, RGB(0.5f)));
  EXPECT_FALSE(point_light(*s, 1).inverse_square.value);
  // Cylinder: height is HALF the length, so it spans center +- height * axis.
  const Cylinder& c = geometry_of<Cylinder>(*s, 1);
  EXPECT_TRUE(near(c.p0, Vec3f(-0.3f, -0.01f, 1)));
  EXPECT_TRUE(near(c.p1, Vec3f(-0.3f, 0.39f, 1)));
  EXPECT_EQ(c.radius, 0.15f);
  // Spheres use the default pole (+Y).
  EXPECT_TRUE(near(geometry_of<Sphere>(*s, 0).pole, Vec3f(0, 1, 0)));
  // isreflective gates reflectivity.
  const MaterialDesc& ground = s->materials[static_cast<std::size_t>(s->shapes[0].material)];
  EXPECT_EQ(ground.reflectivity.value, 0.0f);  // "isreflective": false, "reflectivity": 1.0
  const MaterialDesc& mirror = s->materials[static_cast<std::size_t>(s->shapes[2].material)];
  EXPECT_EQ(mirror.reflectivity.value, 1.0f);
  EXPECT_TRUE(near(mirror.specular, RGB(1.0f)));
  EXPECT_FALSE(mirror.refractive.value);
  EXPECT_EQ(mirror.ior.value, 1.0f);
  EXPECT_EQ(mirror.exponent.value, 2.0f);
}

TEST_F(SeedScenes, CgrDefaultsWhenKeysAreAbsent) {
  Diagnostics diag;
  const auto s = load_seed("cgr/binary_primitives.json", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->render.max_depth.value, 8);  // no "nbounces"
  ASSERT_EQ(s->lights.size(), 1u);          // no "lightsources": only the course's ambient term
  EXPECT_TRUE(std::holds_alternative<AmbientLightDesc>(s->lights[0]));
  ASSERT_EQ(s->shapes.size(), 3u);
  ASSERT_EQ(s->materials.size(), 1u);       // no "material": one shared default
  for (const ShapeDesc& shape : s->shapes) EXPECT_EQ(shape.material, 0);
  const Cylinder& c = geometry_of<Cylinder>(*s, 1);
  EXPECT_TRUE(near(c.p0, Vec3f(-0.5f, -0.2f, 1)));
  EXPECT_TRUE(near(c.p1, Vec3f(-0.1f, -0.2f, 1)));
}

TEST_F(SeedScenes, CgrPhongModeUsesTheClassicIntegrator) {
  Diagnostics diag;
  const auto s = load_seed("cgr/simple_phong.json", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->render.integrator.value, "whitted");
  EXPECT_EQ(s->shapes.size(), 4u);
  const Cylinder& c = geometry_of<Cylinder>(*s, 1);
  EXPECT_TRUE(near(c.p0, Vec3f(0.3f, -0.5f, 1)));
  EXPECT_TRUE(near(c.p1, Vec3f(0.3f, 0.5f, 1)));
}

}  // namespace
}  // namespace pt
