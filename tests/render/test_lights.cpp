// Spot lights (both integrators' falloffs against closed forms, where they
// agree and where they differ, and the power the light set chooses them by),
// the classic ambient light, and their native keys.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "path_test_util.h"
#include "render/integrators/builtin.h"
#include "render/lights/spot_light.h"
#include "scene/loader.h"
#include "test_scenes.h"

namespace pt {
namespace {

constexpr float kHeight = 2.0f;  // the spot above the floor z = 0, pointing down
const RGB kCd(0.6f, 0.5f, 0.4f);

float cos_deg(float d) { return std::cos(d * kPi / 180.0f); }

// A white-ish Lambertian floor under a spot light at (0, 0, 2) pointing down.
SceneDescription spot_scene(float cone, float delta, RGB intensity = RGB(3.0f)) {
  SceneDescription d = test::empty_scene(1, 1, {0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0.001f);
  test::add_z_square(d, 0.0f, 10.0f, test::add_material(d, test::diffuse_material(kCd, 1.0f)));
  SpotLightDesc s;
  s.position = Vec3f(0, 0, kHeight);
  s.direction = Vec3f(0, 0, -1);
  s.intensity = intensity;
  s.specular_intensity = intensity;
  s.cone_angle = cone;
  s.cone_delta = delta;
  d.lights.emplace_back(s);
  return d;
}

// The floor point seen at angle theta (its cosine) from the spot's axis.
Vec3f floor_point(float cos_theta) {
  const float tan_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta)) / cos_theta;
  return {kHeight * tan_theta, 0.0f, 0.0f};
}

// The radiance of the floor at p under the spot: kd Cd I cos / r^2 times the cone factor.
RGB expected(Vec3f p, float factor, RGB intensity = RGB(3.0f)) {
  const float r2 = kHeight * kHeight + p.x * p.x;
  return kCd * intensity * (factor * (kHeight / std::sqrt(r2)) / r2);
}

// One pixel looking straight down at p from 1 above through a 0.001 degree field of view.
RGB render_at(SceneDescription d, const std::string& integrator, Vec3f p) {
  d.camera.position = p + Vec3f(0, 0, 1);
  d.camera.look_at = p;
  const Image img = test::render_with(d, integrator, test::path_settings(4, 1));
  return img.pixels.empty() ? RGB(-1.0f) : img.pixels[0];
}

void expect_rgb_near(RGB got, RGB want, float rel) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], rel * std::fabs(want[c]) + 1e-7f) << "channel " << c;
}

TEST(SpotLight, FactorsAreOneInsideZeroOutsideAndHalfWayInTheMiddle) {
  SpotLight s;
  s.cos_end = cos_deg(30.0f);
  s.cos_start = cos_deg(20.0f);
  const float mid = 0.5f * (s.cos_end + s.cos_start), quarter = s.cos_end + 0.25f * (s.cos_start - s.cos_end);
  for (float c : {1.0f, cos_deg(10.0f), s.cos_start}) {
    EXPECT_EQ(s.classic_factor(c), 1.0f);
    EXPECT_EQ(s.smooth_factor(c), 1.0f);
  }
  for (float c : {s.cos_end, cos_deg(35.0f), 0.0f, -1.0f}) {
    EXPECT_EQ(s.classic_factor(c), 0.0f);
    EXPECT_EQ(s.smooth_factor(c), 0.0f);
  }
  EXPECT_NEAR(s.classic_factor(mid), 0.5f, 1e-5f);
  EXPECT_NEAR(s.smooth_factor(mid), 0.5f, 1e-5f);
  EXPECT_NEAR(s.classic_factor(quarter), 0.25f, 1e-4f);
  EXPECT_NEAR(s.smooth_factor(quarter), 0.15625f, 1e-4f);  // t^2 (3 - 2t) at t = 1/4
  // No band: a hard edge at the cone in both.
  s.cos_start = s.cos_end;
  EXPECT_EQ(s.classic_factor(s.cos_end + 1e-6f), 1.0f);
  EXPECT_EQ(s.smooth_factor(s.cos_end - 1e-6f), 0.0f);
}

TEST(SpotLight, PowerIsPiIntensityTimesTheWeightedCone) {
  // A cone of 180 degrees without a band is a point light: 4 pi^2 I.
  SpotLight full;
  full.intensity = RGB(2.0f);
  full.cos_end = full.cos_start = -1.0f;
  PointLight point;
  point.intensity = RGB(2.0f);
  EXPECT_NEAR(full.power(1.0f), point.power(1.0f), 1e-4f * point.power(1.0f));
  // The smoothstep band integrates to half its width in the cosine (pbrt-v4's Phi).
  SpotLight s = full;
  s.cos_end = 0.5f;
  s.cos_start = 0.9f;
  EXPECT_NEAR(s.power(1.0f), kPi * 2.0f * 2.0f * kPi * (0.1f + 0.2f), 1e-4f);
}

// Irradiance from both integrators against the closed form: inside the falloff
// start, outside the cone, half-way through the band (where the two agree) and
// a quarter of the way in (where the classic ramp gives 1/4, smoothstep 5/32).
TEST(SpotLight, BothIntegratorsMatchTheClosedFormInsideOutsideAndAtTheEdge) {
  const SceneDescription d = spot_scene(30.0f, 10.0f);
  const float c_end = cos_deg(30.0f), c_start = cos_deg(20.0f);
  struct Case {
    float cos_theta, classic, path;
  };
  const Case cases[] = {{cos_deg(10.0f), 1.0f, 1.0f},
                        {cos_deg(40.0f), 0.0f, 0.0f},
                        {0.5f * (c_end + c_start), 0.5f, 0.5f},
                        {c_end + 0.25f * (c_start - c_end), 0.25f, 0.15625f}};
  for (const Case& c : cases) {
    const Vec3f p = floor_point(c.cos_theta);
    SCOPED_TRACE("x = " + std::to_string(p.x));
    expect_rgb_near(render_at(d, "whitted", p), expected(p, c.classic), 2e-3f);
    expect_rgb_near(render_at(d, "path", p), expected(p, c.path), 2e-3f);
  }
}

// With a hard edge (cone_delta 0) the two integrators are the same model: they
// agree on every pixel of an image that holds the whole disc of light.
TEST(SpotLight, PathAndWhittedAgreeOnAHardEdgedSpot) {
  SceneDescription d = spot_scene(25.0f, 0.0f);
  d.film.width = d.film.height = 24;
  d.camera.position = Vec3f(0, 0, 6);
  d.camera.look_at = Vec3f(0, 0, 0);
  d.camera.fov_y_deg = 30.0f;
  const Image whitted = test::render_with(d, "whitted", test::path_settings(64, 1));
  const Image path = test::render_path(d, test::path_settings(64, 1));
  ASSERT_EQ(whitted.pixels.size(), path.pixels.size());
  // Pixels on the edge are averages of lit and unlit samples at different
  // positions (the pixel grid vs Sobol): compare the image mean (both converge
  // to the pixel integral, 64 samples each) and every pixel whose footprint on
  // the floor (0.134 wide) is clear of the edge (radius 2 tan 25 deg).
  const double mw = test::image_stats(whitted).mean, mp = test::image_stats(path).mean;
  EXPECT_GT(mw, 0.0);
  EXPECT_NEAR(mp, mw, 1e-2 * mw);
  const float half = 6.0f * std::tan(15.0f * kPi / 180.0f), edge = 2.0f * std::tan(25.0f * kPi / 180.0f);
  int lit = 0, dark = 0;
  for (int y = 0; y < 24; ++y) {
    for (int x = 0; x < 24; ++x) {
      const float fx = ((x + 0.5f) / 24.0f * 2.0f - 1.0f) * half, fy = ((y + 0.5f) / 24.0f * 2.0f - 1.0f) * half;
      const float rho = std::sqrt(fx * fx + fy * fy);
      if (std::fabs(rho - edge) < 0.12f) continue;
      const float w = whitted.at(x, y).r, p = path.at(x, y).r;
      lit += rho < edge;
      dark += rho > edge;
      if (rho > edge) {
        ASSERT_EQ(w, 0.0f);
        ASSERT_EQ(p, 0.0f);
      }
      // Inside, the shading varies by a few per cent across a pixel: both average it.
      ASSERT_NEAR(p, w, 2e-3f * w + 1e-7f) << x << ", " << y;
    }
  }
  EXPECT_GT(lit, 100);
  EXPECT_GT(dark, 100);
}

// ---------------------------------------------------------------- ambient light
// The classic ambient term ka Cd I_a, unshadowed, with ka = kd unless given;
// the path integrator has none.
TEST(AmbientLight, ClassicTermIsKaTimesDiffuseTimesIntensityUnshadowed) {
  SceneDescription d = test::empty_scene(1, 1, {0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0.001f);
  const int floor = test::add_material(d, test::diffuse_material(kCd, 0.8f));
  MaterialDesc weighted = test::diffuse_material(kCd, 0.8f);
  weighted.ka = Sourced<float>(0.1f);
  const int floor_ka = test::add_material(d, weighted);
  Quad left, right;  // two halves of the floor, x < 0 and x > 0
  left.v[0] = Vec3f(-4, -4, 0), left.v[1] = Vec3f(0, -4, 0), left.v[2] = Vec3f(0, 4, 0), left.v[3] = Vec3f(-4, 4, 0);
  right.v[0] = Vec3f(0, -4, 0), right.v[1] = Vec3f(4, -4, 0), right.v[2] = Vec3f(4, 4, 0), right.v[3] = Vec3f(0, 4, 0);
  test::add_shape(d, left, floor);
  test::add_shape(d, right, floor_ka);
  test::add_sphere(d, Vec3f(0, 0, 0.5f), 0.1f, floor);  // shadows nothing of the ambient term
  AmbientLightDesc a;
  a.intensity = RGB(0.5f, 1.0f, 2.0f);
  d.lights.emplace_back(a);
  const Vec3f p_left(-1, 0, 0), p_right(1, 0, 0);
  expect_rgb_near(render_at(d, "whitted", p_left), kCd * RGB(0.5f, 1.0f, 2.0f) * 0.8f, 1e-6f);
  expect_rgb_near(render_at(d, "whitted", p_right), kCd * RGB(0.5f, 1.0f, 2.0f) * 0.1f, 1e-6f);
  EXPECT_EQ(render_at(d, "path", p_left), RGB(0.0f));  // no ambient term, and nothing else lights it
}

// ---------------------------------------------------------------- the native format
std::string scene_with_light(const std::string& light) {
  return R"({ "format": "pathtracer-scene", "version": 1,
              "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0] },
              "materials": { "m": {} },
              "shapes": [{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" }],
              "lights": [)" + light + "] }";
}

TEST(SpotLightFormat, LookAtGivesTheAxisAndDefaultsArePbrtV4s) {
  Diagnostics diag;
  const auto s = load_scene_from_string(
      "mem.json", scene_with_light(R"({ "type": "spot", "position": [0, 4, 0], "look_at": [0, 0, 0], "intensity": [1, 1, 1] })"),
      {}, diag);
  ASSERT_TRUE(s) << diag.format();
  const auto* spot = std::get_if<SpotLightDesc>(&s->lights.at(0));
  ASSERT_NE(spot, nullptr);
  EXPECT_EQ(spot->direction.value, Vec3f(0, -4, 0));
  EXPECT_EQ(spot->cone_angle.value, 30.0f);
  EXPECT_EQ(spot->cone_delta.value, 5.0f);
}

TEST(AmbientLightFormat, TypeAmbientWithIntensityAndTheMaterialsKa) {
  Diagnostics diag;
  std::string text = scene_with_light(R"({ "type": "ambient", "intensity": [0.1, 0.2, 0.3] })");
  text.replace(text.find(R"("m": {})"), 7, R"("m": { "kd": 0.5, "ka": 0.25 })");
  const auto s = load_scene_from_string("mem.json", text, {}, diag);
  ASSERT_TRUE(s) << diag.format();
  const auto* ambient = std::get_if<AmbientLightDesc>(&s->lights.at(0));
  ASSERT_NE(ambient, nullptr);
  EXPECT_EQ(ambient->intensity.value, RGB(0.1f, 0.2f, 0.3f));
  ASSERT_TRUE(s->materials.at(0).ka.has_value());
  EXPECT_EQ(s->materials.at(0).ka->value, 0.25f);
  Diagnostics bad;
  text.replace(text.find("0.25"), 4, "-1.0");
  EXPECT_FALSE(load_scene_from_string("mem.json", text, {}, bad));
  EXPECT_NE(bad.format().find("ka must be >= 0"), std::string::npos) << bad.format();
}

TEST(SpotLightFormat, BadInputIsRefusedAtItsPlace) {
  const struct {
    const char* light;
    const char* message;
  } cases[] = {
      {R"({ "type": "spot", "position": [0, 4, 0], "intensity": [1, 1, 1] })", "missing key 'direction'"},
      {R"({ "type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "look_at": [0, 0, 0], "intensity": [1, 1, 1] })",
       "'direction' or 'look_at', not both"},
      {R"({ "type": "spot", "position": [0, 4, 0], "look_at": [0, 4, 0], "intensity": [1, 1, 1] })",
       "direction must not be zero"},
      {R"({ "type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "intensity": [1, 1, 1], "cone_angle": 0 })",
       "cone_angle must be between"},
      {R"({ "type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "intensity": [1, 1, 1], "cone_delta": 40 })",
       "cone_delta must be between 0 and cone_angle"},
  };
  for (const auto& c : cases) {
    Diagnostics diag;
    EXPECT_FALSE(load_scene_from_string("mem.json", scene_with_light(c.light), {}, diag)) << c.light;
    EXPECT_NE(diag.format().find(c.message), std::string::npos) << diag.format();
    EXPECT_NE(diag.format().find("mem.json:"), std::string::npos) << diag.format();
  }
}

}  // namespace
}  // namespace pt
