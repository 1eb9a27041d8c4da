// render.background_image: an image behind the scene in screen space, seen by
// camera rays that leave the scene only (docs/scene-format.md, "render").
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "path_test_util.h"
#include "scene/loader.h"

namespace pt {
namespace {

constexpr int kW = 64, kH = 32;  // the film; the image is 16 x 8 texels in 4 x 2 blocks of 4 x 4

RGB block_colour(int bx, int by) { return RGB(0.1f + 0.2f * bx, 0.15f + 0.5f * by, 0.9f - 0.1f * (bx + by)); }

std::string write_blocks() {
  const auto path = std::filesystem::temp_directory_path() / "pt_test_background_blocks.exr";
  Image img(16, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) img.at(x, y) = block_colour(x / 4, y / 4);
  std::string error;
  EXPECT_TRUE(write_image(path.string(), img, DisplaySettings{}, error)) << error;
  return path.string();
}

SceneDescription scene_with_image() {
  SceneDescription d = test::empty_scene(kW, kH, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40);
  d.render.background = RGB(0, 1, 0);  // what everything but camera rays sees
  d.render.background_image = TextureDesc{SourceLocation{}, "blocks.exr", write_blocks()};
  return d;
}

// A pixel whose samples' bilinear footprints stay inside one block (film
// pixels 2..13 of each 16) shows that block's texel exactly.
bool inside_a_block(int x, int y) { return x % 16 >= 2 && x % 16 <= 13 && y % 16 >= 2 && y % 16 <= 13; }

TEST(BackgroundImage, APixelThatSeesNothingShowsTheTexel) {
  const SceneDescription d = scene_with_image();
  for (const char* integrator : {"whitted", "path"}) {
    const Image img = test::render_with(d, integrator, test::path_settings(4));
    ASSERT_EQ(img.width, kW);
    int checked = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (!inside_a_block(x, y)) continue;
        const RGB want = block_colour(x / 16, y / 16), got = img.at(x, y);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 1e-5f) << integrator << " " << x << "," << y;
        ++checked;
      }
    EXPECT_EQ(checked, 8 * 12 * 12);
    // Elsewhere a blend of the neighbouring blocks: never the background colour's green alone.
    EXPECT_LT(img.at(16, 16).g, 0.9f);
  }
}

TEST(BackgroundImage, ACropShowsItsPartOfTheSameImage) {
  const SceneDescription d = scene_with_image();
  WorkerPool pool(2);
  const auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  std::string error;
  const auto integrator = make_integrator("path", test::path_settings(2), error);
  Film full(kW, kH), part(kW, kH, PixelRect{21, 9, 50, 27}, {});
  integrator->render(*scene, full, pool);
  integrator->render(*scene, part, pool);
  const Image image = part.image();
  for (int y = 9; y < 27; ++y)
    for (int x = 21; x < 50; ++x) ASSERT_EQ(image.at(x - 21, y - 9), full.pixel(x, y)) << x << "," << y;
}

TEST(BackgroundImage, MirrorsDoNotReflectItAndItLightsNothing) {
  SceneDescription d = scene_with_image();
  test::add_sphere(d, {0, 0, 0}, 1.2f, test::add_material(d, [] {
                     MaterialDesc m;
                     m.type = MaterialType::Mirror;
                     m.specular = RGB(1.0f);
                     return m;
                   }()));
  for (const char* integrator : {"whitted", "path"}) {
    const Image img = test::render_with(d, integrator, test::path_settings(4));
    const RGB centre = img.at(kW / 2, kH / 2);  // the mirror reflects the camera's surroundings: the background colour
    EXPECT_NEAR(centre.r, 0.0f, 1e-6f) << integrator;
    EXPECT_NEAR(centre.g, 1.0f, 1e-5f) << integrator;
    EXPECT_NEAR(centre.b, 0.0f, 1e-6f) << integrator;
  }
  // A white diffuse sphere with a black background and no lights: the image lights nothing.
  SceneDescription dark = scene_with_image();
  dark.render.background = RGB(0.0f);
  test::add_sphere(dark, {0, 0, 0}, 1.2f, test::add_material(dark, test::diffuse_material(RGB(1.0f))));
  const Image img = test::render_with(dark, "path", test::path_settings(16, 8));
  EXPECT_EQ(img.at(kW / 2, kH / 2), RGB(0.0f));
  EXPECT_GT(img.at(3, 3).r, 0.05f);  // while the backdrop shows
}

std::optional<SceneDescription> load_with_image(const std::string& dir, const std::string& image, Diagnostics& diag) {
  const std::string text = R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0] },
  "render": { "background_image": ")" + image + R"(" } })";
  return load_scene_from_string(dir + "/bg.json", text, LoadOptions{}, diag);
}

TEST(BackgroundImage, AMissingFileFailsAtItsKeyBeforeRendering) {
  Diagnostics diag;
  EXPECT_FALSE(load_with_image(std::filesystem::temp_directory_path().string(), "no-such-backdrop.png", diag));
  EXPECT_NE(diag.format().find("bg.json:3:35: error: background image 'no-such-backdrop.png' not found; looked in"),
            std::string::npos)
      << diag.format();
}

TEST(BackgroundImage, AnUnreadableFileFailsWhenTheSceneIsBuilt) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  std::ofstream(dir + "/pt_test_not_an_image.png") << "not a PNG";
  Diagnostics diag;
  const auto d = load_with_image(dir, "pt_test_not_an_image.png", diag);
  ASSERT_TRUE(d) << diag.format();
  WorkerPool pool(1);
  EXPECT_FALSE(build_render_scene(*d, BuildOptions{}, pool, diag));
  EXPECT_NE(diag.format().find("bg.json:3:35: error: cannot read background image 'pt_test_not_an_image.png'"),
            std::string::npos)
      << diag.format();
}

}  // namespace
}  // namespace pt
