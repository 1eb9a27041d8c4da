// What a compositor gets from the command line (docs/output.md): coverage
// alpha and the transparent film, PNG with alpha, Cryptomatte layers and
// header read back with OpenImageIO and decoded, the background's depth,
// --exr-compression (lossless for Cryptomatte ids) and --multipart.
#include <bit>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app_fixture.h"
#include "render/film/cryptomatte.h"

namespace pt::test {
namespace {

// A named sphere ("ball", material "red") on a named floor ("floor", "grey")
// under an area light, with sky above the horizon (a miss) and a bright background.
std::string named_scene(int width, int height, bool transparent = false) {
  return R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 1, 4], "look_at": [0, 0.7, 0], "fov": 40},
  "film": {"width": )" + std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"(},
  "render": {"integrator": "path", "max_depth": 4, "spp": 4, "background": [0.4, 0.5, 0.6],
             "film_transparent": )" + (transparent ? "true" : "false") + R"(},
  "materials": {
    "red": {"type": "lambert", "diffuse": [0.7, 0.1, 0.1]},
    "grey": {"type": "lambert", "diffuse": [0.5, 0.5, 0.5]},
    "light": {"type": "lambert", "diffuse": [0, 0, 0], "emission": [8, 8, 8]}
  },
  "shapes": [
    {"type": "sphere", "name": "ball", "center": [0, 0.5, 0], "radius": 0.5, "material": "red"},
    {"type": "quad", "name": "floor", "vertices": [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]], "material": "grey"},
    {"type": "quad", "vertices": [[-0.5, 2.5, -0.5], [0.5, 2.5, -0.5], [0.5, 2.5, 0.5], [-0.5, 2.5, 0.5]], "material": "light"}
  ]
})";
}

struct Exr {
  std::vector<OIIO::ImageSpec> parts;
  std::map<std::string, std::vector<float>> channels;  // every part's channels, by name
  int width = 0, height = 0;
  float at(const std::string& channel, int x, int y) const {
    return channels.at(channel)[static_cast<std::size_t>(y) * width + x];
  }
};

Exr read_exr(const std::string& file) {
  Exr e;
  auto in = OIIO::ImageInput::open(file);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return e;
  for (int part = 0; in->seek_subimage(part, 0); ++part) {
    const OIIO::ImageSpec spec = in->spec();
    e.parts.push_back(spec);
    e.width = spec.width;
    e.height = spec.height;
    std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(in->read_image(part, 0, 0, spec.nchannels, OIIO::TypeFloat, pixels.data())) << in->geterror();
    for (int c = 0; c < spec.nchannels; ++c) {
      std::vector<float>& channel = e.channels[spec.channelnames[c]];
      for (std::size_t i = 0; i < pixels.size() / spec.nchannels; ++i) channel.push_back(pixels[i * spec.nchannels + c]);
    }
  }
  return e;
}

// The coverage of `name` in a Cryptomatte type's layers at (x, y): the sum of
// the coverages of the ranks holding its id (as a Cryptomatte keyer computes
// a matte), and the sum over all ranks.
std::pair<float, float> matte(const Exr& e, const std::string& type, const std::string& name, int x, int y) {
  const float id = cryptomatte_id(name);
  float mine = 0.0f, all = 0.0f;
  for (int layer = 0; layer < 3; ++layer) {
    const std::string prefix = type + "0" + std::to_string(layer) + ".";
    for (const auto& [id_channel, coverage_channel] : {std::pair{"r", "g"}, std::pair{"b", "a"}}) {
      const float rank_id = e.at(prefix + id_channel, x, y), coverage = e.at(prefix + coverage_channel, x, y);
      all += coverage;
      if (std::bit_cast<uint32_t>(rank_id) == std::bit_cast<uint32_t>(id)) mine += coverage;
    }
  }
  return {mine, all};
}

class ExrCompositing : public AppTest {};

TEST_F(ExrCompositing, CryptomatteLayersHeaderAndMattes) {
  write("s.json", named_scene(48, 32));
  const RunResult r = run("s.json -o out.exr --quiet --aov CryptoObject,CryptoMaterial,Z,IndexOB");
  ASSERT_EQ(r.status, 0) << r.err;
  const Exr e = read_exr(path("out.exr"));
  ASSERT_EQ(e.parts.size(), 1u);
  const OIIO::ImageSpec& spec = e.parts[0];
  // Channels: 3 layers of r, g, b, a per type, all float (ids are bit patterns).
  for (const char* type : {"CryptoObject", "CryptoMaterial"})
    for (const char* layer : {"00", "01", "02"})
      for (const char* c : {"r", "g", "b", "a"}) {
        const std::string name = std::string(type) + layer + "." + c;
        const int index = spec.channelindex(name);
        ASSERT_GE(index, 0) << name;
        EXPECT_EQ(spec.channelformat(index), OIIO::TypeFloat) << name;
      }
  EXPECT_GE(spec.channelindex("IndexOB.X"), 0);
  // The header, under the key Blender would give each type.
  for (const auto& [type, names] : {std::pair<std::string, std::vector<std::string>>{"CryptoObject", {"ball", "floor", "shapes[2]"}},
                                    {"CryptoMaterial", {"red", "grey", "light"}}}) {
    char key[16];
    std::snprintf(key, sizeof key, "%08x", murmurhash3_32(type));
    const std::string prefix = "cryptomatte/" + std::string(key).substr(0, 7) + "/";
    EXPECT_EQ(spec.get_string_attribute(prefix + "name"), type);
    EXPECT_EQ(spec.get_string_attribute(prefix + "hash"), "MurmurHash3_32");
    EXPECT_EQ(spec.get_string_attribute(prefix + "conversion"), "uint32_to_float32");
    const auto manifest = nlohmann::json::parse(spec.get_string_attribute(prefix + "manifest"));
    ASSERT_EQ(manifest.size(), names.size()) << manifest.dump();
    for (const std::string& n : names) EXPECT_EQ(manifest[n], cryptomatte_hex(cryptomatte_id(n))) << n;
  }
  // The ball's centre pixel is all ball; the sky is nothing; every pixel's
  // coverages add up to its alpha (three ids at most, six ranks).
  ASSERT_TRUE(spec.channelindex("A") >= 0);
  const auto centre = matte(e, "CryptoObject", "ball", 24, 17);
  EXPECT_EQ(centre.first, 1.0f);
  EXPECT_EQ(matte(e, "CryptoMaterial", "red", 24, 17).first, 1.0f);
  EXPECT_EQ(e.at("CryptoObject00.r", 24, 17), cryptomatte_id("ball"));
  EXPECT_EQ(e.at("CryptoObject00.b", 24, 17), 0.0f);
  EXPECT_EQ(matte(e, "CryptoObject", "ball", 0, 0).second, 0.0f);
  EXPECT_EQ(e.at("A", 0, 0), 0.0f);
  EXPECT_EQ(e.at("Z", 0, 0), 1e10f);  // the background's depth, as Blender writes it
  int edges = 0;
  for (int y = 0; y < e.height; ++y)
    for (int x = 0; x < e.width; ++x) {
      const auto [ball, all] = matte(e, "CryptoObject", "ball", x, y);
      EXPECT_NEAR(all, e.at("A", x, y), 1e-6f) << x << "," << y;
      if (ball > 0.0f && ball < 1.0f) ++edges;
    }
  EXPECT_GT(edges, 10);  // antialiased: coverage from every sample, not the first
}

TEST_F(ExrCompositing, TransparentFilmPremultipliesAndPngGetsStraightAlpha) {
  write("s.json", named_scene(32, 24, true));
  RunResult r = run("s.json -o t.exr -o t.png -o t.jpg --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const Exr e = read_exr(path("t.exr"));
  EXPECT_EQ(e.parts[0].get_int_attribute("pathtracer:filmTransparent", -1), 1);
  EXPECT_EQ(e.at("A", 0, 0), 0.0f);  // sky: transparent and black
  EXPECT_EQ(e.at("B", 0, 0), 0.0f);
  EXPECT_EQ(e.at("A", 16, 14), 1.0f);  // the ball
  EXPECT_GT(e.at("R", 16, 14), 0.01f);
  auto png = OIIO::ImageInput::open(path("t.png"));
  ASSERT_TRUE(png);
  ASSERT_EQ(png->spec().nchannels, 4);
  std::vector<unsigned char> rgba(32 * 24 * 4);
  ASSERT_TRUE(png->read_image(0, 0, 0, 4, OIIO::TypeUInt8, rgba.data()));
  EXPECT_EQ(rgba[3], 0);                         // the sky
  EXPECT_EQ(rgba[(14 * 32 + 16) * 4 + 3], 255);  // the ball
  auto jpg = OIIO::ImageInput::open(path("t.jpg"));
  ASSERT_TRUE(jpg);
  EXPECT_EQ(jpg->spec().nchannels, 3);  // no alpha: the premultiplied image, over black
  // An opaque film: the sky shows, alpha is still the coverage, PNG has no alpha.
  write("o.json", named_scene(32, 24, false));
  r = run("o.json -o o.exr -o o.png --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const Exr o = read_exr(path("o.exr"));
  EXPECT_EQ(o.parts[0].get_int_attribute("pathtracer:filmTransparent", -1), 0);
  EXPECT_EQ(o.at("A", 0, 0), 0.0f);
  EXPECT_FLOAT_EQ(o.at("B", 0, 0), 0.6f);
  EXPECT_EQ(OIIO::ImageInput::open(path("o.png"))->spec().nchannels, 3);
  // --film-transparent does what the scene key does.
  r = run("o.json -o f.exr --quiet --film-transparent");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_exr(path("f.exr")).at("B", 0, 0), 0.0f);
}

TEST_F(ExrCompositing, CompressionsAreWrittenAndKeepCryptomatteIdsExact) {
  write("s.json", named_scene(24, 16));
  ASSERT_EQ(run("s.json -o zip.exr --quiet --aov CryptoObject,albedo").status, 0);
  const Exr reference = read_exr(path("zip.exr"));
  EXPECT_EQ(reference.parts[0].get_string_attribute("compression"), "zip");
  for (const std::string c : {"none", "rle", "zips", "piz", "b44", "b44a", "dwaa", "dwab:90"}) {
    SCOPED_TRACE(c);
    const RunResult r = run("s.json -o c.exr --quiet --aov CryptoObject,albedo --exr-compression " + c);
    ASSERT_EQ(r.status, 0) << r.err;
    const Exr e = read_exr(path("c.exr"));
    EXPECT_EQ(e.parts[0].get_string_attribute("compression"), c.substr(0, c.find(':')));
    // Ids and coverages bit for bit (dwa is lossy on R, G, B only: the ids are r, g, b, a).
    for (const auto& [name, values] : reference.channels)
      if (name.rfind("Crypto", 0) == 0) {
        EXPECT_EQ(e.channels.at(name), values) << name;
      }
  }
  RunResult r = run("s.json -o c.exr --aov CryptoObject --exr-compression pxr24");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("pxr24 rounds 32-bit floats to 24 bits"), std::string::npos) << r.err;
  EXPECT_EQ(run("s.json -o c.exr --quiet --exr-compression pxr24").status, 0);  // fine without ids
  for (const char* bad : {"lzw", "zip:9", "dwaa:0", "dwaa:x"}) {
    r = run(std::string("s.json -o c.exr --exr-compression ") + bad);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("--exr-compression"), std::string::npos) << r.err;
  }
}

TEST_F(ExrCompositing, MultipartWritesOnePartPerLayerWithTheSameData) {
  write("s.json", named_scene(24, 16));
  ASSERT_EQ(run("s.json -o one.exr --quiet --aov albedo,Z,CryptoObject --cryptomatte-levels 4").status, 0);
  ASSERT_EQ(run("s.json -o parts.exr --quiet --aov albedo,Z,CryptoObject --cryptomatte-levels 4 --multipart").status, 0);
  const Exr one = read_exr(path("one.exr")), parts = read_exr(path("parts.exr"));
  ASSERT_EQ(one.parts.size(), 1u);
  ASSERT_EQ(parts.parts.size(), 5u);  // rgba, albedo, Z, CryptoObject00, CryptoObject01
  const std::vector<std::string> names = {"rgba", "albedo", "Z", "CryptoObject00", "CryptoObject01"};
  char key[16];
  std::snprintf(key, sizeof key, "%08x", murmurhash3_32("CryptoObject"));
  for (std::size_t p = 0; p < parts.parts.size(); ++p) {  // every part has the whole header
    EXPECT_EQ(parts.parts[p].get_string_attribute("oiio:subimagename"), names[p]);
    EXPECT_EQ(parts.parts[p].get_string_attribute("pathtracer:integrator"), "path") << p;
    EXPECT_EQ(parts.parts[p].get_string_attribute("cryptomatte/" + std::string(key).substr(0, 7) + "/name"),
              "CryptoObject")
        << p;
  }
  EXPECT_EQ(parts.parts[3].channelnames, (std::vector<std::string>{"CryptoObject00.r", "CryptoObject00.g",
                                                                   "CryptoObject00.b", "CryptoObject00.a"}));
  EXPECT_EQ(one.channels, parts.channels);  // the same channels, the same values
  EXPECT_EQ(one.channels.size(), 4u + 3u + 1u + 8u);
}

}  // namespace
}  // namespace pt::test
