// A Path of Light area light rendered by the path integrator: it lights the
// scene as the family's point light of the same intensity does near its axis
// (docs/scene-format.md, "Area lights in Path of Light files"), on both backends;
// the classic integrator lights it the same (docs/rendering.md).
#include <gtest/gtest.h>

#include <string>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace pt {
namespace {

// A white floor of 3 x 3 seen from the side; the light 5 above its centre, out of the frame.
std::string scene(const std::string& light) {
  return R"({ "nbounces": 1,
  "camera": { "type": "pinhole", "width": 16, "height": 16, "fov": 30,
              "position": [0, -6, 2], "lookat": [0, 6, -2], "up": [0, 0, 1] },
  "scene": { "backgroundcolor": [0, 0, 0], "lightsources": [ )" + light + R"( ],
    "shapes": [ { "type": "plane", "v0": [-1.5, -1.5, 0], "v1": [1.5, -1.5, 0], "v2": [1.5, 1.5, 0],
                  "v3": [-1.5, 1.5, 0], "material": { "kd": 1, "ks": 0, "diffusecolor": [1, 1, 1] } } ] } })";
}

// Mean of the image's red channel, rendered by `integrator` (path unless given).
double mean_radiance(const std::string& text, AccelKind accel, const char* integrator_name = "path") {
  Diagnostics diag;
  const auto d = load_scene_from_string("course.json", text, LoadOptions{}, diag);
  EXPECT_TRUE(d) << diag.format();
  if (!d) return -1;
  WorkerPool pool(2);
  BuildOptions options;
  options.accel = accel;
  const auto rs = build_render_scene(*d, options, pool, diag);
  if (!rs) return -2;
  IntegratorSettings settings;
  settings.spp = 64;
  settings.max_depth = 1;
  std::string error;
  const auto integrator = make_integrator(integrator_name, settings, error);
  EXPECT_TRUE(integrator) << error;
  if (!integrator) return -1;
  Film film(rs->width, rs->height);
  integrator->render(*rs, film, pool);
  const Image img = film.image();
  double sum = 0;
  for (const RGB& p : img.pixels) sum += p.r;
  return sum / static_cast<double>(img.pixels.size());
}

// A 0.2 x 0.2 lamp 5 above the floor's centre. Its corners run counter-clockwise seen
// from above: the floor sees the lamp's back, lit because course area lights are two-sided.
const std::string kArea = R"({ "type": "arealight", "v0": [-0.1, -0.1, 5], "v1": [0.1, -0.1, 5],
                               "v2": [0.1, 0.1, 5], "v3": [-0.1, 0.1, 5], "id": [100, 100, 100],
                               "is": [100, 100, 100], "samples": 4 })";

TEST(CourseAreaLightRender, LightsTheFloorAsThePointLightOfTheSameIntensity) {
  const std::string point = R"({ "type": "pointlight", "position": [0, 0, 5], "id": [100, 100, 100],
                                  "is": [100, 100, 100] })";
  const double reference = mean_radiance(scene(point), AccelKind::Bvh);
  ASSERT_GT(reference, 0.01);
  for (AccelKind accel : {AccelKind::Bvh, AccelKind::Embree}) {
    const double lit = mean_radiance(scene(kArea), accel);
    // The lamp's own cosine dims the floor's corners (down to 5 / sqrt(29.5) = 0.92);
    // the estimate's noise at 64 spp is well under 1%.
    EXPECT_GT(lit, 0.90 * reference) << (accel == AccelKind::Bvh ? "bvh" : "embree");
    EXPECT_LT(lit, 1.01 * reference) << (accel == AccelKind::Bvh ? "bvh" : "embree");
  }
}

// The classic integrator samples the same lamp at its "samples" points per
// shading point and lights the Lambert floor in the point lights' units
// (docs/rendering.md): it agrees with the path integrator.
TEST(CourseAreaLightRender, WhittedLightsTheFloorAsThePathIntegratorDoes) {
  const double path = mean_radiance(scene(kArea), AccelKind::Bvh);
  ASSERT_GT(path, 0.01);
  for (AccelKind accel : {AccelKind::Bvh, AccelKind::Embree}) {
    const double whitted = mean_radiance(scene(kArea), accel, "whitted");
    // Both estimate the same integral; 64 spp x 4 light samples (whitted) and
    // 64 (path) over 256 pixels: the means differ by well under 1% (measured: 0.16%).
    EXPECT_NEAR(whitted, path, 0.01 * path) << (accel == AccelKind::Bvh ? "bvh" : "embree");
  }
}

}  // namespace
}  // namespace pt
