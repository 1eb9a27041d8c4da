// Renders through the orthographic and spherical cameras: a spherical render
// of a scene made only of an environment map is that map, and an orthographic
// view of a sphere is a disc of the sphere's own radius at any distance.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "path_test_util.h"

namespace pt {
namespace {

// A latitude-longitude map with a distinct value in every texel.
std::string write_map(int w, int h) {
  const auto path = std::filesystem::temp_directory_path() / "pt_test_camera_env.exr";
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = RGB(0.1f + x / float(w), 0.2f + y / float(h), ((x * 7 + y * 3) % 5) / 5.0f + 0.05f);
  std::string error;
  EXPECT_TRUE(write_image(path.string(), img, DisplaySettings{}, error)) << error;
  return path.string();
}

TEST(SphericalCameraRender, AnEnvironmentRendersAsItsOwnMap) {
  // 2 x 2 pixels per texel: every camera sample finds the texel under its
  // pixel, but for directions that round across a texel edge (the pixel edges
  // are texel edges), so nearly every pixel is the texel exactly and the rest
  // are close. Both integrators, which sample pixels differently.
  const int mw = 32, mh = 16;
  const std::string file = write_map(mw, mh);
  Image map;
  std::string error;
  ASSERT_TRUE(read_image(file, map, error)) << error;
  SceneDescription d = test::empty_scene(2 * mw, 2 * mh, {0.5f, -2, 3}, {0.5f, -2, 2}, {0, 1, 0});
  d.camera.type = CameraType::Spherical;
  d.render.background.where = SourceLocation{};
  EnvironmentDesc env;
  env.resolved = file;
  d.environment = env;
  for (const char* integrator : {"path", "whitted"}) {
    const Image img = test::render_with(d, integrator, test::path_settings(4));
    ASSERT_EQ(img.width, 2 * mw);
    std::size_t exact = 0;
    double abs_diff = 0, sum_img = 0, sum_map = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const RGB a = img.at(x, y), b = map.at(x / 2, y / 2);
        exact += std::abs(a.r - b.r) < 1e-5f && std::abs(a.g - b.g) < 1e-5f && std::abs(a.b - b.b) < 1e-5f;
        for (int c = 0; c < 3; ++c) {
          abs_diff += std::abs(a[c] - b[c]);
          sum_img += a[c];
          sum_map += b[c];
        }
      }
    const double n = static_cast<double>(img.width) * img.height;
    EXPECT_GE(exact, static_cast<std::size_t>(0.9 * n)) << integrator;
    EXPECT_LT(abs_diff / (3 * n), 5e-3) << integrator;                       // mean |difference| per channel
    EXPECT_NEAR(sum_img / sum_map, 1.0, 2e-3) << integrator;                  // the same total
  }
}

TEST(OrthographicCameraRender, ASphereIsADiscOfItsOwnRadiusAtAnyDistance) {
  // A black sphere of radius 1 against a white background, seen by an
  // orthographic camera with a 4 x 4 view: it covers pi / 16 of the frame
  // whether the camera is 3 or 300 units away.
  for (float distance : {3.0f, 300.0f}) {
    SceneDescription d = test::empty_scene(128, 128, {0, 0, distance}, {0, 0, 0}, {0, 1, 0});
    d.camera.type = CameraType::Orthographic;
    d.camera.view_height = 4.0f;
    d.render.background = RGB(1.0f);
    test::add_sphere(d, {0, 0, 0}, 1.0f, test::add_material(d, test::diffuse_material(RGB(0.0f))));
    const Image img = test::render_with(d, "whitted", test::path_settings(4));
    const test::Stats s = test::image_stats(img);
    EXPECT_NEAR(1.0 - s.mean, kPi / 16.0, 2e-3) << distance;
  }
}

}  // namespace
}  // namespace pt
