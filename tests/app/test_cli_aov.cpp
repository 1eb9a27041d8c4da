// The command line's AOV, crop and replay options (docs/output.md), run as a
// process in a temporary folder.
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

}  // namespace
}  // namespace pt
