// Scenes for the guides' tests (render/guiding/light_guide.h, path_guide.h): a
// courtyard that sees its sky through an opening, under an environment map
// and a sun, and a white sphere under a uniform map (a furnace); and a guide
// learned over a scene.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "core/rng.h"
#include "io/image_io.h"
#include "path_test_util.h"
#include "render/render_scene.h"
#include "test_scenes.h"

namespace pt::test {

// A latitude-longitude map written once per process: `uniform` 1 everywhere, else a bright
// band above the horizon and distinct texels (so that the guide has something to learn).
inline std::string guide_test_environment(bool uniform) {
  const auto path = std::filesystem::temp_directory_path() /
                    (std::string("pt_test_light_guide_") + (uniform ? "uniform" : "sky") + ".exr");
  Image img(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      img.at(x, y) = uniform ? RGB(1.0f)
                             : RGB(0.2f + (y < 12 ? 1.5f : 0.1f) + 0.02f * static_cast<float>(x % 7),
                                   0.3f + 0.05f * static_cast<float>((x * 3 + y) % 5), y < 16 ? 1.2f : 0.2f);
  std::string error;
  EXPECT_TRUE(write_image(path.string(), img, DisplaySettings{}, error)) << error;
  return path.string();
}

// A larger map of the same sky with a small, very bright disc (a sun in the
// map): the bins' coarse grid would smear it (EnvironmentBins::coarse_chi2 >
// LightGuide::kMaxCoarseChi2), so the guide keeps the map's own sampling.
inline std::string guide_test_sun_environment() {
  const auto path = std::filesystem::temp_directory_path() / "pt_test_light_guide_sun_in_map.exr";
  Image img(512, 256);  // bins of 16 x 16 texels, cells of 2 x 2
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x)
      img.at(x, y) = RGB(0.2f + (y < 96 ? 1.5f : 0.1f) + 0.02f * static_cast<float>(x % 7), 0.4f, y < 128 ? 1.2f : 0.2f);
  for (int y = 61; y < 64; ++y)  // 3 x 3 texels across cell borders
    for (int x = 281; x < 284; ++x) img.at(x, y) = RGB(5000.0f);
  std::string error;
  EXPECT_TRUE(write_image(path.string(), img, DisplaySettings{}, error)) << error;
  return path.string();
}

// A floor, four walls 3 high around it and a roof with a square opening in
// the middle, a camera inside: most of the sky is hidden from most points.
// `sun_in_map`: under guide_test_sun_environment() instead.
inline SceneDescription courtyard_scene(bool sun, bool sun_in_map = false) {
  SceneDescription d = empty_scene(32, 32, {0.2f, 0.6f, 1.6f}, {-0.3f, 0.9f, -1.0f}, {0, 1, 0}, 70);
  EnvironmentDesc env;
  env.resolved = sun_in_map ? guide_test_sun_environment() : guide_test_environment(false);
  d.environment = env;
  if (sun) {
    DirectionalLightDesc s;
    s.direction = Vec3f(0.3f, -1.0f, 0.4f);
    s.irradiance = RGB(3.0f, 2.8f, 2.5f);
    d.lights.emplace_back(s);
  }
  const int white = add_material(d, diffuse_material(RGB(0.6f, 0.58f, 0.55f)));
  auto quad = [&](Vec3f a, Vec3f b, Vec3f c, Vec3f e) {
    Quad q;
    q.v[0] = a; q.v[1] = b; q.v[2] = c; q.v[3] = e;
    add_shape(d, q, white);
  };
  const float w = 2.0f, h = 3.0f, o = 0.6f;  // half width, height, half opening
  quad({-w, 0, -w}, {-w, 0, w}, {w, 0, w}, {w, 0, -w});    // floor, facing up
  quad({-w, 0, -w}, {w, 0, -w}, {w, h, -w}, {-w, h, -w});  // back wall
  quad({-w, 0, w}, {-w, h, w}, {w, h, w}, {w, 0, w});      // front wall
  quad({-w, 0, -w}, {-w, h, -w}, {-w, h, w}, {-w, 0, w});  // left wall
  quad({w, 0, -w}, {w, 0, w}, {w, h, w}, {w, h, -w});      // right wall
  // The roof, facing down, around the opening |x|, |z| < o.
  quad({-w, h, -w}, {w, h, -w}, {w, h, -o}, {-w, h, -o});
  quad({-w, h, o}, {w, h, o}, {w, h, w}, {-w, h, w});
  quad({-w, h, -o}, {-o, h, -o}, {-o, h, o}, {-w, h, o});
  quad({o, h, -o}, {w, h, -o}, {w, h, o}, {o, h, o});
  return d;
}

// A sphere of albedo `albedo` under a uniform map of radiance 1: every pixel
// that sees it is exactly `albedo` (it is convex: one bounce, then the sky).
inline SceneDescription furnace_scene(float albedo) {
  SceneDescription d = empty_scene(16, 16, {0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 30);
  EnvironmentDesc env;
  env.resolved = guide_test_environment(true);
  d.environment = env;
  add_sphere(d, {0, 0, 0}, 1.0f, add_material(d, diffuse_material(RGB(albedo))));
  return d;
}

// A guide (LightGuide or PathGuide) learned over `d` with its own pre-pass:
// `paths_per_pixel` paths, depth 6, `seed`.
template <class Guide>
struct Learned {
  std::unique_ptr<RenderScene> scene;
  std::unique_ptr<Guide> guide;
};

template <class Guide>
Learned<Guide> learn_guide(const SceneDescription& d, int threads, int paths_per_pixel, uint64_t seed) {
  WorkerPool pool(threads);
  Learned<Guide> l;
  l.scene = build(d, pool);
  EXPECT_TRUE(l.scene);
  if (l.scene) l.guide = std::make_unique<Guide>(Guide::learn(*l.scene, pool, paths_per_pixel, 6, seed));
  return l;
}

// Points inside the courtyard (floor, walls, mid-air).
inline Vec3f courtyard_point(Rng& rng) {
  return Vec3f(rng.next_float() * 3.8f - 1.9f, rng.next_float() * 2.9f + 0.05f, rng.next_float() * 3.8f - 1.9f);
}

}  // namespace pt::test
