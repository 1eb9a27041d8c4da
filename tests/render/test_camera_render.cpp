// Renders through the orthographic and spherical cameras: a spherical render
// of a scene made only of an environment map is that map, a spherical render
// of a scene is its environment map, a mirrored camera transform flips the
// image, and an orthographic view of a sphere is a disc of the sphere's own
// radius at any distance.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "path_test_util.h"
#include "scene/loader.h"

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

// The round trip the other way: a scene rendered by a spherical camera is an
// environment map that shows, to a pinhole camera at the same point, what that
// camera sees of the scene itself. The spherical camera is turned by 30 degrees
// about +y, so the map is read with rotation 30 (docs/scene-format.md). The
// scene's emitters (flat colours, nothing lit) make the images piecewise
// constant: only pixels on an outline may differ, by the map's resampling
// (measured: 97.6-99.8% of the pixels within 0.02, means within 3e-4).
TEST(SphericalCameraRender, ARenderServesAsTheEnvironmentMapOfItsScene) {
  const Vec3f eye(0.3f, 1.0f, 0.2f);
  const float turn = 30.0f;
  const Vec3f forward(-std::sin(turn * kPi / 180.0f), 0.0f, -std::cos(turn * kPi / 180.0f));
  SceneDescription scene = test::empty_scene(384, 192, eye, eye + forward, {0, 1, 0});
  scene.camera.type = CameraType::Spherical;
  scene.render.background = RGB(0.2f, 0.3f, 0.5f);
  auto lamp = [&](RGB c) { return test::add_material(scene, test::emitter_material(c)); };
  test::add_sphere(scene, {0, 1, -3}, 0.8f, lamp(RGB(1, 0.1f, 0.1f)));
  test::add_sphere(scene, {3, 1.5f, 0.5f}, 0.8f, lamp(RGB(0.1f, 1, 0.1f)));
  test::add_shape(scene, Cone{{-3, 0, 0.5f}, {-3, 2.5f, 0.5f}, 0.8f, 0.0f}, lamp(RGB(0.1f, 0.1f, 1)));
  Disc floor;
  floor.center = Vec3f(0, 0, 0);
  floor.normal = Vec3f(0, 1, 0);
  floor.radius = 2.0f;
  test::add_shape(scene, floor, lamp(RGB(1, 1, 0.1f)));
  for (MaterialDesc& m : scene.materials) {
    m.two_sided = true;
    m.light_samples = 1;  // whitted shades the black lamps by the others: one shadow ray each will do
  }
  const Image panorama = test::render_with(scene, "whitted", test::path_settings(4));
  ASSERT_EQ(panorama.width, 384);
  const auto file = std::filesystem::temp_directory_path() / "pt_test_spherical_round_trip.exr";
  std::string error;
  ASSERT_TRUE(write_image(file.string(), panorama, DisplaySettings{}, error)) << error;

  SceneDescription direct = scene;
  direct.camera.type = CameraType::Pinhole;
  direct.camera.fov_y_deg = 70.0f;
  direct.film.width = direct.film.height = 64;
  SceneDescription mapped = direct;
  mapped.shapes.clear();
  mapped.render.background.where = SourceLocation{};
  mapped.render.background = RGB(0.0f);
  EnvironmentDesc env;
  env.resolved = file.string();
  env.rotation_deg = turn;
  mapped.environment = env;
  for (const Vec3f view : {Vec3f(1, 0.3f, -1), Vec3f(-1, -0.2f, 0.4f), Vec3f(0.2f, -1, -0.5f)}) {
    direct.camera.look_at = mapped.camera.look_at = eye + view;
    const Image a = test::render_with(direct, "whitted", test::path_settings(1));
    const Image b = test::render_with(mapped, "whitted", test::path_settings(1));
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
      float worst = 0.0f;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a.pixels[i][c] - b.pixels[i][c]));
      same += worst < 0.02f;
    }
    EXPECT_GT(same, 0.95 * a.pixels.size()) << "view " << view.x << " " << view.y << " " << view.z;
    EXPECT_NEAR(test::image_stats(a).mean, test::image_stats(b).mean, 2e-3 * test::image_stats(a).mean);
  }
  std::filesystem::remove(file);
}

// A camera transform with a mirror flips the image, as a reflection in
// pbrt-v4's camera transform or Mitsuba 3's to_world does: a camera on the
// mirror plane sees the scene mirrored left-right, and the whole scene
// mirrored with its camera renders the same image as the original.
TEST(CameraTransformRender, AMirrorFlipsTheImageAndAMirroredSceneLooksTheSame) {
  auto render = [](const std::string& shape_xf, const std::string& camera_xf) {
    const std::string text = R"({ "format": "pathtracer-scene", "version": 1,
      "camera": { "position": [0, 1, 5], "look_at": [0, 0.8, 0], "fov": 50, "transform": )" + camera_xf + R"( },
      "film": { "width": 64, "height": 48 },
      "render": { "integrator": "whitted", "background": [0.1, 0.1, 0.2] },
      "materials": { "r": { "type": "lambert", "diffuse": [0, 0, 0], "emission": [1, 0.2, 0.1] },
                     "g": { "type": "lambert", "diffuse": [0, 0, 0], "emission": [0.1, 1, 0.2], "two_sided": true } },
      "shapes": [
        { "type": "sphere", "center": [-1.2, 1.3, 0], "radius": 0.6, "material": "r", "transform": )" + shape_xf + R"( },
        { "type": "cone", "p0": [0.8, 0, -0.5], "p1": [1.4, 1.6, 0], "radius": 0.5, "material": "g", "transform": )" +
                             shape_xf + R"( },
        { "type": "polygon", "vertices": [[-2, 0, -1], [0.5, 0, -1], [0, 0.8, -1]], "material": "g",
          "transform": )" + shape_xf + R"( } ] })";
    Diagnostics diag;
    const auto d = load_scene_from_string("mirror.json", text, LoadOptions{}, diag);
    EXPECT_TRUE(d) << diag.format();
    // One sample at each pixel's centre: the classic pixel grid jitters
    // several, which would not be mirror images of each other.
    return d ? test::render_with(*d, "whitted", test::path_settings(1)) : Image();
  };
  const std::string none = "[]", mirror = R"([ { "scale": [-1, 1, 1] } ])";
  const Image original = render(none, none);
  const Image flipped = render(none, mirror);
  const Image both = render(mirror, mirror);
  ASSERT_EQ(original.width, 64);
  ASSERT_EQ(flipped.width, 64);
  ASSERT_EQ(both.width, 64);
  std::size_t same_flipped = 0, same_both = 0;
  auto close = [](RGB a, RGB b) {
    return std::abs(a.r - b.r) < 1e-3f && std::abs(a.g - b.g) < 1e-3f && std::abs(a.b - b.b) < 1e-3f;
  };
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      same_flipped += close(original.at(x, y), flipped.at(63 - x, y));
      same_both += close(original.at(x, y), both.at(x, y));
    }
  // Pixels on an outline may round differently (the mirrored shapes are
  // instances, intersected in their own space); nearly all are equal.
  EXPECT_GE(same_flipped, 64u * 48u * 99 / 100);
  EXPECT_GE(same_both, 64u * 48u * 99 / 100);
  EXPECT_GT(test::rmse(original, flipped), 0.05) << "the scene is not symmetric: the flip must show";
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
