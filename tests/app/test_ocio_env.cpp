// $OCIO as users set it (docs/rendering.md, "Output and display transforms"):
// the application, run with OCIO naming a config file in its environment,
// encodes display images through that config's displays, views and looks.
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "app_fixture.h"
#include "io/image_io.h"

namespace pt::test {
namespace {


// Every pixel sees the background: linear 0.25 (native scene: OCIO applies).
const char* kGreyScene = R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 30},
  "film": {"width": 8, "height": 6},
  "render": {"integrator": "whitted", "spp": 1, "background": [0.25, 0.25, 0.25]},
  "materials": {"grey": {"diffuse": [0.5, 0.5, 0.5]}},
  "shapes": [{"type": "sphere", "center": [0, 0, 50], "radius": 1, "material": "grey"}]
})";

class OcioEnvironment : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    // One display with two views (sRGB-encoded and raw) and a look that doubles.
    std::ifstream in(std::string(PT_TEST_DATA_DIR) + "/data/ocio/two-views-one-look.ocio");
    write("config.ocio", std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
    write("grey.json", kGreyScene);
  }
  // Runs with $OCIO naming the config (an absolute path, as users set it).
  RunResult run_ocio(const std::string& args) const { return run(args, "OCIO='" + path("config.ocio") + "'"); }
  // The one 8-bit code of a uniform display image (checked uniform).
  int code(const std::string& file) const {
    Image img;
    std::string error;
    EXPECT_TRUE(read_image(path(file), img, error)) << error;
    if (img.pixels.empty()) return -1;
    for (const RGB& p : img.pixels) EXPECT_EQ(p, img.pixels[0]) << file;
    return static_cast<int>(img.pixels[0].g * 255.0f + 0.5f);
  }
};

TEST_F(OcioEnvironment, DisplayViewAndLookComeFromTheConfigItNames) {
  // The config's default view (Standard, sRGB-encoded): linear 0.25 -> 137.
  RunResult r = run_ocio("grey.json -o default.png --report run.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(code("default.png"), 137);
  const nlohmann::json display = read_json("run.json")["display"];
  EXPECT_EQ(display["ocio_config"], path("config.ocio"));  // recorded from the environment
  EXPECT_NE(display["pipeline"].get<std::string>().find("Standard"), std::string::npos) << display;
  // Its Raw view exists only in the config: 0.25 -> 64 (255 * 0.25 = 63.75).
  r = run_ocio("grey.json -o raw.png --display sRGB --view Raw --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(code("raw.png"), 64);
  // Its look doubles the value first: 0.5 raw -> 128.
  r = run_ocio("grey.json -o look.png --view Raw --look brighter --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(code("look.png"), 128);
  // Without $OCIO the built-in views apply, which have no 'Raw'.
  r = run("grey.json -o builtin.png --view Raw");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("'standard', 'aces'"), std::string::npos) << r.err;
}

TEST_F(OcioEnvironment, AViewTheConfigLacksIsRefusedListingItsViews) {
  const RunResult r = run_ocio("grey.json -o out.png -o out.exr --view Filmic");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no view 'Filmic'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'Standard', 'Raw'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("out.png")));
  EXPECT_FALSE(std::filesystem::exists(path("out.exr")));  // refused before rendering: nothing written
  // A display it lacks likewise names the one it has.
  const RunResult d = run_ocio("grey.json -o out.png --display P3");
  EXPECT_EQ(d.status, 2);
  EXPECT_NE(d.err.find("no display 'P3'"), std::string::npos) << d.err;
  EXPECT_NE(d.err.find("'sRGB'"), std::string::npos) << d.err;
}

}  // namespace
}  // namespace pt::test
