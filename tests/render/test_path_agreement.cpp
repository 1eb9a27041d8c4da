// Estimators that must converge to the same image: light sampling alone, BSDF
// sampling alone and MIS; the Embree and BVH backends; a glass sphere of index
// 1 and no sphere at all; the light BVH and power-proportional light choice
// (render.light_sampler) on scenes with several lights.
//
// Method: each image is rendered with S independent seeds; the image is cut
// into blocks, and each block's mean over the seeds and its standard error
// (the spread of the S block means / sqrt(S)) are compared: two estimates
// agree if every block and channel differs by less than kSigmas combined
// standard errors. With S = 16 the errors are estimated with 15 degrees of
// freedom; a two-sided Student t of 15 degrees exceeds 5 with probability
// 1.5e-4, so 48 comparisons (16 blocks, 3 channels) raise a false alarm with
// probability below 1%.
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "light_guide_scenes.h"
#include "path_test_util.h"
#include "scene/loader.h"

namespace pt {
namespace {

using test::add_material;
using test::add_shape;
using test::add_sphere;
using test::microfacet_desc;

constexpr int kSeeds = 16;
constexpr double kSigmas = 5.0;
constexpr int kBlocks = 4;  // per side

// Empty where our BVH builds `d`; else why not (a build without it).
std::string bvh_unavailable(const SceneDescription& d) {
  WorkerPool pool(1);
  Diagnostics diag;
  BuildOptions options;
  options.accel = AccelKind::Bvh;
  return build_render_scene(d, options, pool, diag) ? std::string() : diag.format();
}

struct BlockEstimate {
  std::vector<double> mean, error;  // per block and channel
};

BlockEstimate estimate(const std::function<Image(uint64_t)>& render) {
  std::vector<std::vector<double>> per_seed;
  for (int s = 0; s < kSeeds; ++s) {
    const Image img = render(static_cast<uint64_t>(s) + 1);
    std::vector<double> blocks(kBlocks * kBlocks * 3, 0.0);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const int b = (y * kBlocks / img.height) * kBlocks + x * kBlocks / img.width;
        for (int c = 0; c < 3; ++c) blocks[b * 3 + c] += img.at(x, y)[c];
      }
    per_seed.push_back(blocks);
  }
  BlockEstimate e;
  const std::size_t n = per_seed[0].size();
  e.mean.assign(n, 0.0);
  e.error.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0, sum2 = 0;
    for (const auto& b : per_seed) {
      sum += b[i];
      sum2 += b[i] * b[i];
    }
    const double m = sum / kSeeds;
    e.mean[i] = m;
    e.error[i] = std::sqrt(std::max(0.0, (sum2 - kSeeds * m * m) / (kSeeds - 1)) / kSeeds);
  }
  return e;
}

::testing::AssertionResult agree(const BlockEstimate& a, const BlockEstimate& b) {
  std::ostringstream os;
  bool ok = true;
  for (std::size_t i = 0; i < a.mean.size(); ++i) {
    const double sigma = std::sqrt(a.error[i] * a.error[i] + b.error[i] * b.error[i]);
    const double diff = std::fabs(a.mean[i] - b.mean[i]);
    if (!(diff <= kSigmas * sigma + 1e-9 * std::fabs(a.mean[i]))) {
      ok = false;
      os << "block " << i / 3 << " channel " << i % 3 << ": " << a.mean[i] << " vs " << b.mean[i] << " (sigma "
         << sigma << ")\n";
    }
  }
  return ok ? ::testing::AssertionSuccess() : ::testing::AssertionFailure() << os.str();
}

MaterialDesc lambert(RGB albedo) {
  MaterialDesc m;
  m.type = MaterialType::Lambert;
  m.diffuse = albedo;
  return m;
}

// A floor, a back wall, a glossy and a diffuse sphere, lit by a one-sided quad
// light facing down, a small sphere light and a dim uniform environment: every
// kind of light that can be hit, and glossy and diffuse surfaces.
SceneDescription mis_scene() {
  SceneDescription d = test::empty_scene(32, 32, {0, 1.0f, 4.0f}, {0, 0.6f, 0}, {0, 1, 0}, 45);
  d.render.background = RGB(0.15f, 0.2f, 0.3f);
  const int white = add_material(d, lambert(RGB(0.7f)));
  Quad floor, wall, light;
  floor.v[0] = Vec3f(-2, 0, -2); floor.v[1] = Vec3f(-2, 0, 2); floor.v[2] = Vec3f(2, 0, 2); floor.v[3] = Vec3f(2, 0, -2);
  wall.v[0] = Vec3f(-2, 0, -1); wall.v[1] = Vec3f(2, 0, -1); wall.v[2] = Vec3f(2, 2, -1); wall.v[3] = Vec3f(-2, 2, -1);
  light.v[0] = Vec3f(-0.5f, 2, -0.5f); light.v[1] = Vec3f(0.5f, 2, -0.5f); light.v[2] = Vec3f(0.5f, 2, 0.5f); light.v[3] = Vec3f(-0.5f, 2, 0.5f);
  add_shape(d, floor, white);
  add_shape(d, wall, white);
  add_shape(d, light, add_material(d, test::emitter_material(RGB(4.0f, 3.5f, 3.0f))));
  MaterialDesc glossy;
  glossy.kd = 0.3f;
  glossy.diffuse = RGB(0.8f, 0.3f, 0.2f);
  glossy.ks = 0.6f;
  glossy.exponent = 30.0f;
  add_sphere(d, {-0.6f, 0.5f, 0.0f}, 0.5f, add_material(d, glossy));
  add_sphere(d, {0.7f, 0.35f, 0.3f}, 0.35f, add_material(d, lambert(RGB(0.3f, 0.6f, 0.4f))));
  add_sphere(d, {1.2f, 1.4f, -0.4f}, 0.12f, add_material(d, test::emitter_material(RGB(30.0f, 20.0f, 10.0f))));
  return d;
}

BlockEstimate estimate_strategy(const SceneDescription& d, LightStrategy strategy, int spp) {
  return estimate([&](uint64_t seed) {
    IntegratorSettings s = test::path_settings(spp, 8, seed);
    s.light_strategy = strategy;
    return test::render_path(d, s);
  });
}

TEST(PathAgreement, LightSamplingBsdfSamplingAndMisConvergeToTheSameImage) {
  const SceneDescription d = mis_scene();
  const BlockEstimate mis = estimate_strategy(d, LightStrategy::Mis, 32);
  const BlockEstimate light = estimate_strategy(d, LightStrategy::LightOnly, 32);
  const BlockEstimate bsdf = estimate_strategy(d, LightStrategy::BsdfOnly, 128);
  EXPECT_TRUE(agree(mis, light)) << "MIS vs light sampling";
  EXPECT_TRUE(agree(mis, bsdf)) << "MIS vs BSDF sampling";
  EXPECT_TRUE(agree(light, bsdf)) << "light vs BSDF sampling";
}

// The MIS scene with its glossy sphere an anisotropic rough conductor, its
// diffuse sphere a rough coated diffuse, a rough dielectric sphere in front
// and a metallic-roughness sphere (metallic 0.5) beside it.
SceneDescription microfacet_scene() {
  SceneDescription d = mis_scene();
  d.materials[2] = microfacet_desc(MaterialType::Conductor, 0.15f, 0.4f);
  MaterialDesc plastic = microfacet_desc(MaterialType::CoatedDiffuse, 0.2f, 0.2f);
  plastic.reflectance.value = RGB(0.3f, 0.6f, 0.4f);
  d.materials[3] = plastic;
  add_sphere(d, {0.15f, 0.45f, 0.9f}, 0.3f, add_material(d, microfacet_desc(MaterialType::Dielectric, 0.2f, 0.2f)));
  MaterialDesc gltf = microfacet_desc(MaterialType::MetallicRoughness, 0.25f, 0.25f);
  gltf.reflectance.value = RGB(0.9f, 0.6f, 0.3f);
  gltf.metallic.value = 0.5f;
  add_sphere(d, {-0.9f, 0.3f, 1.0f}, 0.3f, add_material(d, gltf));
  return d;
}

TEST(PathAgreement, MicrofacetMaterialsConvergeToTheSameImageWithEveryStrategy) {
  // Half the sample counts of the test above (the rough glass lengthens paths).
  const SceneDescription d = microfacet_scene();
  const BlockEstimate mis = estimate_strategy(d, LightStrategy::Mis, 16);
  const BlockEstimate light = estimate_strategy(d, LightStrategy::LightOnly, 16);
  const BlockEstimate bsdf = estimate_strategy(d, LightStrategy::BsdfOnly, 64);
  EXPECT_TRUE(agree(mis, light)) << "MIS vs light sampling";
  EXPECT_TRUE(agree(mis, bsdf)) << "MIS vs BSDF sampling";
  EXPECT_TRUE(agree(light, bsdf)) << "light vs BSDF sampling";
}

TEST(PathAgreement, TheTestCanFail) {
  // The comparison is sharp enough to see a 5% change of one light.
  SceneDescription brighter = mis_scene();
  brighter.materials[1].emission = RGB(4.0f, 3.5f, 3.0f) * 1.05f;  // the quad light
  EXPECT_FALSE(agree(estimate_strategy(mis_scene(), LightStrategy::Mis, 32),
                     estimate_strategy(brighter, LightStrategy::Mis, 32)));
}

TEST(PathAgreement, GlassOfIndexOneIsEmptySpaceWhenLit) {
  // Lit by the quad light, a glass sphere of index 1 blocks next-event
  // estimation (shadow rays treat it as opaque) but BSDF rays pass it with
  // weight 1 and find the light instead: the converged image is the same.
  const SceneDescription without = mis_scene();
  SceneDescription with = mis_scene();
  MaterialDesc g;
  g.type = MaterialType::Glass;
  g.ior = 1.0f;
  add_sphere(with, {0.1f, 1.2f, 0.2f}, 0.3f, add_material(with, g));
  EXPECT_TRUE(agree(estimate_strategy(without, LightStrategy::Mis, 16), estimate_strategy(with, LightStrategy::Mis, 32)));
}

TEST(PathAgreement, BothBackendsConvergeToTheSameImage) {
  const SceneDescription d = mis_scene();
  if (const std::string why = bvh_unavailable(d); !why.empty()) GTEST_SKIP() << "no BVH backend in this build: " << why;
  auto with_backend = [&](AccelKind kind) {
    return estimate([&](uint64_t seed) {
      BuildOptions options;
      options.accel = kind;
      return test::render_with(d, "path", test::path_settings(16, 8, seed), 2, options);
    });
  };
  EXPECT_TRUE(agree(with_backend(AccelKind::Embree), with_backend(AccelKind::Bvh)));
}

// ---------------------------------------------------------------- light samplers
BlockEstimate estimate_sampler(const SceneDescription& d, LightSamplerType sampler, int spp, int width, int height) {
  return estimate([&](uint64_t seed) {
    BuildOptions options;
    options.light_sampler = sampler;
    options.width_override = width;
    options.height_override = height;
    return test::render_with(d, "path", test::path_settings(spp, 5, seed), 2, options);
  });
}

void expect_samplers_agree(const SceneDescription& d, int spp, int width = 32, int height = 24) {
  EXPECT_TRUE(agree(estimate_sampler(d, LightSamplerType::Bvh, spp, width, height),
                    estimate_sampler(d, LightSamplerType::Power, spp, width, height)))
      << "light BVH vs power";
}

std::optional<SceneDescription> load_file(const std::string& path) {
  Diagnostics diag;
  std::optional<SceneDescription> d = load_scene(path, LoadOptions{}, diag);
  EXPECT_TRUE(d) << diag.format();
  return d;
}

// The MIS scene (quad, sphere light, sky) with a spot and two point lights.
TEST(PathAgreement, LightSamplersAgreeOnAreaSpotPointLightsAndSky) {
  SceneDescription d = mis_scene();
  SpotLightDesc spot;
  spot.position = Vec3f(-1.0f, 1.8f, 1.0f);
  spot.direction = Vec3f(0.3f, -1.0f, -0.5f);
  spot.intensity = RGB(6.0f, 5.0f, 4.0f);
  spot.cone_angle = 25.0f;
  spot.cone_delta = 5.0f;
  d.lights.emplace_back(spot);
  PointLightDesc point;
  point.position = Vec3f(1.5f, 1.2f, 1.0f);
  point.intensity = RGB(0.4f, 0.5f, 0.8f);
  d.lights.emplace_back(point);
  point.position = Vec3f(-1.5f, 0.3f, 0.5f);
  d.lights.emplace_back(point);
  expect_samplers_agree(d, 16, 32, 32);
}

TEST(PathAgreement, LightSamplersAgreeOnTheClassicLightsScene) {  // spot, point, directional, sphere lamp
  const auto d = load_file(std::string(PT_TEST_DATA_DIR) + "/data/scenes/classic-lights.json");
  if (d) expect_samplers_agree(*d, 8, 24, 18);
}

TEST(PathAgreement, LightSamplersAgreeOnInstancedMeshLights) {  // an instanced mesh light, a spherical camera
  const auto d = load_file(std::string(PT_TEST_DATA_DIR) + "/data/scenes/panorama.json");
  if (d) expect_samplers_agree(*d, 16, 32, 16);
}

TEST(PathAgreement, LightSamplersAgreeOnTheManyLightsRoom) {  // 248 lamps
  const auto d = load_file(std::string(PT_SCENES_DIR) + "/many-lights.json");
  if (d) expect_samplers_agree(*d, 8);
}

TEST(PathAgreement, LightSamplersRenderTheCornellBoxBitForBit) {
  // One light: neither sampler spends a sample dimension on the choice.
  const auto d = load_file(std::string(PT_SCENES_DIR) + "/cornell-box.json");
  if (!d) return;
  const auto render = [&](LightSamplerType sampler) {
    BuildOptions options;
    options.light_sampler = sampler;
    options.width_override = 32;
    options.height_override = 32;
    return test::render_with(*d, "path", test::path_settings(4, 8, 1), 2, options);
  };
  const Image a = render(LightSamplerType::Bvh), b = render(LightSamplerType::Power);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(a.pixels[i][c], b.pixels[i][c]) << "pixel " << i;
}

// ---------------------------------------------------------------- light guiding
// render.light_guiding (render/guiding/light_guide.h) changes how the sky and
// the sun are sampled, never what the image converges to: a courtyard lit
// through its roof's opening by an environment map and a sun, guided and
// plain, on both backends.
// The guides' pre-pass paths per pixel (render.light_guiding,
// render.path_guiding); 0 = off.
struct Guiding {
  int light = 0;
  int path = 0;
};

BlockEstimate estimate_guided(const SceneDescription& d, Guiding guiding, AccelKind accel) {
  return estimate([&](uint64_t seed) {
    BuildOptions options;
    options.accel = accel;
    IntegratorSettings s = test::path_settings(16, 6, seed);
    s.light_guiding = guiding.light;
    s.path_guiding = guiding.path;
    return test::render_with(d, "path", s, 2, options);
  });
}

TEST(PathAgreement, LightGuidingConvergesToThePlainImageWithSkyAndSun) {
  const SceneDescription d = test::courtyard_scene(true);
  const BlockEstimate plain = estimate_guided(d, {}, AccelKind::Embree);
  EXPECT_TRUE(agree(plain, estimate_guided(d, {.light = 4}, AccelKind::Embree))) << "Embree";
  if (const std::string why = bvh_unavailable(d); !why.empty()) GTEST_SKIP() << "no BVH backend in this build: " << why;
  EXPECT_TRUE(agree(plain, estimate_guided(d, {.light = 4}, AccelKind::Bvh))) << "BVH";
}

TEST(PathAgreement, LightGuidingConvergesToThePlainImageWithSkyAlone) {
  const SceneDescription d = test::courtyard_scene(false);
  EXPECT_TRUE(agree(estimate_guided(d, {}, AccelKind::Embree), estimate_guided(d, {.light = 8}, AccelKind::Embree)));
}

// The tests above' skies are smooth: the guide draws the plain part of its mixture from
// the bins' coarse grid. Here the sky holds a sun disc: the map's own sampling.
TEST(PathAgreement, LightGuidingConvergesToThePlainImageWithASunInTheMap) {
  const SceneDescription d = test::courtyard_scene(false, true);
  EXPECT_TRUE(agree(estimate_guided(d, {}, AccelKind::Embree), estimate_guided(d, {.light = 8}, AccelKind::Embree)));
}

// ---------------------------------------------------------------- every infinite light
// Where the lights are a sun and a sky (LightSet::each_lights), next-event
// estimation samples both at every vertex (IntegratorSettings::estimate_each_light)
// instead of choosing one: the image converges to the one-light estimator's
// (same test as above: 16 seeds, every block within 5 combined standard
// errors), plain and light-guided; and the estimator is used only there: with
// a sky alone, or an area light beside the sky, the image is bit for bit the
// one-light estimator's, and with a sun and a sky it is not.
Image render_each(const SceneDescription& d, bool each, int light_guiding, int spp, uint64_t seed) {
  IntegratorSettings s = test::path_settings(spp, 6, seed);
  s.light_guiding = light_guiding;
  s.estimate_each_light = each;
  return test::render_path(d, s);
}

TEST(PathAgreement, EveryInfiniteLightAtEveryVertexConvergesToTheChosenOne) {
  const SceneDescription d = test::courtyard_scene(true);
  for (const int guiding : {0, 4}) {
    const auto estimate_each = [&](bool each) {
      return estimate([&](uint64_t seed) { return render_each(d, each, guiding, 16, seed); });
    };
    EXPECT_TRUE(agree(estimate_each(false), estimate_each(true))) << "light_guiding " << guiding;
  }
}

TEST(PathAgreement, EveryInfiniteLightAtEveryVertexOnlyWithAFewInfiniteLights) {
  const auto same = [](const Image& a, const Image& b) {
    if (a.pixels.size() != b.pixels.size()) return false;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        if (a.pixels[i][c] != b.pixels[i][c]) return false;
    return true;
  };
  const auto unchanged = [&](const SceneDescription& d, int guiding) {
    return same(render_each(d, false, guiding, 4, 3), render_each(d, true, guiding, 4, 3));
  };
  EXPECT_TRUE(unchanged(mis_scene(), 0)) << "area lights and a sky";
  EXPECT_TRUE(unchanged(test::courtyard_scene(false), 0)) << "a sky alone";
  EXPECT_TRUE(unchanged(test::courtyard_scene(false), 4)) << "a sky alone, guided";
  EXPECT_FALSE(unchanged(test::courtyard_scene(true), 0)) << "a sun and a sky";
  auto cornell = load_file(std::string(PT_SCENES_DIR) + "/cornell-box.json");
  ASSERT_TRUE(cornell);
  cornell->film.width = 32;
  cornell->film.height = 32;
  EXPECT_TRUE(unchanged(*cornell, 0)) << "the Cornell box";
}

// ---------------------------------------------------------------- path guiding
// render.path_guiding (render/guiding/path_guide.h) changes how bounce
// directions are sampled (a mixture with the BSDF's sampling, used in MIS with
// next-event estimation), never what the image converges to: the courtyard,
// lit mostly through bounces, guided and plain, on both backends; and the
// microfacet scene (glossy, rough conductor, coated, rough glass and Lambert
// surfaces under area lights) with a smooth glass sphere added (delta lobes).
TEST(PathAgreement, PathGuidingConvergesToThePlainImageInTheCourtyard) {
  const SceneDescription d = test::courtyard_scene(true);
  const BlockEstimate plain = estimate_guided(d, {}, AccelKind::Embree);
  EXPECT_TRUE(agree(plain, estimate_guided(d, {.path = 8}, AccelKind::Embree))) << "Embree";
  EXPECT_TRUE(agree(plain, estimate_guided(d, {.light = 4, .path = 8}, AccelKind::Embree))) << "Embree, light guiding too";
  if (const std::string why = bvh_unavailable(d); !why.empty()) GTEST_SKIP() << "no BVH backend in this build: " << why;
  EXPECT_TRUE(agree(plain, estimate_guided(d, {.path = 8}, AccelKind::Bvh))) << "BVH";
}

TEST(PathAgreement, PathGuidingConvergesToThePlainImageWithMicrofacetsAndGlass) {
  SceneDescription d = microfacet_scene();
  add_sphere(d, {-0.9f, 0.25f, 0.8f}, 0.25f, add_material(d, microfacet_desc(MaterialType::Dielectric, 0.0f, 0.0f)));
  EXPECT_TRUE(agree(estimate_guided(d, {}, AccelKind::Embree), estimate_guided(d, {.path = 8}, AccelKind::Embree)));
}

}  // namespace
}  // namespace pt
