// The classic integrator against closed-form answers on scenes built in code.
#include <cmath>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/builtin.h"
#include "render/integrators/integrator.h"
#include "test_scenes.h"

namespace pt {
namespace {

using test::add_material;
using test::add_point_light;
using test::add_sphere;
using test::add_z_square;

void expect_rgb_rel(RGB actual, RGB expected, float rel) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(actual[c], expected[c], rel * std::fabs(expected[c]) + 1e-7f) << "channel " << c;
}

Image render(const RenderScene& scene, const std::string& name, int max_depth, WorkerPool& pool, int spp = 1) {
  IntegratorSettings settings;
  settings.max_depth = max_depth;
  settings.spp = spp;
  std::string error;
  auto integrator = make_integrator(name, settings, error);
  EXPECT_TRUE(integrator) << error;
  Film film(scene.width, scene.height);
  integrator->render(scene, film, pool);
  return film.image();
}

// A Lambert-like floor (kd = 1, ks = 0) lit by a point light straight above:
// L = kd * diffuse * I * cos(theta) / r^2, no pi, no ambient.
TEST(Whitted, DiffuseMatchesClosedForm) {
  WorkerPool pool(2);
  const float h = 2.0f;
  const RGB diffuse(0.5f, 0.25f, 1.0f), intensity(3.0f, 3.0f, 3.0f);
  SceneDescription d = test::empty_scene(9, 9, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30);
  add_z_square(d, 0.0f, 10.0f, add_material(d, test::diffuse_material(diffuse, 1.0f)));
  add_point_light(d, {0, 0, h}, intensity, RGB(0));
  auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  const Image img = render(*scene, "whitted", 5, pool);

  // Centre pixel: the camera ray hits the point right below the light.
  expect_rgb_rel(img.at(4, 4), diffuse * intensity / (h * h), 1e-4f);
  // Every pixel: the hit point p on z = 0 gives r^2 = |p - light|^2 and cos = h / r.
  for (int y = 0; y < 9; ++y) {
    for (int x = 0; x < 9; ++x) {
      const Ray ray = scene->camera.generate_ray({x + 0.5f, y + 0.5f});
      const Vec3f p = ray.at(-ray.origin.z / ray.dir.z);
      const float r2 = length_squared(p - Vec3f(0, 0, h));
      const float cos_theta = h / std::sqrt(r2);
      expect_rgb_rel(img.at(x, y), diffuse * intensity * (cos_theta / r2), 1e-4f);
    }
  }
}

// The CGR course's lights do not fall off with distance: L = kd * diffuse * I * cos(theta).
TEST(Whitted, LightWithoutFalloff) {
  WorkerPool pool(1);
  const RGB diffuse(0.5f, 0.25f, 1.0f);
  SceneDescription d = test::empty_scene(9, 9, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30);
  add_z_square(d, 0.0f, 10.0f, add_material(d, test::diffuse_material(diffuse, 0.9f)));
  add_point_light(d, {0, 0, 3}, RGB(0.75f), RGB(0.75f), /*inverse_square=*/false);
  auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  const Vec3f eye(0, 0, 5), p(1.0f, 0.5f, 0.0f);
  const float cos_theta = 3.0f / length(Vec3f(0, 0, 3) - p);
  expect_rgb_rel(whitted_radiance(*scene, Ray{eye, normalize(p - eye)}, 5), diffuse * (0.9f * 0.75f * cos_theta),
                 1e-4f);
}

// Blinn-Phong lobe: with the light and the eye both straight above, n.h = 1.
TEST(Whitted, SpecularMatchesClosedForm) {
  WorkerPool pool(2);
  MaterialDesc m;
  m.kd = 0.0f;
  m.ks = 0.5f;
  m.exponent = 10.0f;
  m.specular = RGB(1.0f, 0.5f, 0.25f);
  SceneDescription d = test::empty_scene(9, 9, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30);
  add_z_square(d, 0.0f, 10.0f, add_material(d, m));
  add_point_light(d, {0, 0, 2}, RGB(100), RGB(8.0f));
  auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  const Ray centre = scene->camera.generate_ray({4.5f, 4.5f});
  expect_rgb_rel(whitted_radiance(*scene, centre, 5), RGB(1.0f, 0.5f, 0.25f) * (0.5f * 8.0f / 4.0f), 1e-4f);
  // Off-centre: n.h < 1, so the lobe falls off as (n.h)^10.
  const Vec3f p(0.8f, 0.0f, 0.0f), eye(0, 0, 5), light(0, 0, 2);
  const Vec3f l = normalize(light - p), v = normalize(eye - p);
  const float nh = normalize(l + v).z;
  const Ray off{eye, normalize(p - eye)};
  expect_rgb_rel(whitted_radiance(*scene, off, 5),
                 RGB(1.0f, 0.5f, 0.25f) * (0.5f * std::pow(nh, 10.0f) * 8.0f / length_squared(light - p)), 1e-4f);
}

// The floor point below an occluder gets nothing from the light (no ambient); a
// point beside the shadow is fully lit.
TEST(Whitted, HardShadow) {
  WorkerPool pool(2);
  SceneDescription d = test::empty_scene(16, 16, {3, 0, 3}, {0, 0, 0}, {0, 0, 1}, 40);
  const int floor = add_material(d, test::diffuse_material(RGB(1), 1.0f));
  add_z_square(d, 0.0f, 10.0f, floor);
  add_sphere(d, {0, 0, 1}, 0.3f, floor);
  add_point_light(d, {0, 0, 2}, RGB(4), RGB(0));
  auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  const Vec3f eye(3, 0, 3);
  EXPECT_EQ(whitted_radiance(*scene, Ray{eye, normalize(Vec3f(0, 0, 0) - eye)}, 5), RGB(0, 0, 0));
  EXPECT_EQ(whitted_radiance(*scene, Ray{eye, normalize(Vec3f(0.4f, 0.3f, 0) - eye)}, 5), RGB(0, 0, 0));
  const Vec3f lit(1.5f, 0, 0);
  const float r2 = length_squared(Vec3f(0, 0, 2) - lit);
  expect_rgb_rel(whitted_radiance(*scene, Ray{eye, normalize(lit - eye)}, 5), RGB(4 * (2 / std::sqrt(r2)) / r2),
                 1e-4f);
}

// Mirror: a perfect mirror (reflectivity 1) in the plane z = 0 shows exactly
// what a camera sees of the mirrored scene (object and light reflected in z = 0)
// without the mirror.
TEST(Whitted, MirrorShowsTheReflectedScene) {
  WorkerPool pool(2);
  auto object = [] {
    MaterialDesc m = test::diffuse_material(RGB(0.8f, 0.4f, 0.2f), 0.9f);
    m.ks = 0.4f;
    m.exponent = 12.0f;
    return m;
  }();
  auto make = [&](bool with_mirror) {
    SceneDescription d = test::empty_scene(48, 36, {0.3f, -3, 2.5f}, {0, 0, 0}, {0, 0, 1}, 50);
    d.render.background = RGB(0.1f, 0.2f, 0.3f);
    const int obj = add_material(d, object);
    const float side = with_mirror ? 1.0f : -1.0f;
    if (with_mirror) {
      MaterialDesc mirror = test::diffuse_material(RGB(1), 1.0f);
      mirror.reflectivity = 1.0f;
      add_z_square(d, 0.0f, 50.0f, add_material(d, mirror));
    }
    add_sphere(d, {0.2f, 0.1f, side * 0.8f}, 0.5f, obj);
    add_point_light(d, {2.0f, -1.0f, side * 1.0f}, RGB(6), RGB(3));
    return d;
  };
  auto with = test::build(make(true), pool);
  auto without = test::build(make(false), pool);
  ASSERT_TRUE(with && without);
  const Image a = render(*with, "whitted", 3, pool);
  const Image b = render(*without, "whitted", 3, pool);

  int compared = 0, showing_object = 0, off = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      Intersection isect;
      if (!with->intersect(with->camera.generate_ray({x + 0.5f, y + 0.5f}), isect) || isect.hit.shape != 0) continue;
      ++compared;
      if (!(b.at(x, y) == RGB(0.1f, 0.2f, 0.3f))) ++showing_object;
      const RGB da = a.at(x, y) - b.at(x, y);
      if (std::fabs(da.r) + std::fabs(da.g) + std::fabs(da.b) > 1e-4f) ++off;
    }
  }
  EXPECT_GT(compared, 48 * 36 / 3);
  EXPECT_GT(showing_object, 50);  // the reflection really shows the sphere
  // Pixels whose ray grazes the sphere's silhouette may flip between hit and miss.
  EXPECT_LE(off, compared / 100) << off << " of " << compared << " mirror pixels differ";
}

// reflectivity r blends: (1 - r) * local + r * reflected; beyond max_depth a ray carries nothing.
TEST(Whitted, ReflectivityBlendAndDepthLimit) {
  WorkerPool pool(1);
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 30);
  MaterialDesc mirror = test::emitter_material(RGB(0.2f, 0, 0));
  mirror.reflectivity = 0.25f;
  add_z_square(d, 0.0f, 10.0f, add_material(d, mirror));
  add_z_square(d, 2.0f, 10.0f, add_material(d, test::emitter_material(RGB(0, 1, 0))));
  auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  const Ray down{{0, 0, 1}, {0, 0, -1}};
  expect_rgb_rel(whitted_radiance(*scene, down, 1), RGB(0.15f, 0.25f, 0), 1e-6f);
  expect_rgb_rel(whitted_radiance(*scene, down, 0), RGB(0.15f, 0, 0), 1e-6f);
}

TEST(Fresnel, KnownValues) {
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f, 1.5f), 0.04f, 1e-6f);  // ((n-1)/(n+1))^2
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f, 1.0f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f, 1.0f), 0.0f, 1e-7f);
  // Brewster's angle (tan = 1.5): the p-polarised part vanishes, Rs = 0.1479.
  const float brewster = std::atan(1.5f);
  EXPECT_NEAR(fresnel_dielectric(std::cos(brewster), 1.0f, 1.5f), 0.5f * 0.147929f, 2e-5f);
  // Total internal reflection beyond the critical angle asin(1/1.5) = 41.81 degrees.
  EXPECT_EQ(fresnel_dielectric(std::cos(42.5f * kPi / 180), 1.5f, 1.0f), 1.0f);
  EXPECT_LT(fresnel_dielectric(std::cos(41.0f * kPi / 180), 1.5f, 1.0f), 1.0f);
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.0f, 1.5f), 1.0f, 1e-6f);  // grazing
}

// A dielectric interface in z = 0 (ior 1.5) with a green emitter below and a
// red one above: what a ray sees splits by the exact Fresnel weight.
class Dielectric : public ::testing::Test {
 protected:
  void SetUp() override {
    SceneDescription d = test::empty_scene(8, 8, {0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 30);
    MaterialDesc glass;
    glass.refractive = true;
    glass.ior = 1.5f;
    add_z_square(d, 0.0f, 100.0f, add_material(d, glass));
    add_z_square(d, -1.0f, 100.0f, add_material(d, test::emitter_material(RGB(0, 1, 0))));
    add_z_square(d, 1.0f, 100.0f, add_material(d, test::emitter_material(RGB(1, 0, 0))));
    scene_ = test::build(d, pool_);
    ASSERT_TRUE(scene_);
    // The square's outward side is +z (corners counter-clockwise from above): below is inside.
    Intersection probe;
    ASSERT_TRUE(scene_->intersect(Ray{{0, 0, 0.5f}, {0, 0, -1}}, probe));
    ASSERT_GT(probe.geo.ng.z, 0.99f);
  }
  // A ray from inside the glass (z = -0.5) going up at `degrees` from the normal.
  RGB from_inside(float degrees) const {
    const float a = degrees * kPi / 180.0f;
    return whitted_radiance(*scene_, Ray{{0, 0, -0.5f}, {std::sin(a), 0, std::cos(a)}}, 4);
  }

  WorkerPool pool_{1};
  std::unique_ptr<RenderScene> scene_;
};

TEST_F(Dielectric, TotalInternalReflection) {
  for (float deg : {42.5f, 60.0f, 80.0f}) {
    const RGB c = from_inside(deg);
    EXPECT_NEAR(c.g, 1.0f, 1e-5f) << deg;
    EXPECT_EQ(c.r, 0.0f) << deg;
  }
  const RGB below_critical = from_inside(41.0f);
  EXPECT_GT(below_critical.r, 0.0f);
  EXPECT_NEAR(below_critical.r + below_critical.g, 1.0f, 1e-5f);
}

TEST_F(Dielectric, NormalIncidenceSplitsFourPercent) {
  expect_rgb_rel(from_inside(0.0f), RGB(0.96f, 0.04f, 0), 1e-4f);
  // From outside (entering): 4% reflected back up to red, 96% transmitted to green.
  const RGB outside = whitted_radiance(*scene_, Ray{{0, 0, 0.5f}, {0, 0, -1}}, 4);
  expect_rgb_rel(outside, RGB(0.04f, 0.96f, 0), 1e-4f);
}

TEST_F(Dielectric, ObliqueSplitFollowsFresnel) {
  const float deg = 30.0f;
  const float F = fresnel_dielectric(std::cos(deg * kPi / 180), 1.5f, 1.0f);
  expect_rgb_rel(from_inside(deg), RGB(1 - F, F, 0), 1e-4f);
  EXPECT_EQ(whitted_radiance(*scene_, Ray{{0, 0, -0.5f}, {0, 0, 1}}, 0), RGB(0, 0, 0));  // depth limit
}

// An area light (a square lamp of side 1 at height 4, facing down) above a
// white floor, with an occluder of the same size at height 2 between them:
// its shadow is black only under the occluder (|x| <= 0.5), a penumbra out to
// |x| = 1.5 where part of the lamp shows, and full light beyond.
class AreaLightShadow : public ::testing::Test {
 protected:
  static std::unique_ptr<RenderScene> build(WorkerPool& pool, bool occluder) {
    SceneDescription d = test::empty_scene(9, 9, {0, 0, 8}, {0, 0, 0}, {0, 1, 0}, 30);
    add_z_square(d, 0.0f, 10.0f, add_material(d, test::diffuse_material(RGB(1.0f))));
    MaterialDesc lamp = test::emitter_material(RGB(2.0f));
    lamp.two_sided = true;  // the square's normal is +z
    add_z_square(d, 4.0f, 0.5f, add_material(d, lamp));
    if (occluder) add_z_square(d, 2.0f, 0.5f, add_material(d, test::diffuse_material(RGB(0.5f))));
    return test::build(d, pool);
  }
  // The floor at (x, 0, 0), seen from just above it.
  static RGB floor_at(const RenderScene& scene, float x) {
    return whitted_radiance(scene, Ray{{x, 0.0f, 0.01f}, {0, 0, -1}}, 1);
  }
};

TEST_F(AreaLightShadow, OccluderCastsAPenumbraNotAHardShadow) {
  WorkerPool pool(2);
  const auto open = build(pool, false);
  const auto shadowed = build(pool, true);
  ASSERT_TRUE(open && shadowed);
  EXPECT_EQ(floor_at(*shadowed, 0.0f), RGB(0, 0, 0));  // the umbra: no sample sees the lamp
  EXPECT_EQ(floor_at(*shadowed, 0.3f), RGB(0, 0, 0));
  // Half the lamp (x > 0 on it) is seen from x = 1: the 4 x 4 strata split
  // there, so 8 of the 16 default samples pass, the nearer half a little brighter.
  const float half = floor_at(*shadowed, 1.0f).r / floor_at(*open, 1.0f).r;
  EXPECT_GT(half, 0.4f);
  EXPECT_LT(half, 0.6f);
  // Inside the penumbra the light grows with x.
  EXPECT_LT(floor_at(*shadowed, 0.7f).r, floor_at(*shadowed, 1.0f).r);
  EXPECT_LT(floor_at(*shadowed, 1.0f).r, floor_at(*shadowed, 1.3f).r);
  EXPECT_GT(floor_at(*shadowed, 0.7f).r, 0.0f);
  // Beyond the penumbra nothing is occluded: the same samples, the same value.
  EXPECT_EQ(floor_at(*shadowed, 1.6f), floor_at(*open, 1.6f));
  EXPECT_GT(floor_at(*open, 1.6f).r, 0.0f);
}

// Right below the lamp the floor receives kd Cd E / pi in the point lights'
// units, E = L times the lamp's projected solid angle (exact for a rectangle
// seen from a point on its axis, below); 16 stratified samples of a lamp this
// small are within 0.1% (tolerance 2%).
TEST_F(AreaLightShadow, BelowTheLampTheClassicUnitsOfThePointLights) {
  WorkerPool pool(2);
  const auto open = build(pool, false);
  ASSERT_TRUE(open);
  // Irradiance under the centre of an a x b rectangle at height h (radiance L):
  // four quadrants, each pi L F with the view factor F = [x/sqrt(1+x^2) atan(y/sqrt(1+x^2))
  // + y/sqrt(1+y^2) atan(x/sqrt(1+y^2))] / (2 pi), x = a / (2h), y = b / (2h).
  const double x = 0.5 / 4.0, y = x;
  const double quadrant = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                           y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                          2.0;
  const double e_over_pi = 2.0 * 4.0 * quadrant / kPi;  // L = 2, four quadrants
  EXPECT_NEAR(floor_at(*open, 0.0f).r, e_over_pi, 0.02 * e_over_pi);
}

}  // namespace
}  // namespace pt
