// Every regression scene (the seed scenes in ../shared, skipped if absent, and
// scenes/*.json) rendered with Embree and with our BVH, at reduced resolution
// and at most 16 samples per pixel: the images must agree within float
// tolerance. The backends find the same hits (the BVH through the reference
// routines, Embree through its own triangle test, whose t differs from ours in
// the last bits), so paths differ only by rounding; the tolerance allows that:
// a mean absolute difference under 1e-4 and fewer than 0.1% of the channel
// values differing by more than 1e-2 (a hit that flips at a silhouette).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 96;
constexpr int kMaxSpp = 16;

std::vector<std::string> scene_files() {
  std::vector<std::string> out;
  const fs::path seeds = fs::path(PT_SHARED_DIR) / "seed-scenes";
  for (const char* name : {"binary_primitives", "mirror_image", "scene", "simple_phong"})
    out.push_back((seeds / "cgr" / (std::string(name) + ".json")).string());
  out.push_back((seeds / "path-of-light" / "examples" / "example.json").string());
  // scenes/, then the test scenes of tests/data/scenes (transforms and
  // instancing, the classic lights, the orthographic and spherical cameras:
  // not under scenes/, since builds before them cannot read them).
  for (const fs::path& dir : {fs::path(PT_SCENES_DIR), fs::path(PT_TEST_DATA_DIR) / "data" / "scenes"}) {
    std::error_code ec;
    std::vector<std::string> native;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".json") native.push_back(e.path().string());
    std::sort(native.begin(), native.end());
    out.insert(out.end(), native.begin(), native.end());
  }
  return out;
}

bool render(const SceneDescription& desc, AccelKind kind, Image& out, std::string& error) {
  Diagnostics diag;
  WorkerPool pool(2);
  BuildOptions options;
  options.accel = kind;
  options.width_override = kWidth;
  const auto scene = build_render_scene(desc, options, pool, diag);
  if (!scene) {
    error = diag.format();
    return false;
  }
  IntegratorSettings settings;
  settings.max_depth = desc.render.max_depth;
  settings.spp = std::min<int>(desc.render.spp, kMaxSpp);
  const auto integrator = make_integrator(desc.render.integrator, settings, error);
  if (!integrator) return false;
  Film film(scene->width, scene->height);
  integrator->render(*scene, film, pool);
  out = film.image();
  return true;
}

class BackendImages : public ::testing::TestWithParam<std::string> {};

TEST_P(BackendImages, EmbreeAndBvhAgree) {
  const std::string& file = GetParam();
  if (!fs::exists(file)) GTEST_SKIP() << file << " is not available";
  Diagnostics diag;
  const auto desc = load_scene(file, LoadOptions{}, diag);
  ASSERT_TRUE(desc.has_value()) << diag.format();
  Image embree, bvh;
  std::string error;
  ASSERT_TRUE(render(*desc, AccelKind::Embree, embree, error)) << error;
  ASSERT_TRUE(render(*desc, AccelKind::Bvh, bvh, error)) << error;
  ASSERT_EQ(embree.pixels.size(), bvh.pixels.size());
  double sum = 0;
  std::size_t outliers = 0;
  for (std::size_t i = 0; i < embree.pixels.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      const float d = std::fabs(embree.pixels[i][ch] - bvh.pixels[i][ch]);
      sum += d;
      if (!(d <= 1e-2f)) ++outliers;  // NaN counts
    }
  }
  const double values = 3.0 * static_cast<double>(embree.pixels.size());
  EXPECT_LT(sum / values, 1e-4) << file;
  EXPECT_LT(static_cast<double>(outliers), 1e-3 * values) << file << ": " << outliers << " outliers";
}

std::string case_name(const ::testing::TestParamInfo<std::string>& info) {
  const fs::path p(info.param);
  std::string name = p.parent_path().filename().string() + "_" + p.stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, BackendImages, ::testing::ValuesIn(scene_files()), case_name);

}  // namespace
}  // namespace pt
