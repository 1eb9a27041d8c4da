// Catalogue section 8 (docs/numerical-stability.md): total internal reflection,
// refractive index 1, nested and touching glass, for every backend.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "render_util.h"

namespace pt {
namespace {

using test::add_material;
using test::add_shape;
using test::add_sphere;
using test::glass_material;

class Dielectrics : public test::PerBackend {};

// Glass is lossless: in a uniform environment of radiance 1 every path that
// leaves the glass sees radiance 1 and carries weight exactly 1 (reflection and
// refraction are chosen by the Fresnel factor; the radiance scale 1/eta^2 on the
// way in is undone on the way out). So any arrangement of clear glass renders
// as 1 everywhere, and a sample below 1 is a path lost inside: trapped by a
// stray self-intersection (a ray re-hitting the surface it left and ping-ponging
// until the depth limit) or killed by a NaN. With 16 spp a single lost sample
// moves a pixel by 1/16, far beyond the tolerance.
TEST_P(Dielectrics, NestedAndTouchingGlassInAWhiteFurnaceIsExactlyOne) {
  struct Case {
    const char* name;
    void (*add)(SceneDescription&, int glass);
  };
  const Case cases[] = {
      {"concentric spheres", [](SceneDescription& d, int g) {
         add_sphere(d, {0, 0, 0}, 1.0f, g);
         add_sphere(d, {0, 0, 0}, 0.6f, g);
       }},
      {"internally tangent spheres", [](SceneDescription& d, int g) {
         add_sphere(d, {0, 0, 0}, 1.0f, g);
         add_sphere(d, {0.5f, 0, 0}, 0.5f, g);  // touches the outer sphere at (1, 0, 0)
       }},
      {"externally touching spheres", [](SceneDescription& d, int g) {
         add_sphere(d, {-0.5f, 0, 0}, 0.5f, g);
         add_sphere(d, {0.5f, 0, 0}, 0.5f, g);  // touch at the origin, in the middle of the image
       }},
      {"a glass box (mesh) touching a glass sphere", [](SceneDescription& d, int g) {
         add_shape(d, test::box_mesh({-0.8f, -0.5f, -0.5f}, {0, 0.5f, 0.5f}), g);
         add_sphere(d, {0.5f, 0, 0}, 0.5f, g);  // touches the box's face x = 0 at its centre
       }},
      {"tessellated sphere inside a tessellated sphere", [](SceneDescription& d, int g) {
         add_shape(d, test::sphere_mesh({0, 0, 0}, 1.0f, 24, 48), g);
         add_shape(d, test::sphere_mesh({0.2f, 0.1f, 0}, 0.5f, 16, 32), g);
       }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    SceneDescription d = test::empty_scene(40, 40, {0.3f, 0.2f, 4}, {0, 0, 0}, {0, 1, 0}, 35);
    d.render.background = RGB(1.0f);
    c.add(d, add_material(d, glass_material(1.5f)));
    const test::Rendered r = test::render_film_on(kind(), d, test::path_settings(16, 512));
    EXPECT_EQ(r.non_finite.total(), 0u) << r.non_finite.describe();
    const Image& img = r.image;
    ASSERT_EQ(img.pixels.size(), 1600u);
    float lowest = 1.0f, highest = 1.0f;
    for (const RGB& p : img.pixels) {
      lowest = std::min({lowest, p.r, p.g, p.b});
      highest = std::max({highest, p.r, p.g, p.b});
    }
    EXPECT_GT(lowest, 1.0f - 1e-4f);
    EXPECT_LT(highest, 1.0f + 1e-4f);
  }
}

// Two glass boxes sharing a face are two interfaces at the same place: a ray
// reaching it from inside one box meets the leaving face and the entering face
// at the same distance, and whichever the backend reports, the other is lost.
// Without nested-media tracking (docs/numerical-stability.md, section 8) the
// path then counts one interface too few or too many and the radiance scale
// eta^2 of entering and leaving does not cancel. The guarantee is weaker and
// stated as such: nothing non-finite, and energy is never created (no pixel
// of the furnace above 1); the documented remedy is to model the contact as
// one surface.
TEST_P(Dielectrics, CoincidentGlassFacesNeverCreateEnergy) {
  SceneDescription d = test::empty_scene(40, 40, {0.3f, 0.2f, 4}, {0, 0, 0}, {0, 1, 0}, 35);
  d.render.background = RGB(1.0f);
  const int g = add_material(d, glass_material(1.5f));
  add_shape(d, test::box_mesh({-0.8f, -0.5f, -0.5f}, {0, 0.5f, 0.5f}), g);
  add_shape(d, test::box_mesh({0, -0.5f, -0.5f}, {0.8f, 0.5f, 0.5f}), g);  // coincident faces at x = 0
  const test::Rendered r = test::render_film_on(kind(), d, test::path_settings(16, 512));
  const Image& img = r.image;
  ASSERT_TRUE(test::all_finite(img));
  ASSERT_EQ(r.non_finite.total(), 0u) << r.non_finite.describe();  // NaN would be added as black
  for (const RGB& p : img.pixels) ASSERT_LT(p.max_component(), 1.0f + 1e-4f);
}

// A glass slab (a box mesh, index 1.5, 0.5 thick) between the camera and an
// emitter of radiance 1 seen at near-normal incidence (a 2 degree field of
// view): the pixel's expected value is the slab's transmittance with every
// internal reflection summed, (1 - R) / (1 + R) with R = ((n-1)/(n+1))^2 = 0.04,
// i.e. 0.923077 (light reflected back towards the camera meets a black sky).
// Each sample is 0 or 1, so the mean over N samples has standard deviation
// sqrt(T(1-T)/N) = 5.2e-4 here; the tolerance is 5 of those.
TEST_P(Dielectrics, SlabTransmittanceSumsItsInternalReflections) {
  SceneDescription d = test::empty_scene(64, 64, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 2);
  add_shape(d, test::box_mesh({-1, -1, -0.25f}, {1, 1, 0.25f}), add_material(d, glass_material(1.5f)));
  Quad light;  // faces +z, towards the camera
  light.v[0] = Vec3f(-2, -2, -3);
  light.v[1] = Vec3f(2, -2, -3);
  light.v[2] = Vec3f(2, 2, -3);
  light.v[3] = Vec3f(-2, 2, -3);
  add_shape(d, light, add_material(d, test::emitter_material(RGB(1.0f))));
  const Image img = test::render_on(kind(), d, test::path_settings(64, 256));
  const double r = 0.04, expected = (1 - r) / (1 + r);
  const test::Stats s = test::image_stats(img);
  EXPECT_NEAR(s.mean, expected, 5 * std::sqrt(expected * (1 - expected) / (64.0 * 64 * 64)));
}

// Total internal reflection: from inside a slab, beyond the critical angle
// (41.8 degrees for index 1.5), nothing gets out, at either face: the camera
// inside sees black, exactly, under a sky of radiance 1. Below it, it sees light.
TEST_P(Dielectrics, BeyondTheCriticalAngleNothingLeavesTheSlab) {
  auto slab = [&](float view_deg) {
    const float t = view_deg * kPi / 180.0f;
    SceneDescription d = test::empty_scene(16, 16, {0, 0.5f, 0}, {std::sin(t), 0.5f + std::cos(t), 0}, {0, 0, 1}, 6);
    d.render.background = RGB(1.0f);
    add_shape(d, test::box_mesh({-1000, 0, -1000}, {1000, 1, 1000}), add_material(d, glass_material(1.5f)));
    return test::render_on(kind(), d, test::path_settings(16, 200));
  };
  const Image trapped = slab(60.0f);
  for (const RGB& p : trapped.pixels) ASSERT_EQ(p, RGB(0.0f));
  const Image open = slab(20.0f);
  for (const RGB& p : open.pixels) ASSERT_GT(p.r, 1.0f);  // the sky, denser in glass (x 1.5^2 x transmittance)
}

// Index 1: a glass sphere, analytic or tessellated, deflects nothing and
// weighs nothing: the image of a floor under a sky seen through it equals the
// image without it, to the noise.
TEST_P(Dielectrics, IndexOneIsInvisible) {
  SceneDescription base = test::empty_scene(48, 48, {0, 1.5f, 4}, {0, 0.5f, 0}, {0, 1, 0}, 40);
  base.render.background = RGB(0.3f, 0.5f, 0.8f);
  Quad floor;
  floor.v[0] = Vec3f(-3, 0, -3);
  floor.v[1] = Vec3f(-3, 0, 3);
  floor.v[2] = Vec3f(3, 0, 3);
  floor.v[3] = Vec3f(3, 0, -3);
  add_shape(base, floor, add_material(base, test::lambert_material(RGB(0.7f, 0.6f, 0.5f))));
  // A path through the glass draws random numbers for its (delta) glass
  // events and its shadow rays are blocked by the sphere (BSDF sampling then
  // carries that light with full weight), so the two renders' noise differs
  // while their expectations agree: compared statistically.
  const IntegratorSettings settings = test::path_settings(256, 64);
  const Image empty = test::render_on(kind(), base, settings);
  for (int tessellated = 0; tessellated < 2; ++tessellated) {
    SCOPED_TRACE(tessellated ? "tessellated sphere" : "analytic sphere");
    SceneDescription d = base;
    const int g = add_material(d, glass_material(1.0f));
    if (tessellated)
      add_shape(d, test::sphere_mesh({0, 0.6f, 0}, 0.6f, 24, 48), g);
    else
      add_sphere(d, {0, 0.6f, 0}, 0.6f, g);
    const Image with_glass = test::render_on(kind(), d, settings);
    // Noise: compare 8x8-pixel block means, whose standard deviation at 256
    // spp is below 0.004 here (measured); a lost or deflected ray shows as a
    // block off by far more.
    for (int by = 0; by < 6; ++by)
      for (int bx = 0; bx < 6; ++bx) {
        auto in_block = [&](int x, int y) { return x / 8 == bx && y / 8 == by; };
        const double a = test::channel_stats(empty, -1, in_block).mean;
        const double b = test::channel_stats(with_glass, -1, in_block).mean;
        EXPECT_NEAR(a, b, 0.015 + 0.02 * a) << "block " << bx << "," << by;
      }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Dielectrics, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt
