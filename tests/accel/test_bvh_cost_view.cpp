// The "bvh-cost" debug view (src/render/integrators/heatmap_view.cpp): refused
// up front for a backend that cannot count its work, costlier regions drawn
// further along the ramp, and the legend drawn into the image.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../geometry/test_util.h"
#include "../render/test_scenes.h"
#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/builtin.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"

namespace pt {
namespace {

constexpr int kWidth = 96, kHeight = 64;

// A cheap analytic quad on the left, a dense mesh sphere on the right.
SceneDescription two_halves() {
  SceneDescription d = test::empty_scene(kWidth, kHeight, {0, 0, 6}, {0, 0, 0}, {0, 1, 0}, 40.0f);
  const int m = test::add_material(d, test::diffuse_material(RGB(0.5f)));
  Quad q;
  q.v[0] = Vec3f(-4, -3, 0);
  q.v[1] = Vec3f(-0.2f, -3, 0);
  q.v[2] = Vec3f(-0.2f, 3, 0);
  q.v[3] = Vec3f(-4, 3, 0);
  test::add_shape(d, q, m);
  const TriangleMesh sphere = test::make_uv_sphere({1.4f, 0, 0}, 1.2f, 64, 128);
  TriangleMesh mesh;
  mesh.positions = sphere.positions;
  mesh.indices = sphere.indices;
  test::add_shape(d, mesh, m);
  return d;
}

Image render_cost(const SceneDescription& d, AccelKind kind, std::string& why, bool& refused) {
  WorkerPool pool(2);
  BuildOptions options;
  options.accel = kind;
  auto scene = test::build(d, pool, options);
  std::string error;
  const auto integrator = make_integrator("bvh-cost", IntegratorSettings{}, error);
  EXPECT_NE(integrator, nullptr) << error;
  Film film(scene->width, scene->height);
  refused = !integrator->can_render(*scene, why);
  if (!refused) integrator->render(*scene, film, pool);
  return film.image();
}

// Mean green channel (viridis' green rises monotonically along the ramp) of a window.
float mean_green(const Image& image, int cx, int cy, int r) {
  float sum = 0;
  int n = 0;
  for (int y = cy - r; y <= cy + r; ++y)
    for (int x = cx - r; x <= cx + r; ++x, ++n) sum += image.at(x, y).g;
  return sum / static_cast<float>(n);
}

TEST(BvhCostView, EmbreeIsRefusedBeforeRendering) {
  std::string why;
  bool refused = false;
  render_cost(two_halves(), AccelKind::Embree, why, refused);
  EXPECT_TRUE(refused);
  EXPECT_NE(why.find("--accel=bvh"), std::string::npos) << why;
}

TEST(BvhCostView, CostlierRegionsAreFurtherAlongTheRamp) {
  std::string why;
  bool refused = true;
  const Image image = render_cost(two_halves(), AccelKind::Bvh, why, refused);
  ASSERT_FALSE(refused) << why;
  const float quad = mean_green(image, kWidth / 5, kHeight / 3, 3);
  const float mesh = mean_green(image, 3 * kWidth / 4, kHeight / 3, 3);
  const float empty = mean_green(image, kWidth / 2, 4, 2);  // above both: misses
  EXPECT_GT(mesh, quad + 0.05f) << "the dense mesh must look costlier than the single quad";
  EXPECT_GE(quad, empty);
}

TEST(BvhCostView, LegendIsDrawnIntoTheImage) {
  std::string why;
  bool refused = true;
  const Image image = render_cost(two_halves(), AccelKind::Bvh, why, refused);
  ASSERT_FALSE(refused) << why;
  // The bottom-left panel: the colour bar starts at the ramp's dark end and
  // ends at its yellow end; white digits below it on black.
  // draw_legend at this size: scale 1, margin 2, a 3-pixel bar; the panel is
  // 14 pixels high, the bar kWidth / 3 wide, starting 2 pixels in.
  const int bar_w = kWidth / 3, bar_y = kHeight - 14 + 3;
  const RGB first = image.at(2, bar_y), last = image.at(2 + bar_w - 1, bar_y);
  const RGB dark = cost_colour(0.0f), yellow = cost_colour(1.0f);
  EXPECT_NEAR(first.g, dark.g, 1e-3f);
  EXPECT_NEAR(last.g, yellow.g, 1e-3f);
  EXPECT_GT(last.r, 0.5f);
  int white = 0, black = 0;
  for (int y = kHeight - 8; y < kHeight; ++y) {
    for (int x = 0; x < bar_w; ++x) {
      const RGB c = image.at(x, y);
      white += (c.r == 1.0f && c.g == 1.0f && c.b == 1.0f) ? 1 : 0;
      black += (c.r == 0.0f && c.g == 0.0f && c.b == 0.0f) ? 1 : 0;
    }
  }
  EXPECT_GT(white, 10);  // the numbers
  EXPECT_GT(black, 50);  // the panel
}

TEST(BvhCostView, RampIsClampedAndMonotone) {
  EXPECT_EQ(cost_colour(-1.0f).g, cost_colour(0.0f).g);
  EXPECT_EQ(cost_colour(2.0f).g, cost_colour(1.0f).g);
  EXPECT_EQ(cost_colour(std::nanf("")).g, cost_colour(0.0f).g);
  for (int i = 1; i <= 100; ++i) {
    const float a = static_cast<float>(i - 1) / 100.0f, b = static_cast<float>(i) / 100.0f;
    EXPECT_LE(cost_colour(a).g, cost_colour(b).g) << i;
  }
}

}  // namespace
}  // namespace pt
