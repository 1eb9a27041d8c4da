// Scenes scaled by 1e-3 and 1e3 render the same image, for every backend,
// through the pathtracer executable with the whitted integrator: contact
// shadows under resting objects, mirror and glass secondary rays, shadow rays
// and silhouettes must not depend on the scene's units.
//
// The scene (scenes/contact-and-secondary-rays.json) is rewritten with every
// length multiplied by s (camera, shapes, light positions) and the point
// lights' intensities by s^2, which keeps the irradiance I/r^2 unchanged.
//
// Tolerance: camera rays, reflections and refractions are the same rays in
// units of s, but their floats round differently, so a pixel whose ray passes
// within a rounding error of a silhouette or a shadow edge may flip. Measured
// (both backends, 320x240): no pixel differs by more than 2%, and the mean
// absolute difference is 1.7e-7 of the mean value. Allowed: 0.05% of the
// pixels (38) differing by more than 2%, and a mean absolute difference of
// 2e-5 of the mean. A renderer with a fixed 1e-4 ray offset instead of the
// self-intersection policy fails at 1e-3: 3% of the pixels, mean 1.7e-2
// (light leaks under the resting objects).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "../hostile/run_process.h"
#include "backends.h"
#include "io/image_io.h"

namespace pt {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kScene = fs::path(PT_TEST_DATA_DIR) / "stability" / "scenes" / "contact-and-secondary-rays.json";
constexpr double kMaxDifferingPixels = 5e-4;    // fraction
constexpr float kPixelTolerance = 0.02f;        // relative to the pixel's value (absolute below 1)
constexpr double kMaxMeanDifference = 2e-5;     // relative to the mean value

void scale_points(json& v, double s) {
  if (v.is_array() && !v.empty() && v[0].is_number()) {
    for (json& x : v) x = x.get<double>() * s;
  } else if (v.is_array()) {
    for (json& p : v) scale_points(p, s);
  }
}

// Every length in a native scene multiplied by s; inverse-square intensities by s^2.
json scaled(json scene, double s) {
  json& cam = scene["camera"];
  for (const char* key : {"position", "look_at"}) scale_points(cam[key], s);
  for (json& light : scene["lights"]) {
    scale_points(light["position"], s);
    for (const char* key : {"intensity", "specular_intensity"})
      if (light.contains(key)) scale_points(light[key], s * s);
  }
  for (json& shape : scene["shapes"]) {
    for (const char* key : {"center", "vertices", "p0", "p1", "positions"})
      if (shape.contains(key)) scale_points(shape[key], s);
    if (shape.contains("radius")) shape["radius"] = shape["radius"].get<double>() * s;
  }
  return scene;
}

class ScaledScenes : public test::PerBackend {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pt_scaled_" + std::to_string(::getpid()) + "_" + GetParam());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Renders the scene scaled by s; returns false (with a failure) if the run failed.
  bool render(double s, Image& image) {
    std::ifstream in(kScene);
    const json scene = scaled(json::parse(in), s);
    const std::string name = "scaled_" + std::to_string(s);
    std::ofstream(dir_ / (name + ".json")) << scene.dump(2);
    const test::ProcessResult r =
        test::run_process({PT_PATHTRACER_EXE, name + ".json", "-o", name + ".exr", "--accel=" + GetParam(),
                           "--integrator", "whitted", "--threads", "2", "--quiet"},
                          dir_, dir_, test::ProcessLimits{120, 0});
    if (r.exited && r.exit_code != 0 && r.err.find("not available") != std::string::npos) {
      unavailable_ = r.err;
      return false;
    }
    EXPECT_TRUE(r.exited && r.exit_code == 0) << "scale " << s << ": " << r.err;
    EXPECT_FALSE(test::has_sanitizer_report(r.err)) << r.err;
    std::string error;
    const bool ok = r.exited && r.exit_code == 0 && read_image((dir_ / (name + ".exr")).string(), image, error);
    EXPECT_TRUE(ok) << error;
    return ok;
  }

  fs::path dir_;
  std::string unavailable_;
};

struct Difference {
  double differing_fraction = 0;
  double mean_abs = 0;
  double mean_value = 0;
  int non_finite = 0;
};

Difference compare(const Image& a, const Image& b) {
  Difference d;
  const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  std::size_t differing = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const RGB pa = a.at(x, y), pb = b.at(x, y);
      bool differs = false;
      for (const auto& [va, vb] : {std::pair{pa.r, pb.r}, std::pair{pa.g, pb.g}, std::pair{pa.b, pb.b}}) {
        if (!std::isfinite(va) || !std::isfinite(vb)) ++d.non_finite;
        const float diff = std::fabs(va - vb);
        d.mean_abs += diff;
        d.mean_value += va;
        differs = differs || diff > kPixelTolerance * std::max(1.0f, std::fabs(va));
      }
      differing += differs;
    }
  }
  d.differing_fraction = static_cast<double>(differing) / static_cast<double>(n);
  d.mean_abs /= 3.0 * static_cast<double>(n);
  d.mean_value /= 3.0 * static_cast<double>(n);
  return d;
}

TEST_P(ScaledScenes, RenderTheSameImageAtEveryScale) {
  Image reference;
  if (!render(1.0, reference)) {
    if (!unavailable_.empty()) GTEST_SKIP() << unavailable_;
    return;
  }
  ASSERT_GT(reference.width, 0);
  for (double s : {1e-3, 1e3}) {
    Image image;
    if (!render(s, image)) return;
    ASSERT_EQ(image.width, reference.width);
    ASSERT_EQ(image.height, reference.height);
    const Difference d = compare(reference, image);
    EXPECT_EQ(d.non_finite, 0);
    EXPECT_LE(d.differing_fraction, kMaxDifferingPixels) << "scale " << s;
    EXPECT_LE(d.mean_abs, kMaxMeanDifference * d.mean_value) << "scale " << s;
    std::cout << "[ scaled   ] " << GetParam() << " x" << s << ": " << 100.0 * d.differing_fraction
              << "% of pixels differ by more than " << 100.0f * kPixelTolerance << "%, mean |diff| "
              << d.mean_abs / d.mean_value << " of the mean\n";
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ScaledScenes, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt
