// Catalogue section 9 (docs/numerical-stability.md): lights of zero area or
// zero power, a one-sided area light seen from behind, a very bright very small
// light. For every backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "render_util.h"

namespace pt {
namespace {

using test::add_material;
using test::add_shape;
using test::add_sphere;

class DifficultLights : public test::PerBackend {};

Quad quad(Vec3f a, Vec3f b, Vec3f c, Vec3f e) {
  Quad q;
  q.v[0] = a;
  q.v[1] = b;
  q.v[2] = c;
  q.v[3] = e;
  return q;
}

// A floor, a sphere and an ordinary area light.
SceneDescription lit_floor() {
  SceneDescription d = test::empty_scene(32, 24, {0.3f, 1.2f, 4.0f}, {0, 0.4f, 0}, {0, 1, 0}, 45);
  add_shape(d, quad({-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}),
            add_material(d, test::lambert_material(RGB(0.6f, 0.6f, 0.5f))));
  add_sphere(d, {-0.4f, 0.5f, 0.2f}, 0.5f, add_material(d, test::lambert_material(RGB(0.3f, 0.5f, 0.7f))));
  add_shape(d, quad({-0.5f, 2, -0.5f}, {0.5f, 2, -0.5f}, {0.5f, 2, 0.5f}, {-0.5f, 2, 0.5f}),  // faces down
            add_material(d, test::emitter_material(RGB(8.0f, 7.0f, 6.0f))));
  return d;
}

// Emitters that cannot emit: zero area (a quad collapsed to a point, a
// degenerate triangle, a sphere of radius 0) or zero power. Sampling them
// would divide by a zero area; selection by power never picks them, so the
// image is bit for bit the one without them (the zero-power quad is far
// outside the scene, where it blocks nothing).
TEST_P(DifficultLights, ZeroAreaAndZeroPowerLightsChangeNothing) {
  const SceneDescription base = lit_floor();
  const IntegratorSettings settings = test::path_settings(8, 5);
  const test::Rendered without = test::render_film_on(kind(), base, settings);
  const Image& expected = without.image;
  ASSERT_TRUE(test::all_finite(expected));
  ASSERT_EQ(without.non_finite.total(), 0u) << without.non_finite.describe();

  SceneDescription d = base;
  const int bright = add_material(d, test::emitter_material(RGB(1e4f)));
  const Vec3f p(0.7f, 1.0f, 0.4f);
  add_shape(d, quad(p, p, p, p), bright);
  add_shape(d, make_triangle(Vec3f(-1, 1, 0), Vec3f(0, 1, 0), Vec3f(1, 1, 0)), bright);  // collinear
  add_sphere(d, {0.2f, 1.5f, -0.5f}, 0.0f, bright);
  MaterialDesc dark = test::emitter_material(RGB(0.0f));
  dark.two_sided = true;
  add_shape(d, quad({-50, 50, 50}, {-49, 50, 50}, {-49, 51, 50}, {-50, 51, 50}), add_material(d, dark));
  const test::Rendered with = test::render_film_on(kind(), d, settings);
  EXPECT_EQ(with.non_finite.total(), 0u) << with.non_finite.describe();
  const Image& img = with.image;
  ASSERT_EQ(img.pixels.size(), expected.pixels.size());
  EXPECT_EQ(std::memcmp(img.pixels.data(), expected.pixels.data(), img.pixels.size() * sizeof(RGB)), 0);
}

// A one-sided area light facing up (+y), a floor below it, nothing above: the
// light emits into empty space, so from below (a camera under the light's
// plane) everything is black, exactly: its back and the floor. Turned to face
// down it lights the floor.
TEST_P(DifficultLights, OneSidedLightSeenFromBehindIsBlackAndLightsNothingBehindIt) {
  for (bool faces_up : {true, false}) {
    SceneDescription d = test::empty_scene(24, 24, {0, 0.8f, 3}, {0, 0.5f, 0}, {0, 1, 0}, 60);
    add_shape(d, quad({-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}),
              add_material(d, test::lambert_material(RGB(0.8f))));
    const int e = add_material(d, test::emitter_material(RGB(5.0f)));
    if (faces_up)
      add_shape(d, quad({-0.5f, 1, -0.5f}, {-0.5f, 1, 0.5f}, {0.5f, 1, 0.5f}, {0.5f, 1, -0.5f}), e);
    else
      add_shape(d, quad({-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}), e);
    const Image img = test::render_on(kind(), d, test::path_settings(8, 5));
    const test::Stats s = test::image_stats(img);
    if (faces_up) {
      for (const RGB& p : img.pixels) ASSERT_EQ(p, RGB(0.0f));
    } else {
      EXPECT_GT(s.mean, 0.05);
    }
  }
}

// A sphere light of radius 1e-3 and radiance 1e6 above a Lambert floor
// (albedo 0.5), direct light only: the floor's radiance is exactly
// rho * Le * (r/d)^2 * cos(theta) (a sphere's irradiance is pi Le sin^2(alpha)
// cos(theta) while it is above the horizon), about 0.5 under the light.
// Sampled by solid angle, each estimate is nearly exact, so every floor pixel
// is within 2% of the closed form averaged over its footprint (the sample
// positions in the pixel leave about 0.4% of noise at 16 spp). The camera sees
// the light itself in at most the 4 pixels around its projection. With a wall
// bouncing light back (depth 5), no pixel away from the light is a firefly:
// none exceeds 4x the median of its 3x3 neighbourhood.
float median_of_neighbours(const Image& img, int x, int y) {
  std::vector<float> v;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = x + dx, yy = y + dy;
      if (xx >= 0 && yy >= 0 && xx < img.width && yy < img.height) v.push_back(img.at(xx, yy).r);
    }
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST_P(DifficultLights, TinyBrightSphereLightIsExactAndFireflyFree) {
  const float radius = 1e-3f, le = 1e6f, rho = 0.5f;
  const Vec3f light(0, 1, 0);
  // Straight down from (0, 3, 0) with a vertical field of view of 2 atan(1/3):
  // the image covers the floor square [-1, 1]^2, 1/32 of a unit per pixel.
  SceneDescription d = test::empty_scene(64, 64, {0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 36.8699f);
  add_shape(d, quad({-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}), add_material(d, test::lambert_material(RGB(rho))));
  add_sphere(d, light, radius, add_material(d, test::emitter_material(RGB(le))));

  auto closed_form = [&](float u, float w) {
    const Vec3f to = light - Vec3f(u, 0, w);
    const float dist = length(to);
    return rho * le * (radius / dist) * (radius / dist) * (to.y / dist);
  };
  const test::Rendered direct_render = test::render_film_on(kind(), d, test::path_settings(16, 1));
  const Image& direct = direct_render.image;
  ASSERT_TRUE(test::all_finite(direct));
  ASSERT_EQ(direct_render.non_finite.total(), 0u) << direct_render.non_finite.describe();
  int light_pixels = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const float v = direct.at(x, y).r;
      if (v > 10.0f) {  // the light itself
        ++light_pixels;
        EXPECT_TRUE((x == 31 || x == 32) && (y == 31 || y == 32)) << x << "," << y;
        continue;
      }
      // The closed form averaged over the pixel's footprint (8x8 midpoints).
      // It is symmetric in u and w, so the image's orientation does not matter.
      double expected = 0;
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i)
          expected += closed_form((x + (i + 0.5f) / 8) / 32 - 1, (y + (j + 0.5f) / 8) / 32 - 1) / 64.0;
      ASSERT_NEAR(v, expected, 0.02 * expected) << x << "," << y;
    }
  EXPECT_LE(light_pixels, 4);

  add_shape(d, quad({1.2f, 0, -3}, {1.2f, 3, -3}, {1.2f, 3, 3}, {1.2f, 0, 3}),  // a wall at x = 1.2 facing -x
            add_material(d, test::lambert_material(RGB(0.9f))));
  const test::Rendered bounced_render = test::render_film_on(kind(), d, test::path_settings(16, 5));
  const Image& bounced = bounced_render.image;
  ASSERT_TRUE(test::all_finite(bounced));
  ASSERT_EQ(bounced_render.non_finite.total(), 0u) << bounced_render.non_finite.describe();
  int fireflies = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      if (x >= 30 && x <= 33 && y >= 30 && y <= 33) continue;  // around the light
      if (bounced.at(x, y).r > 4.0f * median_of_neighbours(bounced, x, y)) ++fireflies;
    }
  EXPECT_EQ(fireflies, 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, DifficultLights, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt
