// `--set key=value` scene overrides and the pre-flight memory check (docs/cli.md).
#include <string>

#include <gtest/gtest.h>

#include "app_fixture.h"
#include "io/image_io.h"

namespace pt::test {
namespace {

// A CGR-format scene (the course family; JSON like the native one).
const char* kCgrScene = R"({
  "nbounces": 3, "rendermode": "phong",
  "camera": {"type": "pinhole", "width": 32, "height": 24, "position": [0, 0, 0], "lookAt": [0, 0, 1],
             "upVector": [0, 1, 0], "fov": 45.0, "exposure": 0.1},
  "scene": {
    "backgroundcolor": [0.25, 0.25, 0.25],
    "lightsources": [{"type": "pointlight", "position": [0, 1, 0.5], "intensity": [0.75, 0.75, 0.75]}],
    "shapes": [{"type": "sphere", "center": [-0.3, 0.1, 1], "radius": 0.2}]
  }
})";

class SetOption : public AppTest {};

TEST_F(SetOption, OverridesValuesOfTheNativeFormat) {
  write("s.json", path_scene(32, 24, 1));
  RunResult r = run("s.json -o a.exr --set render.spp=3 --set render.integrator=whitted --set film.width=16 "
                    "--set 'materials.white.diffuse=[0.1,0.2,0.3]' --set 'shapes[0].radius=0.25' --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json rec = read_json("run.json");
  EXPECT_EQ(rec["image"]["spp"], 3);
  EXPECT_EQ(rec["image"]["integrator"], "whitted");  // a bare word is a string
  EXPECT_EQ(rec["image"]["width"], 16);
  EXPECT_EQ(rec["overrides"].size(), 5u);
  // A changed camera changes the image; the same --set twice gives the same image.
  ASSERT_EQ(run("s.json -o wide.exr --spp 1 --set camera.fov=80 --quiet").status, 0);
  ASSERT_EQ(run("s.json -o wide2.exr --spp 1 --set camera.fov=80 --quiet").status, 0);
  ASSERT_EQ(run("s.json -o narrow.exr --spp 1 --quiet").status, 0);
  EXPECT_EQ(slurp(path("wide.exr")).size(), slurp(path("wide2.exr")).size());
  Image wide, wide2, narrow;
  std::string error;
  ASSERT_TRUE(read_image(path("wide.exr"), wide, error));
  ASSERT_TRUE(read_image(path("wide2.exr"), wide2, error));
  ASSERT_TRUE(read_image(path("narrow.exr"), narrow, error));
  EXPECT_TRUE(wide.pixels == wide2.pixels);
  EXPECT_FALSE(wide.pixels == narrow.pixels);
}

TEST_F(SetOption, AddsAKeyTheFileDoesNotHave) {
  write("s.json", path_scene(32, 24, 1));
  const RunResult r = run("s.json -o a.exr --set render.clamp=4 --report run.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json("run.json")["image"]["clamp"], 4.0);
}

TEST_F(SetOption, WorksForTheCourseFormats) {
  write("c.json", kCgrScene);
  const RunResult r = run("c.json -o a.exr --set camera.width=20 --set 'scene.shapes[0].radius=0.3' --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json("run.json")["image"]["width"], 20);
}

TEST_F(SetOption, UnknownKeysNameTheAlternatives) {
  write("s.json", path_scene(32, 24, 1));
  RunResult r = run("s.json -o a.exr --set rendr.spp=2");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--set rendr.spp=2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'render'?"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'camera'"), std::string::npos) << r.err;  // the keys that exist
  // A misspelt last key reaches the importer, which names the valid keys; the note says where it came from.
  r = run("s.json -o a.exr --set render.spq=2");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("'spq'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'spp'?"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("this value comes from --set render.spq=2"), std::string::npos) << r.err;
  r = run("s.json -o a.exr --set 'shapes[7].radius=1'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("'shapes' has 3 elements (indices 0 to 2), no [7]"), std::string::npos) << r.err;
  r = run("s.json -o a.exr --set render.spp.x=1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("cannot look up 'x' in 'render.spp': it is a number, not an object"), std::string::npos) << r.err;
  r = run("s.json -o a.exr --set render.spp");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("expected key=value"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("a.exr")));
}

TEST_F(SetOption, BadValuesAreReportedAtTheFileLocationWithANote) {
  write("s.json", path_scene(32, 24, 1));
  const RunResult r = run("s.json -o a.exr --set render.spp=many");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("s.json:4:"), std::string::npos) << r.err;  // the line of "render"
  EXPECT_NE(r.err.find("\"many\""), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("this value comes from --set render.spp=many"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("a.exr")));
}

class MaxMemory : public AppTest {};

TEST_F(MaxMemory, RefusesARenderThatWouldNotFit) {
  write("s.json", path_scene(32, 24, 1));
  // 4000 x 3000 pixels: the film alone is 40 bytes a pixel, 458 MiB.
  RunResult r = run("s.json -o a.exr --width 4000 --max-memory 256M");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("estimated"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("more than --max-memory 256.00 MiB"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("a.exr")));
  // The same render fits a larger limit (checked at 1 spp and small size to keep the test quick).
  r = run("s.json -o b.exr --width 64 --max-memory 1G --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  r = run("s.json -o c.exr --max-memory lots");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("'lots' is not a size"), std::string::npos) << r.err;
}

// The estimate counts what the AOVs allocate: the film's sums (608 bytes a
// pixel with all of them) and the output buffers (Film::layers(), 144 bytes a
// pixel, the EXR writer's band of packed rows, here every row: 130 bytes,
// albedo, N and nonfinite being half, and OpenEXR's line buffers), against 88
// + 32 (and the line buffers) for the beauty alone; over the crop only. It is an estimate of the process's peak (the process as it
// is after reading the scene, libraries included, plus what the render adds),
// so the limit is set from the plain render's own estimate.
TEST_F(MaxMemory, TheAovSetAloneCanExceedTheLimitAndACropBringsItBack) {
  write("s.json", path_scene(32, 24, 1));
  const std::string all = "albedo,N,P,Z,IndexOB,IndexMA,emission,diffuse_direct,diffuse_indirect,specular_direct,"
                          "specular_indirect,variance,samples,nonfinite";
  // --threads 2: OpenEXR's line buffers, which the estimate counts, are two per thread.
  const std::string size = " --width 256 --height 256 --spp 1 --threads 2 ";
  RunResult r = run("s.json -o p.exr" + size + "--quiet --report plain.json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json plain = read_json("plain.json")["memory"];
  EXPECT_GT(plain["estimate_parts"]["baseline"].get<double>(), 1e6) << plain;  // the process itself counts
  // 256 x 256 pixels: these AOVs add 53.0 MiB (38 - 5.5 MiB of film: 608 bytes a pixel with them,
  // 88 without, the sums being 16-byte exact sums; 23.22 - 2.75 MiB of output buffers: 9 MiB of
  // layers, 8.12 MiB of the EXR writer's one band, 6.09 MiB of OpenEXR's line buffers, 4 of 3 x 16
  // rows of 130 bytes a pixel).
  const uint64_t limit_mib = plain["estimate_bytes"].get<uint64_t>() / (1 << 20) + 20;
  const std::string limit = " --max-memory " + std::to_string(limit_mib) + "M ";
  r = run("s.json -o a.exr" + size + limit + "--aov " + all);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("error: the render needs an estimated "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(", film 38.00 MiB, images 23.22 MiB, textures 0 bytes, "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("more than --max-memory " + std::to_string(limit_mib) + ".00 MiB"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(", geometry and acceleration structure "), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("a.exr")));
  EXPECT_EQ(r.out.find("wrote"), std::string::npos) << r.out;
  // The same render without the AOVs fits ...
  r = run("s.json -o b.exr" + size + limit + "--quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("b.exr")));
  // ... and so does a crop of a sixteenth of the frame with all of them.
  r = run("s.json -o c.exr" + size + limit + "--crop 0,0,0.25,0.25 --quiet --aov " + all);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("c.exr")));
}

// --texture-cache SIZE (docs/cli.md): a cache far smaller than the texture
// (1 MiB against 768 x 768 texels, 3.4 MiB of half-float RGB with its MIP
// levels) changes memory, not the image; a size that is not one is a usage error.
class TextureCacheOption : public AppTest {};

TEST_F(TextureCacheOption, ChangesNoPixelAndRefusesBadSizes) {
  Image noise(768, 768);
  for (std::size_t i = 0; i < noise.pixels.size(); ++i) {
    const uint32_t h = static_cast<uint32_t>(i) * 2654435761u;
    noise.pixels[i] = RGB(static_cast<float>(h >> 24) / 255.0f, static_cast<float>((h >> 16) & 255u) / 255.0f, 0.5f);
  }
  std::string error;
  ASSERT_TRUE(pt::write_image(path("noise.png"), noise, DisplaySettings{}, error)) << error;
  write("t.json", R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 1, 2], "look_at": [0, 0, -4], "fov": 60},
  "film": {"width": 48, "height": 32},
  "render": {"integrator": "whitted", "spp": 4},
  "materials": {"floor": {"type": "lambert", "texture": {"type": "image", "file": "noise.png", "scale": 3}}},
  "lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": [3, 3, 3]}],
  "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"}]
})");
  ASSERT_EQ(run("t.json -o small.exr --texture-cache 1M --quiet").status, 0);
  ASSERT_EQ(run("t.json -o large.exr --texture-cache 1G --quiet").status, 0);
  Image small, large;
  ASSERT_TRUE(read_image(path("small.exr"), small, error)) << error;
  ASSERT_TRUE(read_image(path("large.exr"), large, error)) << error;
  EXPECT_TRUE(small.pixels == large.pixels);
  RunResult r = run("t.json -o a.exr --texture-cache lots");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("'lots' is not a size"), std::string::npos) << r.err;
  r = run("t.json -o a.exr --texture-cache 512K");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("at least 1M"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("a.exr")));
}

}  // namespace
}  // namespace pt::test
