// The registry, the binary mode and the debug views.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <tuple>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/parallel.h"
#include "io/image_io.h"
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

Image render(const RenderScene& scene, const std::string& name, WorkerPool& pool, int spp = 1) {
  IntegratorSettings settings;
  settings.spp = spp;
  std::string error;
  auto integrator = make_integrator(name, settings, error);
  EXPECT_TRUE(integrator) << error;
  Film film(scene.width, scene.height);
  if (integrator) integrator->render(scene, film, pool);
  return film.image();
}

// Two spheres in front of a grey background, seen from +z (Y up).
SceneDescription two_spheres() {
  SceneDescription d = test::empty_scene(40, 30, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40);
  d.render.background = RGB(0.25f);
  const int m = add_material(d, test::diffuse_material(RGB(0.7f), 1.0f));
  add_sphere(d, {-0.8f, 0, 0}, 0.6f, m);
  add_sphere(d, {0.9f, 0.2f, -1}, 0.5f, m);
  add_point_light(d, {0, 3, 3}, RGB(10), RGB(10));
  return d;
}

TEST(Registry, KnowsEveryIntegrator) {
  const auto names = integrator_names();
  for (const char* n : {"whitted", "path", "binary", "normal", "depth", "signature"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
    std::string error;
    EXPECT_TRUE(make_integrator(n, {}, error)) << n;
  }
}

TEST(Registry, UnknownNameListsTheValidOnes) {
  std::string error;
  EXPECT_EQ(make_integrator("pathtracer", {}, error), nullptr);
  EXPECT_NE(error.find("pathtracer"), std::string::npos) << error;
  for (const std::string& n : integrator_names()) EXPECT_NE(error.find(n), std::string::npos) << error;
}

TEST(Binary, PureRedOnHitsBlackElsewhereWhateverTheBackground) {
  WorkerPool pool(2);
  auto scene = test::build(two_spheres(), pool);
  ASSERT_TRUE(scene);
  const Image img = render(*scene, "binary", pool, 4);
  int red = 0, black = 0;
  for (const RGB& p : img.pixels) {
    if (p == RGB(1, 0, 0)) ++red;
    else if (p == RGB(0, 0, 0)) ++black;
    else ADD_FAILURE() << "impure pixel " << p.r << " " << p.g << " " << p.b;
  }
  EXPECT_GT(red, 50);
  EXPECT_GT(black, 50);
  // The pixel at the first sphere's centre is a hit, the corner is not.
  Vec2f px;
  ASSERT_TRUE(scene->camera.project({-0.8f, 0, 0}, px));
  EXPECT_EQ(img.at(static_cast<int>(px.x), static_cast<int>(px.y)), RGB(1, 0, 0));
  EXPECT_EQ(img.at(0, 0), RGB(0, 0, 0));

  // Written as PPM under every display transform, the bytes stay 255,0,0 / 0,0,0.
  const auto dir = std::filesystem::temp_directory_path() / ("pt_binary_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (DisplayTransform t : {DisplayTransform::CgrCourse, DisplayTransform::Linear, DisplayTransform::Srgb}) {
    const std::string path = (dir / "b.ppm").string();
    std::string error;
    ASSERT_TRUE(write_image(path, img, DisplaySettings{t, 0.0f}, error)) << error;
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t header = bytes.size() - img.pixels.size() * 3;
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
      const auto r = static_cast<unsigned char>(bytes[header + 3 * i]);
      const auto g = static_cast<unsigned char>(bytes[header + 3 * i + 1]);
      const auto b = static_cast<unsigned char>(bytes[header + 3 * i + 2]);
      ASSERT_TRUE((r == 255 || r == 0) && g == 0 && b == 0) << i;
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(NormalView, FacingSphereCentreIsBlueish) {
  WorkerPool pool(2);
  auto scene = test::build(two_spheres(), pool);
  ASSERT_TRUE(scene);
  const Image img = render(*scene, "normal", pool);
  Vec2f px;
  ASSERT_TRUE(scene->camera.project({-0.8f, 0, 0.6f}, px));  // the point facing the camera
  const RGB c = img.at(static_cast<int>(px.x), static_cast<int>(px.y));
  EXPECT_NEAR(c.b, 1.0f, 0.02f);
  EXPECT_NEAR(c.r, 0.5f, 0.05f);
  EXPECT_NEAR(c.g, 0.5f, 0.05f);
  EXPECT_EQ(img.at(0, 0), RGB(0, 0, 0));
  for (const RGB& p : img.pixels)
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(p[i] >= 0.0f && p[i] <= 1.0f);
}

TEST(DepthView, NearerIsBrighterAndEverythingIsInRange) {
  WorkerPool pool(2);
  auto scene = test::build(two_spheres(), pool);
  ASSERT_TRUE(scene);
  const Image img = render(*scene, "depth", pool);
  Vec2f near_px, far_px;
  ASSERT_TRUE(scene->camera.project({-0.8f, 0, 0.6f}, near_px));   // front of the near sphere, t = 4.4
  ASSERT_TRUE(scene->camera.project({0.9f, 0.2f, -0.5f}, far_px));  // front of the far sphere
  const float near_v = img.at(static_cast<int>(near_px.x), static_cast<int>(near_px.y)).r;
  const float far_v = img.at(static_cast<int>(far_px.x), static_cast<int>(far_px.y)).r;
  EXPECT_GT(near_v, far_v);
  EXPECT_GT(far_v, 0.0f);
  const float range = depth_view_range(scene->accel->bounds(), scene->camera.position());
  const Ray r = scene->camera.generate_ray({std::floor(near_px.x) + 0.5f, std::floor(near_px.y) + 0.5f});
  Intersection isect;
  ASSERT_TRUE(scene->intersect(r, isect));
  EXPECT_NEAR(near_v, 1.0f - isect.hit.t / range, 1e-5f);
  EXPECT_EQ(img.at(0, 0), RGB(0, 0, 0));
  for (const RGB& p : img.pixels) ASSERT_TRUE(p.r >= 0.0f && p.r <= 1.0f && p.r == p.g && p.g == p.b);
}

TEST(DepthView, RangeIsTheFarthestCorner) {
  Bounds3f b;
  b.extend(Vec3f(-1, -1, -1));
  b.extend(Vec3f(1, 1, 1));
  EXPECT_NEAR(depth_view_range(b, {0, 0, 5}), std::sqrt(2.0f + 36.0f), 1e-5f);
  EXPECT_EQ(depth_view_range(Bounds3f(), {0, 0, 5}), 1.0f);
}

TEST(SignatureView, EachObjectItsOwnStableColour) {
  WorkerPool pool(2);
  auto scene = test::build(two_spheres(), pool);
  ASSERT_TRUE(scene);
  const Image img = render(*scene, "signature", pool);
  Vec2f a, b;
  ASSERT_TRUE(scene->camera.project({-0.8f, 0, 0.6f}, a));
  ASSERT_TRUE(scene->camera.project({0.9f, 0.2f, -0.5f}, b));
  EXPECT_EQ(img.at(static_cast<int>(a.x), static_cast<int>(a.y)), signature_colour(0));
  EXPECT_EQ(img.at(static_cast<int>(b.x), static_cast<int>(b.y)), signature_colour(1));
  EXPECT_EQ(img.at(0, 0), RGB(0, 0, 0));
}

TEST(SignatureView, ColoursAreDistinctAndBright) {
  std::set<std::tuple<float, float, float>> seen;
  for (uint32_t id = 0; id < 1000; ++id) {
    const RGB c = signature_colour(id);
    EXPECT_EQ(c, signature_colour(id));
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(c[i] >= 0.15f && c[i] <= 1.0f);
    seen.insert({c.r, c.g, c.b});
  }
  EXPECT_EQ(seen.size(), 1000u);
}

}  // namespace
}  // namespace pt
