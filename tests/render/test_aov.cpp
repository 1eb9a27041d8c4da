// AOVs: parsing, geometric layers on known hits for every integrator, the path
// and classic integrators' lighting splits (their parts sum to the beauty), the variance and
// sample count, and that AOVs do not depend on threads or tiles.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "test_scenes.h"

namespace pt {
namespace {

TEST(AovList, ParsesNamesTypesAndDefaults) {
  std::vector<AovRequest> aovs;
  ChannelType beauty = ChannelType::Half;
  std::string error;
  ASSERT_TRUE(parse_aov_list("Z:half, albedo,N:float,IndexOB", aovs, beauty, error)) << error;
  EXPECT_EQ(beauty, ChannelType::Float);  // not named: float
  ASSERT_EQ(aovs.size(), 4u);  // catalogue order
  EXPECT_EQ(aovs[0].type, AovType::Albedo);
  EXPECT_EQ(aovs[0].channel_type, ChannelType::Half);  // default
  EXPECT_EQ(aovs[1].type, AovType::Normal);
  EXPECT_EQ(aovs[1].channel_type, ChannelType::Float);  // asked
  EXPECT_EQ(aovs[2].type, AovType::Depth);
  EXPECT_EQ(aovs[2].channel_type, ChannelType::Half);
  EXPECT_EQ(aovs[3].type, AovType::ObjectId);
  EXPECT_EQ(aovs[3].channel_type, ChannelType::Float);
}

TEST(AovList, RejectsUnknownNamesTypesAndDuplicates) {
  std::vector<AovRequest> aovs;
  ChannelType beauty = ChannelType::Float;
  std::string error;
  EXPECT_FALSE(parse_aov_list("albedo,normals", aovs, beauty, error));
  EXPECT_NE(error.find("unknown AOV 'normals'"), std::string::npos) << error;
  for (const std::string& name : aov_names()) EXPECT_NE(error.find(" " + name), std::string::npos) << name;
  EXPECT_FALSE(parse_aov_list("albedo:double", aovs, beauty, error));
  EXPECT_NE(error.find("double"), std::string::npos) << error;
  EXPECT_FALSE(parse_aov_list("N,N:half", aovs, beauty, error));
  EXPECT_NE(error.find("more than once"), std::string::npos) << error;
  EXPECT_FALSE(parse_aov_list("", aovs, beauty, error));
  EXPECT_FALSE(parse_aov_list("beauty:half,beauty", aovs, beauty, error));
  EXPECT_NE(error.find("'beauty' is requested more than once"), std::string::npos) << error;
  EXPECT_FALSE(parse_aov_list("beauty:double", aovs, beauty, error));
  EXPECT_NE(error.find("unknown pixel type 'double'"), std::string::npos) << error;
}

TEST(AovList, BeautyNamesOnlyTheBeautysType) {
  std::vector<AovRequest> aovs;
  ChannelType beauty = ChannelType::Float;
  std::string error;
  ASSERT_TRUE(parse_aov_list("beauty:half", aovs, beauty, error)) << error;
  EXPECT_TRUE(aovs.empty());  // not a layer of its own
  EXPECT_EQ(beauty, ChannelType::Half);
  ASSERT_TRUE(parse_aov_list("N, beauty:float,", aovs, beauty, error)) << error;
  EXPECT_EQ(beauty, ChannelType::Float);
  ASSERT_EQ(aovs.size(), 1u);
  EXPECT_EQ(aovs[0].type, AovType::Normal);
  ASSERT_TRUE(parse_aov_list("beauty", aovs, beauty, error)) << error;
  EXPECT_EQ(beauty, ChannelType::Float);  // the default
  // Film::layers writes the beauty's R, G, B, A with that type; the values stay the same floats.
  Film film(4, 2);
  film.add(1, 1, PixelSum{0.5, 0.25, 2.0, 1.0, 1.0, 1});
  const LayeredImage as_float = film.layers(), as_half = film.layers(ChannelType::Half);
  EXPECT_EQ(as_float.layers[0].type, ChannelType::Float);
  EXPECT_EQ(as_half.layers[0].type, ChannelType::Half);
  EXPECT_EQ(as_half.layers[0].values, as_float.layers[0].values);
}

std::vector<AovRequest> aovs(const std::string& list) {
  std::vector<AovRequest> out;
  ChannelType beauty = ChannelType::Float;
  std::string error;
  EXPECT_TRUE(parse_aov_list(list, out, beauty, error)) << error;
  return out;
}

// Camera at (0, 0, 5) looking down -z at a Lambert square in z = 0 (shape 0),
// a sphere above it (shape 1, another material) and a point light.
constexpr int kW = 32, kH = 24;
const RGB kPlaneColour(0.2f, 0.5f, 0.7f);

std::unique_ptr<RenderScene> plane_scene(WorkerPool& pool) {
  SceneDescription d = test::empty_scene(kW, kH, Vec3f(0, 0, 5), Vec3f(0, 0, 0), Vec3f(0, 1, 0), 50.0f);
  MaterialDesc plane = test::diffuse_material(kPlaneColour);
  plane.type = MaterialType::Lambert;
  test::add_z_square(d, 0.0f, 10.0f, test::add_material(d, plane));
  test::add_sphere(d, Vec3f(1.0f, 0.5f, 1.0f), 0.6f, test::add_material(d, test::diffuse_material(RGB(0.9f))));
  test::add_point_light(d, Vec3f(0, 2, 4), RGB(20.0f), RGB(20.0f));
  return test::build(d, pool);
}

TEST(Aov, GeometricLayersOfAKnownHitForEveryIntegrator) {
  WorkerPool pool(2);
  const auto scene = plane_scene(pool);
  ASSERT_TRUE(scene);
  const Camera& camera = scene->camera;
  // A pixel whose centre sees the plane, away from the sphere; and one on the sphere.
  const int px = 4, py = 18;
  Vec2f sphere_px;
  ASSERT_TRUE(camera.project(Vec3f(1.0f, 0.5f, 1.6f), sphere_px));
  const int sx = static_cast<int>(sphere_px.x), sy = static_cast<int>(sphere_px.y);
  const Ray centre = camera.generate_ray(Vec2f(px + 0.5f, py + 0.5f));
  const float t = -centre.origin.z / centre.dir.z;
  const Vec3f p = centre.origin + centre.dir * t;

  for (const std::string& name : integrator_names()) {
    if (name == "bvh-cost") continue;  // needs --accel=bvh; has no camera-ray AOVs (docs/output.md)
    SCOPED_TRACE(name);
    IntegratorSettings settings;
    settings.spp = 1;
    std::string error;
    Film film(kW, kH, PixelRect{0, 0, kW, kH}, aovs("albedo,N,P,Z,IndexOB,IndexMA"));
    make_integrator(name, settings, error)->render(*scene, film, pool);
    const std::vector<float> albedo = film.aov_value(AovType::Albedo, px, py);
    EXPECT_FLOAT_EQ(albedo[0], kPlaneColour.r);
    EXPECT_FLOAT_EQ(albedo[1], kPlaneColour.g);
    EXPECT_FLOAT_EQ(albedo[2], kPlaneColour.b);
    const std::vector<float> n = film.aov_value(AovType::Normal, px, py);
    EXPECT_NEAR(n[0], 0.0f, 1e-6f);
    EXPECT_NEAR(n[1], 0.0f, 1e-6f);
    EXPECT_NEAR(n[2], 1.0f, 1e-6f);
    if (name != "path") {  // the classic loop samples the pixel centre at 1 spp
      const std::vector<float> pos = film.aov_value(AovType::Position, px, py);
      EXPECT_NEAR(pos[0], p.x, 1e-4f);
      EXPECT_NEAR(pos[1], p.y, 1e-4f);
      EXPECT_NEAR(pos[2], 0.0f, 1e-4f);
    }
    // Depth along the view axis, not along the ray: every plane point is 5 away.
    EXPECT_NEAR(film.aov_value(AovType::Depth, px, py)[0], 5.0f, 1e-4f);
    EXPECT_GT(t, 5.05f);  // the ray length differs
    EXPECT_EQ(film.aov_value(AovType::ObjectId, px, py)[0], 1.0f);
    EXPECT_EQ(film.aov_value(AovType::ObjectId, sx, sy)[0], 2.0f);
    EXPECT_EQ(film.aov_value(AovType::MaterialId, px, py)[0], 1.0f);
    EXPECT_EQ(film.aov_value(AovType::MaterialId, sx, sy)[0], 2.0f);
    EXPECT_NEAR(film.aov_value(AovType::Depth, sx, sy)[0], 5.0f - 1.6f, 0.1f);
  }
}

TEST(Aov, MissesAndAbsentLayers) {
  WorkerPool pool(1);
  SceneDescription d = test::empty_scene(8, 8, Vec3f(0, 0, 5), Vec3f(0, 0, 0), Vec3f(0, 1, 0));
  const auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  Film film(8, 8, PixelRect{0, 0, 8, 8}, aovs("Z,IndexOB,N"));
  IntegratorSettings settings;
  std::string error;
  make_integrator("path", settings, error)->render(*scene, film, pool);
  EXPECT_EQ(film.aov_value(AovType::Depth, 3, 3)[0], kBackgroundDepth);
  EXPECT_EQ(film.aov_value(AovType::ObjectId, 3, 3)[0], 0.0f);
  EXPECT_EQ(film.aov_value(AovType::Normal, 3, 3)[2], 0.0f);
  EXPECT_TRUE(film.aov_value(AovType::Albedo, 3, 3).empty());  // not requested: not stored
  EXPECT_EQ(Film(8, 8).aov_slots(), 0);
}

// Lambert floor, a glossy Phong sphere, a mirror sphere and a visible area light.
std::unique_ptr<RenderScene> lighting_scene(WorkerPool& pool) {
  SceneDescription d = test::empty_scene(kW, kH, Vec3f(0, 1.5f, 6), Vec3f(0, 0.5f, 0), Vec3f(0, 1, 0), 55.0f);
  MaterialDesc floor = test::diffuse_material(RGB(0.6f, 0.5f, 0.4f));
  floor.type = MaterialType::Lambert;
  Quad q;
  q.v[0] = Vec3f(-5, 0, -5);
  q.v[1] = Vec3f(-5, 0, 5);
  q.v[2] = Vec3f(5, 0, 5);
  q.v[3] = Vec3f(5, 0, -5);
  test::add_shape(d, q, test::add_material(d, floor));
  MaterialDesc glossy = test::diffuse_material(RGB(0.3f, 0.6f, 0.3f), 0.6f);
  glossy.ks = 0.5f;
  glossy.exponent = 40.0f;
  test::add_sphere(d, Vec3f(-0.8f, 0.7f, 0), 0.7f, test::add_material(d, glossy));
  MaterialDesc mirror;
  mirror.type = MaterialType::Mirror;
  mirror.specular = RGB(0.9f);
  test::add_sphere(d, Vec3f(0.9f, 0.6f, 0.5f), 0.6f, test::add_material(d, mirror));
  Quad light;  // facing down, seen from the camera at a grazing angle
  light.v[0] = Vec3f(-1, 2.5f, -1);
  light.v[1] = Vec3f(1, 2.5f, -1);
  light.v[2] = Vec3f(1, 2.5f, 1);
  light.v[3] = Vec3f(-1, 2.5f, 1);
  MaterialDesc emitter = test::emitter_material(RGB(4.0f));
  emitter.two_sided = true;
  test::add_shape(d, light, test::add_material(d, emitter));
  return test::build(d, pool);
}

// Every pixel's `parts` (non-negative) sum to its beauty, and each part is used somewhere.
void expect_parts_sum_to_beauty(const Film& film, const std::vector<AovType>& parts) {
  std::vector<double> totals(parts.size());
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const RGB beauty = film.pixel(x, y);
      RGB sum;
      for (std::size_t i = 0; i < parts.size(); ++i) {
        const std::vector<float> v = film.aov_value(parts[i], x, y);
        sum += RGB(v[0], v[1], v[2]);
        for (float c : v) {
          EXPECT_GE(c, 0.0f);
          totals[i] += c;
        }
      }
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], beauty[c], 1e-5f * std::max(1.0f, beauty[c])) << x << "," << y;
    }
  for (std::size_t i = 0; i < parts.size(); ++i) EXPECT_GT(totals[i], 0.0) << aov_info(parts[i]).name << " is never used";
}

TEST(Aov, PathLightingSplitSumsToTheBeauty) {
  WorkerPool pool(2);
  const auto scene = lighting_scene(pool);
  ASSERT_TRUE(scene);
  for (const float clamp : {0.0f, 1.5f}) {
    SCOPED_TRACE(clamp);
    IntegratorSettings settings;
    settings.spp = 16;
    settings.clamp = clamp;
    settings.max_depth = 6;
    std::string error;
    Film film(kW, kH, PixelRect{0, 0, kW, kH},
              aovs("emission,diffuse_direct,diffuse_indirect,specular_direct,specular_indirect"));
    make_integrator("path", settings, error)->render(*scene, film, pool);
    expect_parts_sum_to_beauty(film, {AovType::Emission, AovType::DiffuseDirect, AovType::DiffuseIndirect,
                                      AovType::SpecularDirect, AovType::SpecularIndirect});
  }
}

// The classic integrator's scene: the lighting scene's floor, a glossy Phong
// sphere that also reflects, a glass sphere, a point, a spot and an ambient
// light, and a background the camera sees; with `area_light`, an emissive
// quad above them too (sampled by whitted: its diffuse and specular terms).
std::unique_ptr<RenderScene> classic_scene(WorkerPool& pool, bool area_light = false) {
  SceneDescription d = test::empty_scene(kW, kH, Vec3f(0, 1.5f, 6), Vec3f(0, 0.5f, 0), Vec3f(0, 1, 0), 55.0f);
  d.render.background = RGB(0.1f, 0.2f, 0.3f);
  Quad q;
  q.v[0] = Vec3f(-3, 0, -3);
  q.v[1] = Vec3f(-3, 0, 3);
  q.v[2] = Vec3f(3, 0, 3);
  q.v[3] = Vec3f(3, 0, -3);
  test::add_shape(d, q, test::add_material(d, test::diffuse_material(RGB(0.6f, 0.5f, 0.4f), 0.8f)));
  MaterialDesc glossy = test::diffuse_material(RGB(0.3f, 0.6f, 0.3f), 0.6f);
  glossy.ks = 0.5f;
  glossy.exponent = 40.0f;
  glossy.reflectivity = 0.3f;
  glossy.ka = Sourced<float>(0.2f);
  test::add_sphere(d, Vec3f(-0.8f, 0.7f, 0), 0.7f, test::add_material(d, glossy));
  MaterialDesc glass;
  glass.refractive = true;
  glass.ior = 1.5f;
  test::add_sphere(d, Vec3f(0.9f, 0.6f, 0.5f), 0.6f, test::add_material(d, glass));
  test::add_point_light(d, Vec3f(1, 3, 2), RGB(3.0f), RGB(3.0f));
  SpotLightDesc spot;
  spot.position = Vec3f(-1, 3, 1);
  spot.direction = Vec3f(0.2f, -1, -0.3f);
  spot.intensity = spot.specular_intensity = RGB(4.0f, 3.0f, 2.0f);
  d.lights.emplace_back(spot);
  AmbientLightDesc ambient;
  ambient.intensity = RGB(0.2f, 0.25f, 0.3f);
  d.lights.emplace_back(ambient);
  if (area_light) {
    MaterialDesc lamp = test::diffuse_material(RGB(0.0f), 0.0f);
    lamp.emission = RGB(6.0f, 5.0f, 4.0f);
    lamp.two_sided = true;
    lamp.light_samples = 4;
    Quad l;
    l.v[0] = Vec3f(-0.5f, 3, -0.5f);
    l.v[1] = Vec3f(0.5f, 3, -0.5f);
    l.v[2] = Vec3f(0.5f, 3, 0.5f);
    l.v[3] = Vec3f(-0.5f, 3, 0.5f);
    test::add_shape(d, l, test::add_material(d, lamp));
  }
  return test::build(d, pool);
}

void whitted_split_sums_to_the_beauty(bool area_light) {
  SCOPED_TRACE(area_light ? "with an area light" : "delta lights");
  WorkerPool pool(2);
  const auto scene = classic_scene(pool, area_light);
  ASSERT_TRUE(scene);
  IntegratorSettings settings;
  settings.spp = 4;
  std::string error;
  Film film(kW, kH, PixelRect{0, 0, kW, kH}, aovs("emission,ambient,diffuse_direct,specular_direct,specular_indirect"));
  make_integrator("whitted", settings, error)->render(*scene, film, pool);
  expect_parts_sum_to_beauty(film, {AovType::Emission, AovType::Ambient, AovType::DiffuseDirect,
                                    AovType::SpecularDirect, AovType::SpecularIndirect});
  // The beauty with the AOVs is the beauty without them, bit for bit.
  Film plain(kW, kH);
  make_integrator("whitted", settings, error)->render(*scene, plain, pool);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ASSERT_EQ(plain.pixel(x, y), film.pixel(x, y)) << x << "," << y;
}

TEST(Aov, WhittedSplitSumsToTheBeauty) {
  for (bool area_light : {false, true}) whitted_split_sums_to_the_beauty(area_light);
}

// Whitted's area-light samples come from the pixel sampler: replaying each
// sample of a pixel on its own (--pixel X,Y --sample N) gives the samples the
// full render averaged.
TEST(Aov, WhittedAreaLightSamplesReplayExactly) {
  WorkerPool pool(2);
  const auto scene = classic_scene(pool, true);
  const auto without = classic_scene(pool, false);
  ASSERT_TRUE(scene && without);
  constexpr int kSpp = 4;
  IntegratorSettings settings;
  settings.spp = kSpp;
  std::string error;
  Film film(kW, kH), dark(kW, kH);
  make_integrator("whitted", settings, error)->render(*scene, film, pool);
  make_integrator("whitted", settings, error)->render(*without, dark, pool);
  int x = -1, y = -1;  // the pixel the lamp brightens most
  float gain = 0.0f;
  for (int j = 0; j < kH; ++j)
    for (int i = 0; i < kW; ++i)
      if (film.pixel(i, j).r - dark.pixel(i, j).r > gain) {
        gain = film.pixel(i, j).r - dark.pixel(i, j).r;
        x = i, y = j;
      }
  ASSERT_GT(gain, 0.05f);
  double sum[3] = {};
  for (int s = 0; s < kSpp; ++s) {
    IntegratorSettings one = settings;
    one.only_sample = s;
    Film replay(kW, kH, PixelRect{x, y, x + 1, y + 1});
    make_integrator("whitted", one, error)->render(*scene, replay, pool);
    for (int c = 0; c < 3; ++c) sum[c] += replay.pixel(x, y)[c];
  }
  for (int c = 0; c < 3; ++c) EXPECT_EQ(film.pixel(x, y)[c], static_cast<float>(sum[c] / kSpp)) << c;
}

TEST(Aov, DiffuseOnlySceneHasNoSpecularLight) {
  WorkerPool pool(2);
  const auto scene = plane_scene(pool);  // Lambert and kd-only Phong: no glossy or mirror lobe
  ASSERT_TRUE(scene);
  IntegratorSettings settings;
  settings.spp = 4;
  std::string error;
  Film film(kW, kH, PixelRect{0, 0, kW, kH}, aovs("diffuse_direct,diffuse_indirect,specular_direct,specular_indirect"));
  make_integrator("path", settings, error)->render(*scene, film, pool);
  double diffuse = 0.0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      for (AovType t : {AovType::SpecularDirect, AovType::SpecularIndirect})
        for (float c : film.aov_value(t, x, y)) ASSERT_EQ(c, 0.0f) << x << "," << y;
      for (float c : film.aov_value(AovType::DiffuseDirect, x, y)) diffuse += c;
    }
  EXPECT_GT(diffuse, 0.0);
}

TEST(Aov, VarianceAndSampleCountMatchTheSamples) {
  WorkerPool pool(2);
  const auto scene = lighting_scene(pool);
  ASSERT_TRUE(scene);
  constexpr int kSpp = 32;
  IntegratorSettings settings;
  settings.spp = kSpp;
  std::string error;
  const auto path = make_integrator("path", settings, error);
  const int x = kW / 2, y = kH - 4;  // the floor, lit and noisy
  Film film(kW, kH, PixelRect{x, y, x + 1, y + 1}, aovs("variance,samples"));
  path->render(*scene, film, pool);
  EXPECT_EQ(film.aov_value(AovType::Samples, x, y)[0], static_cast<float>(kSpp));
  // The spread of the individual samples, each replayed on its own.
  double sum[3] = {}, sq[3] = {};
  for (int s = 0; s < kSpp; ++s) {
    IntegratorSettings one = settings;
    one.only_sample = s;
    Film replay(kW, kH, PixelRect{x, y, x + 1, y + 1});
    make_integrator("path", one, error)->render(*scene, replay, pool);
    const RGB v = replay.pixel(x, y);
    for (int c = 0; c < 3; ++c) {
      sum[c] += v[c];
      sq[c] += static_cast<double>(v[c]) * v[c];
    }
  }
  const std::vector<float> var = film.aov_value(AovType::Variance, x, y);
  for (int c = 0; c < 3; ++c) {
    const double mean = sum[c] / kSpp;
    const double expected = (sq[c] - sum[c] * mean) / (kSpp - 1) / kSpp;
    EXPECT_GT(expected, 0.0);
    EXPECT_NEAR(var[c], expected, 1e-4 * expected) << c;
  }
}

TEST(Aov, IndependentOfThreadsAndTiles) {
  const auto render = [](int threads, int tile) {
    WorkerPool pool(threads);
    const auto scene = lighting_scene(pool);
    IntegratorSettings settings;
    settings.spp = 4;
    settings.tile_size = tile;
    settings.filter = PixelFilterType::Gaussian;
    std::string error;
    Film film(kW, kH, PixelRect{3, 2, 29, 21}, aovs("albedo,N,P,Z,IndexOB,diffuse_direct,variance,nonfinite"));
    make_integrator("path", settings, error)->render(*scene, film, pool);
    return film.layers();
  };
  const LayeredImage a = render(1, 16), b = render(2, 5);
  ASSERT_EQ(a.layers.size(), b.layers.size());
  for (std::size_t i = 0; i < a.layers.size(); ++i) {
    SCOPED_TRACE(a.layers[i].name);
    ASSERT_EQ(a.layers[i].values.size(), b.layers[i].values.size());
    EXPECT_EQ(0, std::memcmp(a.layers[i].values.data(), b.layers[i].values.data(),
                             a.layers[i].values.size() * sizeof(float)));
  }
}

// The resolve of every pixel (layers(): the filtered averages a run of
// adjacent layers at a time) gives the bits of each AOV's own values
// (aov_value), whatever the order of the layers around the averages, for
// pixels with weight, without (weights that cancel), and with negative
// weights (the albedo clamped at 0).
TEST(AovResolve, LayersHoldEachAovsOwnValues) {
  for (const char* list : {"albedo,N,P,Z,emission,diffuse_direct,diffuse_indirect,specular_direct,specular_indirect,"
                           "variance,samples,nonfinite,CryptoObject,CryptoMaterial",
                           "P,albedo,Z,N,variance,emission", "albedo", "N,diffuse_direct", "Z,CryptoObject"}) {
    std::vector<AovRequest> aovs;
    ChannelType beauty = ChannelType::Float;
    std::string error;
    ASSERT_TRUE(parse_aov_list(list, aovs, beauty, error)) << error;
    Film film(8, 4, PixelRect{0, 0, 8, 4}, aovs);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x) {
        AovScratch scratch = film.make_scratch();
        const int samples = x == 3 || x == 5 ? 2 : 1 + (x + y) % 3;
        for (int k = 0; k < samples; ++k) {
          // Pixel (3, y): two samples whose weights cancel; x = 5: the second
          // weight negative, so that the albedo's red sum is (clamped at 0).
          const float w = x == 3 ? (k == 0 ? 0.5f : -0.5f) : x == 5 ? (k == 0 ? 1.0f : -0.9f)
                                                                   : 0.3f + 0.2f * static_cast<float>(k + y);
          const float f = 0.1f + 0.37f * static_cast<float>(x + 2 * y + 3 * k);
          AovSample a;
          a.hit = (x + k) % 4 != 0;
          a.albedo = RGB(f, 0.5f * f, 1.0f - f);
          a.normal = Vec3f(std::sin(f), std::cos(f), -f);
          a.position = Vec3f(f, -f, 2.0f * f);
          a.depth = 3.0f * f;
          a.crypto_object = static_cast<float>(1 + (x + k) % 3) * 1.5f;
          a.crypto_material = static_cast<float>(1 + (y + k) % 2) * 2.5f;
          a.emission = RGB(f * f, 0.0f, -f);
          a.diffuse_direct = RGB(1.0f / (1.0f + f), f, 0.25f);
          a.diffuse_indirect = a.specular_direct = a.specular_indirect = RGB(f, f, f);
          const RGB radiance(f, 2.0f * f, 0.5f);
          film.accumulate(scratch, a, radiance, w, false);
          PixelSum p;
          p.add(radiance, w, a.hit);
          film.add(x, y, p);
        }
        film.add_aovs(x, y, scratch);
      }
    const LayeredImage layers = film.layers();
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x) {
        std::vector<float> expected;
        for (const AovRequest& r : film.aovs()) {
          const std::vector<float> v = film.aov_value(r.type, x, y);
          expected.insert(expected.end(), v.begin(), v.end());
        }
        std::vector<float> resolved;
        const auto pixel = static_cast<std::size_t>(y * 8 + x);
        for (std::size_t l = 1; l < layers.layers.size(); ++l) {  // the beauty's aside
          const std::size_t n = layers.layers[l].channels.size();
          resolved.insert(resolved.end(), layers.layers[l].values.begin() + static_cast<std::ptrdiff_t>(pixel * n),
                          layers.layers[l].values.begin() + static_cast<std::ptrdiff_t>((pixel + 1) * n));
        }
        ASSERT_EQ(resolved.size(), expected.size()) << list;
        for (std::size_t c = 0; c < expected.size(); ++c)
          EXPECT_EQ(std::bit_cast<uint32_t>(resolved[c]), std::bit_cast<uint32_t>(expected[c]))
              << list << ": pixel (" << x << ", " << y << ") channel " << c << ": " << resolved[c] << " against "
              << expected[c];
        if (x == 5 && std::string(list) == "albedo") {
          EXPECT_EQ(resolved[0], 0.0f) << "clamped";
        }
      }
  }
}

}  // namespace
}  // namespace pt
