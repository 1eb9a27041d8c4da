// The command line's AOV, crop and replay options (docs/output.md), run as a
// process in a temporary folder.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "app_fixture.h"
#include "io/image_io.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

// A small CGR-format scene (see ../shared/seed-scenes/CONVENTIONS.md): 32 x 24.
const char* kScene = R"({
  "nbounces": 3,
  "rendermode": "phong",
  "camera": {
    "type": "pinhole", "width": 32, "height": 24,
    "position": [0, 0, 0], "lookAt": [0, 0, 1], "upVector": [0, 1, 0], "fov": 45.0, "exposure": 0.1
  },
  "scene": {
    "backgroundcolor": [0.25, 0.25, 0.25],
    "lightsources": [{"type": "pointlight", "position": [0, 1, 0.5], "intensity": [0.75, 0.75, 0.75]}],
    "shapes": [
      {"type": "sphere", "center": [-0.3, 0.1, 1], "radius": 0.2},
      {"type": "triangle", "v0": [0, 0, 1], "v1": [0.5, 0, 1], "v2": [0.25, 0.25, 1]}
    ]
  }
}
)";

using Result = test::RunResult;

// Runs every command on the CGR scene above (app_fixture.h's folder and runner).
class CliOutput : public test::AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    write("scene.json", kScene);
  }
  Result run(const std::string& args) const { return AppTest::run("scene.json " + args); }
};

TEST_F(CliOutput, UnknownAovIsAUsageErrorListingTheValidNames) {
  const Result r = run("-o out.exr --aov albedo,depth");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown AOV 'depth'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("diffuse_direct"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out.exr")));
}

TEST_F(CliOutput, BadCropsAndReplaysAreUsageErrors) {
  for (const char* args : {"-o out.exr --crop 0.5,0.5,0.4,1", "-o out.exr --crop 0,0,1", "-o out.exr --crop 0,0,1,1.5",
                           "-o out.exr --crop-px 30,0,5,5", "-o out.exr --crop-px 0,0,0,5",
                           "-o out.exr --crop-px 2147483647,0,5,5", "-o out.exr --crop-px 0,0,5,2147483647",
                           "-o out.exr --crop 0,0,1,1 --crop-px 0,0,4,4", "--replay 40,3,0", "--replay 3,3,1",
                           "--replay 3,3"}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_FALSE(fs::exists(path("out.exr")));
}

TEST_F(CliOutput, CropWritesTheCropAndItsPixelsMatchTheFullRender) {
  ASSERT_EQ(run("-o full.exr --integrator path --spp 2 --quiet").status, 0);
  const Result r = run("-o crop.exr -o crop.png --integrator path --spp 2 --crop-px 5,4,10,7 --aov Z,IndexOB");
  ASSERT_EQ(r.status, 0) << r.err;
  Image full, crop, png;
  std::string error;
  ASSERT_TRUE(read_image(path("full.exr"), full, error)) << error;
  ASSERT_TRUE(read_image(path("crop.exr"), crop, error)) << error;
  ASSERT_TRUE(read_image(path("crop.png"), png, error)) << error;
  ASSERT_EQ(crop.width, 10);
  ASSERT_EQ(crop.height, 7);
  EXPECT_EQ(png.width, 10);
  EXPECT_EQ(png.height, 7);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 10; ++x) EXPECT_EQ(crop.at(x, y), full.at(x + 5, y + 4)) << x << "," << y;
  // Fractions: [0.25, 0.75) x [0.5, 1) of 32 x 24.
  ASSERT_EQ(run("-o frac.exr --crop 0.25,0.5,0.75,1 --quiet").status, 0);
  Image frac;
  ASSERT_TRUE(read_image(path("frac.exr"), frac, error)) << error;
  EXPECT_EQ(frac.width, 16);
  EXPECT_EQ(frac.height, 12);
}

TEST_F(CliOutput, ReplayPrintsTheSampleOfAOneSppRender) {
  ASSERT_EQ(run("-o one.exr --integrator path --spp 1 --quiet").status, 0);
  const Result r = run("--replay 12,10,0 --integrator path --spp 1");
  ASSERT_EQ(r.status, 0) << r.err;
  Image one;
  std::string error;
  ASSERT_TRUE(read_image(path("one.exr"), one, error)) << error;
  float v[3] = {};
  const std::string key = "replay pixel (12, 10) sample 0: radiance ";
  const std::size_t at = r.out.find(key);
  ASSERT_NE(at, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at + key.size(), "%g %g %g", &v[0], &v[1], &v[2]), 3) << r.out;
  EXPECT_EQ(v[0], one.at(12, 10).r);
  EXPECT_EQ(v[1], one.at(12, 10).g);
  EXPECT_EQ(v[2], one.at(12, 10).b);
  // The sample's AOVs follow: pixel (12, 10) sees the sphere (object 1; the triangle is 2).
  EXPECT_NE(r.out.find("  IndexOB: 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  diffuse_direct:"), std::string::npos) << r.out;
}

// The replay of sample `sample` of pixel (12, 10): its radiance and filter
// weight (1 if not printed), parsed from stdout; false (with the output in
// `why`) if absent.
bool replay_values(const Result& r, int sample, RGB& radiance, double& weight, std::string& why) {
  const std::string key = "replay pixel (12, 10) sample " + std::to_string(sample) + ": radiance ";
  const std::size_t at = r.out.find(key);
  const std::size_t w = r.out.find("  filter weight: ");
  why = "status " + std::to_string(r.status) + "\n" + r.out + r.err;
  if (r.status != 0 || at == std::string::npos) return false;
  weight = 1.0;
  return std::sscanf(r.out.c_str() + at + key.size(), "%g %g %g", &radiance.r, &radiance.g, &radiance.b) == 3 &&
         (w == std::string::npos || std::sscanf(r.out.c_str() + w, "  filter weight: %lg", &weight) == 1);
}

// Replay reproduces exactly the samples the render accumulated, whatever its
// pass plan: the filtered mean of the replays of every sample of a pixel is
// the rendered pixel. The jittered sampler and the classic integrators' pixel
// grid stratify per pass (docs/cli.md), so a replay must draw sample N as the
// pass that rendered it did; the 2-spp jittered render in passes of 1 was
// 0.206037 at this pixel while the replays averaged 0.199813.
TEST_F(CliOutput, ReplaysOfEverySampleAverageToTheRenderedPixel) {
  struct Plan {
    std::string options;
    int spp;
  };
  const Plan plans[] = {
      {"--integrator path --sampler jittered --spp 2 --pass-spp 1", 2},
      {"--integrator path --sampler jittered --filter mitchell --spp 8 --pass-spp 4", 8},
      {"--integrator path --sampler jittered --spp 6", 6},              // one pass
      {"--integrator path --sampler sobol --spp 4 --pass-spp 3", 4},    // unequal passes: 3 + 1
      {"--integrator whitted --spp 8 --pass-spp 4", 8},                 // 2x2 grid per pass
      {"--integrator whitted --spp 18 --checkpoint c.ckpt", 18},        // checkpoints: passes of 9 (3x3)
  };
  for (const Plan& p : plans) {
    SCOPED_TRACE(p.options);
    ASSERT_EQ(run("-o full.exr --quiet " + p.options).status, 0);
    Image full;
    std::string error;
    ASSERT_TRUE(read_image(path("full.exr"), full, error)) << error;
    double sum[3] = {}, weights = 0;
    for (int n = 0; n < p.spp; ++n) {
      const std::string replay = "--replay 12,10," + std::to_string(n);
      RGB v;
      double w = 0;
      ASSERT_TRUE(replay_values(run(p.options + " " + replay), n, v, w, error)) << replay << ": " << error;
      for (int c = 0; c < 3; ++c) sum[c] += w * v[c];
      weights += w;
    }
    ASSERT_NE(weights, 0.0);
    const RGB pixel = full.at(12, 10);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / weights, pixel[c], 1e-6 * (1 + std::fabs(pixel[c]))) << c;
  }
}

// A render with a time budget and no --spp replays with the same options: the
// sample's pass size comes from the plan (equal passes of --pass-spp, 2 here),
// so samples 0 and 1 are the first pass, the 2-spp render in one pass.
TEST_F(CliOutput, ATimeBudgetRenderReplaysWithoutSpp) {
  ASSERT_EQ(run("-o two.exr --quiet --integrator path --sampler jittered --spp 2").status, 0);
  Image two;
  std::string error;
  ASSERT_TRUE(read_image(path("two.exr"), two, error)) << error;
  double sum = 0;
  for (int n = 0; n < 2; ++n) {
    RGB v;
    double w = 0;
    ASSERT_TRUE(replay_values(run("--integrator path --sampler jittered --time-budget 5 --pass-spp 2 --replay 12,10," +
                                  std::to_string(n)),
                              n, v, w, error))
        << error;
    sum += v.r;
  }
  EXPECT_NEAR(sum / 2, two.at(12, 10).r, 1e-6);
}

// A replay writes nothing: not the outputs, checkpoint or run record of the
// command it was added to (they would hold one pixel).
TEST_F(CliOutput, AReplayWritesNoFiles) {
  const Result r = run("-o out.exr --checkpoint c.ckpt --report run.json --spp 4 --replay 1,1,2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("replay pixel (1, 1) sample 2"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("out.exr")));
  EXPECT_FALSE(fs::exists(path("c.ckpt")));
  EXPECT_FALSE(fs::exists(path("run.json")));
}

}  // namespace
}  // namespace pt
