// The native camera types and the keys each reads (docs/scene-format.md, "camera").
#include <gtest/gtest.h>

#include <string>

#include "scene_test_util.h"

namespace pt {
namespace {

std::optional<SceneDescription> load_camera(const std::string& camera, Diagnostics& diag) {
  const std::string text = R"({ "format": "pathtracer-scene", "version": 1,
  "camera": )" + camera + "\n}\n";
  return load_scene_from_string("cam.json", text, LoadOptions{}, diag);
}

TEST(CameraKeys, EveryTypeAndItsSpellings) {
  const std::pair<const char*, CameraType> cases[] = {
      {R"("pinhole")", CameraType::Pinhole},
      {R"("perspective")", CameraType::Pinhole},
      {R"("thin_lens", "lens_radius": 0.1, "focus_distance": 2)", CameraType::ThinLens},
      {R"("thinlens", "lens_radius": 0.1, "focus_distance": 2)", CameraType::ThinLens},
      {R"("orthographic", "view_height": 3)", CameraType::Orthographic},
      {R"("spherical")", CameraType::Spherical}};
  for (const auto& [type, expected] : cases) {
    Diagnostics diag;
    const auto s =
        load_camera(std::string(R"({ "position": [0, 0, 0], "look_at": [0, 0, -1], "type": )") + type + " }", diag);
    ASSERT_TRUE(s) << type << "\n" << diag.format();
    EXPECT_EQ(diag.all().size(), 0u) << diag.format();
    EXPECT_EQ(s->camera.type, expected) << type;
  }
}

TEST(CameraKeys, OrthographicViewExtents) {
  Diagnostics diag;
  auto s = load_camera(R"({ "type": "orthographic", "position": [0, 0, 0], "look_at": [0, 0, -1],
                            "view_width": 8 })", diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(s->camera.view_width.value, 8.0f);
  EXPECT_EQ(s->camera.view_height.value, 2.0f);  // the default, unused when the width is given

  Diagnostics both;
  EXPECT_FALSE(load_camera(R"({ "type": "orthographic", "position": [0, 0, 0], "look_at": [0, 0, -1],
                                "view_width": 8, "view_height": 2 })", both));
  EXPECT_NE(both.format().find("cam.json:3:47: error: give view_height or view_width, not both"), std::string::npos)
      << both.format();

  Diagnostics zero;
  EXPECT_FALSE(load_camera(R"({ "type": "orthographic", "position": [0, 0, 0], "look_at": [0, 0, -1],
                                "view_height": 0 })", zero));
  EXPECT_NE(zero.format().find("cam.json:3:48: error: view_height must be > 0, got 0"), std::string::npos)
      << zero.format();
}

TEST(CameraKeys, AKeyTheTypeDoesNotReadIsAnError) {
  Diagnostics fov;
  EXPECT_FALSE(load_camera(R"({ "type": "spherical", "position": [0, 0, 0], "look_at": [0, 0, -1], "fov": 90 })",
                           fov));
  EXPECT_NE(fov.format().find("'fov' does not apply to a spherical camera"), std::string::npos) << fov.format();

  Diagnostics view;
  EXPECT_FALSE(load_camera(R"({ "position": [0, 0, 0], "look_at": [0, 0, -1], "view_height": 2 })", view));
  EXPECT_NE(view.format().find("'view_height' does not apply to a pinhole camera (it reads: fov)"),
            std::string::npos)
      << view.format();

  Diagnostics lens;
  EXPECT_FALSE(load_camera(R"({ "type": "orthographic", "position": [0, 0, 0], "look_at": [0, 0, -1],
                                "lens_radius": 0.1 })", lens));
  EXPECT_NE(lens.format().find("'lens_radius' does not apply to an orthographic camera (it reads: view_height, "
                               "view_width)"),
            std::string::npos)
      << lens.format();
}

}  // namespace
}  // namespace pt
