// The pathtracer command line, run as a process in a temporary folder.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app_fixture.h"
#include "io/image_io.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

// A small CGR-format scene (see ../shared/seed-scenes/CONVENTIONS.md).
std::string cgr_scene(const std::string& mode, const std::string& extra_camera_key = "") {
  return R"({
  "nbounces": 3,
  "rendermode": ")" + mode + R"(",
  "camera": {
    "type": "pinhole", "width": 32, "height": 24,
    "position": [0, 0, 0], "lookAt": [0, 0, 1], "upVector": [0, 1, 0],
    "fov": 45.0, "exposure": 0.1)" + extra_camera_key + R"(
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
}

using Result = test::RunResult;

class Cli : public test::AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    write("binary.json", cgr_scene("binary"));
    write("phong.json", cgr_scene("phong"));
  }

  // Files in the folder other than the scenes the fixture wrote.
  std::vector<std::string> outputs() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string n = e.path().filename().string();
      if (e.path().extension() != ".json") names.push_back(n);
    }
    return names;
  }
};

TEST_F(Cli, RendersAndWritesTheImage) {
  const Result r = run("phong.json -o out.ppm");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("out.ppm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("render"), std::string::npos) << r.out;
  Image img;
  std::string error;
  ASSERT_TRUE(read_image(path("out.ppm"), img, error)) << error;
  EXPECT_EQ(img.width, 32);
  EXPECT_EQ(img.height, 24);
  EXPECT_EQ(outputs(), std::vector<std::string>{"out.ppm"});
}

TEST_F(Cli, SeveralOutputsFromOneRender) {
  const Result r = run("phong.json -o a.exr -o b.png --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_TRUE(fs::exists(path("a.exr")));
  EXPECT_TRUE(fs::exists(path("b.png")));
}

TEST_F(Cli, BinaryModeIsPureRedAndBlack) {
  const Result r = run("binary.json -o b.ppm --spp 4");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string bytes = slurp(path("b.ppm"));
  const std::string header = "P6\n32 24\n255\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  int red = 0, black = 0;
  for (std::size_t i = header.size(); i + 2 < bytes.size(); i += 3) {
    const auto p = [&](std::size_t k) { return static_cast<unsigned char>(bytes[i + k]); };
    if (p(0) == 255 && p(1) == 0 && p(2) == 0) ++red;
    else if (p(0) == 0 && p(1) == 0 && p(2) == 0) ++black;
    else ADD_FAILURE() << "impure pixel at byte " << i;
  }
  EXPECT_GT(red, 10);
  EXPECT_GT(black, 10);
}

TEST_F(Cli, ResolutionOverride) {
  ASSERT_EQ(run("phong.json -o o.exr --width 16 --height 10").status, 0);
  Image img;
  std::string error;
  ASSERT_TRUE(read_image(path("o.exr"), img, error)) << error;
  EXPECT_EQ(img.width, 16);
  EXPECT_EQ(img.height, 10);
  ASSERT_EQ(run("phong.json -o p.exr --width 64").status, 0);
  ASSERT_TRUE(read_image(path("p.exr"), img, error)) << error;
  EXPECT_EQ(img.height, 48);  // keeps 32:24
}

TEST_F(Cli, OversizedResolutionOverrideIsRefusedBeforeAllocating) {
  // Each side within the per-side limit, the product far beyond the pixel limit.
  Result r = run("phong.json -o big.exr --width 32768 --height 32768");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("32768x32768 = 1073741824 pixels"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
  // One side given: the aspect ratio (32:24) makes the other exceed the per-side limit.
  r = run("phong.json -o big.exr --height 32000");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("42667x32000"), std::string::npos) << r.err;
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, SameImageForAnyThreadCount) {
  ASSERT_EQ(run("phong.json -o one.exr --threads 1 --spp 3").status, 0);
  ASSERT_EQ(run("phong.json -o two.exr --threads 2 --spp 3").status, 0);
  Image a, b;
  std::string error;
  ASSERT_TRUE(read_image(path("one.exr"), a, error)) << error;
  ASSERT_TRUE(read_image(path("two.exr"), b, error)) << error;
  EXPECT_EQ(a.pixels, b.pixels);
}

TEST_F(Cli, ReportRecordsSettingsAndPhases) {
  const Result r = run("phong.json -o out.exr --threads 2 --spp 3 --seed 7 --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("run.json")));
  EXPECT_EQ(j["image"]["width"], 32);
  EXPECT_EQ(j["image"]["height"], 24);
  EXPECT_EQ(j["image"]["spp"], 3);
  EXPECT_EQ(j["image"]["seed"], 7);
  EXPECT_EQ(j["image"]["integrator"], "whitted");
  EXPECT_EQ(j["threads"], 2);
  EXPECT_EQ(j["accel"]["primitive_count"], 2);
  EXPECT_NE(j["accel"]["backend"].get<std::string>().find("bvh"), std::string::npos);
  double sum = 0;
  for (const char* phase : {"parse", "mesh_load", "texture_load", "scene_build", "accel_build", "render", "write"}) {
    const double t = j["timings"][phase];
    EXPECT_GE(t, 0.0) << phase;
    sum += t;
  }
  EXPECT_NEAR(j["timings"]["total"].get<double>(), sum, 1e-9);
}

// Embree's memory monitor gives the structure's bytes and its build's peak
// (primitive references beside the structure); our BVH records no peak (0).
TEST_F(Cli, ReportRecordsEmbreesBuildPeak) {
  const Result r = run("phong.json -o out.ppm --accel=embree --report embree.json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json e = nlohmann::json::parse(slurp(path("embree.json")));
  const auto bytes = e["accel"]["memory_bytes"].get<uint64_t>();
  EXPECT_GT(bytes, 0u);
  EXPECT_GE(e["accel"]["build_peak_bytes"].get<uint64_t>(), bytes);
  ASSERT_EQ(run("phong.json -o out.ppm --accel=bvh --report bvh.json").status, 0);
  EXPECT_EQ(nlohmann::json::parse(slurp(path("bvh.json")))["accel"]["build_peak_bytes"], 0);
}

TEST_F(Cli, PathIntegratorOptionsAreUsedAndRecorded) {
  // The CGR rendermode "pathtracer" selects the path integrator.
  write("path.json", cgr_scene("pathtracer"));
  const Result r = run("path.json -o out.exr --spp 4 --max-depth 3 --filter gaussian --clamp 2.5 --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("clamp"), std::string::npos) << r.out;  // a clamp that is on is said
  const nlohmann::json j = nlohmann::json::parse(slurp(path("run.json")));
  EXPECT_EQ(j["image"]["integrator"], "path");
  EXPECT_EQ(j["image"]["max_depth"], 3);
  EXPECT_EQ(j["image"]["filter"], "gaussian");
  EXPECT_EQ(j["image"]["clamp"], 2.5);
  Image img;
  std::string error;
  ASSERT_TRUE(read_image(path("out.exr"), img, error)) << error;
  for (const RGB& p : img.pixels) ASSERT_LE(p.max_component(), 2.5f);
  // Off by default, and recorded as 0.
  ASSERT_EQ(run("path.json -o out.exr --spp 1 --report run.json").status, 0);
  EXPECT_EQ(nlohmann::json::parse(slurp(path("run.json")))["image"]["clamp"], 0.0);
  EXPECT_EQ(nlohmann::json::parse(slurp(path("run.json")))["image"]["filter"], "box");
}

TEST_F(Cli, IntegratorOptionOverridesTheScene) {
  const Result r = run("phong.json -o out.exr --integrator path --spp 2 --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(path("run.json")))["image"]["integrator"], "path");
}

// A small native-format scene (display images go through OpenColorIO).
std::string native_scene() {
  return R"({"format": "pathtracer-scene", "version": 1,
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
    "film": {"width": 24, "height": 16},
    "materials": {"grey": {"diffuse": [0.5, 0.5, 0.5]}},
    "lights": [{"type": "point", "position": [0, 2, 3], "intensity": [6, 6, 6]}],
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}]})";
}

// Mean 8-bit code of a display image.
double mean_code(const std::string& file) {
  Image img;
  std::string error;
  EXPECT_TRUE(read_image(file, img, error)) << error;
  double sum = 0;
  for (const RGB& p : img.pixels) sum += p.r + p.g + p.b;
  return 255.0 * sum / (3.0 * static_cast<double>(img.pixels.size()));
}

TEST_F(Cli, DisplayViewAndExposureChangeOnlyTheDisplayImage) {
  // The CGR scene keeps its course curve; a native scene goes through OCIO.
  write("native.json", native_scene());
  ASSERT_EQ(run("native.json -o std.png -o std.exr").status, 0);
  ASSERT_EQ(run("native.json -o aces.png -o aces.exr --view aces").status, 0);
  ASSERT_EQ(run("native.json -o bright.png --exposure 1").status, 0);
  EXPECT_NE(slurp(path("std.png")), slurp(path("aces.png")));
  EXPECT_EQ(slurp(path("std.exr")).size(), slurp(path("aces.exr")).size());  // EXR: scene-linear, untouched
  Image a, b;
  std::string error;
  ASSERT_TRUE(read_image(path("std.exr"), a, error));
  ASSERT_TRUE(read_image(path("aces.exr"), b, error));
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_GT(mean_code(path("bright.png")), mean_code(path("std.png")) + 5.0);
}

TEST_F(Cli, BadDisplayOptionsAreRefusedBeforeRendering) {
  write("native.json", native_scene());
  Result r = run("native.json -o out.png --view filmic");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("'standard', 'aces'"), std::string::npos) << r.err;
  write("config.ocio", "ocio_profile_version: 2\nroles: {default: lin, scene_linear: lin}\n"
                       "displays: {sRGB: [!<View> {name: Raw, colorspace: lin}]}\n"
                       "colorspaces: [!<ColorSpace> {name: lin}]\n");
  r = run("native.json -o out.png --ocio-config config.ocio --display P3");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no display 'P3'"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("render"), std::string::npos) << r.out;
  EXPECT_EQ(outputs(), std::vector<std::string>{"config.ocio"});
  // A course scene keeps its documented curve: the view is ignored, with a warning.
  r = run("phong.json -o course.png --view aces");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --view"), std::string::npos) << r.err;
}

TEST_F(Cli, NoReportForABadScene) {
  write("bad.json", "{ \"camera\": ");
  const Result r = run("bad.json -o out.png --report run.json");
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(fs::exists(path("run.json")));
}

TEST_F(Cli, BadSceneWritesNothing) {
  write("bad.json", "{\n  \"camera\": {\n    \"width\": 32,,\n  }\n}\n");
  const Result r = run("bad.json -o out.png");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("bad.json:3:"), std::string::npos) << r.err;  // file:line:col
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, MissingSceneWritesNothing) {
  const Result r = run("nowhere.json -o out.png");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("nowhere.json"), std::string::npos) << r.err;
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, StrictTurnsWarningsIntoErrors) {
  write("extra.json", cgr_scene("phong", ",\n    \"aperture\": 0.5"));
  const Result lenient = run("extra.json -o a.png");
  EXPECT_EQ(lenient.status, 0) << lenient.err;
  EXPECT_NE(lenient.err.find("aperture"), std::string::npos) << lenient.err;  // the warning is printed
  const Result strict = run("extra.json -o b.png --strict");
  EXPECT_EQ(strict.status, 1);
  EXPECT_NE(strict.err.find("aperture"), std::string::npos) << strict.err;
  EXPECT_FALSE(fs::exists(path("b.png")));
}

TEST_F(Cli, BadCommandLinesExitWithTwo) {
  for (const char* args : {"phong.json -o out.png --frobnicate", "phong.json -o out.png --threads 0",
                           "phong.json -o out.png --threads -2", "phong.json -o out.png --spp 0",
                           "phong.json -o out.png --integrator nope", "phong.json -o out.png --accel=optix",
                           "phong.json -o out.png --max-depth -1", "phong.json -o out.png --filter tent",
                           "phong.json -o out.png --clamp -1", "phong.json -o out.png --clamp x",
                           "phong.json", "-o out.png"}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, UnsupportedExtensionIsRefusedBeforeRendering) {
  const Result r = run("phong.json -o out.tiff");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find(".exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(".ppm"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("render"), std::string::npos) << r.out;
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, BvhBackendRendersTheSameImageAsEmbree) {
  const Result r = run("phong.json -o bvh.exr --accel=bvh --report bvh.json");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(run("phong.json -o embree.exr --accel=embree").status, 0);
  Image a, b;
  std::string error;
  ASSERT_TRUE(read_image(path("bvh.exr"), a, error)) << error;
  ASSERT_TRUE(read_image(path("embree.exr"), b, error)) << error;
  // The same image but for camera rays within rounding of the triangle's edge
  // on the image's centre line: Embree's triangle test is not ours, and there
  // the two may decide differently (docs/geometry.md; accel_crosscheck counts
  // such rays). Measured: 1 pixel of 768 differs, by a whole hit against a miss.
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const bool same = std::fabs(a.pixels[i].r - b.pixels[i].r) <= 1e-5f &&
                      std::fabs(a.pixels[i].g - b.pixels[i].g) <= 1e-5f &&
                      std::fabs(a.pixels[i].b - b.pixels[i].b) <= 1e-5f;
    if (!same) ++differ;
    if (!same) std::cout << "[ differs  ] pixel " << i << "\n";
  }
  EXPECT_LE(differ, 2u) << "of " << a.pixels.size() << " pixels";
  EXPECT_NE(slurp(path("bvh.json")).find("\"bvh ("), std::string::npos) << "the run record names the backend";
}

TEST_F(Cli, BvhCostViewNeedsTheBvhBackend) {
  const Result refused = run("phong.json -o cost.png --integrator bvh-cost --accel=embree");
  EXPECT_NE(refused.status, 0);
  EXPECT_NE(refused.err.find("--accel=bvh"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.out.find("render"), std::string::npos) << refused.out;
  EXPECT_TRUE(outputs().empty());
  const Result r = run("phong.json -o cost.png --integrator bvh-cost --accel=bvh");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("cost.png")));
}

TEST_F(Cli, VersionAndHelp) {
  const Result v = run("--version");
  EXPECT_EQ(v.status, 0);
  for (const char* what : {"pathtracer", "Embree", "OpenImageIO", "TBB"})
    EXPECT_NE(v.out.find(what), std::string::npos) << what << "\n" << v.out;
  const Result h = run("--help");
  EXPECT_EQ(h.status, 0);
  for (const char* what : {"--output", "--accel", "--threads", "--spp", "--seed", "--integrator", "--strict",
                           "--max-depth", "--filter", "--clamp"})
    EXPECT_NE(h.out.find(what), std::string::npos) << what;
}


// --help lists the options by task (issue 21), then three examples; the
// examples are real command lines: each runs here (the showcase small and at
// 1 spp, "scene.json" a small path-traced scene, the time budget capped by --spp).
TEST_F(Cli, HelpGroupsTheOptionsByTaskAndEndsWithExamplesThatRun) {
  const Result h = run("--help");
  ASSERT_EQ(h.status, 0) << h.err;
  const std::vector<std::pair<std::string, std::vector<std::string>>> groups = {
      {"Scene and output:", {"--output", "--width", "--set", "--accel", "--threads", "--view"}},
      {"Quality:", {"--spp", "--integrator", "--max-depth", "--sampler", "--filter", "--clamp", "--seed"}},
      {"Long renders:", {"--time-budget", "--pass-spp", "--checkpoint", "--resume", "--max-memory", "--report"}},
      {"Compositing:", {"--aov", "--cryptomatte-levels", "--film-transparent", "--exr-compression", "--crop"}},
      {"Debugging:", {"--pixel", "--sample", "--replay", "--strict", "--version"}},
      {"Examples:", {}}};
  std::size_t previous = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::size_t at = h.out.find("\n" + groups[g].first + "\n");
    ASSERT_NE(at, std::string::npos) << groups[g].first << "\n" << h.out;
    EXPECT_GT(at, previous) << groups[g].first << " out of order";
    const std::size_t end = g + 1 < groups.size() ? h.out.find("\n" + groups[g + 1].first + "\n") : h.out.size();
    for (const std::string& option : groups[g].second) {
      const std::size_t o = h.out.find(option + " ", at);
      EXPECT_TRUE(o != std::string::npos && o < end) << option << " is not under " << groups[g].first;
    }
    previous = at;
  }
  EXPECT_EQ(h.out.find("\nOptions:\n"), std::string::npos) << "an option left in CLI11's default group";

  write("scene.json", test::path_scene(160, 120, 64));
  fs::create_directories(path("out"));
  std::istringstream lines(h.out.substr(h.out.find("\nExamples:\n")));
  int examples = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  pathtracer ", 0) != 0) continue;
    ++examples;
    std::string args = line.substr(std::string("  pathtracer ").size());
    const std::string showcase = "scenes/showcase.json";
    if (const std::size_t s = args.find(showcase); s != std::string::npos)
      args.replace(s, showcase.size(), "'" PT_SCENES_DIR "/showcase.json' --spp 1 --width 48");
    // A time budget alone ignores the scene's spp: bound the render by its sample count.
    if (args.find("--time-budget") != std::string::npos) args += " --spp 2";
    const Result r = run(args + " --quiet");
    EXPECT_EQ(r.status, 0) << line << "\n" << r.err;
  }
  EXPECT_EQ(examples, 3) << h.out;
  EXPECT_TRUE(fs::exists(path("out/showcase.exr")));
  EXPECT_TRUE(fs::exists(path("frame.exr")));
  EXPECT_TRUE(fs::exists(path("frame.ckpt")));
}

}  // namespace
}  // namespace pt
