// The multi-layer EXR a render writes, read back with OpenImageIO: channel
// names and types, the crop as data window inside the full display window,
// the values, and the metadata (the camera matrices checked by projecting a
// known world point). Display formats of a crop hold the crop only.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <map>

#include <OpenImageIO/imageio.h>

#include "core/parallel.h"
#include "io/image_io.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "test_scenes.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

constexpr int kW = 40, kH = 30;
const PixelRect kCrop{6, 4, 31, 22};
const Vec3f kCentre(0.5f, 0.25f, 0.0f);

struct Rendered {
  std::unique_ptr<RenderScene> scene;
  std::unique_ptr<Film> film;
};

Rendered render(WorkerPool& pool) {
  SceneDescription d = test::empty_scene(kW, kH, Vec3f(1, 2, 6), Vec3f(0, 0, 0), Vec3f(0, 1, 0), 45.0f);
  test::add_z_square(d, -1.0f, 5.0f, test::add_material(d, test::diffuse_material(RGB(0.3f, 0.6f, 0.9f))));
  test::add_sphere(d, kCentre, 0.7f, test::add_material(d, test::diffuse_material(RGB(0.8f))));
  test::add_point_light(d, Vec3f(2, 3, 4), RGB(20.0f), RGB(20.0f));
  Rendered r;
  r.scene = test::build(d, pool);
  std::vector<AovRequest> aovs;
  ChannelType beauty = ChannelType::Float;
  std::string error;
  EXPECT_TRUE(parse_aov_list("albedo,N,P,Z,IndexOB,IndexMA,diffuse_direct:half,variance,samples,nonfinite", aovs,
                             beauty, error));
  r.film = std::make_unique<Film>(kW, kH, kCrop, aovs);
  IntegratorSettings settings;
  settings.spp = 4;
  make_integrator("path", settings, error)->render(*r.scene, *r.film, pool);
  return r;
}

ImageMetadata metadata_of(const RenderScene& scene) {
  RenderStamp stamp;
  stamp.render_seconds = 1.25;
  stamp.spp = 4;
  stamp.seed = 12345678901234ull;
  stamp.backend = "embree test";
  stamp.integrator = "path";
  stamp.software_version = PT_VERSION;
  stamp.partial = true;
  stamp.has_camera = true;
  stamp.world_to_camera = scene.camera.world_to_camera();
  stamp.world_to_ndc = scene.camera.world_to_ndc();
  ImageMetadata m;
  add_render_stamp(m, stamp);
  return m;
}

// p (a row vector, w = 1) times the row-major 4x4 matrix m.
std::array<float, 4> transform(Vec3f p, const float* m) {
  std::array<float, 4> out{};
  for (int c = 0; c < 4; ++c) out[c] = p.x * m[c] + p.y * m[4 + c] + p.z * m[8 + c] + m[12 + c];
  return out;
}

class ExrOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pt_exr_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(ExrOutput, LayersTypesWindowsValuesAndMetadata) {
  WorkerPool pool(2);
  const Rendered r = render(pool);
  ASSERT_TRUE(r.scene);
  std::string error;
  const std::string file = path("layers.exr");
  ASSERT_TRUE(write_layered_image(file, r.film->layers(), DisplaySettings{}, error, metadata_of(*r.scene))) << error;

  auto in = OIIO::ImageInput::open(file);
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.x, kCrop.x0);
  EXPECT_EQ(spec.y, kCrop.y0);
  EXPECT_EQ(spec.width, kCrop.width());
  EXPECT_EQ(spec.height, kCrop.height());
  EXPECT_EQ(spec.full_x, 0);
  EXPECT_EQ(spec.full_y, 0);
  EXPECT_EQ(spec.full_width, kW);
  EXPECT_EQ(spec.full_height, kH);

  const std::map<std::string, OIIO::TypeDesc> expected = {
      {"R", OIIO::TypeFloat}, {"G", OIIO::TypeFloat}, {"B", OIIO::TypeFloat}, {"A", OIIO::TypeFloat},
      {"albedo.R", OIIO::TypeHalf}, {"albedo.G", OIIO::TypeHalf}, {"albedo.B", OIIO::TypeHalf},
      {"N.X", OIIO::TypeHalf}, {"N.Y", OIIO::TypeHalf}, {"N.Z", OIIO::TypeHalf},
      {"P.X", OIIO::TypeFloat}, {"P.Y", OIIO::TypeFloat}, {"P.Z", OIIO::TypeFloat},
      {"Z", OIIO::TypeFloat}, {"IndexOB.X", OIIO::TypeFloat}, {"IndexMA.X", OIIO::TypeFloat},
      {"diffuse_direct.R", OIIO::TypeHalf}, {"diffuse_direct.G", OIIO::TypeHalf},
      {"diffuse_direct.B", OIIO::TypeHalf}, {"variance.R", OIIO::TypeFloat}, {"variance.G", OIIO::TypeFloat},
      {"variance.B", OIIO::TypeFloat}, {"samples.X", OIIO::TypeFloat}, {"nonfinite.X", OIIO::TypeHalf}};
  ASSERT_EQ(spec.nchannels, static_cast<int>(expected.size()));
  std::map<std::string, int> index;
  for (int c = 0; c < spec.nchannels; ++c) {
    const std::string& name = spec.channelnames[c];
    ASSERT_TRUE(expected.count(name)) << name;
    EXPECT_EQ(spec.channelformat(c), expected.at(name)) << name;
    index[name] = c;
  }
  EXPECT_EQ(spec.channelnames[0], "R");
  EXPECT_EQ(spec.channelnames[3], "A");

  // Values: every channel against the film (half channels to half precision).
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, pixels.data())) << in->geterror();
  const LayeredImage layers = r.film->layers();
  for (const ImageLayer& layer : layers.layers)
    for (std::size_t c = 0; c < layer.channels.size(); ++c)
      for (std::size_t i = 0; i < layers.pixel_count(); ++i) {
        const float want = layer.values[i * layer.channels.size() + c];
        const float got = pixels[i * spec.nchannels + index.at(layer.channels[c])];
        if (layer.type == ChannelType::Float) {
          ASSERT_EQ(got, want) << layer.channels[c];
        } else {
          ASSERT_NEAR(got, want, 1e-3f * std::max(1.0f, std::fabs(want))) << layer.channels[c];
        }
      }

  // Metadata.
  EXPECT_EQ(spec.get_int_attribute("pathtracer:spp"), 4);
  EXPECT_EQ(spec.get_int_attribute("pathtracer:partial"), 1);
  EXPECT_EQ(spec.get_string_attribute("pathtracer:seed"), "12345678901234");
  EXPECT_EQ(spec.get_string_attribute("pathtracer:integrator"), "path");
  EXPECT_EQ(spec.get_string_attribute("pathtracer:backend"), "embree test");
  EXPECT_EQ(spec.get_string_attribute("pathtracer:version"), PT_VERSION);
  EXPECT_FLOAT_EQ(spec.get_float_attribute("pathtracer:renderTime"), 1.25f);
  const OIIO::ParamValue* chroma = spec.find_attribute("chromaticities");
  ASSERT_TRUE(chroma);
  ASSERT_EQ(chroma->type().numelements() * chroma->type().aggregate, 8u);
  const float* xy = static_cast<const float*>(chroma->data());
  const float rec709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(xy[i], rec709[i]);

  const OIIO::ParamValue* w2c = spec.find_attribute("worldToCamera", OIIO::TypeMatrix44);
  const OIIO::ParamValue* w2n = spec.find_attribute("worldToNDC", OIIO::TypeMatrix44);
  ASSERT_TRUE(w2c && w2n);
  // A known world point: the sphere's point nearest the camera, seen in the crop.
  const Vec3f p = kCentre + normalize(r.scene->camera.position() - kCentre) * 0.7f;
  Vec2f film_px;
  ASSERT_TRUE(r.scene->camera.project(p, film_px));
  const std::array<float, 4> ndc = transform(p, static_cast<const float*>(w2n->data()));
  ASSERT_GT(ndc[3], 0.0f);
  const float px = (ndc[0] / ndc[3] + 1.0f) * 0.5f * kW, py = (1.0f - ndc[1] / ndc[3]) * 0.5f * kH;
  EXPECT_NEAR(px, film_px.x, 1e-3f);
  EXPECT_NEAR(py, film_px.y, 1e-3f);
  // Camera space looks down -z: the point's z is minus its depth along the view axis.
  const std::array<float, 4> cam = transform(p, static_cast<const float*>(w2c->data()));
  const float depth = dot(p - r.scene->camera.position(), r.scene->camera.forward());
  EXPECT_NEAR(cam[2], -depth, 1e-4f);
  EXPECT_NEAR(cam[3], 1.0f, 1e-6f);
  // ... and the Z layer at that pixel holds the same depth (a hit near the point).
  ASSERT_TRUE(kCrop.contains(static_cast<int>(film_px.x), static_cast<int>(film_px.y)));
  const std::vector<float> z =
      r.film->aov_value(AovType::Depth, static_cast<int>(film_px.x), static_cast<int>(film_px.y));
  EXPECT_NEAR(z[0], depth, 0.02f);
}

TEST_F(ExrOutput, DisplayFormatsOfACropHoldTheCropOnly) {
  WorkerPool pool(2);
  const Rendered r = render(pool);
  std::string error;
  for (const char* name : {"crop.png", "crop.ppm"}) {
    ASSERT_TRUE(write_layered_image(path(name), r.film->layers(), DisplaySettings{}, error)) << error;
    Image back;
    ASSERT_TRUE(read_image(path(name), back, error)) << error;
    EXPECT_EQ(back.width, kCrop.width()) << name;
    EXPECT_EQ(back.height, kCrop.height()) << name;
  }
  EXPECT_FALSE(write_layered_image(path("missing/dir/x.exr"), r.film->layers(), DisplaySettings{}, error));
  EXPECT_FALSE(fs::exists(path("missing/dir/x.exr")));
}

}  // namespace
}  // namespace pt
