// The orthographic and spherical cameras, and what every kind promises:
// project() and film_position() invert generate_ray(), the EXR matrices agree
// with project(), and the spherical camera's layout is the environment map's.
#include <cmath>

#include <gtest/gtest.h>

#include "render/camera/camera.h"
#include "render/lights/environment.h"

namespace pt {
namespace {

CameraDesc desc(CameraType type, Vec3f eye, Vec3f target, Vec3f up) {
  CameraDesc d;
  d.type = type;
  d.position = eye;
  d.look_at = target;
  d.up = up;
  return d;
}

void expect_near(Vec3f a, Vec3f b, float eps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

// Film positions spread over the frame, away from its edges (the spherical
// camera's seam and poles are tested on their own).
std::vector<Vec2f> film_positions(int w, int h) {
  std::vector<Vec2f> out;
  for (int i = 1; i < 8; ++i)
    for (int j = 1; j < 8; ++j) out.emplace_back(w * (i + 0.13f * j) / 8.5f, h * (j + 0.07f * i) / 8.5f);
  return out;
}

TEST(OrthographicCamera, ParallelRaysOverTheViewRectangle) {
  CameraDesc d = desc(CameraType::Orthographic, {1, 2, 10}, {1, 2, 0}, {0, 1, 0});
  d.view_height = 4.0f;
  const Camera cam(d, 200, 100);  // aspect 2: the view is 8 x 4
  for (Vec2f px : film_positions(200, 100)) expect_near(cam.generate_ray(px).dir, Vec3f(0, 0, -1), 0);
  expect_near(cam.generate_ray({100, 50}).origin, Vec3f(1, 2, 10), 1e-6f);
  expect_near(cam.generate_ray({0, 0}).origin, Vec3f(1 - 4, 2 + 2, 10), 1e-5f);      // top-left corner
  expect_near(cam.generate_ray({200, 100}).origin, Vec3f(1 + 4, 2 - 2, 10), 1e-5f);  // bottom-right
  EXPECT_FALSE(cam.has_lens());
}

TEST(OrthographicCamera, ViewWidthGivesTheHeightByTheAspectRatio) {
  CameraDesc d = desc(CameraType::Orthographic, {0, 0, 0}, {0, 0, -1}, {0, 1, 0});
  d.view_width = 6.0f;
  const Camera cam(d, 300, 100);  // 6 x 2
  expect_near(cam.generate_ray({300, 0}).origin, Vec3f(3, 1, 0), 1e-5f);
}

TEST(OrthographicCamera, DepthIsTheRayLengthAndPointsBehindDoNotProject) {
  const Camera cam(desc(CameraType::Orthographic, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}), 64, 64);
  const Ray r = cam.generate_ray({10.5f, 40.25f});
  EXPECT_NEAR(cam.depth(r.at(3.5f)), 3.5f, 1e-5f);
  Vec2f px;
  EXPECT_FALSE(cam.project({0, 0, 6}, px));
  EXPECT_TRUE(cam.project({0.5f, 0.5f, -100}, px));
}

TEST(SphericalCamera, LayoutAroundTheViewDirection) {
  // Looking along +x with +z up: right = forward x up = -y.
  const Camera cam(desc(CameraType::Spherical, {1, 1, 1}, {2, 1, 1}, {0, 0, 3}), 360, 180);
  expect_near(cam.generate_ray({180, 90}).dir, Vec3f(1, 0, 0), 1e-6f);   // centre: forward
  expect_near(cam.generate_ray({270, 90}).dir, Vec3f(0, -1, 0), 1e-6f);  // u = 3/4: right
  expect_near(cam.generate_ray({90, 90}).dir, Vec3f(0, 1, 0), 1e-6f);    // u = 1/4: left
  expect_near(cam.generate_ray({0, 90}).dir, Vec3f(-1, 0, 0), 1e-6f);    // the seam: behind
  expect_near(cam.generate_ray({123, 0}).dir, Vec3f(0, 0, 1), 1e-6f);    // top row: up
  expect_near(cam.generate_ray({17, 180}).dir, Vec3f(0, 0, -1), 1e-6f);  // bottom row: down
  expect_near(cam.generate_ray({17, 45}).origin, Vec3f(1, 1, 1), 0);
  EXPECT_NEAR(cam.depth(Vec3f(1, 4, 5)), 5.0f, 1e-6f);  // distance from the camera
  EXPECT_FALSE(cam.world_to_ndc().has_value());         // worldToCamera only
}

// The spherical camera renders what the environment map reads: a camera
// looking down -z with +y up has the layout of a map with up +y and rotation
// 0, and one turned by `a` degrees counter-clockwise about +y (seen from
// above) that of the map with rotation `a`.
TEST(SphericalCamera, SameLayoutAsTheEnvironmentMap) {
  const int w = 64, h = 32;
  for (float a : {0.0f, 30.0f, -75.0f, 180.0f}) {
    const float t = a * kPi / 180.0f;
    const Vec3f forward(-std::sin(t), 0, -std::cos(t));  // -z turned counter-clockwise about +y
    const Camera cam(desc(CameraType::Spherical, {0, 0, 0}, forward, {0, 1, 0}), w, h);
    const EnvironmentMap env(Texture(1, 1, {RGB(1)}), Vec3f(0, 1, 0), a, 1.0f);
    for (Vec2f px : film_positions(w, h)) {
      const Vec2f uv = env.direction_to_uv(cam.generate_ray(px).dir);
      EXPECT_NEAR(std::fmod(uv.x * w - px.x + 1.5f * w, static_cast<float>(w)) - 0.5f * w, 0.0f, 2e-3f) << a;
      EXPECT_NEAR(uv.y * h, px.y, 2e-3f) << a;
    }
  }
}

// project() and film_position() invert generate_ray() for every kind; the
// EXR worldToNDC, where there is one, maps a point to the same pixel.
TEST(CameraKinds, ProjectionInvertsGenerateRay) {
  CameraDesc thin = desc(CameraType::ThinLens, {0, 1, 4}, {0.3f, 0, 0}, {0, 1, 0});
  thin.lens_radius = 0.3f;
  thin.focus_distance = 3.0f;
  for (const CameraDesc& d : {desc(CameraType::Pinhole, {0, 1, 4}, {0.3f, 0, 0}, {0, 1, 0}), thin,
                              desc(CameraType::Orthographic, {0, 1, 4}, {0.3f, 0, 0}, {0, 1, 0}),
                              desc(CameraType::Spherical, {0, 1, 4}, {0.3f, 0, 0}, {0, 1, 0})}) {
    const Camera cam(d, 160, 90);
    const std::optional<std::array<float, 16>> ndc = cam.world_to_ndc();
    for (Vec2f px : film_positions(160, 90)) {
      const Ray r = cam.generate_ray(px, Vec2f(0.8f, 0.3f));
      const Vec2f back = cam.film_position(r);
      EXPECT_NEAR(back.x, px.x, 2e-3f);
      EXPECT_NEAR(back.y, px.y, 2e-3f);
      const Vec3f p = cam.generate_ray(px).at(2.5f);  // through the lens centre
      Vec2f projected;
      ASSERT_TRUE(cam.project(p, projected));
      EXPECT_NEAR(projected.x, px.x, 2e-3f);
      EXPECT_NEAR(projected.y, px.y, 2e-3f);
      if (!ndc) continue;
      const std::array<float, 16>& m = *ndc;
      float o[4];
      for (int c = 0; c < 4; ++c) o[c] = p.x * m[c] + p.y * m[4 + c] + p.z * m[8 + c] + m[12 + c];
      EXPECT_NEAR(0.5f * (o[0] / o[3] + 1.0f) * 160, px.x, 2e-3f);
      EXPECT_NEAR(0.5f * (1.0f - o[1] / o[3]) * 90, px.y, 2e-3f);
    }
  }
}

// worldToCamera: the camera at the origin looking down -z, for every kind.
TEST(CameraKinds, WorldToCameraLooksDownMinusZ) {
  for (CameraType type : {CameraType::Pinhole, CameraType::Orthographic, CameraType::Spherical}) {
    const Camera cam(desc(type, {1, 2, 3}, {1, 2, -7}, {0, 1, 0}), 32, 32);
    const std::array<float, 16> m = cam.world_to_camera();
    const Vec3f p(1, 2, -1);  // 4 in front
    float o[3];
    for (int c = 0; c < 3; ++c) o[c] = p.x * m[c] + p.y * m[4 + c] + p.z * m[8 + c] + m[12 + c];
    EXPECT_NEAR(o[0], 0.0f, 1e-6f);
    EXPECT_NEAR(o[1], 0.0f, 1e-6f);
    EXPECT_NEAR(o[2], -cam.depth(p), 1e-6f);
  }
}

}  // namespace
}  // namespace pt
