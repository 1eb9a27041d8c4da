#include <cmath>

#include <gtest/gtest.h>

#include "render/camera/camera.h"
#include "render/lights/environment.h"

namespace pt {
namespace {

CameraDesc make_desc(Vec3f eye, Vec3f target, Vec3f up, float fov, bool left_handed = false) {
  CameraDesc d;
  d.position = eye;
  d.look_at = target;
  d.up = up;
  d.fov_y_deg = fov;
  d.left_handed = left_handed;
  return d;
}

void expect_near(Vec3f a, Vec3f b, float eps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

TEST(Camera, ImageCentreLooksAlongForward) {
  const Vec3f eye(1, 2, 3), target(4, 6, 3);
  const Camera cam(make_desc(eye, target, Vec3f(0, 0, 2), 35), 640, 480);
  const Ray r = cam.generate_ray({320, 240});
  expect_near(r.origin, eye, 0);
  expect_near(r.dir, normalize(target - eye), 1e-6f);
  EXPECT_NEAR(length(r.dir), 1.0f, 1e-6f);
  expect_near(cam.forward(), normalize(target - eye), 1e-6f);
}

TEST(Camera, DirectionsAreUnitLength) {
  const Camera cam(make_desc({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90), 200, 100);
  for (Vec2f px : {Vec2f(0, 0), Vec2f(200, 100), Vec2f(13.5f, 77.25f)})
    EXPECT_NEAR(length(cam.generate_ray(px).dir), 1.0f, 1e-6f);
}

// Path of Light: Z up, right-handed (right = forward x up). Looking along +Y
// with +Z up, world +X is on the right of the image and +Z at the top.
TEST(Camera, PathOfLightConvention) {
  const Camera cam(make_desc({0, 0, 0}, {0, 1, 0}, {0, 0, 0.5f}, 40), 100, 100);
  Vec2f px;
  ASSERT_TRUE(cam.project({1, 5, 0}, px));
  EXPECT_GT(px.x, 50.0f);
  EXPECT_NEAR(px.y, 50.0f, 1e-4f);
  ASSERT_TRUE(cam.project({0, 5, 1}, px));
  EXPECT_NEAR(px.x, 50.0f, 1e-4f);
  EXPECT_LT(px.y, 50.0f);  // row 0 is the top
}

// CGR: Y up, left-handed (right = up x forward). Looking down +Z with +Y up,
// world +X is on the right of the image.
TEST(Camera, CgrConvention) {
  const Camera cam(make_desc({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 45, /*left_handed=*/true), 120, 80);
  Vec2f right, top;
  ASSERT_TRUE(cam.project({1, 0, 5}, right));
  EXPECT_GT(right.x, 60.0f);
  EXPECT_NEAR(right.y, 40.0f, 1e-4f);
  ASSERT_TRUE(cam.project({0, 1, 5}, top));
  EXPECT_NEAR(top.x, 60.0f, 1e-4f);
  EXPECT_LT(top.y, 40.0f);
  // The same description right-handed is the mirror image.
  const Camera rh(make_desc({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 45, false), 120, 80);
  Vec2f mirrored;
  ASSERT_TRUE(rh.project({1, 0, 5}, mirrored));
  EXPECT_NEAR(mirrored.x, 120.0f - right.x, 1e-3f);
  EXPECT_NEAR(mirrored.y, right.y, 1e-4f);
}

// fov is the vertical full angle: a point at half that angle above the axis
// lands on the top edge; the horizontal extent follows the aspect ratio.
TEST(Camera, VerticalFovEdges) {
  const float fov = 60.0f, d = 4.0f;
  const float h = d * std::tan(0.5f * fov * kPi / 180.0f);
  const Camera cam(make_desc({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, fov), 300, 150);
  Vec2f px;
  ASSERT_TRUE(cam.project({0, h, -d}, px));
  EXPECT_NEAR(px.x, 150.0f, 1e-3f);
  EXPECT_NEAR(px.y, 0.0f, 1e-3f);
  ASSERT_TRUE(cam.project({0, -h, -d}, px));
  EXPECT_NEAR(px.y, 150.0f, 1e-3f);
  ASSERT_TRUE(cam.project({2 * h, 0, -d}, px));  // aspect 2
  EXPECT_NEAR(px.x, 300.0f, 1e-3f);
  // And the corner ray points exactly at the corner of the frustum.
  expect_near(cam.generate_ray({300, 0}).dir, normalize(Vec3f(2 * h, h, -d)), 1e-6f);
}

TEST(Camera, ProjectInvertsGenerateRay) {
  for (bool lh : {false, true}) {
    const Camera cam(make_desc({0.5f, -3, 2}, {0.2f, 1, 1.4f}, {0, 0, 1}, 50, lh), 160, 90);
    for (Vec2f px : {Vec2f(0.5f, 0.5f), Vec2f(80, 45), Vec2f(159.5f, 3.25f), Vec2f(17, 88)}) {
      const Ray r = cam.generate_ray(px);
      Vec2f back;
      ASSERT_TRUE(cam.project(r.at(3.7f), back));
      EXPECT_NEAR(back.x, px.x, 2e-3f);
      EXPECT_NEAR(back.y, px.y, 2e-3f);
    }
  }
}

// The CGR courses' pixel convention (CameraDesc::film_offset): film position p
// looks where p + offset looks without one, and project() gives p back.
TEST(Camera, FilmOffsetShiftsEveryRay) {
  CameraDesc shifted = make_desc({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 45, /*left_handed=*/true);
  const Camera plain(shifted, 120, 80);
  shifted.film_offset = Vec2f(-1.0f, 0.25f);
  const Camera cam(shifted, 120, 80);
  for (Vec2f px : {Vec2f(0.5f, 0.5f), Vec2f(60, 40), Vec2f(119.5f, 3.25f)}) {
    expect_near(cam.generate_ray(px).dir, plain.generate_ray(Vec2f(px.x - 1.0f, px.y + 0.25f)).dir, 1e-6f);
    Vec2f back;
    ASSERT_TRUE(cam.project(cam.generate_ray(px).at(2.0f), back));
    EXPECT_NEAR(back.x, px.x, 2e-3f);
    EXPECT_NEAR(back.y, px.y, 2e-3f);
  }
}

TEST(Camera, PointsBehindDoNotProject) {
  const Camera cam(make_desc({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 45), 64, 64);
  Vec2f px;
  EXPECT_FALSE(cam.project({0, 0, 1}, px));
  EXPECT_FALSE(cam.project({0, 0, 0}, px));
}

TEST(Camera, UpNeedNotBeUnitOrOrthogonal) {
  const Camera a(make_desc({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 40), 64, 48);
  const Camera b(make_desc({0, 0, 0}, {0, 1, 0}, {0, 0.7f, 3}, 40), 64, 48);
  for (Vec2f px : {Vec2f(0, 0), Vec2f(64, 48), Vec2f(10, 40)})
    expect_near(a.generate_ray(px).dir, b.generate_ray(px).dir, 1e-6f);
}

TEST(Camera, PinholeIgnoresTheLensSample) {
  const Camera cam(make_desc({1, 2, 3}, {0, 0, 0}, {0, 1, 0}, 45), 64, 48);
  EXPECT_FALSE(cam.has_lens());
  const Ray a = cam.generate_ray({10, 20});
  const Ray b = cam.generate_ray({10, 20}, {0.9f, 0.1f});
  expect_near(a.origin, b.origin, 0);
  expect_near(a.dir, b.dir, 0);
}

// Thin lens: every ray for one film position leaves a point of the lens disk
// and passes through the same point of the plane in focus.
TEST(Camera, ThinLensFocusesOnTheFocalPlane) {
  CameraDesc d = make_desc({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 45);
  d.type = CameraType::ThinLens;
  d.lens_radius = 0.2f;
  d.focus_distance = 5.0f;
  const Camera cam(d, 64, 48);
  ASSERT_TRUE(cam.has_lens());
  const Vec2f px(13.25f, 40.5f);
  const Ray pinhole = cam.generate_ray(px);
  const Vec3f focus = pinhole.at(5.0f / -pinhole.dir.z);
  expect_near(cam.generate_ray(px, {0.5f, 0.5f}).dir, pinhole.dir, 1e-6f);  // the lens centre
  for (Vec2f lens : {Vec2f(0, 0), Vec2f(0.99f, 0.5f), Vec2f(0.3f, 0.8f), Vec2f(0.7f, 0.05f)}) {
    const Ray r = cam.generate_ray(px, lens);
    EXPECT_NEAR(length(r.dir), 1.0f, 1e-6f);
    EXPECT_NEAR(r.origin.z, 0.0f, 1e-6f);                   // on the lens plane
    EXPECT_LE(length(r.origin), 0.2f + 1e-6f);               // inside the aperture
    const Vec3f hit = r.at((focus.z - r.origin.z) / r.dir.z);
    expect_near(hit, focus, 1e-4f);
  }
  // Off the focal plane, different lens points see different places (blur).
  const Ray a = cam.generate_ray(px, {0.05f, 0.5f}), b = cam.generate_ray(px, {0.95f, 0.5f});
  EXPECT_GT(length(a.at(2.0f / -a.dir.z) - b.at(2.0f / -b.dir.z)), 0.05f);
}

// A camera of `type` (fov 45 where it has one).
CameraDesc desc(CameraType type, Vec3f eye, Vec3f target, Vec3f up) {
  CameraDesc d = make_desc(eye, target, up, 45);
  d.type = type;
  return d;
}

// ---------------------------------------------------------------- orthographic and spherical cameras
// What every kind promises: project() and film_position() invert
// generate_ray(), the EXR matrices agree with project(), and the spherical
// camera's layout is the environment map's.

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
