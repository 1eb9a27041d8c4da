#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "render/lights/environment.h"
#include "render/textures/texture.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

float srgb_decode(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

class TextureFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pt_texture_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, int w, int h, int nc, OIIO::TypeDesc type, const void* data) {
    const std::string path = (dir_ / name).string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out != nullptr);
    OIIO::ImageSpec spec(w, h, nc, type);
    EXPECT_TRUE(out->open(path, spec)) << out->geterror();
    EXPECT_TRUE(out->write_image(type, data)) << out->geterror();
    out->close();
    return path;
  }

  fs::path dir_;
};

TEST(Texture, BilinearAtTexelCentresAndBetween) {
  const Texture t(2, 2, {RGB(1, 0, 0), RGB(0, 1, 0), RGB(0, 0, 1), RGB(1, 1, 1)});
  // uv (0,0) is the top-left corner of the top-left texel; centres are at 0.25 and 0.75.
  EXPECT_EQ(t.lookup({0.25f, 0.25f}), RGB(1, 0, 0));
  EXPECT_EQ(t.lookup({0.75f, 0.25f}), RGB(0, 1, 0));
  EXPECT_EQ(t.lookup({0.25f, 0.75f}), RGB(0, 0, 1));
  const RGB mid = t.lookup({0.5f, 0.25f});
  EXPECT_NEAR(mid.r, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.g, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.b, 0.0f, 1e-6f);
}

TEST(Texture, RepeatWrap) {
  const Texture t(2, 2, {RGB(1, 0, 0), RGB(0, 1, 0), RGB(0, 0, 1), RGB(1, 1, 1)});
  for (Vec2f uv : {Vec2f(0.25f, 0.25f), Vec2f(0.6f, 0.1f), Vec2f(0.9f, 0.7f)}) {
    const RGB a = t.lookup(uv);
    for (Vec2f shift : {Vec2f(1, 0), Vec2f(-1, 0), Vec2f(0, 3), Vec2f(-2, -5)}) {
      const RGB b = t.lookup(uv + shift);
      EXPECT_NEAR(a.r, b.r, 1e-5f);
      EXPECT_NEAR(a.g, b.g, 1e-5f);
      EXPECT_NEAR(a.b, b.b, 1e-5f);
    }
  }
  // The corner blends the four texels across the wrap.
  const RGB c = t.lookup({0, 0});
  EXPECT_NEAR(c.r, 0.5f, 1e-6f);
  EXPECT_NEAR(c.g, 0.5f, 1e-6f);
  EXPECT_NEAR(c.b, 0.5f, 1e-6f);
}

TEST_F(TextureFiles, EightBitIsLinearised) {
  const unsigned char px[] = {255, 128, 0, 0, 64, 255};
  const std::string path = write("t.png", 2, 1, 3, OIIO::TypeDesc::UINT8, px);
  Texture t;
  std::string error;
  ASSERT_TRUE(Texture::load(path, t, error)) << error;
  ASSERT_EQ(t.width(), 2);
  ASSERT_EQ(t.height(), 1);
  const RGB a = t.lookup({0.25f, 0.5f});
  EXPECT_NEAR(a.r, 1.0f, 1e-5f);
  EXPECT_NEAR(a.g, srgb_decode(128 / 255.0f), 1e-5f);
  EXPECT_NEAR(a.b, 0.0f, 1e-6f);
  const RGB b = t.lookup({0.75f, 0.5f});
  EXPECT_NEAR(b.g, srgb_decode(64 / 255.0f), 1e-5f);
  EXPECT_NEAR(b.b, 1.0f, 1e-5f);
}

TEST_F(TextureFiles, FloatIsLinearAsItIs) {
  const float px[] = {2.5f, 0.25f, 0.0f};
  const std::string path = write("t.exr", 1, 1, 3, OIIO::TypeDesc::FLOAT, px);
  Texture t;
  std::string error;
  ASSERT_TRUE(Texture::load(path, t, error)) << error;
  EXPECT_EQ(t.lookup({0.5f, 0.5f}), RGB(2.5f, 0.25f, 0.0f));
}

TEST_F(TextureFiles, GreyAndAlphaBecomeRgb) {
  const unsigned char grey[] = {128};
  Texture t;
  std::string error;
  ASSERT_TRUE(Texture::load(write("g.png", 1, 1, 1, OIIO::TypeDesc::UINT8, grey), t, error)) << error;
  const float g = srgb_decode(128 / 255.0f);
  EXPECT_NEAR(t.lookup({0.5f, 0.5f}).r, g, 1e-5f);
  EXPECT_NEAR(t.lookup({0.5f, 0.5f}).b, g, 1e-5f);
  // Alpha does not darken the colour.
  const unsigned char rgba[] = {255, 255, 255, 0};
  ASSERT_TRUE(Texture::load(write("a.png", 1, 1, 4, OIIO::TypeDesc::UINT8, rgba), t, error)) << error;
  EXPECT_NEAR(t.lookup({0.5f, 0.5f}).g, 1.0f, 1e-5f);
}

TEST_F(TextureFiles, MissingOrCorruptFileFails) {
  Texture t;
  std::string error;
  EXPECT_FALSE(Texture::load((dir_ / "nope.png").string(), t, error));
  EXPECT_FALSE(error.empty());
  const std::string junk = (dir_ / "junk.png").string();
  { std::FILE* f = std::fopen(junk.c_str(), "wb"); std::fputs("not a png", f); std::fclose(f); }
  error.clear();
  EXPECT_FALSE(Texture::load(junk, t, error));
  EXPECT_FALSE(error.empty());
}

// The size an image declares is checked before anything is decoded: a PNG of
// 70 bytes declaring 100000 x 100000 pixels (tests/hostile/files) is refused
// with the sizes and the limits, not allocated (it ended in std::bad_alloc).
TEST(TextureLimits, AHugeDeclaredSizeIsRefusedBeforeDecoding) {
  Texture t;
  std::string error;
  const std::string path = std::string(PT_TEST_DATA_DIR) + "/hostile/files/huge-declared-size.png";
  EXPECT_FALSE(Texture::load(path, t, error));
  EXPECT_NE(error.find("the image declares 100000x100000 = 10000000000 pixels (240000000000 bytes decoded)"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("at most 268435456 pixels and 4294967296 bytes"), std::string::npos) << error;
  EXPECT_EQ(t.width(), 0);
}

// Both limits apply, at their exact values: a 4x4 RGB image is 16 pixels and
// 16 * (3 * 4 + 12) = 384 bytes decoded; a grey one reads one channel (256 bytes).
TEST_F(TextureFiles, PixelAndByteLimitsApplyAtTheirValues) {
  std::vector<unsigned char> px(4 * 4 * 3, 200);
  const std::string rgb = write("rgb.png", 4, 4, 3, OIIO::TypeDesc::UINT8, px.data());
  const std::string grey = write("grey.png", 4, 4, 1, OIIO::TypeDesc::UINT8, px.data());
  Texture t;
  std::string error;
  EXPECT_TRUE(Texture::load(rgb, t, error, TextureLimits{16, 384})) << error;
  EXPECT_EQ(t.width(), 4);
  EXPECT_FALSE(Texture::load(rgb, t, error, TextureLimits{15, 384}));
  EXPECT_NE(error.find("at most 15 pixels"), std::string::npos) << error;
  EXPECT_FALSE(Texture::load(rgb, t, error, TextureLimits{16, 383}));
  EXPECT_NE(error.find("(384 bytes decoded)"), std::string::npos) << error;
  EXPECT_TRUE(Texture::load(grey, t, error, TextureLimits{16, 256})) << error;
  EXPECT_FALSE(Texture::load(grey, t, error, TextureLimits{16, 255}));
}

// An unreadable file is reported with the system's reason (root reads anything).
TEST_F(TextureFiles, AnUnreadableFileSaysWhy) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root, which can read a chmod 000 file";
  const unsigned char px[] = {1, 2, 3};
  const std::string path = write("locked.png", 1, 1, 3, OIIO::TypeDesc::UINT8, px);
  fs::permissions(path, fs::perms::none);
  Texture t;
  std::string error;
  EXPECT_FALSE(Texture::load(path, t, error));
  EXPECT_NE(error.find("cannot open the file: Permission denied"), std::string::npos) << error;
}

}  // namespace
}  // namespace pt

// ---------------------------------------------------------------- environment texels (issue 20)

namespace pt {
namespace {

class EnvironmentTexels : public TextureFiles {
 protected:
  // A 4x2 float map of 0.5 with texel (x, y) set to `v`; loads it as an environment.
  std::unique_ptr<EnvironmentMap> load(int x, int y, RGB v, float intensity, std::string& error,
                                       std::string& warning) {
    std::vector<float> px(4 * 2 * 3, 0.5f);
    px[static_cast<std::size_t>(y * 4 + x) * 3] = v.r;
    px[static_cast<std::size_t>(y * 4 + x) * 3 + 1] = v.g;
    px[static_cast<std::size_t>(y * 4 + x) * 3 + 2] = v.b;
    EnvironmentDesc desc;
    desc.resolved = write("sky.exr", 4, 2, 3, OIIO::TypeDesc::FLOAT, px.data());
    desc.intensity.value = intensity;
    return EnvironmentMap::load(desc, error, {}, &warning);
  }
};

TEST_F(EnvironmentTexels, NegativeTexelsAreClampedWithAWarningNamingTheFirst) {
  std::string error, warning;
  const auto env = load(2, 1, RGB(-50, 0.25f, 0.5f), 1.0f, error, warning);
  ASSERT_TRUE(env) << error;
  EXPECT_NE(warning.find("1 texel has negative values, clamped to 0 (the first: texel (2, 1) = (-50, 0.25, 0.5)"),
            std::string::npos)
      << warning;
  // No direction sees negative radiance: the texel is (0, 0.25, 0.5) now.
  for (int i = 0; i < 64; ++i) {
    const float a = 2.0f * kPi * static_cast<float>(i) / 64.0f;
    for (float yv : {-0.7f, 0.0f, 0.7f}) {
      const RGB L = env->radiance(normalize(Vec3f(std::cos(a), yv, std::sin(a))));
      EXPECT_GE(L.r, 0.0f);
      EXPECT_GE(L.g, 0.0f);
      EXPECT_GE(L.b, 0.0f);
    }
  }
  std::string clean;
  ASSERT_TRUE(load(0, 0, RGB(0.5f), 1.0f, error, clean));
  EXPECT_EQ(clean, "");
}

TEST_F(EnvironmentTexels, NonFiniteOrOverflowingTexelsAreRefusedByName) {
  std::string error, warning;
  EXPECT_FALSE(load(3, 0, RGB(std::numeric_limits<float>::infinity(), 1, 1), 1.0f, error, warning));
  EXPECT_NE(error.find("texel (3, 0) = (inf, 1, 1) is not finite"), std::string::npos) << error;
  EXPECT_FALSE(load(1, 1, RGB(1, std::nanf(""), 1), 1.0f, error, warning));
  EXPECT_NE(error.find("texel (1, 1) = (1, nan, 1) is not finite"), std::string::npos) << error;
  // Finite, but 1e20 times an intensity of 1e20 overflows a path's float radiance.
  EXPECT_FALSE(load(0, 1, RGB(1e20f, 1, 1), 1e20f, error, warning));
  EXPECT_NE(error.find("texel (0, 1) = (1e+20, 1, 1) times the intensity"), std::string::npos) << error;
  EXPECT_TRUE(load(0, 1, RGB(1e20f, 1, 1), 1.0f, error, warning)) << error;
}

}  // namespace
}  // namespace pt
