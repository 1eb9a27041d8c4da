// The command line's AOV, crop and replay options (docs/output.md), run as a
// process in a temporary folder.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
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

// What an integrator produces is the registry's (IntegratorInfo::aovs): any
// other AOV is refused before rendering, listing those it can produce.
TEST_F(CliOutput, AnAovTheIntegratorCannotProduceIsRefusedListingThoseItCan) {
  Result r = run("-o out.exr --aov albedo,diffuse_indirect");  // the scene's integrator: whitted
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--aov: the whitted integrator cannot produce AOV 'diffuse_indirect'; it produces: albedo N P Z "
                       "IndexOB IndexMA emission diffuse_direct specular_direct specular_indirect variance samples "
                       "nonfinite ambient CryptoObject CryptoMaterial"),
            std::string::npos)
      << r.err;
  r = run("-o out.exr --integrator path --aov ambient");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the path integrator cannot produce AOV 'ambient'; it produces: albedo N P Z IndexOB IndexMA "
                       "emission diffuse_direct diffuse_indirect specular_direct specular_indirect variance"),
            std::string::npos)
      << r.err;
  r = run("-o out.exr --integrator normal --aov N,specular_direct");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the normal integrator cannot produce AOV 'specular_direct'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out.exr")));
  r = run("-o out.exr --quiet --aov emission,ambient,diffuse_direct,specular_direct,specular_indirect");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("out.exr")));
}

// The path integrator leaves an ambient light out, saying so once.
TEST_F(CliOutput, PathWarnsOnceAboutAnAmbientLight) {
  write("ambient.json", R"({ "format": "pathtracer-scene", "version": 1,
    "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0] }, "film": { "width": 8, "height": 6 },
    "lights": [{ "type": "ambient", "intensity": [0.1, 0.1, 0.1] }, { "type": "ambient", "intensity": [0.2, 0.2, 0.2] },
               { "type": "point", "position": [0, 3, 3], "intensity": [1, 1, 1] }],
    "shapes": [{ "type": "sphere", "center": [0, 0, 0], "radius": 1 }] })");
  Result r = AppTest::run("ambient.json -o a.png --integrator path --spp 1");
  EXPECT_EQ(r.status, 0) << r.err;
  const std::string warning = "an ambient light is not physical: the path integrator leaves it out";
  const std::size_t at = r.err.find(warning);
  EXPECT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning, at + 1), std::string::npos) << r.err;  // once
  EXPECT_NE(r.err.find("ambient.json:"), std::string::npos) << r.err;
  r = AppTest::run("ambient.json -o w.png --spp 1");  // whitted: the classic term, no warning
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("ambient light"), std::string::npos) << r.err;
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

// The documented interface is --pixel X,Y with --sample N (0 by default);
// --replay X,Y,N is a shorthand for the same thing: one code path, the same
// output.
TEST_F(CliOutput, PixelAndSampleReplayExactlyAsTheReplayShorthand) {
  const Result a = run("--integrator path --spp 4 --pixel 12,10 --sample 3");
  const Result b = run("--integrator path --spp 4 --replay 12,10,3");
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_NE(a.out.find("replay pixel (12, 10) sample 3: radiance "), std::string::npos) << a.out;
  EXPECT_EQ(a.out, b.out);
  const Result zero = run("--integrator path --spp 4 --pixel 12,10");
  ASSERT_EQ(zero.status, 0) << zero.err;
  EXPECT_EQ(zero.out, run("--integrator path --spp 4 --replay 12,10,0").out);
  EXPECT_NE(zero.out.find("replay pixel (12, 10) sample 0: "), std::string::npos) << zero.out;
}

// Bad replays are usage errors (exit 2) that name the option as it was
// spelt; the two spellings exclude each other, and --sample needs --pixel.
TEST_F(CliOutput, BadReplaysNameTheirOption) {
  struct Case {
    const char* args;
    const char* message;  // on stderr
  };
  const Case cases[] = {
      {"--pixel 40,3", "error: --pixel: pixel (40, 3) is not inside the 32x24 frame"},
      {"--replay 40,3,0", "error: --replay: pixel (40, 3) is not inside the 32x24 frame"},
      {"--pixel -1,3", "error: --pixel: pixel (-1, 3) is not inside the 32x24 frame"},
      {"--pixel 2147483647,0", "error: --pixel: pixel (2147483647, 0) is not inside the 32x24 frame"},
      {"--pixel 3,3 --sample 1", "error: --sample: sample 1 is not one of the render's 1 samples per pixel"},
      {"--replay 3,3,1", "error: --replay: sample 1 is not one of the render's 1 samples per pixel"},
      {"--pixel 3,3 --sample -1", "error: --sample: sample -1 is negative"},
      {"--replay 3,3,-2", "error: --replay: sample -2 is negative"},
      {"--sample 0", "--sample requires --pixel"},
      {"--pixel 3,3 --replay 3,3,0", "excludes"},
      {"--pixel 3,3 --sample 0 --replay 3,3,0", "excludes"},
      {"--pixel 3", "--pixel"},
      {"--pixel 3,x", "--pixel"},
      {"--replay 3,3", "--replay"},
  };
  for (const Case& c : cases) {
    const Result r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out.find("replay pixel"), std::string::npos) << c.args;
  }
}

// A backdrop image of +Inf behind a sphere (test::backdrop_scene): the camera
// rays that miss the sphere carry non-finite samples. The warning names the
// first and the flags that replay it; those flags, added to the same command,
// print that very sample, non-finite.
TEST_F(CliOutput, TheNonFiniteWarningGivesTheFlagsThatReplayTheFirstOffender) {
  write("hot.json", test::backdrop_scene("inf.exr", 32, 24, 4));
  write_image("inf.exr", 4, 4, std::numeric_limits<float>::infinity());
  const Result r = AppTest::run("hot.json -o hot.exr --spp 4 --seed 3");
  ASSERT_EQ(r.status, 0) << r.err;
  int x = -1, y = -1, sample = -1;
  const std::size_t first = r.err.find("first at pixel (");
  ASSERT_NE(first, std::string::npos) << r.err;
  ASSERT_EQ(std::sscanf(r.err.c_str() + first, "first at pixel (%d, %d) sample %d", &x, &y, &sample), 3) << r.err;
  const std::string flags =
      "--pixel " + std::to_string(x) + "," + std::to_string(y) + " --sample " + std::to_string(sample);
  EXPECT_NE(r.err.find("; to replay the first, run this command again with " + flags + "\n"), std::string::npos)
      << r.err;
  const Result replay = AppTest::run("hot.json -o hot.exr --spp 4 --seed 3 " + flags);
  ASSERT_EQ(replay.status, 0) << replay.err;
  const std::string line = "replay pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") sample " +
                           std::to_string(sample) + ": radiance ";
  const std::size_t at = replay.out.find(line);
  ASSERT_NE(at, std::string::npos) << replay.out;
  float rgb[3];
  ASSERT_EQ(std::sscanf(replay.out.c_str() + at + line.size(), "%f %f %f", &rgb[0], &rgb[1], &rgb[2]), 3)
      << replay.out;
  EXPECT_FALSE(std::isfinite(rgb[0]) && std::isfinite(rgb[1]) && std::isfinite(rgb[2])) << replay.out;
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
