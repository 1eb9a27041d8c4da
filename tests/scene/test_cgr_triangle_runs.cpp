// A CGR file's long runs of "triangle" shapes with equal materials become one
// mesh (src/scene/cgr_triangle_runs.h): what the description keeps and drops,
// where the messages stay, and the same images as the triangles one by one,
// on both backends and with both course integrators.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/cgr_triangle_runs.h"
#include "scene/loader.h"

namespace pt {
namespace {

constexpr int kCells = 8;  // a bumpy 8x8 grid: 128 triangles
const char* const kMaterial =
    R"("material": {"ks": 0.3, "kd": 0.7, "specularexponent": 20, "diffusecolor": [0.8, 0.6, 0.4], )"
    R"("specularcolor": [1, 1, 1], "isreflective": false, "reflectivity": 1.0, "isrefractive": false, )"
    R"("refractiveindex": 1.0})";

Vec3f grid_point(int i, int j) {
  const float x = -1.0f + 2.0f * static_cast<float>(i) / kCells, z = -1.0f + 2.0f * static_cast<float>(j) / kCells;
  return Vec3f(x, 0.2f * std::sin(3.0f * x) * std::cos(3.0f * z), z);
}

std::string point(Vec3f p) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.6f, %.6f, %.6f]", static_cast<double>(p.x), static_cast<double>(p.y),
                static_cast<double>(p.z));
  return text;
}

std::string triangle(Vec3f a, Vec3f b, Vec3f c) {
  return R"({"type": "triangle", "v0": )" + point(a) + R"(, "v1": )" + point(b) + R"(, "v2": )" + point(c) + ", " +
         kMaterial + "},\n";
}

// One shape a line (line 4 + its index): the grid's triangles (a zero-area
// one before each one listed in `breaks`, by the triangle's number), a sphere,
// three more triangles.
std::string course_file(const std::string& mode, const std::vector<int>& breaks = {}) {
  std::string shapes;
  int n = 0;
  for (int i = 0; i < kCells; ++i) {
    for (int j = 0; j < kCells; ++j) {
      for (int half = 0; half < 2; ++half, ++n) {
        if (std::find(breaks.begin(), breaks.end(), n) != breaks.end())
          shapes += triangle(Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(2, 0, 0));
        const Vec3f a = grid_point(i, j), b = grid_point(i + 1, j), c = grid_point(i + 1, j + 1), d = grid_point(i, j + 1);
        shapes += half == 0 ? triangle(a, c, b) : triangle(a, d, c);
      }
    }
  }
  shapes += R"({"type": "sphere", "center": [0.3, 0.4, 0.2], "radius": 0.25, "material": {"diffusecolor": [0.3, 0.3, 0.9]}},)";
  shapes += '\n';  // appended apart: "\n" + triangle(...) trips GCC 12's -Wrestrict (a false positive)
  shapes += triangle(Vec3f(-1, 0.5, -1), Vec3f(-0.5, 0.5, -1), Vec3f(-1, 1, -1));
  shapes += triangle(Vec3f(-0.5, 0.5, -1), Vec3f(-0.5, 1, -1), Vec3f(-1, 1, -1));
  shapes += triangle(Vec3f(0.5, 0.5, -1), Vec3f(1, 0.5, -1), Vec3f(1, 1, -1));
  shapes.resize(shapes.size() - 2);  // the last ",\n"
  return R"({"rendermode": ")" + mode + R"(", "nbounces": 3, "spp": 4,
"camera": {"type": "pinhole", "width": 40, "height": 30, "position": [0, 1.6, 2.4], "lookAt": [0, 0, 0], "upVector": [0, 1, 0], "fov": 45},
"scene": {"backgroundcolor": [0.1, 0.1, 0.1], "lightsources": [{"type": "pointlight", "position": [1, 3, 2], "intensity": [0.8, 0.8, 0.8]}], "shapes": [
)" + shapes + "]}}";
}

std::optional<SceneDescription> load(const std::string& text, Diagnostics& diag) {
  return load_scene_from_string("run.json", text, LoadOptions{}, diag);
}

static_assert(CgrTriangleRuns::kMinRun == 64, "the files below are built around runs of 64");

TEST(CgrTriangleRuns, ALongRunIsOneMeshWithOneMaterial) {
  Diagnostics diag;
  const auto s = load(course_file("phong"), diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.warning_count(), 0) << diag.format();
  // The 128 grid triangles, the sphere, the three triangles (a run too short to merge).
  ASSERT_EQ(s->shapes.size(), 5u);
  const auto& mesh = std::get<TriangleMesh>(s->shapes[0].geometry);
  ASSERT_EQ(mesh.triangle_count(), 128u);
  EXPECT_EQ(mesh.positions.size(), 384u);  // the corners as written, three a triangle
  EXPECT_TRUE(mesh.normals.empty() && mesh.uvs.empty());
  EXPECT_LT(length(mesh.positions[0] - grid_point(0, 0)), 1e-5f);
  EXPECT_LT(length(mesh.positions[383] - grid_point(kCells, kCells)), 1e-5f);
  EXPECT_EQ(s->shapes[0].where.line, 4);  // the first triangle's place
  // Cryptomatte's object names: the run, then every later shape by its place in the file.
  EXPECT_EQ(s->shapes[0].name, "shapes[0-127]");
  EXPECT_EQ(s->shapes[1].name, "shapes[128]");
  EXPECT_EQ(s->shapes[4].name, "shapes[131]");
  // One material for the run; the sphere's and each short-run triangle's own.
  EXPECT_EQ(s->materials.size(), 5u);
  EXPECT_EQ(s->shapes[0].material, 0);
  EXPECT_EQ(s->shapes[1].material, 1);
  EXPECT_EQ(s->shapes[4].material, 4);
  EXPECT_EQ(s->materials[0].name, "material 0");
}

TEST(CgrTriangleRuns, AZeroAreaTriangleStaysAShapeWarnedAtItsPlace) {
  Diagnostics diag;
  const auto s = load(course_file("phong", {70}), diag);  // shapes[70] is the zero-area one
  ASSERT_TRUE(s) << diag.format();
  ASSERT_EQ(diag.warning_count(), 1) << diag.format();
  EXPECT_EQ(diag.all()[0].where.line, 4 + 70) << diag.format();
  EXPECT_NE(diag.all()[0].message.find("degenerate"), std::string::npos);
  // shapes[0-69] merged; shapes[70]; 58 triangles (too few to merge); the sphere; three triangles.
  ASSERT_EQ(s->shapes.size(), 1u + 1u + 58u + 1u + 3u);
  EXPECT_EQ(std::get<TriangleMesh>(s->shapes[0].geometry).triangle_count(), 70u);
  EXPECT_EQ(s->shapes[0].name, "shapes[0-69]");
  EXPECT_EQ(s->shapes[1].name, "shapes[70]");
  EXPECT_EQ(s->shapes[1].where.line, 4 + 70);
}

TEST(CgrTriangleRuns, AProblemWithTheRunsMaterialIsReportedOnceAtItsFirstCopy) {
  std::string text = course_file("phong");
  for (std::size_t at = text.find("\"kd\": 0.7"); at != std::string::npos; at = text.find("\"kd\": 0.7", at))
    text.replace(at, 9, "\"kd\": -10");
  Diagnostics diag;
  EXPECT_FALSE(load(text, diag));
  // The run (one material), the three short-run triangles (one each).
  EXPECT_EQ(diag.error_count(), 4) << diag.format();
  EXPECT_EQ(diag.all()[0].where.line, 4) << diag.format();
}

// A render of `text` with `kind`.
Image render(const std::string& text, AccelKind kind) {
  Diagnostics diag;
  const auto desc = load(text, diag);
  EXPECT_TRUE(desc) << diag.format();
  if (!desc) return Image{};
  WorkerPool pool(2);
  BuildOptions options;
  options.accel = kind;
  const auto scene = build_render_scene(*desc, options, pool, diag);
  EXPECT_TRUE(scene) << diag.format();
  IntegratorSettings settings;
  settings.spp = desc->render.spp.value;
  settings.max_depth = desc->render.max_depth.value;
  std::string error;
  const auto integrator = make_integrator(desc->render.integrator.value, settings, error);
  EXPECT_TRUE(integrator) << error;
  Film film(scene->width, scene->height);
  integrator->render(*scene, film, pool);
  return film.image();
}

// The merged file against the same triangles kept one by one (a zero-area
// triangle every 32 keeps each run short of 64). Each pixel's samples are the
// same rays; they meet the same triangles, except a ray through an edge that
// two triangles share exactly, where either is the nearest (both backends
// break such ties by traversal order). So: nearly every pixel bit-identical,
// and the images' means within 1e-3.
TEST(CgrTriangleRuns, RendersAsTheTrianglesOneByOne) {
  for (const char* mode : {"phong", "pathtracer"}) {
    const std::string merged = course_file(mode), separate = course_file(mode, {32, 64, 96});
    {
      Diagnostics diag;
      const auto s = load(separate, diag);
      ASSERT_TRUE(s);
      ASSERT_EQ(s->shapes.size(), 128u + 3u + 4u);  // nothing merged
    }
    for (AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
      const Image a = render(merged, kind), b = render(separate, kind);
      ASSERT_EQ(a.pixels.size(), b.pixels.size());
      ASSERT_FALSE(a.pixels.empty());
      std::size_t same = 0;
      double mean_a = 0, mean_b = 0;
      for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        same += a.pixels[i] == b.pixels[i];
        mean_a += a.pixels[i].r + a.pixels[i].g + a.pixels[i].b;
        mean_b += b.pixels[i].r + b.pixels[i].g + b.pixels[i].b;
      }
      const double n = static_cast<double>(a.pixels.size());
      EXPECT_GE(static_cast<double>(same) / n, 0.98) << mode << " " << static_cast<int>(kind);
      EXPECT_NEAR(mean_a / (3 * n), mean_b / (3 * n), 1e-3) << mode << " " << static_cast<int>(kind);
      EXPECT_GT(mean_a / (3 * n), 0.12) << "lit, not only the background";
    }
  }
}

}  // namespace
}  // namespace pt
