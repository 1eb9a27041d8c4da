// Procedural textures (render/textures/procedural.h), texture mappings, and
// the footprint of a pixel (render/textures/footprint.h).
#include <cmath>

#include <gtest/gtest.h>

#include "render/camera/camera.h"
#include "render/textures/footprint.h"
#include "render/textures/texture.h"

namespace pt {
namespace {

const RGB kRed(1, 0, 0), kBlue(0, 0, 1);

TEST(Checker, PointValues) {
  const CheckerTexture c{kRed, kBlue, false};
  EXPECT_EQ(evaluate(c, {0.5f, 0.5f, 0}, {}, {}), kRed);
  EXPECT_EQ(evaluate(c, {1.5f, 0.5f, 0}, {}, {}), kBlue);
  EXPECT_EQ(evaluate(c, {-0.5f, 0.5f, 0}, {}, {}), kBlue);
  EXPECT_EQ(evaluate(c, {-0.5f, -0.5f, 0}, {}, {}), kRed);
  EXPECT_EQ(evaluate(c, {2.5f, 7.5f, 9.5f}, {}, {}), kBlue);  // 2D: z is not read
  const CheckerTexture cube{kRed, kBlue, true};
  EXPECT_EQ(evaluate(cube, {2.5f, 7.5f, 9.5f}, {}, {}), kRed);  // 2 + 7 + 9 is even
  EXPECT_EQ(evaluate(cube, {2.5f, 7.5f, 10.5f}, {}, {}), kBlue);
}

// The box average of the square wave (+1 where floor(x) is even).
TEST(Checker, WaveAverageIsExact) {
  EXPECT_EQ(checker_wave_average(0.5f, 0.0f), 1.0f);
  EXPECT_EQ(checker_wave_average(1.5f, 0.0f), -1.0f);
  EXPECT_NEAR(checker_wave_average(0.5f, 0.25f), 1.0f, 1e-6f);   // [0.25, 0.75]: all even
  EXPECT_NEAR(checker_wave_average(1.0f, 0.25f), 0.0f, 1e-6f);   // [0.75, 1.25]: half and half
  EXPECT_NEAR(checker_wave_average(1.0f, 1.0f), 0.0f, 1e-6f);    // [0, 2]: one period
  EXPECT_NEAR(checker_wave_average(0.75f, 0.5f), 0.5f, 1e-6f);   // [0.25, 1.25]: 0.75 even, 0.25 odd
  EXPECT_NEAR(checker_wave_average(-0.5f, 0.25f), -1.0f, 1e-6f);
}

// A footprint spanning whole periods blends the two colours evenly: the
// filtered checker does not alias into either colour.
TEST(Checker, AWideFootprintGivesTheMean) {
  const CheckerTexture c{kRed, kBlue, false};
  const RGB wide = evaluate(c, {0.3f, 0.7f, 0}, {4.0f, 0, 0}, {0, 4.0f, 0});
  EXPECT_NEAR(wide.r, 0.5f, 1e-5f);
  EXPECT_NEAR(wide.b, 0.5f, 1e-5f);
  // Half a square wide, centred on an edge along u: half of each colour.
  const RGB edge = evaluate(c, {1.0f, 0.5f, 0}, {0.5f, 0, 0}, {0, 0.01f, 0});
  EXPECT_NEAR(edge.r, 0.5f, 1e-4f);
}

TEST(Noise, LatticeZerosRangeAndMean) {
  EXPECT_EQ(perlin_noise({0, 0, 0}), 0.0f);
  EXPECT_EQ(perlin_noise({3, -7, 12}), 0.0f);
  double sum = 0;
  float lo = 0, hi = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3f p(std::fmod(0.7548776f * static_cast<float>(i), 50.0f), std::fmod(0.5698403f * static_cast<float>(i), 50.0f),
                  std::fmod(0.3141592f * static_cast<float>(i), 50.0f));
    const float n = perlin_noise(p);
    sum += n;
    lo = std::min(lo, n);
    hi = std::max(hi, n);
  }
  EXPECT_GE(lo, -1.05f);
  EXPECT_LE(hi, 1.05f);
  EXPECT_GT(hi - lo, 1.0f);  // it varies
  EXPECT_LT(std::fabs(sum / 20000.0), 0.03);
  EXPECT_EQ(perlin_noise({1.25f, 2.5f, 3.75f}), perlin_noise({1.25f, 2.5f, 3.75f}));
}

// fBm drops the octaves finer than the footprint: none at all for a footprint
// of a lattice cell or more (the blend's midpoint), every one for a point.
TEST(Noise, FbmDropsOctavesFinerThanTheFootprint) {
  const Vec3f p(0.37f, 1.91f, 2.53f);
  EXPECT_EQ(fbm(p, {1.0f, 0, 0}, {0, 1.0f, 0}, 0.5f, 8), 0.0f);
  EXPECT_EQ(fbm(p, {}, {}, 0.5f, 1), perlin_noise(p));
  EXPECT_NEAR(fbm(p, {}, {}, 0.5f, 2), perlin_noise(p) + 0.5f * perlin_noise(p * 1.99f), 1e-6f);
  // A footprint of 1/8: 2 whole octaves (n = -1 - log2(1/8) = 2).
  EXPECT_NEAR(fbm(p, {0.125f, 0, 0}, {}, 0.5f, 8), perlin_noise(p) + 0.5f * perlin_noise(p * 1.99f), 1e-6f);
  const NoiseTexture t{kRed, kBlue, 6, 0.5f};
  const RGB mid = evaluate(t, p, {2.0f, 0, 0}, {0, 2.0f, 0});
  EXPECT_NEAR(mid.r, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.b, 0.5f, 1e-6f);
}

// scale multiplies the coordinates; the transform moves the pattern (its
// inverse maps the lookup point); the object mapping reads the position.
TEST(TextureMapping, ScaleTransformAndObjectSpace) {
  TextureMapping m;
  m.scale = Vec3f(4.0f, 2.0f, 1.0f);
  Vec3f dx, dy;
  const TexCoord tc(Vec2f(0.25f, 0.5f), {0.01f, 0}, {0, 0.02f}, Vec3f(5, 6, 7), {1, 0, 0}, {0, 1, 0});
  Vec3f c = m.coordinates(tc, dx, dy);
  EXPECT_EQ(c, Vec3f(1.0f, 1.0f, 0.0f));
  EXPECT_EQ(dx, Vec3f(0.04f, 0, 0));
  EXPECT_EQ(dy, Vec3f(0, 0.04f, 0));
  m.scale = Vec3f(1.0f);
  m.transform = Transform(Affine::translate(1, 0, 0));
  c = m.coordinates(tc, dx, dy);
  EXPECT_NEAR(c.x, -0.75f, 1e-6f);
  EXPECT_EQ(dx, Vec3f(0.01f, 0, 0));  // a translation moves no footprint
  m.transform.reset();
  m.object = true;
  EXPECT_EQ(m.coordinates(tc, dx, dy), Vec3f(5, 6, 7));
  EXPECT_EQ(dy, Vec3f(0, 1, 0));
  // Through a Texture: a 3D checker in object space.
  TextureMapping object;
  object.object = true;
  const Texture cube(CheckerTexture{kRed, kBlue, true}, object);
  EXPECT_EQ(cube.eval(TexCoord(Vec2f(0.1f, 0.1f), {}, {}, Vec3f(0.5f, 0.5f, 0.5f))), kRed);
  EXPECT_EQ(cube.eval(TexCoord(Vec2f(0.1f, 0.1f), {}, {}, Vec3f(0.5f, 0.5f, 1.5f))), kBlue);
  EXPECT_EQ(cube.alpha(TexCoord(Vec2f(0.1f, 0.1f), {}, {}, Vec3f(0.5f, 0.5f, 1.5f))), 1.0f / 3.0f);
}

// Least squares from dp to duv: dp/du = x, dp/dv = 2y; a step of 0.1 along x
// is 0.1 in u, one of 0.1 along y 0.05 in v. Where v does not change (a
// cylinder's cap), u still gets its footprint.
TEST(Footprint, UvFromPartials) {
  Vec2f dx, dy;
  uv_footprint({1, 0, 0}, {0, 2, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}, dx, dy);
  EXPECT_NEAR(dx.x, 0.1f, 1e-7f);
  EXPECT_NEAR(dx.y, 0.0f, 1e-7f);
  EXPECT_NEAR(dy.y, 0.05f, 1e-7f);
  // A skewed frame: dp/dv = x + y.
  uv_footprint({1, 0, 0}, {1, 1, 0}, {0, 0.1f, 0}, {0.1f, 0, 0}, dx, dy);
  EXPECT_NEAR(dx.x, -0.1f, 1e-6f);
  EXPECT_NEAR(dx.y, 0.1f, 1e-6f);
  uv_footprint({2, 0, 0}, {0, 0, 0}, {0.1f, 0.3f, 0}, {0, 0.1f, 0}, dx, dy);
  EXPECT_NEAR(dx.x, 0.05f, 1e-7f);
  EXPECT_EQ(dx.y, 0.0f);
  EXPECT_EQ(dy.x, 0.0f);
}

// A pinhole camera looking straight at the plane z = 0 from distance 2, fov
// 90 degrees, 100 pixels high: a pixel at the centre covers 2 * 2 / 100 =
// 0.04 scene units, from the differential and (about) from the spread.
TEST(Footprint, FromTheCamera) {
  CameraDesc desc;
  desc.position = Vec3f(0, 0, 2);
  desc.look_at = Vec3f(0, 0, 0);
  desc.fov_y_deg = 90.0f;
  const Camera camera(desc, 100, 100);
  const RayDifferential d = camera.differential({50, 50}, {0.5f, 0.5f});
  const Ray x = camera.generate_ray({51, 50});
  EXPECT_EQ(d.dx_dir, x.dir);
  Vec3f dpdx, dpdy;
  ASSERT_TRUE(footprint_from_differential(d, {0, 0, 0}, {0, 0, 1}, dpdx, dpdy));
  EXPECT_NEAR(length(dpdx), 0.04f, 1e-4f);
  EXPECT_NEAR(length(dpdy), 0.04f, 1e-4f);
  EXPECT_NEAR(dot(dpdx, dpdy), 0.0f, 1e-6f);
  const CameraSpread spread = CameraSpread::of(camera, 100, 100);
  EXPECT_EQ(spread.origin, 0.0f);
  footprint_from_camera(spread, {0, 0, 0}, {0, 0, 1}, dpdx, dpdy);
  EXPECT_NEAR(length(dpdx), 0.04f, 1e-3f);
  // Seen at 60 degrees from the normal, the footprint stretches by 1 / cos.
  footprint_from_camera(spread, {0, 0, 0}, {std::sin(1.0471976f), 0, std::cos(1.0471976f)}, dpdx, dpdy);
  EXPECT_NEAR(std::max(length(dpdx), length(dpdy)), 0.08f, 2e-3f);
  // A differential whose offset rays miss the plane (parallel) gives none.
  const RayDifferential parallel{{0, 0, 1}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}};
  EXPECT_FALSE(footprint_from_differential(parallel, {0, 0, 0}, {0, 0, 1}, dpdx, dpdy));
}

}  // namespace
}  // namespace pt
