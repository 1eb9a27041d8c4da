// The scene keys of the path tracer (docs/scene-format.md): material types and
// two-sided emission, directional lights, the environment map, the pixel
// filter and the clamp; the thin-lens spellings of third-party Path of Light
// files; CGR's "pathtracer" render mode.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene_test_util.h"

namespace pt {
namespace {

namespace fs = std::filesystem;
using test::near;

std::optional<SceneDescription> load_text(const std::string& path, const std::string& text, Diagnostics& diag) {
  return load_scene_from_string(path, text, LoadOptions{}, diag);
}

TEST(PathKeys, DefaultsAreTheClassicModel) {
  Diagnostics diag;
  const auto s = load_text("s.json", R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 1, 5], "look_at": [0, 1, 0] },
  "materials": { "m": {} },
  "shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ] })", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->materials[0].type.value, MaterialType::Phong);
  EXPECT_FALSE(s->materials[0].two_sided.value);
  EXPECT_EQ(s->render.filter.value, PixelFilterType::Box);
  EXPECT_EQ(s->render.clamp.value, 0.0f);
  EXPECT_FALSE(s->environment.has_value());
}

// An emitter's "light_samples": the classic integrator's samples of it per
// shading point (docs/rendering.md); absent: 0, the integrator's default.
TEST(PathKeys, LightSamplesOfAnEmitter) {
  const std::string head = R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 1, 5], "look_at": [0, 1, 0] }, "materials": { "m": )";
  const std::string tail = R"( }, "shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ] })";
  Diagnostics diag;
  const auto s = load_text("s.json", head + R"({ "type": "lambert", "emission": [1, 1, 1], "light_samples": 9 })" + tail,
                           diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->materials[0].light_samples.value, 9);
  const auto plain = load_text("s.json", head + R"({ "emission": [1, 1, 1] })" + tail, diag);
  ASSERT_TRUE(plain) << diag.format();
  EXPECT_EQ(plain->materials[0].light_samples.value, 0);
  Diagnostics bad;
  EXPECT_FALSE(load_text("s.json", head + R"({ "emission": [1, 1, 1], "light_samples": 0 })" + tail, bad));
  EXPECT_NE(bad.format().find("'light_samples' must be at least 1"), std::string::npos) << bad.format();
}

TEST(PathKeys, EveryKeyIsRead) {
  const fs::path dir = fs::temp_directory_path() / ("pt-path-keys-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "sky.hdr") << "not decoded by the loader";
  const std::string scene = (dir / "s.json").string();
  Diagnostics diag;
  const auto s = load_text(scene, R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 1, 5], "look_at": [0, 1, 0] },
  "render": { "integrator": "path", "filter": "mitchell", "clamp": 8 },
  "environment": { "file": "sky.hdr", "rotation": 90, "intensity": 0.5, "up": [0, 0, 1] },
  "materials": {
    "matte": { "type": "lambert", "diffuse": [0.5, 0.4, 0.3], "kd": 0.9 },
    "chrome": { "type": "mirror", "specular": [0.9, 0.8, 0.7] },
    "glass": { "type": "glass", "ior": 1.33 },
    "lamp": { "type": "lambert", "diffuse": [0, 0, 0], "emission": [4, 3, 2], "two_sided": true }
  },
  "lights": [ { "type": "directional", "direction": [1, -2, 0], "irradiance": [3, 2, 1] } ],
  "shapes": [
    { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "matte" },
    { "type": "sphere", "center": [2, 0, 0], "radius": 1, "material": "chrome" },
    { "type": "sphere", "center": [4, 0, 0], "radius": 1, "material": "glass" },
    { "type": "quad", "vertices": [[0, 3, 0], [1, 3, 0], [1, 3, 1], [0, 3, 1]], "material": "lamp" }
  ] })", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.all().size(), 0u) << diag.format();
  EXPECT_EQ(s->render.filter.value, PixelFilterType::Mitchell);
  EXPECT_EQ(s->render.clamp.value, 8.0f);
  ASSERT_TRUE(s->environment.has_value());
  EXPECT_EQ(s->environment->file.value, "sky.hdr");
  EXPECT_EQ(fs::path(s->environment->resolved), dir / "sky.hdr");
  EXPECT_EQ(s->environment->rotation_deg.value, 90.0f);
  EXPECT_EQ(s->environment->intensity.value, 0.5f);
  EXPECT_TRUE(near(s->environment->up, Vec3f(0, 0, 1)));
  ASSERT_EQ(s->materials.size(), 4u);
  EXPECT_EQ(s->materials[0].type.value, MaterialType::Lambert);
  EXPECT_EQ(s->materials[0].kd.value, 0.9f);
  EXPECT_EQ(s->materials[1].type.value, MaterialType::Mirror);
  EXPECT_TRUE(near(s->materials[1].specular, RGB(0.9f, 0.8f, 0.7f)));
  EXPECT_EQ(s->materials[2].type.value, MaterialType::Glass);
  EXPECT_EQ(s->materials[2].ior.value, 1.33f);
  EXPECT_TRUE(s->materials[3].two_sided.value);
  ASSERT_EQ(s->lights.size(), 1u);
  const auto& sun = std::get<DirectionalLightDesc>(s->lights[0]);
  EXPECT_TRUE(near(sun.direction, Vec3f(1, -2, 0)));
  EXPECT_TRUE(near(sun.irradiance, RGB(3, 2, 1)));
  EXPECT_EQ(sun.irradiance.where.line, 11);
  fs::remove_all(dir);
}

TEST(PathKeys, PathOfLightThinLensAcceptsThirdPartySpellings) {
  Diagnostics diag;
  const auto s = load_text("pol.json", R"({
  "camera": { "type": "thinlens", "width": 8, "height": 8, "fov": 40, "position": [0, -5, 1],
              "lookat": [0, 1, 0], "up": [0, 0, 1], "lens_radius": 0.2, "focaldistance": 4 },
  "scene": { "shapes": [] }
})", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.all().size(), 0u) << diag.format();
  EXPECT_EQ(s->camera.lens_radius.value, 0.2f);
  EXPECT_EQ(s->camera.focus_distance.value, 4.0f);
  // Two spellings of one value are an error, and so is none.
  Diagnostics twice;
  EXPECT_FALSE(load_text("pol.json", R"({
  "camera": { "type": "thinlens", "width": 8, "height": 8, "fov": 40, "position": [0, -5, 1],
              "lookat": [0, 1, 0], "up": [0, 0, 1], "lensradius": 0.2, "focusdistance": 4, "focal_distance": 4 },
  "scene": { "shapes": [] }
})", twice));
  EXPECT_NE(twice.format().find("'focal_distance' and 'focusdistance' say the same thing"), std::string::npos)
      << twice.format();
  Diagnostics none;
  EXPECT_FALSE(load_text("pol.json", R"({
  "camera": { "type": "thinlens", "width": 8, "height": 8, "fov": 40, "position": [0, -5, 1],
              "lookat": [0, 1, 0], "up": [0, 0, 1], "lensradius": 0.2 },
  "scene": { "shapes": [] }
})", none));
  EXPECT_NE(none.format().find("a thin-lens camera needs its distance in focus: one of"), std::string::npos) << none.format();
}

TEST(PathKeys, CgrPathtracerModeSelectsThePathIntegrator) {
  Diagnostics diag;
  const auto s = load_text("cgr.json", R"({ "rendermode": "pathtracer",
  "camera": { "type": "pinhole", "width": 8, "height": 8, "position": [0, 0, 0], "lookAt": [0, 0, 1],
              "upVector": [0, 1, 0], "fov": 45, "exposure": 0.1 },
  "scene": { "backgroundcolor": [0.25, 0.25, 0.25], "shapes": [] } })", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->render.integrator.value, "path");
}

}  // namespace
}  // namespace pt
