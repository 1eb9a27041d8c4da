// Coverage (docs/output.md): the beauty's alpha against the exact area of a
// disc in each pixel, the transparent film (premultiplied beauty, the
// background still lighting the scene), Cryptomatte ranks from every sample,
// Cryptomatte's names, the background's depth, and the layers a filter with
// negative lobes must keep in range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "test_scenes.h"

namespace pt {
namespace {

// Orthographic camera at (0, 0, 5) looking down -z: the view is [-1, 1]^2 in
// x and y over kN x kN pixels, pixel (i, j) covers x in [-1 + i s, -1 + (i+1) s]
// and y in [1 - (j+1) s, 1 - j s] with s = 2 / kN.
constexpr int kN = 16;
constexpr double kPixel = 2.0 / kN;

SceneDescription ortho_scene() {
  SceneDescription d = test::empty_scene(kN, kN, Vec3f(0, 0, 5), Vec3f(0, 0, 0), Vec3f(0, 1, 0));
  d.camera.type = CameraType::Orthographic;
  d.camera.view_height = 2.0f;
  d.render.integrator = std::string("path");
  return d;
}

// The exact fraction of pixel (i, j) inside the disc of radius r about (cx, cy)
// (midpoint rule over x of the chord's overlap with the pixel's rows; the
// integrand is continuous, so 4000 steps leave an error far below 1e-4).
double disc_coverage(int i, int j, double cx, double cy, double r) {
  const double x0 = -1.0 + i * kPixel, y0 = 1.0 - (j + 1) * kPixel, y1 = y0 + kPixel;
  constexpr int kSteps = 4000;
  double area = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    const double x = x0 + (k + 0.5) * kPixel / kSteps, dx = x - cx;
    if (std::fabs(dx) >= r) continue;
    const double h = std::sqrt(r * r - dx * dx);
    area += std::max(0.0, std::min(y1, cy + h) - std::max(y0, cy - h));
  }
  return area / kSteps / kPixel;
}

float alpha_at(const Film& film, int x, int y) {
  const LayeredImage image = film.layers();
  return image.layers[0].values[(static_cast<std::size_t>(y) * image.width + x) * 4 + 3];
}

Film render(const RenderScene& scene, WorkerPool& pool, IntegratorSettings settings,
            const std::vector<AovRequest>& aovs = {}) {
  Film film(kN, kN, PixelRect{0, 0, kN, kN}, aovs);
  std::string error;
  make_integrator("path", settings, error)->render(scene, film, pool);
  return film;
}

// An emissive disc (a sphere seen head on, emission 1, no lights) in front of
// a background of radiance 3.
std::unique_ptr<RenderScene> glowing_sphere(WorkerPool& pool, double r) {
  SceneDescription d = ortho_scene();
  d.render.background = RGB(3.0f);
  test::add_sphere(d, Vec3f(0.1f, -0.05f, 0), static_cast<float>(r), test::add_material(d, test::emitter_material(RGB(1.0f))));
  return test::build(d, pool);
}

TEST(Coverage, AlphaIsTheCoveredFractionOfEachPixel) {
  WorkerPool pool(2);
  constexpr double kR = 0.7;
  const auto scene = glowing_sphere(pool, kR);
  ASSERT_TRUE(scene);
  IntegratorSettings settings;
  settings.spp = 256;  // Sobol': the estimate of an edge's area converges about as 1/spp
  settings.max_depth = 0;
  const Film film = render(*scene, pool, settings);
  double worst = 0.0, total = 0.0;
  int edges = 0;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const double exact = disc_coverage(i, j, 0.1, -0.05, kR);
      const float a = alpha_at(film, i, j);
      if (exact == 0.0 || exact == 1.0) {
        EXPECT_EQ(a, static_cast<float>(exact)) << i << "," << j;
        continue;
      }
      ++edges;
      worst = std::max(worst, std::fabs(a - exact));
      total += std::fabs(a - exact);
      // The beauty is the disc's 1 over the covered part and the background's 3 elsewhere.
      EXPECT_NEAR(film.pixel(i, j).r, a * 1.0f + (1.0f - a) * 3.0f, 1e-5f) << i << "," << j;
    }
  EXPECT_GT(edges, 20);
  EXPECT_LT(worst, 0.02) << "largest |alpha - exact coverage| over " << edges << " edge pixels";
  EXPECT_LT(total / edges, 0.005);
}

TEST(Coverage, TransparentFilmPremultipliesAndStillLights) {
  WorkerPool pool(2);
  const auto glowing = glowing_sphere(pool, 0.7);
  ASSERT_TRUE(glowing);
  IntegratorSettings settings;
  settings.spp = 64;
  settings.max_depth = 0;
  settings.film_transparent = true;
  const Film film = render(*glowing, pool, settings, {{AovType::Emission, ChannelType::Float}});
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const float a = alpha_at(film, i, j);
      // Premultiplied: the disc's radiance 1 times its coverage; the background adds nothing.
      EXPECT_NEAR(film.pixel(i, j).r, a, 1e-6f) << i << "," << j;
      EXPECT_NEAR(film.aov_value(AovType::Emission, i, j)[0], a, 1e-6f) << i << "," << j;
    }
  EXPECT_EQ(alpha_at(film, 0, 0), 0.0f);
  EXPECT_EQ(film.pixel(0, 0), RGB());

  // A diffuse sphere lit only by the background (the path integrator's
  // uniform environment): the sphere is lit exactly as on an opaque film.
  SceneDescription d = ortho_scene();
  d.render.background = RGB(0.5f, 0.7f, 1.0f);
  test::add_sphere(d, Vec3f(0, 0, 0), 0.7f, test::add_material(d, test::diffuse_material(RGB(0.8f))));
  const auto lit = test::build(d, pool);
  ASSERT_TRUE(lit);
  settings.max_depth = 4;
  settings.spp = 4;
  const Film transparent = render(*lit, pool, settings);
  settings.film_transparent = false;
  const Film opaque = render(*lit, pool, settings);
  EXPECT_GT(transparent.pixel(kN / 2, kN / 2).b, 0.1f);
  EXPECT_EQ(transparent.pixel(kN / 2, kN / 2), opaque.pixel(kN / 2, kN / 2));  // same samples, same light
  EXPECT_EQ(alpha_at(transparent, kN / 2, kN / 2), 1.0f);
  EXPECT_EQ(transparent.pixel(0, 0), RGB());
  EXPECT_EQ(opaque.pixel(0, 0), RGB(0.5f, 0.7f, 1.0f));
  EXPECT_EQ(alpha_at(opaque, 0, 0), 0.0f);  // alpha is coverage whether or not the film is transparent
}

// Decoded ranks of a Cryptomatte AOV at (x, y): (id, coverage) pairs.
std::vector<std::pair<float, float>> ranks(const Film& film, AovType type, int x, int y) {
  const std::vector<float> v = film.aov_value(type, x, y);
  std::vector<std::pair<float, float>> out;
  for (std::size_t k = 0; k + 1 < v.size(); k += 2) out.emplace_back(v[k], v[k + 1]);
  return out;
}

TEST(Coverage, CryptomatteRanksEveryIdBySummedWeight) {
  // Two overlapping discs: "left" in front, "right" behind it, each with its own material.
  WorkerPool pool(2);
  SceneDescription d = ortho_scene();
  MaterialDesc red = test::diffuse_material(RGB(0.8f, 0.1f, 0.1f)), blue = test::diffuse_material(RGB(0.1f, 0.1f, 0.8f));
  red.name = "red";
  blue.name = "blue";
  test::add_sphere(d, Vec3f(-0.3f, 0, 1), 0.5f, test::add_material(d, red));
  test::add_sphere(d, Vec3f(0.35f, 0, 0), 0.5f, test::add_material(d, blue));
  d.shapes[0].name = "left";
  d.shapes[1].name = "right";
  test::add_point_light(d, Vec3f(0, 0, 4), RGB(5.0f), RGB(5.0f));
  const auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->names.objects, (std::vector<std::string>{"left", "right"}));
  EXPECT_EQ(scene->names.materials, (std::vector<std::string>{"red", "blue"}));
  IntegratorSettings settings;
  settings.spp = 64;
  const Film film = render(*scene, pool, settings,
                           {{AovType::CryptoObject, ChannelType::Float, 6}, {AovType::CryptoMaterial, ChannelType::Float, 6}});
  const float left = cryptomatte_id("left"), right = cryptomatte_id("right"), red_id = cryptomatte_id("red");
  // Fully inside "left" (centre x = -0.3 is pixel 5): that id with coverage 1, nothing else.
  const auto inside = ranks(film, AovType::CryptoObject, 5, kN / 2);
  ASSERT_EQ(inside.size(), 6u);
  EXPECT_EQ(inside[0], std::make_pair(left, 1.0f));
  for (std::size_t k = 1; k < inside.size(); ++k) EXPECT_EQ(inside[k], std::make_pair(0.0f, 0.0f));
  EXPECT_EQ(ranks(film, AovType::CryptoMaterial, 5, kN / 2)[0], std::make_pair(red_id, 1.0f));
  int shared = 0;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const auto r = ranks(film, AovType::CryptoObject, i, j);
      float sum = 0.0f;
      for (std::size_t k = 0; k < r.size(); ++k) {
        sum += r[k].second;
        if (k > 0) {
          EXPECT_LE(r[k].second, r[k - 1].second) << i << "," << j;  // ranked
        }
      }
      // Every sample that hit something is in a rank: the coverages add up to alpha.
      EXPECT_NEAR(sum, alpha_at(film, i, j), 1e-6f) << i << "," << j;
      if (r[1].second > 0.0f) {
        ++shared;
        EXPECT_TRUE((r[0].first == left && r[1].first == right) || (r[0].first == right && r[1].first == left));
      }
      // Left of the overlap, "left"'s coverage is its disc's area in the pixel.
      if (i < 5) {
        const double exact = disc_coverage(i, j, -0.3, 0.0, 0.5);
        const float got = r[0].first == left ? r[0].second : 0.0f;
        EXPECT_NEAR(got, exact, 0.05) << i << "," << j;
      }
    }
  EXPECT_GT(shared, 3);  // pixels where both are seen
}

// One pixel's Cryptomatte from `ids`, one sample each of weight 1, added in
// passes of `pass` samples (a scratch per pass, as the render loop does).
Film ranked_pixel(const std::vector<float>& ids, int ranks, std::size_t pass) {
  Film film(1, 1, PixelRect{0, 0, 1, 1}, {{AovType::CryptoObject, ChannelType::Float, ranks}});
  AovScratch scratch = film.make_scratch();
  for (std::size_t first = 0; first < ids.size(); first += pass) {
    scratch.clear();
    PixelSum sum;
    for (std::size_t i = first; i < std::min(ids.size(), first + pass); ++i) {
      AovSample s;
      s.crypto_object = ids[i];
      film.accumulate(scratch, s, RGB(), 1.0f, false);
      sum.add(RGB(), 1.0f, true);
    }
    film.add(0, 0, sum);
    film.add_aovs(0, 0, scratch);
  }
  return film;
}

std::string film_state(const Film& film) {
  std::ostringstream out;
  film.write_state(out);
  return out.str();
}

TEST(Coverage, RanksKeepTheSmallestIdsWhateverThePassesAndSortByCoverage) {
  // 3.5 comes first but is the largest of three ids for two ranks: the
  // smallest two are kept, each with every sample's weight.
  const std::vector<float> ids = {3.5f, 2.5f, 2.5f, 1.5f, 2.5f, 3.5f};
  const Film one_pass = ranked_pixel(ids, 2, ids.size());
  EXPECT_EQ(one_pass.aov_value(AovType::CryptoObject, 0, 0), (std::vector<float>{2.5f, 0.5f, 1.5f, 1.0f / 6.0f}));
  // The same bits in passes of 1, 2, 4 samples (first-come ranks would keep
  // 3.5 and lose 1.5 in one pass, but keep 1.5 in passes of one sample).
  for (std::size_t pass : {1u, 2u, 4u}) EXPECT_EQ(film_state(ranked_pixel(ids, 2, pass)), film_state(one_pass)) << pass;
  // Enough ranks: every id, in any order of the samples.
  std::vector<float> reversed(ids.rbegin(), ids.rend());
  EXPECT_EQ(ranked_pixel(reversed, 4, 3).aov_value(AovType::CryptoObject, 0, 0),
            (std::vector<float>{2.5f, 0.5f, 3.5f, 1.0f / 3.0f, 1.5f, 1.0f / 6.0f, 0.0f, 0.0f}));
}

TEST(Coverage, CryptomatteNamesOfShapesInstancesAndMaterials) {
  WorkerPool pool(1);
  SceneDescription d = ortho_scene();
  const int m = test::add_material(d, test::diffuse_material(RGB(0.5f)));
  d.materials[0].name = "grey";
  test::add_sphere(d, Vec3f(0, 0, 0), 0.2f, m);  // unnamed: its place in the file
  ObjectDesc tree;
  tree.name = "tree";
  ShapeDesc leaf;
  leaf.geometry = Sphere{};
  tree.shapes.push_back(leaf);
  d.objects.push_back(tree);
  d.instances.resize(3);
  d.instances[1].name = "big tree";
  d.instances[2].material = test::add_material(d, test::diffuse_material(RGB(0.9f)));  // unnamed material
  d.materials.back().name.clear();
  const auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  const SceneNames& n = scene->names;
  EXPECT_EQ(n.objects, (std::vector<std::string>{"shapes[0]", "tree", "big tree"}));
  EXPECT_EQ(n.object_id(0, kNoInstance), cryptomatte_id("shapes[0]"));
  EXPECT_EQ(n.object_id(1, 0), cryptomatte_id("tree"));  // unnamed instances share their object's name
  EXPECT_EQ(n.object_id(1, 1), cryptomatte_id("big tree"));
  EXPECT_EQ(n.object_id(1, 2), cryptomatte_id("tree"));
  EXPECT_EQ(n.materials, (std::vector<std::string>{"grey", "materials[1]"}));
}

TEST(Coverage, BackgroundDepthIsBlendersAndMitchellKeepsMattesInRange) {
  WorkerPool pool(2);
  SceneDescription d = ortho_scene();
  test::add_sphere(d, Vec3f(0, 0, 0), 0.7f, test::add_material(d, test::diffuse_material(RGB(0.9f))));
  test::add_point_light(d, Vec3f(0, 0, 4), RGB(30.0f), RGB(30.0f));
  const auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  IntegratorSettings settings;
  settings.spp = 16;
  settings.filter = PixelFilterType::Mitchell;
  const Film film = render(*scene, pool, settings,
                           {{AovType::Albedo, ChannelType::Float}, {AovType::Depth, ChannelType::Float},
                            {AovType::CryptoObject, ChannelType::Float, 6}});
  EXPECT_EQ(film.aov_value(AovType::Depth, 0, 0)[0], 1e10f);  // what Cycles writes for the background
  EXPECT_NEAR(film.aov_value(AovType::Depth, kN / 2, kN / 2)[0], 5.0f - 0.7f, 0.05f);
  const LayeredImage image = film.layers();
  float lowest_beauty = 0.0f;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const float a = alpha_at(film, i, j);
      EXPECT_GE(a, 0.0f);
      EXPECT_LE(a, 1.0f);
      for (float c : film.aov_value(AovType::Albedo, i, j)) EXPECT_GE(c, 0.0f) << i << "," << j;
      for (const auto& [id, coverage] : ranks(film, AovType::CryptoObject, i, j)) {
        EXPECT_GE(coverage, 0.0f);
        EXPECT_LE(coverage, 1.0f);
      }
      lowest_beauty = std::min(lowest_beauty, film.pixel(i, j).r);
    }
  // The beauty keeps the filter's negative lobes (docs/output.md): its value is not clamped.
  EXPECT_LT(lowest_beauty, 0.0f);
}

}  // namespace
}  // namespace pt
