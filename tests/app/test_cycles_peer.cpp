// The Cycles peer tool (tools/peers/cycles/scene_to_cycles.py, issue 18): Debian's Blender 3.4
// renders one of our scenes, and its EXR has the scene's size and, on a small diffuse scene lit by a
// one-sided area light and a point light, the mean our renderer gives within 3% at a few samples.
// Measured: Cycles' mean at 32 spp over three seeds and ours at 256 spp over two all lie within 0.3%
// of each other (0.1703-0.1709 in red); a bounce cap off by one moves the mean by 8% (max_depth 3:
// 0.1842), and a point light in Blender's watts unconverted or a two-sided lamp under the ceiling by
// far more. A scene with features the tool does not convert is refused with every feature listed
// and no output written. Skipped when CMake found no `blender`.
#include <cmath>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app_fixture.h"

namespace pt::test {
namespace {

const std::string kRoom = R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 1, 3.2], "look_at": [0, 0.9, 0], "fov": 45},
  "film": {"width": 40, "height": 30},
  "render": {"integrator": "path", "max_depth": 2, "spp": 16, "filter": "box"},
  "materials": {
    "white": {"type": "lambert", "diffuse": [0.7, 0.7, 0.7]},
    "red": {"type": "lambert", "diffuse": [0.7, 0.1, 0.1]},
    "glass": {"type": "glass", "ior": 1.5},
    "lamp": {"type": "lambert", "diffuse": [0, 0, 0], "emission": [6, 6, 6]}
  },
  "lights": [{"type": "point", "position": [0.6, 1.5, 0.8], "intensity": [0.3, 0.3, 0.3]}],
  "shapes": [
    {"type": "quad", "vertices": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]], "material": "white"},
    {"type": "quad", "vertices": [[-1, 0, -1], [1, 0, -1], [1, 2, -1], [-1, 2, -1]], "material": "white"},
    {"type": "quad", "vertices": [[-1, 0, -1], [-1, 2, -1], [-1, 2, 1], [-1, 0, 1]], "material": "red"},
    {"type": "mesh", "positions": [[-1, 2, -1], [1, 2, -1], [1, 2, 1], [-1, 2, 1]], "indices": [[0, 2, 1], [0, 3, 2]],
     "material": "white"},
    {"type": "sphere", "center": [-0.4, 0.35, -0.2], "radius": 0.35, "material": "white"},
    {"type": "sphere", "center": [0.45, 0.3, 0.2], "radius": 0.3, "material": "glass"},
    {"type": "quad", "vertices": [[-0.3, 1.98, -0.3], [0.3, 1.98, -0.3], [0.3, 1.98, 0.3], [-0.3, 1.98, 0.3]],
     "material": "lamp"}
  ]
})";

// Mean of the first three channels, and the size.
double image_mean(const std::string& file, int& width, int& height) {
  auto in = OIIO::ImageInput::open(file);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return -1.0;
  const OIIO::ImageSpec spec = in->spec();
  width = spec.width;
  height = spec.height;
  std::vector<float> px(static_cast<std::size_t>(width) * height * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, px.data()));
  double sum = 0.0;
  for (std::size_t i = 0; i < px.size(); i += spec.nchannels) sum += px[i] + px[i + 1] + px[i + 2];
  return sum / (3.0 * width * height);
}

class CyclesPeer : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();  // the test's own scratch folder
    if (std::string(PT_BLENDER_EXE).empty()) GTEST_SKIP() << "blender not found (Debian: apt-get install blender)";
  }
  RunResult cycles(const std::string& scene, const std::string& out, int spp) {
    return run_command("'" PT_BLENDER_EXE "' -b --factory-startup --python '" PT_CYCLES_SCRIPT "' -- '" + path(scene) +
                       "' --spp " + std::to_string(spp) + " --seed 3 --threads 2 -o '" + path(out) + "'");
  }
};

TEST_F(CyclesPeer, RendersOurSceneWithOurMean) {
  write("room.json", kRoom);
  const RunResult r = cycles("room.json", "cycles.exr", 32);
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Cycles render time:"), std::string::npos) << r.out;
  ASSERT_EQ(run("room.json -o ours.exr --spp 256 --threads 2 --quiet").status, 0);
  int w = 0, h = 0, ow = 0, oh = 0;
  const double theirs = image_mean(path("cycles.exr"), w, h);
  const double ours = image_mean(path("ours.exr"), ow, oh);
  EXPECT_EQ(w, 40);
  EXPECT_EQ(h, 30);
  ASSERT_GT(ours, 0.05);
  EXPECT_NEAR(theirs / ours, 1.0, 0.03) << "Cycles' mean " << theirs << ", ours " << ours;
}

TEST_F(CyclesPeer, RefusesWhatItCannotConvert) {
  std::string scene = kRoom;
  const auto replace = [&scene](const std::string& from, const std::string& to) {
    const std::size_t at = scene.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    scene.replace(at, from.size(), to);
  };
  replace(R"("filter": "box")", R"("filter": "gaussian")");
  replace(R"({"type": "glass", "ior": 1.5})", R"({"type": "coateddiffuse"})");
  replace(R"({"type": "sphere", "center": [-0.4)",
          R"({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 1, 0], "radius": 0.1}, {"type": "sphere", "center": [-0.4)");
  write("bad.json", scene);
  const RunResult r = cycles("bad.json", "bad.exr", 1);
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  for (const char* what : {"render.filter 'gaussian'", "materials.glass: coateddiffuse", "shape type 'cylinder'"})
    EXPECT_NE(r.err.find(what), std::string::npos) << what << " not in: " << r.err;
  EXPECT_FALSE(std::ifstream(path("bad.exr")).good());
}

}  // namespace
}  // namespace pt::test
