// Blender reading our EXR (docs/output.md): every layer becomes a pass
// (single-channel layers included: no "unknown channel token"), its
// Cryptomatte node finds our Cryptomatte layers from the header, and the
// matte it extracts for an object (from the single-part file) and for a
// material (from the --multipart file) is the coverage our own layers give. Runs Debian's Blender 3.4 headless (blender_read_exr.py);
// skipped when CMake found no `blender` (apt-get install blender).
#include <algorithm>
#include <bit>
#include <cmath>
#include <tuple>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app_fixture.h"
#include "render/film/cryptomatte.h"

namespace pt::test {
namespace {

const std::string kScene = R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 1, 4], "look_at": [0, 0.6, 0], "fov": 40},
  "film": {"width": 40, "height": 30},
  "render": {"integrator": "path", "max_depth": 3, "spp": 16, "filter": "gaussian"},
  "materials": {
    "red": {"type": "lambert", "diffuse": [0.7, 0.1, 0.1]},
    "grey": {"type": "lambert", "diffuse": [0.5, 0.5, 0.5]},
    "light": {"type": "lambert", "diffuse": [0, 0, 0], "emission": [8, 8, 8]}
  },
  "shapes": [
    {"type": "sphere", "name": "ball", "center": [-0.3, 0.5, 0], "radius": 0.5, "material": "red"},
    {"type": "sphere", "name": "ball 2", "center": [0.5, 0.4, -0.6], "radius": 0.4, "material": "grey"},
    {"type": "quad", "name": "floor", "vertices": [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]], "material": "grey"},
    {"type": "quad", "vertices": [[-0.5, 2.5, -0.5], [0.5, 2.5, -0.5], [0.5, 2.5, 0.5], [-0.5, 2.5, 0.5]], "material": "light"}
  ]
})";

std::vector<float> read_channels(const std::string& file, const std::vector<std::string>& names, int& width,
                                 int& height) {
  auto in = OIIO::ImageInput::open(file);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  width = spec.width;
  height = spec.height;
  std::vector<float> all(static_cast<std::size_t>(width) * height * spec.nchannels), out;
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, all.data()));
  for (std::size_t i = 0; i < all.size() / spec.nchannels; ++i)
    for (const std::string& n : names) {
      const int c = spec.channelindex(n);
      EXPECT_GE(c, 0) << n;
      out.push_back(c >= 0 ? all[i * spec.nchannels + c] : 0.0f);
    }
  return out;
}

// Our own matte of `name`: the sum of the coverages of the ranks holding its id.
std::vector<float> our_matte(const std::string& file, const std::string& type, const std::string& name) {
  std::vector<std::string> channels;
  for (const char* layer : {"00", "01", "02"})
    for (const char* c : {".r", ".g", ".b", ".a"}) channels.push_back(type + layer + c);
  int w = 0, h = 0;
  const std::vector<float> v = read_channels(file, channels, w, h);
  const uint32_t id = std::bit_cast<uint32_t>(cryptomatte_id(name));
  std::vector<float> matte(static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < matte.size(); ++i)
    for (std::size_t k = 0; k < 6; ++k)
      if (std::bit_cast<uint32_t>(v[i * 12 + 2 * k]) == id) matte[i] += v[i * 12 + 2 * k + 1];
  return matte;
}

class BlenderReadsOurExr : public AppTest {
 protected:
  // Runs the script on `exr`; its stdout and stderr go to `log`.
  void blender(const std::string& exr, const std::string& type, const std::string& name, const std::string& out) {
    const RunResult r = run_command("'" PT_BLENDER_EXE "' -b --factory-startup --python '" PT_BLENDER_SCRIPT "' -- '" +
                                    path(exr) + "' 40 30 " + type + " '" + name + "' '" + path(out + ".exr") + "' '" +
                                    path(out + ".json") + "'");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    log += r.out + r.err;
  }
  std::string log;
};

TEST_F(BlenderReadsOurExr, PassesAndCryptomatteMattes) {
  if (std::string(PT_BLENDER_EXE).empty()) GTEST_SKIP() << "blender not found (Debian: apt-get install blender)";
  write("s.json", kScene);
  const std::string aovs = " --quiet --aov albedo,N,Z,IndexOB,IndexMA,samples,nonfinite,CryptoObject,CryptoMaterial";
  ASSERT_EQ(run("s.json -o out.exr" + aovs).status, 0);
  ASSERT_EQ(run("s.json -o parts.exr --multipart" + aovs).status, 0);  // the same data, one part per layer
  blender("out.exr", "CryptoObject", "ball", "object");
  blender("parts.exr", "CryptoMaterial", "grey", "material");
  EXPECT_EQ(log.find("unknown channel token"), std::string::npos) << log;
  EXPECT_EQ(log.find("multilayer read"), std::string::npos) << log;
  for (const char* json : {"object.json", "material.json"}) {
    SCOPED_TRACE(json);
    const nlohmann::json passes = read_json(json);
    for (const char* pass : {"Combined", "Alpha", "Depth", "albedo", "N", "IndexOB", "IndexMA", "samples", "nonfinite",
                             "CryptoObject00", "CryptoObject01", "CryptoObject02", "CryptoMaterial00",
                             "CryptoMaterial01", "CryptoMaterial02"})
      EXPECT_NE(std::find(passes["passes"].begin(), passes["passes"].end(), pass), passes["passes"].end())
          << pass << " not among " << passes["passes"].dump();
    // The layers Blender's Cryptomatte node offers, found from our header.
    const std::string layers = passes["cryptomatte_layers"];
    EXPECT_NE(layers.find("('CryptoObject', 'CryptoMaterial')"), std::string::npos) << layers;
  }

  for (const auto& [out, type, name] : {std::tuple<std::string, std::string, std::string>{"object", "CryptoObject", "ball"},
                                        {"material", "CryptoMaterial", "grey"}}) {
    SCOPED_TRACE(out);
    int w = 0, h = 0;
    const std::vector<float> theirs = read_channels(path(out + ".exr"), {"R"}, w, h);
    const std::vector<float> ours = our_matte(path("out.exr"), type, name);
    ASSERT_EQ(w, 40);
    ASSERT_EQ(h, 30);
    ASSERT_EQ(theirs.size(), ours.size());
    int partial = 0, full = 0;
    float worst = 0.0f;
    for (std::size_t i = 0; i < ours.size(); ++i) {
      worst = std::max(worst, std::fabs(theirs[i] - ours[i]));
      partial += ours[i] > 0.0f && ours[i] < 1.0f;
      full += ours[i] == 1.0f;
    }
    EXPECT_LT(worst, 1e-5f) << "largest difference between Blender's matte and our coverage";
    EXPECT_GT(full, 20);
    EXPECT_GT(partial, 10);  // an antialiased edge, as Blender extracted it
  }
}

}  // namespace
}  // namespace pt::test
