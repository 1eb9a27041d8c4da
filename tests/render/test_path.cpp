// The path integrator against answers known in closed form: white furnaces,
// pbrt's analytic sphere, glass of index 1, total internal reflection, the
// units of delta lights, one-sided emission. Tolerances are stated per test,
// derived from the noise measured at the sample counts used.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "path_test_util.h"

namespace pt {
namespace {

using test::add_material;
using test::add_point_light;
using test::add_shape;
using test::add_sphere;

MaterialDesc lambert(RGB albedo) {
  MaterialDesc m;
  m.type = MaterialType::Lambert;
  m.diffuse = albedo;
  return m;
}

MaterialDesc glass(float ior) {
  MaterialDesc m;
  m.type = MaterialType::Glass;
  m.ior = ior;
  return m;
}

MaterialDesc blinn_phong(float ks, float exponent, float kd = 0.0f) {
  MaterialDesc m;
  m.kd = kd;
  m.diffuse = RGB(1.0f);
  m.ks = ks;
  m.exponent = exponent;
  return m;
}

// A unit sphere at the origin in a uniform environment of radiance 1 (the
// background colour), seen from z = 4 so that it fills the middle of the image.
SceneDescription furnace(const MaterialDesc& material, int size = 16) {
  SceneDescription d = test::empty_scene(size, size, {0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 30);
  d.render.background = RGB(1.0f);
  add_sphere(d, {0, 0, 0}, 1.0f, add_material(d, material));
  return d;
}

// ---------------------------------------------------------------- precision
TEST(PathFilmPrecision, HundredThousandSamplesLoseNothing) {
  // An empty scene whose background is 0.1: every sample of every pixel is
  // exactly 0.1f, so the resolved pixel must be 0.1f to the last bit, whatever
  // the filter's weights. Accumulating in float would not survive this: after
  // 10^4 additions of 0.1 each addition rounds by up to half an ulp of 1000
  // (about 3e-5), and the mean of 10^5 samples comes out off by 1e-4 to 1e-3
  // relative (0.1, 0.3, 0.7 checked in float32); the film's double sums keep it exact to far below a float ulp.
  const RGB background(0.1f, 0.3f, 0.7f);
  SceneDescription d = test::empty_scene(2, 2, {0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 30);
  d.render.background = background;
  for (PixelFilterType filter : {PixelFilterType::Box, PixelFilterType::Gaussian, PixelFilterType::Mitchell}) {
    IntegratorSettings settings = test::path_settings(100000, 4, 3);
    settings.filter = filter;
    const Image img = test::render_path(d, settings);
    ASSERT_EQ(img.width, 2);
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(img.at(x, y)[c], background[c]) << "pixel " << x << "," << y << " channel " << c << " filter "
                                                    << static_cast<int>(filter);
  }
}

// ---------------------------------------------------------------- furnaces
TEST(PathFurnace, WhiteLambertSphereIsInvisible) {
  // Albedo 1 under radiance 1 reflects radiance 1 everywhere. A convex sphere
  // sees only the environment, so one bounce carries everything. MIS with the
  // environment's (uniform) light sampling makes one sample's standard
  // deviation about 0.19 (measured over 16 seeds); at 16384 spp a pixel's is
  // 0.0015, so every pixel is required within 1% (6.7 sigma) and the image
  // mean (64 pixels) within 0.05% (over 10 sigma).
  const Image img = test::render_path(furnace(lambert(RGB(1.0f)), 8), test::path_settings(16384));
  for (const RGB& p : img.pixels)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(p[c], 1.0f, 0.01f);
  EXPECT_NEAR(test::image_stats(img).mean, 1.0, 5e-4);
}

TEST(PathFurnace, NormalisedBlinnPhongNeverExceedsOne) {
  // The lobe's albedo is at most 1 (close to 1 only for a sharp lobe near
  // normal incidence), so no pixel may exceed 1 beyond the noise. At 4096 spp a
  // pixel's standard deviation is at most 0.003 (measured): 1.015 is 5 sigma.
  for (float exponent : {1.0f, 20.0f, 1000.0f}) {
    const Image img = test::render_path(furnace(blinn_phong(1.0f, exponent), 8), test::path_settings(4096));
    for (const RGB& p : img.pixels) ASSERT_LE(p.max_component(), 1.015f) << "exponent " << exponent;
    EXPECT_LE(test::image_stats(img).mean, 1.002) << "exponent " << exponent;
  }
}

TEST(PathFurnace, CourseMaterialWithKdPlusKsAboveOneStaysBelowOne) {
  // kd = ks = 0.8 is scaled to 0.5 + 0.5 (docs/path-tracing.md); as above.
  const Image img = test::render_path(furnace(blinn_phong(0.8f, 10.0f, 0.8f), 8), test::path_settings(4096));
  for (const RGB& p : img.pixels) ASSERT_LE(p.max_component(), 1.015f);
  EXPECT_LE(test::image_stats(img).mean, 1.002);
}

// ---------------------------------------------------------------- pbrt's analytic scene
TEST(PathAnalytic, InsideADiffuseSphereWithAPointLightAtItsCentre) {
  // pbrt's test: inside a unit sphere of albedo 0.5 with a point light of
  // radiant intensity pi W/sr at its centre, the direct radiance is 0.5 and
  // the interreflections double it: L = 0.5 / (1 - 0.5) = 1 everywhere.
  // In our units (docs/path-tracing.md) radiant intensity pi is intensity 1.
  // One sample's standard deviation is about 0.40 (Russian roulette; measured
  // over 16 seeds), so at 8192 spp a pixel's is 0.0044: every pixel must be
  // within 0.025 of 1 (pbrt's tolerance; 5.7 sigma).
  SceneDescription d = test::empty_scene(6, 6, {0, 0, 0.3f}, {0, 0, -1}, {0, 1, 0}, 60);
  add_sphere(d, {0, 0, 0}, 1.0f, add_material(d, lambert(RGB(0.5f))));
  add_point_light(d, {0, 0, 0}, RGB(1.0f), RGB(1.0f));
  const Image img = test::render_path(d, test::path_settings(8192, 1000));
  for (const RGB& p : img.pixels)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(p[c], 1.0f, 0.025f);
  // The direct part alone (one bounce) is exactly 0.5: no randomness reaches it.
  const Image direct = test::render_path(d, test::path_settings(4, 1));
  for (const RGB& p : direct.pixels) ASSERT_NEAR(p.r, 0.5f, 1e-4f);
}

TEST(PathAnalytic, RussianRouletteIsUnbiasedForEveryPolicy) {
  // The same scene (L = 1 everywhere, half of it from interreflections) under
  // roulette policies from none to one that ends most paths at the first bounce
  // (threshold 8: a throughput of 0.5 survives with probability 1/16 and is
  // scaled by 16). Every policy must average 1. The tolerance is 5 standard
  // errors of the image mean, estimated from the spread of the 36 pixel means
  // (independent estimates: each pixel has its own scramble), and the standard
  // error itself is bounded, so a policy so noisy that the test could not see
  // a bias fails too.
  SceneDescription d = test::empty_scene(6, 6, {0, 0, 0.3f}, {0, 0, -1}, {0, 1, 0}, 60);
  add_sphere(d, {0, 0, 0}, 1.0f, add_material(d, lambert(RGB(0.5f))));
  add_point_light(d, {0, 0, 0}, RGB(1.0f), RGB(1.0f));
  struct Policy {
    int depth;
    float threshold;
  };
  for (const Policy policy : {Policy{64, 1.0f}, Policy{3, 1.0f}, Policy{3, 1.0f / 3.0f}, Policy{1, 8.0f}}) {
    SCOPED_TRACE("roulette depth " + std::to_string(policy.depth) + ", threshold " +
                 std::to_string(policy.threshold));
    IntegratorSettings s = test::path_settings(1024, 64, 7);
    s.roulette_depth = policy.depth;
    s.roulette_threshold = policy.threshold;
    const Image img = test::render_path(d, s);
    double sum = 0.0, sum2 = 0.0;
    for (const RGB& p : img.pixels) {
      sum += p.r;
      sum2 += static_cast<double>(p.r) * p.r;
    }
    const double n = static_cast<double>(img.pixels.size());
    const double mean = sum / n;
    const double standard_error = std::sqrt(std::max(0.0, (sum2 / n - mean * mean) / (n - 1.0)));
    EXPECT_LT(standard_error, 0.01);
    EXPECT_NEAR(mean, 1.0, std::max(5.0 * standard_error, 1e-4));
  }
}

// ---------------------------------------------------------------- delta lights
SceneDescription lit_plane(float kd) {
  SceneDescription d = test::empty_scene(12, 12, {0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 30);
  test::add_z_square(d, 0.0f, 2.0f, add_material(d, test::diffuse_material(RGB(0.6f, 0.5f, 0.4f), kd)));
  return d;
}

TEST(PathLights, PointLightsAgreeWithTheClassicIntegrator) {
  // Same units as the classic integrator: on a diffuse scene the direct light
  // of both is kd Cd I cos / r^2. One bounce of the path integrator is its
  // direct light; both average over the pixel (16 samples), so they agree to
  // the difference of two 1024-sample estimates of the shading's average over
  // a pixel (it varies by up to 11% across one, so one estimate's standard
  // deviation is at most 0.1%): < 1%.
  SceneDescription d = lit_plane(0.9f);
  add_point_light(d, {0.3f, -0.2f, 1.5f}, RGB(2.0f, 1.5f, 1.0f), RGB(2.0f, 1.5f, 1.0f));
  const Image whitted = test::render_with(d, "whitted", test::path_settings(1024, 1));
  const Image path = test::render_path(d, test::path_settings(1024, 1));
  for (std::size_t i = 0; i < path.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(path.pixels[i][c], whitted.pixels[i][c], 1e-2f * whitted.pixels[i][c] + 1e-6f);
  EXPECT_NEAR(test::image_stats(path).mean, test::image_stats(whitted).mean, 1e-3 * test::image_stats(whitted).mean);
}

TEST(PathLights, DirectionalLightGivesAlbedoTimesIrradianceOverPi) {
  SceneDescription d = lit_plane(1.0f);
  DirectionalLightDesc sun;
  sun.direction = Vec3f(0.0f, 0.6f, -0.8f);  // cos = 0.8 on the plane
  sun.irradiance = RGB(3.0f);
  d.lights.emplace_back(sun);
  const Image path = test::render_path(d, test::path_settings(4, 1));
  const Image whitted = test::render_with(d, "whitted", test::path_settings(4, 1));
  const float expected = 0.6f * 3.0f * 0.8f * kInvPi;
  for (std::size_t i = 0; i < path.pixels.size(); ++i) {
    ASSERT_NEAR(path.pixels[i].r, expected, 1e-5f);
    ASSERT_NEAR(whitted.pixels[i].r, expected, 1e-5f);
  }
}

TEST(PathLights, EmissionIsOneSidedUnlessTwoSided) {
  // Two emissive quads in z = 0: the left one faces +z (the camera), the
  // right one faces -z (away from it).
  for (bool two_sided : {false, true}) {
    SceneDescription d = test::empty_scene(8, 4, {0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 40);
    MaterialDesc e = test::emitter_material(RGB(2.0f, 1.0f, 0.5f));
    e.two_sided = two_sided;
    const int m = add_material(d, e);
    Quad front, back;
    front.v[0] = Vec3f(-2.0f, -1, 0);  // counter-clockwise seen from +z
    front.v[1] = Vec3f(-0.05f, -1, 0);
    front.v[2] = Vec3f(-0.05f, 1, 0);
    front.v[3] = Vec3f(-2.0f, 1, 0);
    back.v[0] = Vec3f(0.05f, -1, 0);  // clockwise seen from +z
    back.v[1] = Vec3f(0.05f, 1, 0);
    back.v[2] = Vec3f(2.0f, 1, 0);
    back.v[3] = Vec3f(2.0f, -1, 0);
    add_shape(d, front, m);
    add_shape(d, back, m);
    const Image img = test::render_path(d, test::path_settings(4, 0));
    EXPECT_FLOAT_EQ(img.at(2, 2).r, 2.0f);                     // the front of the left quad
    EXPECT_FLOAT_EQ(img.at(5, 2).r, two_sided ? 2.0f : 0.0f);  // the back of the right one
  }
}

// ---------------------------------------------------------------- textured emission
// A white floor lit from z = 1 by a 1 x 1 light facing down whose emission
// texture is white on one half (u < 0.5) and black on the other, seen from
// below the light by a camera looking straight down: by symmetry the image's
// mean is half the untextured light's, whichever way the light is sampled.
// The light is a quad (sampled as a parallelogram), an 8-triangle mesh
// (triangles picked by area) or that mesh squeezed by an instance's
// non-uniform scale (triangles picked by world area).
SceneDescription floor_under_textured_light(int kind, bool textured) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 0.9f}, {0, 0, 0}, {0, 1, 0}, 60);
  test::add_z_square(d, 0.0f, 3.0f, add_material(d, test::diffuse_material(RGB(1.0f))));
  TextureDesc halves;
  halves.type = TextureType::Checker;
  halves.color0 = RGB(1.0f);
  halves.color1 = RGB(0.0f);
  halves.scale = Vec3f(2, 1, 1);  // floor(2u) + floor(v): u < 0.5 is color0
  d.textures.push_back(halves);
  MaterialDesc e = test::emitter_material(RGB(1.0f));
  if (textured) e.emission_texture = 0;
  const int light = add_material(d, e);
  if (kind == 0) {
    Quad q;  // u along +y, v along +x; (v1 - v0) x (v3 - v0) = -z
    q.v[0] = Vec3f(-0.5f, -0.5f, 1);
    q.v[1] = Vec3f(-0.5f, 0.5f, 1);
    q.v[2] = Vec3f(0.5f, 0.5f, 1);
    q.v[3] = Vec3f(0.5f, -0.5f, 1);
    add_shape(d, q, light);
    return d;
  }
  const float sx = kind == 2 ? 0.5f : 1.0f;  // squeezed in x, stretched back by the instance
  TriangleMesh m;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) {
      const float x = -0.5f + 0.5f * static_cast<float>(i), y = -0.5f + 0.5f * static_cast<float>(j);
      m.positions.emplace_back(x * sx, y, 1.0f);
      m.uvs.emplace_back(y + 0.5f, x + 0.5f);  // as the quad's
    }
  for (uint32_t j = 0; j < 2; ++j)
    for (uint32_t i = 0; i < 2; ++i) {
      const uint32_t a = j * 3 + i, b = a + 1, c = a + 4, dd = a + 3;
      m.indices.insert(m.indices.end(), {a, dd, c, a, c, b});  // clockwise from +z: facing down
    }
  if (kind == 1) {
    add_shape(d, m, light);
    return d;
  }
  ObjectDesc o;
  o.name = "lamp";
  ShapeDesc s;
  s.geometry = m;
  s.material = light;
  o.shapes.push_back(s);
  d.objects.push_back(o);
  InstanceDesc inst;
  inst.transform = Sourced<Transform>(Transform(Affine::scale(2.0f, 1.0f, 1.0f)));
  d.instances.push_back(inst);
  return d;
}

TEST(PathLights, TexturedEmittersLightWithTheirTextureForEveryStrategy) {
  for (int kind = 0; kind < 3; ++kind) {
    const SceneDescription textured = floor_under_textured_light(kind, true);
    const SceneDescription plain = floor_under_textured_light(kind, false);
    for (const LightStrategy strategy : {LightStrategy::Mis, LightStrategy::LightOnly, LightStrategy::BsdfOnly}) {
      IntegratorSettings settings = test::path_settings(256, 1, 7);  // direct light only
      settings.light_strategy = strategy;
      const double half = test::image_stats(test::render_path(textured, settings)).mean;
      const double full = test::image_stats(test::render_path(plain, settings)).mean;
      EXPECT_GT(full, 0.1) << kind;
      EXPECT_NEAR(half / full, 0.5, 0.03) << "light " << kind << ", strategy " << static_cast<int>(strategy);
    }
  }
  // Seen directly (from below, the light filling the view): half of it white, half black.
  SceneDescription seen = floor_under_textured_light(0, true);
  seen.camera.position = Vec3f(0, 0, 0.2f);
  seen.camera.look_at = Vec3f(0, 0, 1);
  seen.camera.fov_y_deg = 40.0f;
  const Image img = test::render_path(seen, test::path_settings(16, 0));
  float lo = 1e9f, hi = -1e9f;
  for (const RGB& p : img.pixels) {
    lo = std::min(lo, p.r);
    hi = std::max(hi, p.r);
  }
  EXPECT_NEAR(test::image_stats(img).mean, 0.5, 0.05);
  EXPECT_NEAR(lo, 0.0f, 1e-3f);
  EXPECT_NEAR(hi, 1.0f, 1e-3f);
}

// Glass's transmittance (MTL's Tf) tints each crossing: a glass square of
// index 1 (no reflection) in front of a white emitter shows the tint.
TEST(PathGlass, TransmittanceTintsTheLightThatCrosses) {
  SceneDescription d = test::empty_scene(4, 4, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 20);
  test::add_z_square(d, 0.0f, 3.0f, add_material(d, test::emitter_material(RGB(1.0f))));
  MaterialDesc glass;
  glass.type = MaterialType::Glass;
  glass.ior = 1.0f;
  glass.transmittance = RGB(0.5f, 0.25f, 1.0f);
  test::add_z_square(d, 1.0f, 3.0f, add_material(d, glass));
  for (const char* integrator : {"path", "whitted"}) {
    const Image img = test::render_with(d, integrator, test::path_settings(4, 4));
    for (const RGB& p : img.pixels) {
      ASSERT_NEAR(p.r, 0.5f, 1e-5f) << integrator;
      ASSERT_NEAR(p.g, 0.25f, 1e-5f) << integrator;
      ASSERT_NEAR(p.b, 1.0f, 1e-5f) << integrator;
    }
  }
}

// ---------------------------------------------------------------- glass
// Writes a small latitude-longitude map with a distinct value in every texel.
std::string write_test_environment() {
  const auto path = std::filesystem::temp_directory_path() / "pt_test_path_env.exr";
  Image img(32, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) img.at(x, y) = RGB(0.1f + x / 32.0f, 0.2f + y / 16.0f, ((x * 7 + y * 3) % 5) / 5.0f);
  std::string error;
  EXPECT_TRUE(write_image(path.string(), img, DisplaySettings{}, error)) << error;
  return path.string();
}

TEST(PathGlass, IndexOneRendersLikeEmptySpace) {
  // Seen against an environment map, a glass sphere of index 1 changes no
  // camera ray: each passes both interfaces undeflected with weight 1. The
  // map is looked up per texel, so only rays whose direction rounds across a
  // texel edge may differ.
  SceneDescription d = test::empty_scene(48, 48, {0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 40);
  EnvironmentDesc env;
  env.resolved = write_test_environment();
  d.environment = env;
  const Image empty = test::render_path(d, test::path_settings(4));
  add_sphere(d, {0, 0, 0}, 1.2f, add_material(d, glass(1.0f)));
  const Image with_glass = test::render_path(d, test::path_settings(4));
  std::size_t same = 0;
  for (std::size_t i = 0; i < empty.pixels.size(); ++i) same += std::memcmp(&empty.pixels[i], &with_glass.pixels[i], sizeof(RGB)) == 0;
  EXPECT_GE(same, empty.pixels.size() * 99 / 100);
  EXPECT_LT(test::rmse(empty, with_glass), 2e-3);
}

TEST(PathGlass, SlabBeyondTheCriticalAngleReflectsEverything) {
  // The camera sits inside a glass slab (0 < y < 1, index 1.5; its faces'
  // normals point out of it) under a uniform sky of radiance 1. Looking at the
  // top face 60 degrees from its normal, beyond the critical angle (41.8
  // degrees), every ray is totally reflected, at the bottom face too, and stays
  // trapped: the image is black. With index 1 the same rays see the sky; at
  // 20 degrees from the normal they leave the glass.
  auto slab = [](float ior, float view_deg) {
    const float t = view_deg * kPi / 180.0f;
    SceneDescription d = test::empty_scene(8, 8, {0, 0.5f, 0}, {std::sin(t), 0.5f + std::cos(t), 0}, {0, 0, 1}, 6);
    d.render.background = RGB(1.0f);
    const int m = add_material(d, glass(ior));
    const float w = 1000.0f;
    Quad top, bottom;
    top.v[0] = Vec3f(-w, 1, -w); top.v[1] = Vec3f(-w, 1, w); top.v[2] = Vec3f(w, 1, w); top.v[3] = Vec3f(w, 1, -w);
    bottom.v[0] = Vec3f(-w, 0, -w); bottom.v[1] = Vec3f(w, 0, -w); bottom.v[2] = Vec3f(w, 0, w); bottom.v[3] = Vec3f(-w, 0, w);
    add_shape(d, top, m);
    add_shape(d, bottom, m);
    return test::render_path(d, test::path_settings(16, 200));
  };
  const Image trapped = slab(1.5f, 60.0f);
  for (const RGB& p : trapped.pixels) ASSERT_EQ(p, RGB(0.0f));
  const Image clear = slab(1.0f, 60.0f);
  for (const RGB& p : clear.pixels) ASSERT_NEAR(p.r, 1.0f, 1e-5f);
  // Below the critical angle light gets in: the radiance inside is the sky's,
  // scaled by the transmittance and 1.5^2 (radiance is denser in glass), plus
  // what the faces reflect.
  const Image open = slab(1.5f, 20.0f);
  for (const RGB& p : open.pixels) ASSERT_GT(p.r, 1.0f);
}

// ---------------------------------------------------------------- sampling and the film
SceneDescription small_lit_scene() {
  SceneDescription d = test::empty_scene(21, 17, {0.3f, 1.0f, 4.0f}, {0, 0.4f, 0}, {0, 1, 0}, 45);
  d.render.background = RGB(0.1f, 0.12f, 0.2f);
  Quad floor;
  floor.v[0] = Vec3f(-3, 0, -3); floor.v[1] = Vec3f(-3, 0, 3); floor.v[2] = Vec3f(3, 0, 3); floor.v[3] = Vec3f(3, 0, -3);
  add_shape(d, floor, add_material(d, lambert(RGB(0.6f, 0.6f, 0.5f))));
  add_sphere(d, {-0.6f, 0.5f, 0.3f}, 0.5f, add_material(d, blinn_phong(0.6f, 40.0f, 0.4f)));
  add_sphere(d, {0.7f, 0.4f, -0.2f}, 0.4f, add_material(d, glass(1.5f)));
  add_sphere(d, {0.5f, 2.0f, 1.0f}, 0.2f, add_material(d, test::emitter_material(RGB(20.0f, 16.0f, 12.0f))));
  add_point_light(d, {-1.0f, 2.5f, 1.0f}, RGB(1.0f), RGB(1.0f));
  return d;
}

TEST(PathDeterminism, BitIdenticalForAnyThreadCountAndTileSize) {
  const SceneDescription d = small_lit_scene();
  auto render = [&](int threads, int tile) {
    IntegratorSettings s = test::path_settings(8);
    s.tile_size = tile;
    s.seed = 3;
    return test::render_path(d, s, threads);
  };
  const Image reference = render(1, 16);
  for (auto [threads, tile] : {std::pair{2, 16}, std::pair{4, 5}, std::pair{3, 1}}) {
    const Image other = render(threads, tile);
    ASSERT_EQ(std::memcmp(reference.pixels.data(), other.pixels.data(), reference.pixels.size() * sizeof(RGB)), 0)
        << threads << " threads, tile " << tile;
  }
}

TEST(PathFilm, ProgressivePassesAddUpToOneRenderExactly) {
  // Samples [0, 16) at once, and the same samples in passes of other sizes
  // added in any order: the film's sums are exact (render/film/exact_sum.h),
  // so every pixel's sums are the same bits.
  const SceneDescription d = small_lit_scene();
  WorkerPool pool(2);
  auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  std::string error;
  Film once(scene->width, scene->height);
  make_integrator("path", test::path_settings(16), error)->render(*scene, once, pool);
  using Passes = std::vector<std::pair<int, int>>;  // first sample, count
  for (const Passes& passes : {Passes{{0, 8}, {8, 8}}, Passes{{8, 8}, {0, 8}}, Passes{{5, 11}, {0, 2}, {2, 3}}}) {
    Film film(scene->width, scene->height);
    for (const auto& [first, count] : passes) {
      IntegratorSettings s = test::path_settings(count);
      s.first_sample = first;
      make_integrator("path", s, error)->render(*scene, film, pool);
    }
    for (int y = 0; y < film.height(); ++y)
      for (int x = 0; x < film.width(); ++x) {
        const PixelSum &a = once.sum(x, y), &b = film.sum(x, y);
        ASSERT_TRUE(a.r == b.r && a.g == b.g && a.b == b.b && a.weight == b.weight) << x << "," << y;
        ASSERT_EQ(b.samples, 16u);
      }
  }
}

TEST(PathFilm, ClampLimitsEverySample) {
  const SceneDescription d = small_lit_scene();
  IntegratorSettings s = test::path_settings(4);
  s.clamp = 0.5f;
  const Image img = test::render_path(d, s);
  for (const RGB& p : img.pixels) ASSERT_LE(p.max_component(), 0.5f + 1e-6f);
}

TEST(PathFilm, FiltersPreserveTheMeanOfASmoothImage) {
  // Filter importance sampling: the Gaussian's weights are positive, the
  // Mitchell filter's are negative where the filter is; on a furnace (all 1)
  // every filter gives exactly 1.
  for (PixelFilterType f : {PixelFilterType::Box, PixelFilterType::Gaussian, PixelFilterType::Mitchell}) {
    SceneDescription d = test::empty_scene(8, 8, {0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 30);
    d.render.background = RGB(1.0f);
    IntegratorSettings s = test::path_settings(16);
    s.filter = f;
    const Image img = test::render_path(d, s);
    for (const RGB& p : img.pixels) ASSERT_NEAR(p.g, 1.0f, 1e-5f);
  }
}

TEST(PathCamera, ThinLensBlursWhatIsOutOfFocus) {
  // A bright sphere in front of the plane in focus is blurred over more pixels
  // with a larger aperture; its total light is unchanged.
  auto render = [](float lens_radius) {
    SceneDescription d = test::empty_scene(40, 40, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30);
    d.camera.type = CameraType::ThinLens;
    d.camera.lens_radius = lens_radius;
    d.camera.focus_distance = 5.0f;
    add_sphere(d, {0, 0, 2.5f}, 0.15f, add_material(d, test::emitter_material(RGB(1.0f))));
    return test::render_path(d, test::path_settings(64, 0));
  };
  auto lit_pixels = [](const Image& img) {
    int n = 0;
    for (const RGB& p : img.pixels) n += p.r > 0.01f;
    return n;
  };
  const Image sharp = render(0.0f), blurred = render(0.2f);
  EXPECT_GT(lit_pixels(blurred), 2 * lit_pixels(sharp));
  EXPECT_NEAR(test::image_stats(blurred).mean, test::image_stats(sharp).mean, 0.1 * test::image_stats(sharp).mean);
}

}  // namespace
}  // namespace pt
