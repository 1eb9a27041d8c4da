// Image regression: every seed scene (../shared/seed-scenes, skipped if absent)
// and every scene in scenes/ is rendered at reduced resolution and compared with
// a golden EXR in tests/data, produced by this renderer and checked by eye.
//
// Tolerance (allows floating-point differences across CPUs and Embree ISA
// paths, e.g. silhouette pixels that flip between hit and miss): the mean
// absolute difference over all channels is below 1e-4, and fewer than 0.1% of
// the channel values differ by more than 1e-2.
//
// To regenerate after an intended change: PT_UPDATE_GOLDEN=1 test_render_regression
// (and look at the images: PT_GOLDEN_PNG_DIR=<dir> also writes PNG previews).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "io/image_io.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160;  // height follows each scene's aspect ratio
constexpr double kMeanTolerance = 1e-4;
constexpr float kOutlierThreshold = 1e-2f;
constexpr double kOutlierFraction = 1e-3;

struct Case {
  std::string scene;   // path of the scene file
  std::string golden;  // file name in tests/data
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.golden; }

std::vector<Case> cases() {
  std::vector<Case> out;
  const fs::path seeds = fs::path(PT_SHARED_DIR) / "seed-scenes";
  for (const char* name : {"binary_primitives", "mirror_image", "scene", "simple_phong"})
    out.push_back({(seeds / "cgr" / (std::string(name) + ".json")).string(), std::string("cgr_") + name + ".exr"});
  out.push_back({(seeds / "path-of-light" / "examples" / "example.json").string(), "path_of_light_example.exr"});
  std::error_code ec;
  std::vector<Case> native;
  for (const auto& e : fs::directory_iterator(PT_SCENES_DIR, ec))
    // Hidden files are tools' scratch copies (time_to_error.py's sized scenes), not scenes of the project.
    if (e.path().extension() == ".json" && e.path().filename().string().front() != '.')
      native.push_back({e.path().string(), "scenes_" + e.path().stem().string() + ".exr"});
  std::sort(native.begin(), native.end(), [](const Case& a, const Case& b) { return a.golden < b.golden; });
  out.insert(out.end(), native.begin(), native.end());
  return out;
}

bool render_scene_file(const std::string& path, Image& out, DisplaySettings& display, std::string& error) {
  Diagnostics diag;
  const auto desc = load_scene(path, LoadOptions{}, diag);
  if (!desc) {
    error = diag.format();
    return false;
  }
  WorkerPool pool(2);
  BuildOptions options;
  options.width_override = kWidth;
  const auto scene = build_render_scene(*desc, options, pool, diag);
  if (!scene) {
    error = diag.format();
    return false;
  }
  IntegratorSettings settings;
  settings.max_depth = desc->render.max_depth;
  settings.spp = desc->render.spp;
  settings.filter = desc->render.filter;
  settings.clamp = desc->render.clamp;
  const auto integrator = make_integrator(desc->render.integrator, settings, error);
  if (!integrator) return false;
  Film film(scene->width, scene->height);
  integrator->render(*scene, film, pool);
  out = film.image();
  display = DisplaySettings{desc->film.display, desc->film.exposure};
  return true;
}

// Textured scenes built, rendered and destroyed one after another in one
// process, alone or two alive at once and destroyed in either order, as this
// binary renders its goldens: each render equals the first. OpenImageIO 2.4's
// per-thread cache state once outlived a scene's cache and corrupted a later
// one's (an abort in ImageCacheImpl::decr_tiles). Whether this scene-level
// check hit that depended on which pool thread looked up what and on where the
// allocator put each cache; CachedTextures.CachesComeAndGoAcrossThreads
// reproduces it deterministically with a thread that outlives the caches.
TEST(RegressionProcess, TexturedScenesComeAndGo) {
  const std::string path = (fs::path(PT_SCENES_DIR) / "textures.json").string();
  Diagnostics diag;
  const auto desc = load_scene(path, LoadOptions{}, diag);
  ASSERT_TRUE(desc) << diag.format();
  WorkerPool pool(2);
  BuildOptions options;
  options.width_override = 48;
  options.texture_cache_bytes = uint64_t{1} << 20;  // small: tiles come and go
  IntegratorSettings settings;
  settings.max_depth = desc->render.max_depth;
  settings.spp = 2;
  std::string error;
  const auto integrator = make_integrator(desc->render.integrator, settings, error);
  ASSERT_TRUE(integrator) << error;
  const auto render = [&](const RenderScene& scene) {
    Film film(scene.width, scene.height);
    integrator->render(scene, film, pool);
    return film.image().pixels;
  };
  std::vector<RGB> first;
  for (int round = 0; round < 6; ++round) {
    auto a = build_render_scene(*desc, options, pool, diag);
    ASSERT_TRUE(a) << diag.format();
    if (round == 0) first = render(*a);
    ASSERT_TRUE(render(*a) == first) << "round " << round;
    if (round % 3 == 0) continue;  // one scene alone
    auto b = build_render_scene(*desc, options, pool, diag);
    ASSERT_TRUE(b) << diag.format();
    ASSERT_TRUE(render(*b) == first) << "round " << round;
    ASSERT_TRUE(render(*a) == first) << "round " << round;
    if (round % 3 == 1) a.reset();  // a first, then b; else b first
  }
}

class Regression : public ::testing::TestWithParam<Case> {};

TEST_P(Regression, MatchesGolden) {
  const Case& c = GetParam();
  if (!fs::exists(c.scene)) GTEST_SKIP() << c.scene << " is not available";
  Image image;
  DisplaySettings display;
  std::string error;
  ASSERT_TRUE(render_scene_file(c.scene, image, display, error)) << error;

  const fs::path golden = fs::path(PT_TEST_DATA_DIR) / "data" / c.golden;
  if (std::getenv("PT_UPDATE_GOLDEN") != nullptr) {
    ASSERT_TRUE(write_image(golden.string(), image, display, error)) << error;
    if (const char* dir = std::getenv("PT_GOLDEN_PNG_DIR")) {
      const fs::path png = fs::path(dir) / fs::path(c.golden).replace_extension(".png");
      ASSERT_TRUE(write_image(png.string(), image, display, error)) << error;
    }
    GTEST_SKIP() << "wrote " << golden;
  }

  Image expected;
  ASSERT_TRUE(read_image(golden.string(), expected, error))
      << error << "\n(no golden image: run with PT_UPDATE_GOLDEN=1 and check the result by eye)";
  ASSERT_EQ(image.width, expected.width);
  ASSERT_EQ(image.height, expected.height);
  double sum = 0;
  std::size_t outliers = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      const float d = std::fabs(image.pixels[i][ch] - expected.pixels[i][ch]);
      sum += d;
      if (!(d <= kOutlierThreshold)) ++outliers;  // NaN counts as an outlier
    }
  }
  const double values = static_cast<double>(image.pixels.size()) * 3.0;
  EXPECT_LT(sum / values, kMeanTolerance) << c.golden;
  EXPECT_LT(static_cast<double>(outliers), kOutlierFraction * values) << c.golden << ": " << outliers << " outliers";
}

std::string case_name(const ::testing::TestParamInfo<Case>& param) {
  std::string name = fs::path(param.param.golden).stem().string();
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, Regression, ::testing::ValuesIn(cases()), case_name);

}  // namespace
}  // namespace pt
