// The EXR the application writes, read back with OpenImageIO as a compositor
// would (docs/output.md): every AOV's channels and types, the crop as data
// window, and every metadata key with the values the command line asked for.
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app_fixture.h"

namespace pt::test {
namespace {

// Every AOV, some with a type other than their default.
const char* kAllAovs =
    "albedo,N:float,P:half,Z,IndexOB,IndexMA,emission:half,diffuse_direct,diffuse_indirect,specular_direct,"
    "specular_indirect:half,variance,samples,nonfinite";

// Channel -> type for kAllAovs with the beauty as `beauty`.
std::map<std::string, OIIO::TypeDesc> expected_channels(OIIO::TypeDesc beauty) {
  const OIIO::TypeDesc h = OIIO::TypeHalf, f = OIIO::TypeFloat;
  std::map<std::string, OIIO::TypeDesc> c = {{"R", beauty}, {"G", beauty}, {"B", beauty}, {"A", beauty},
                                             {"Z", f}, {"IndexOB.X", f}, {"IndexMA.X", f}, {"samples.X", f},
                                             {"nonfinite.X", h}};
  const std::map<std::string, OIIO::TypeDesc> rgb = {
      {"albedo", h}, {"emission", h}, {"diffuse_direct", f}, {"diffuse_indirect", f}, {"specular_direct", f},
      {"specular_indirect", h}, {"variance", f}};
  for (const auto& [layer, type] : rgb)
    for (const char* s : {".R", ".G", ".B"}) c[layer + s] = type;
  for (const char* s : {".X", ".Y", ".Z"}) {
    c[std::string("N") + s] = f;
    c[std::string("P") + s] = h;
  }
  return c;
}

// p' = (x, y, z, 1) M, M row-major (Imath's convention).
std::array<float, 4> transform(const float* p, const float* m) {
  std::array<float, 4> out{};
  for (int j = 0; j < 4; ++j) out[j] = p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + m[12 + j];
  return out;
}

struct Exr {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // every channel, as float
  std::map<std::string, int> index;
  float at(const std::string& channel, int i) const {
    return pixels[static_cast<std::size_t>(i) * spec.nchannels + index.at(channel)];
  }
};

Exr read_exr(const std::string& file) {
  Exr e;
  auto in = OIIO::ImageInput::open(file);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return e;
  e.spec = in->spec();
  e.pixels.resize(static_cast<std::size_t>(e.spec.width) * e.spec.height * e.spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, e.spec.nchannels, OIIO::TypeFloat, e.pixels.data())) << in->geterror();
  for (int c = 0; c < e.spec.nchannels; ++c) e.index[e.spec.channelnames[c]] = c;
  return e;
}

class ExrReadBack : public AppTest {};

TEST_F(ExrReadBack, EveryAovChannelTypeTheCropWindowAndEveryMetadataKey) {
  write("s.json", path_scene(48, 32, 1));
  const RunResult r = run(std::string("s.json -o out.exr --spp 3 --seed 12345678901234 --accel bvh --crop-px 8,4,20,16 "
                                      "--sampler jittered --filter box --max-depth 7 --clamp 20 "
                                      "--report run.json --quiet --aov ") + kAllAovs);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json rec = read_json("run.json");
  const Exr exr = read_exr(path("out.exr"));
  const OIIO::ImageSpec& spec = exr.spec;

  // Channels: every name, with its type; the beauty first.
  const std::map<std::string, OIIO::TypeDesc> want = expected_channels(OIIO::TypeFloat);
  ASSERT_EQ(spec.nchannels, 36);
  ASSERT_EQ(want.size(), 36u);
  for (int c = 0; c < spec.nchannels; ++c) {
    const std::string& name = spec.channelnames[c];
    ASSERT_TRUE(want.count(name)) << "unexpected channel " << name;
    EXPECT_EQ(spec.channelformat(c), want.at(name)) << name;
  }
  EXPECT_EQ(exr.index.size(), want.size());  // no name twice
  const std::vector<std::string> first(spec.channelnames.begin(), spec.channelnames.begin() + 4);
  EXPECT_EQ(first, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(spec.alpha_channel, 3);

  // The crop is the data window; the display window is the frame.
  EXPECT_EQ(spec.x, 8);
  EXPECT_EQ(spec.y, 4);
  EXPECT_EQ(spec.width, 20);
  EXPECT_EQ(spec.height, 16);
  EXPECT_EQ(spec.full_x, 0);
  EXPECT_EQ(spec.full_y, 0);
  EXPECT_EQ(spec.full_width, 48);
  EXPECT_EQ(spec.full_height, 32);

  // Every metadata key, with its type and value.
  const auto attribute = [&](const char* name, OIIO::TypeDesc type) {
    const OIIO::ParamValue* p = spec.find_attribute(name);
    EXPECT_TRUE(p) << name;
    if (p) {
      EXPECT_EQ(p->type(), type) << name;
    }
    return p;
  };
  const std::string version = rec["software"]["version"];
  ASSERT_FALSE(version.empty());
  attribute("pathtracer:renderTime", OIIO::TypeFloat);
  EXPECT_GT(spec.get_float_attribute("pathtracer:renderTime"), 0.0f);
  EXPECT_FLOAT_EQ(spec.get_float_attribute("pathtracer:renderTime"), rec["timings"]["render"].get<float>());
  attribute("pathtracer:spp", OIIO::TypeInt);
  EXPECT_EQ(spec.get_int_attribute("pathtracer:spp"), 3);
  attribute("pathtracer:seed", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:seed"), "12345678901234");
  attribute("pathtracer:backend", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:backend").substr(0, 4), "bvh ");
  EXPECT_EQ(spec.get_string_attribute("pathtracer:backend"), rec["accel"]["backend"].get<std::string>());
  attribute("pathtracer:integrator", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:integrator"), "path");
  // How the samples were taken (the firefly clamp above all: an image that was
  // clamped must say so).
  attribute("pathtracer:sampler", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:sampler"), "jittered");
  attribute("pathtracer:filter", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:filter"), "box");  // P must project into its pixel
  attribute("pathtracer:lightSampler", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:lightSampler"), "bvh");  // the default render.light_sampler
  attribute("pathtracer:lightGuiding", OIIO::TypeInt);
  EXPECT_EQ(spec.get_int_attribute("pathtracer:lightGuiding", -1), 0);  // off by default
  attribute("pathtracer:pathGuiding", OIIO::TypeInt);
  EXPECT_EQ(spec.get_int_attribute("pathtracer:pathGuiding", -1), 0);  // off by default
  attribute("pathtracer:shadowTerminatorOffset", OIIO::TypeFloat);
  attribute("pathtracer:maxDepth", OIIO::TypeInt);
  EXPECT_EQ(spec.get_int_attribute("pathtracer:maxDepth"), 7);
  attribute("pathtracer:clamp", OIIO::TypeFloat);
  EXPECT_EQ(spec.get_float_attribute("pathtracer:clamp"), 20.0f);
  attribute("pathtracer:version", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:version"), version);
  attribute("pathtracer:partial", OIIO::TypeInt);
  EXPECT_EQ(spec.get_int_attribute("pathtracer:partial", -1), 0);
  attribute("Software", OIIO::TypeString);
  EXPECT_EQ(spec.get_string_attribute("Software"), "pathtracer " + version);
  const OIIO::ParamValue* chroma = attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8));
  ASSERT_TRUE(chroma);
  const float rec709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(static_cast<const float*>(chroma->data())[i], rec709[i]) << i;
  const OIIO::ParamValue* w2c = attribute("worldToCamera", OIIO::TypeMatrix44);
  const OIIO::ParamValue* w2n = attribute("worldToNDC", OIIO::TypeMatrix44);
  ASSERT_TRUE(w2c && w2n);
  const auto* to_camera = static_cast<const float*>(w2c->data());
  const auto* to_ndc = static_cast<const float*>(w2n->data());

  // The matrices, as a compositor uses them: the camera (path_scene: eye (0, 1, 4)
  // looking at (0, 0.5, 0)) is the origin of camera space, looking down -z ...
  const float eye[3] = {0, 1, 4}, target[3] = {0, 0.5f, 0};
  const std::array<float, 4> e = transform(eye, to_camera), t = transform(target, to_camera);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(e[j], 0.0f, 1e-5f) << j;
  EXPECT_NEAR(t[0], 0.0f, 1e-5f);
  EXPECT_NEAR(t[1], 0.0f, 1e-5f);
  EXPECT_NEAR(t[2], -std::sqrt(16.25f), 1e-5f);
  const std::array<float, 4> n = transform(target, to_ndc);  // ... and the frame's centre in NDC
  EXPECT_NEAR(n[0] / n[3], 0.0f, 1e-5f);
  EXPECT_NEAR(n[1] / n[3], 0.0f, 1e-5f);
  // Every pixel's first-hit position (P, half) projects into that pixel, at the depth of its Z.
  int hits = 0;
  for (int i = 0; i < spec.width * spec.height; ++i) {
    const float z = exr.at("Z", i);
    if (z == 1e10f) continue;  // a miss (Blender's background depth)
    ++hits;
    const int px = spec.x + i % spec.width, py = spec.y + i / spec.width;
    const float p[3] = {exr.at("P.X", i), exr.at("P.Y", i), exr.at("P.Z", i)};
    const std::array<float, 4> q = transform(p, to_ndc);
    const float sx = (q[0] / q[3] + 1.0f) * 0.5f * 48.0f, sy = (1.0f - q[1] / q[3]) * 0.5f * 32.0f;
    const float slack = 0.02f;  // P is stored as half
    EXPECT_GE(sx, px - slack) << px << "," << py;
    EXPECT_LT(sx, px + 1 + slack) << px << "," << py;
    EXPECT_GE(sy, py - slack) << px << "," << py;
    EXPECT_LT(sy, py + 1 + slack) << px << "," << py;
    EXPECT_NEAR(transform(p, to_camera)[2], -z, 0.01f * z) << px << "," << py;
  }
  EXPECT_GT(hits, 100);  // the floor and the sphere fill most of the crop

  // The layers hold what they say: 3 samples everywhere, no non-finite one, an
  // alpha that is the covered fraction of the 3 samples (the box filter), a
  // beauty that is the sum of the lighting split (half layers: to half precision).
  for (int i = 0; i < spec.width * spec.height; ++i) {
    ASSERT_EQ(exr.at("samples.X", i), 3.0f) << i;
    ASSERT_EQ(exr.at("nonfinite.X", i), 0.0f) << i;
    const float a = exr.at("A", i);
    ASSERT_TRUE(a == 0.0f || a == static_cast<float>(1.0 / 3.0) || a == static_cast<float>(2.0 / 3.0) || a == 1.0f)
        << a << " at " << i;
    if (exr.at("Z", i) != 1e10f) {
      ASSERT_GT(a, 0.0f) << i;  // the first sample hit
    }
    for (const char* c : {"R", "G", "B"}) {
      float sum = 0;
      for (const char* layer : {"emission", "diffuse_direct", "diffuse_indirect", "specular_direct", "specular_indirect"})
        sum += exr.at(std::string(layer) + "." + c, i);
      ASSERT_NEAR(sum, exr.at(c, i), 2e-3f * std::max(1.0f, exr.at(c, i))) << c << " " << i;
    }
  }
  // The run record says the same.
  EXPECT_EQ(rec["output"]["beauty_type"], "float");
  EXPECT_EQ(rec["output"]["aovs"].size(), 14u);
  EXPECT_EQ(rec["output"]["crop"], (nlohmann::json{{"x", 8}, {"y", 4}, {"width", 20}, {"height", 16}}));
}

TEST_F(ExrReadBack, BeautyIsFloatByDefaultAndHalfWhenAsked) {
  write("s.json", path_scene(24, 16, 2));
  ASSERT_EQ(run("s.json -o float.exr --quiet").status, 0);
  const RunResult r = run("s.json -o half.exr --aov beauty:half,Z --report run.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const Exr f = read_exr(path("float.exr")), h = read_exr(path("half.exr"));
  ASSERT_EQ(f.spec.nchannels, 4);
  ASSERT_EQ(h.spec.nchannels, 5);
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(f.spec.channelformat(c), OIIO::TypeFloat) << f.spec.channelnames[c];
    EXPECT_EQ(h.spec.channelnames[c], f.spec.channelnames[c]);
    EXPECT_EQ(h.spec.channelformat(c), OIIO::TypeHalf) << h.spec.channelnames[c];
  }
  EXPECT_EQ(h.spec.channelformat(h.index.at("Z")), OIIO::TypeFloat);  // the AOVs keep their own types
  EXPECT_NE(f.spec.get_string_attribute("pathtracer:backend").find("bvh"), std::string::npos);
  // The same pixels, rounded to half (11 significant bits).
  int differ = 0;
  for (int i = 0; i < f.spec.width * f.spec.height; ++i)
    for (const char* c : {"R", "G", "B", "A"}) {
      const float want = f.at(c, i), got = h.at(c, i);
      ASSERT_NEAR(got, want, std::ldexp(std::fabs(want), -11) + 1e-7f) << c << " " << i;
      differ += got != want;
    }
  EXPECT_GT(differ, 0);  // really rounded
  EXPECT_EQ(read_json("run.json")["output"]["beauty_type"], "half");
}

}  // namespace
}  // namespace pt::test
