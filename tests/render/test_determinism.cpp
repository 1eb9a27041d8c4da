// The image is bit-identical for any thread count and tile size (hence tile
// order), and depends on the seed only through the sample positions.
#include <cstring>
#include <utility>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/integrators/render_loop.h"
#include "test_scenes.h"

namespace pt {
namespace {

using test::add_material;
using test::add_point_light;
using test::add_sphere;
using test::add_z_square;

SceneDescription scene_with_everything() {
  SceneDescription d = test::empty_scene(53, 41, {0.5f, -4, 2.5f}, {0, 0, 0.4f}, {0, 0, 1}, 45);
  d.render.background = RGB(0.05f, 0.1f, 0.2f);
  // Textures too: a filtered checker (footprints from ray differentials and,
  // after the mirror bounce, from the camera's spread), object-space noise,
  // and a sphere cut out by a checker alpha.
  TextureDesc checker, noise;
  checker.type = TextureType::Checker;
  checker.scale = Vec3f(6.0f);
  noise.type = TextureType::Noise;
  noise.object_mapping = true;
  noise.scale = Vec3f(3.0f);
  d.textures = {checker, noise};
  MaterialDesc floor = test::diffuse_material(RGB(0.8f, 0.7f, 0.6f), 0.9f);
  floor.texture = 0;
  floor.ks = 0.3f;
  floor.exponent = 8;
  floor.reflectivity = 0.3f;
  add_z_square(d, 0.0f, 4.0f, add_material(d, floor));
  MaterialDesc glass;
  glass.refractive = true;
  glass.ior = 1.5f;
  add_sphere(d, {-0.6f, 0, 0.5f}, 0.5f, add_material(d, glass));
  MaterialDesc cut = test::diffuse_material(RGB(0.2f, 0.5f, 0.9f));
  cut.texture = 1;
  cut.alpha_texture = 0;
  add_sphere(d, {0.7f, 0.5f, 0.6f}, 0.6f, add_material(d, cut));
  add_point_light(d, {1, -2, 3}, RGB(20), RGB(20));
  add_point_light(d, {-2, 1, 2}, RGB(5, 2, 1), RGB(5, 2, 1));
  return d;
}

Image render(const SceneDescription& d, int threads, int tile, int spp, uint64_t seed) {
  WorkerPool pool(threads);
  auto scene = test::build(d, pool);
  EXPECT_TRUE(scene);
  if (!scene) return {};
  IntegratorSettings settings;
  settings.max_depth = 6;
  settings.spp = spp;
  settings.seed = seed;
  settings.tile_size = tile;
  std::string error;
  auto integrator = make_integrator("whitted", settings, error);
  Film film(scene->width, scene->height);
  integrator->render(*scene, film, pool);
  return film.image();
}

bool identical(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(RGB)) == 0;
}

TEST(Determinism, BitIdenticalForAnyThreadCountAndTileSize) {
  const SceneDescription d = scene_with_everything();
  for (int spp : {1, 4, 5}) {
    const Image reference = render(d, 1, 16, spp, 7);
    for (auto [threads, tile] : {std::pair{2, 16}, std::pair{4, 16}, std::pair{4, 7}, std::pair{3, 1},
                                 std::pair{2, 64}}) {
      EXPECT_TRUE(identical(reference, render(d, threads, tile, spp, 7)))
          << "spp " << spp << ", threads " << threads << ", tile " << tile;
    }
  }
}

TEST(Determinism, SeedChangesOnlyJitteredImages) {
  const SceneDescription d = scene_with_everything();
  EXPECT_TRUE(identical(render(d, 2, 16, 1, 1), render(d, 2, 16, 1, 2)));  // pixel centres
  EXPECT_FALSE(identical(render(d, 2, 16, 4, 1), render(d, 2, 16, 4, 2)));
}

// The tiles are the unit of work a thread takes: a small image on many threads
// gets smaller tiles (at least kTilesPerThread a thread, down to kMinTileSize),
// so that the last tile, run while the other threads wait, is a small share.
TEST(Determinism, SmallImagesOnManyThreadsAreCutIntoSmallerTiles) {
  EXPECT_EQ(scheduled_tile_size(16, 1920, 1080, 16), 16);  // 8160 tiles
  EXPECT_EQ(scheduled_tile_size(16, 256, 256, 2), 16);     // 256 tiles, 128 a thread
  EXPECT_EQ(scheduled_tile_size(16, 256, 256, 16), 8);     // 1024 tiles, 64 a thread
  EXPECT_EQ(scheduled_tile_size(16, 256, 256, 64), 4);     // at most kMinTileSize
  EXPECT_EQ(scheduled_tile_size(16, 64, 64, 16), kMinTileSize);
  EXPECT_EQ(scheduled_tile_size(5, 8, 8, 64), 5);          // never below kMinTileSize by halving
  EXPECT_EQ(scheduled_tile_size(1, 8, 8, 64), 1);          // a requested size below it is kept
  EXPECT_EQ(scheduled_tile_size(0, 8, 8, 1), 1);
  for (int threads : {1, 2, 3, 16, 64}) {
    const int tile = scheduled_tile_size(16, 300, 200, threads);
    const int tiles = ((300 + tile - 1) / tile) * ((200 + tile - 1) / tile);
    EXPECT_TRUE(tiles >= kTilesPerThread * threads || tile == kMinTileSize) << threads << " threads: " << tile;
    EXPECT_TRUE(tile == 16 || tiles / 4 < kTilesPerThread * threads) << "halved once too often: " << tile;
  }
}

}  // namespace
}  // namespace pt
