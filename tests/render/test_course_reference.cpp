// The official course scenes against the courses' own reference images
// (../shared/reference/course-official, skipped when absent): issue 14 part A.
// Each scene is rendered at the reference's resolution and sample count, encoded
// through the scene's display transform, and compared in 8-bit values.
// The inferred model and what is still unmatched: docs/rendering.md, "The course
// reference images".
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imagebuf.h>

#include "core/parallel.h"
#include "io/display.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

const fs::path kShared = fs::path(PT_SHARED_DIR);

struct Codes {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // interleaved, 3 per pixel
};

// The scene rendered as the course would be: its own resolution and spp, its display transform.
Codes render_codes(const fs::path& scene_file, const std::vector<std::string>& overrides) {
  Codes out;
  Diagnostics diag;
  LoadOptions load;
  load.overrides = overrides;
  const auto desc = load_scene(scene_file.string(), load, diag);
  EXPECT_TRUE(desc.has_value()) << diag.format();
  if (!desc) return out;
  WorkerPool pool(2);
  const auto scene = build_render_scene(*desc, BuildOptions{}, pool, diag);
  EXPECT_TRUE(scene != nullptr) << diag.format();
  if (!scene) return out;
  IntegratorSettings settings;
  settings.max_depth = desc->render.max_depth;
  settings.spp = desc->render.spp;
  std::string error;
  const auto integrator = make_integrator(desc->render.integrator, settings, error);
  EXPECT_TRUE(integrator != nullptr) << error;
  if (!integrator) return out;
  Film film(scene->width, scene->height);
  integrator->render(*scene, film, pool);
  const Image image = film.image();
  const auto encoder = DisplayEncoder::create(DisplaySettings{desc->film.display, desc->film.exposure}, error);
  EXPECT_TRUE(encoder != nullptr) << error;
  if (!encoder) return out;
  out.width = scene->width;
  out.height = scene->height;
  out.rgb.resize(static_cast<std::size_t>(out.width) * out.height * 3);
  encoder->encode(image.pixels.data(), image.pixels.size(), out.rgb.data());
  return out;
}

Codes read_reference(const fs::path& file) {
  Codes out;
  OIIO::ImageBuf buf(file.string());
  if (!buf.read(0, 0, true, OIIO::TypeDesc::UINT8)) return out;
  const OIIO::ImageSpec& spec = buf.spec();
  out.width = spec.width;
  out.height = spec.height;
  out.rgb.resize(static_cast<std::size_t>(out.width) * out.height * 3);
  buf.get_pixels(OIIO::ROI(0, out.width, 0, out.height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, out.rgb.data());
  return out;
}

// Mean absolute difference per channel, in 8-bit levels.
std::array<double, 3> mean_abs_difference(const Codes& a, const Codes& b) {
  std::array<double, 3> sum{};
  for (std::size_t i = 0; i < a.rgb.size(); ++i) sum[i % 3] += std::abs(int(a.rgb[i]) - int(b.rgb[i]));
  const double pixels = static_cast<double>(a.rgb.size() / 3);
  for (double& s : sum) s /= pixels;
  return sum;
}

// Intersection over union of the pixels whose largest channel is above half.
double mask_iou(const Codes& a, const Codes& b) {
  std::size_t both = 0, either = 0;
  for (std::size_t p = 0; p < a.rgb.size(); p += 3) {
    auto on = [p](const Codes& c) { return std::max({c.rgb[p], c.rgb[p + 1], c.rgb[p + 2]}) > 127; };
    both += on(a) && on(b);
    either += on(a) || on(b);
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

struct Pair {
  Codes ours, reference;
};

// Skips (returns false) when the shared course files are absent.
bool load_pair(const std::string& scene, const std::string& reference, Pair& out,
               const std::vector<std::string>& overrides = {}) {
  const fs::path scene_file = kShared / "seed-scenes" / scene;
  const fs::path reference_file = kShared / "reference" / "course-official" / reference;
  if (!fs::exists(scene_file) || !fs::exists(reference_file)) return false;
  out.ours = render_codes(scene_file, overrides);
  out.reference = read_reference(reference_file);
  EXPECT_EQ(out.ours.width, out.reference.width);
  EXPECT_EQ(out.ours.height, out.reference.height);
  return out.ours.rgb.size() == out.reference.rgb.size() && !out.ours.rgb.empty();
}

#define PT_LOAD_OR_SKIP(...) \
  Pair pair;                 \
  if (!load_pair(__VA_ARGS__)) GTEST_SKIP() << "course files or reference images not available"

// The target of issue 14 is at most 3/255 per channel over the frame; the
// bounds keep what the inferred model reaches (docs/rendering.md, "The course
// reference images"), with about half a level of margin.
// simple_phong: 0.24, 0.28, 0.44 (1.8, 2.6, 2.4 with the power curve and kd Cd ambient).
TEST(CourseReference, CgrSimplePhongWithin3Levels) {
  PT_LOAD_OR_SKIP("cgr/simple_phong.json", "cgr/simple_phong.png", pair);
  const std::array<double, 3> mad = mean_abs_difference(pair.ours, pair.reference);
  for (int c = 0; c < 3; ++c) EXPECT_LE(mad[c], 1.0) << "channel " << c;
}

// scene.json in phong mode: 1.27, 1.06, 1.43 (9.6, 9.5, 9.1 with the power curve).
TEST(CourseReference, CgrScenePhongWithin3Levels) {
  PT_LOAD_OR_SKIP("cgr/scene.json", "cgr/scene_phong.png", pair, {"rendermode=phong"});
  const std::array<double, 3> mad = mean_abs_difference(pair.ours, pair.reference);
  for (int c = 0; c < 3; ++c) EXPECT_LE(mad[c], 2.0) << "channel " << c;
}

// Not at the 6/255 target (docs/rendering.md: the figure's reflection weight
// differs between its floor and its back wall, and its textured floor clamps
// the light's factor at 1; together 10.4 of the remaining levels); the bound
// keeps what is reached (11.5, 11.5, 12.5; 17.9 before the texture rules).
TEST(CourseReference, PathOfLightExampleBounded) {
  PT_LOAD_OR_SKIP("path-of-light/examples/example.json", "path-of-light/example.png", pair);
  const std::array<double, 3> mad = mean_abs_difference(pair.ours, pair.reference);
  for (int c = 0; c < 3; ++c) EXPECT_LE(mad[c], 13.0) << "channel " << c;
}

// The target: binary masks with IoU >= 0.997, without any shift (0.9985 and
// 0.9924 before the course's pixel positions, CameraDesc::film_offset).
TEST(CourseReference, CgrBinaryMasksWithoutShift) {
  for (const char* name : {"scene", "binary_primitives"}) {
    const std::string reference = std::string("cgr/") + (std::string(name) == "scene" ? "scene_binary" : name) + ".png";
    Pair pair;
    if (!load_pair(std::string("cgr/") + name + ".json", reference, pair)) GTEST_SKIP() << "course files not available";
    EXPECT_GE(mask_iou(pair.ours, pair.reference), 0.997) << name;
  }
}

}  // namespace
}  // namespace pt
