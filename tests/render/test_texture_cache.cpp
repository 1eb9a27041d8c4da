// Image textures through the texture cache (render/textures/texture_cache.h):
// MIP level selection from the footprint, wrap modes, sRGB decoding before
// filtering, .tx files beside an image, the size limits, and a cache far
// smaller than the image giving the very same values.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "core/srgb.h"
#include "render/textures/texture.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

class CachedTextures : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pt_texcache_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, int w, int h, int nc, const std::vector<unsigned char>& data) {
    const std::string path = (dir_ / name).string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out != nullptr);
    const OIIO::ImageSpec spec(w, h, nc, OIIO::TypeDesc::UINT8);
    EXPECT_TRUE(out->open(path, spec)) << out->geterror();
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, data.data())) << out->geterror();
    out->close();
    return path;
  }

  // A tiled, MIP-mapped linear float file (what maketx writes; OpenEXR here,
  // as OpenImageIO 2.4 writes MIP levels to no TIFF) of size n x n whose
  // level k is the constant k / 10 in every channel.
  std::string write_levels(const std::string& name, int n) {
    const std::string exr = (dir_ / (name + ".exr")).string();
    const std::string path = (dir_ / name).string();
    auto out = OIIO::ImageOutput::create(exr);
    EXPECT_TRUE(out != nullptr && out->supports("mipmap"));
    OIIO::ImageSpec spec(n, n, 3, OIIO::TypeDesc::FLOAT);
    spec.tile_width = spec.tile_height = 16;
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("textureformat", "Plain Texture");  // MIP-mapped
    EXPECT_TRUE(out->open(exr, spec)) << out->geterror();
    for (int k = 0, size = n; size >= 1; ++k, size /= 2) {
      if (k > 0) {
        spec.width = spec.height = spec.full_width = spec.full_height = size;
        EXPECT_TRUE(out->open(exr, spec, OIIO::ImageOutput::AppendMIPLevel)) << out->geterror();
      }
      const std::vector<float> level(static_cast<std::size_t>(size) * size * 3, static_cast<float>(k) / 10.0f);
      EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, level.data())) << out->geterror();
    }
    out->close();
    fs::rename(exr, path);
    return path;
  }

  fs::path dir_;
};

Texture open(const TextureCache& cache, const std::string& path, TextureFilter filter, TextureWrap wrap = TextureWrap::Repeat,
             bool raw = false, std::string* warning = nullptr) {
  OpenedImage opened;
  std::string error;
  EXPECT_TRUE(cache.open(path, raw, filter, wrap, TextureLimits{}, opened, error)) << error;
  if (warning != nullptr) *warning = opened.warning;
  return Texture(opened.image);
}

// A footprint of w texels in u and v on an n-texel image.
TexCoord footprint(Vec2f uv, float texels, int n) {
  const float d = texels / static_cast<float>(n);
  return TexCoord(uv, {d, 0.0f}, {0.0f, d});
}

// The level a trilinear lookup reads follows the footprint in texels: 1 the
// finest, 4 the third (level 2), and between 4 and 8 a blend of levels 2 and
// 3 linear in the width (OpenImageIO's), so 6 is halfway.
TEST_F(CachedTextures, TrilinearReadsTheLevelOfTheFootprint) {
  const std::string image = write_levels("levels.tx", 64);
  TextureCache cache;
  const Texture t = open(cache, image, TextureFilter::Trilinear);
  EXPECT_NEAR(t.eval(TexCoord(Vec2f(0.3f, 0.6f))).r, 0.0f, 1e-6f);
  EXPECT_NEAR(t.eval(footprint({0.3f, 0.6f}, 1.0f, 64)).r, 0.0f, 1e-3f);
  EXPECT_NEAR(t.eval(footprint({0.3f, 0.6f}, 4.0f, 64)).r, 0.2f, 1e-3f);
  EXPECT_NEAR(t.eval(footprint({0.3f, 0.6f}, 6.0f, 64)).r, 0.25f, 1e-3f);
  EXPECT_NEAR(t.eval(footprint({0.3f, 0.6f}, 64.0f, 64)).r, 0.6f, 1e-3f);
  // Point and bilinear filters read the finest level whatever the footprint.
  EXPECT_EQ(open(cache, image, TextureFilter::Bilinear).eval(footprint({0.3f, 0.6f}, 16.0f, 64)).r, 0.0f);
  EXPECT_EQ(open(cache, image, TextureFilter::Point).eval(footprint({0.3f, 0.6f}, 16.0f, 64)).r, 0.0f);
}

// The anisotropic filter sizes its level by the footprint's shorter axis: a
// footprint 16 texels long and 2 wide reads about level 1, where trilinear
// (by the longer axis) reads level 4.
TEST_F(CachedTextures, AnisotropicReadsTheShorterAxis) {
  const std::string image = write_levels("levels.tx", 64);
  TextureCache cache;
  const TexCoord tc(Vec2f(0.5f, 0.5f), {16.0f / 64.0f, 0.0f}, {0.0f, 2.0f / 64.0f});
  EXPECT_NEAR(open(cache, image, TextureFilter::Trilinear).eval(tc).r, 0.4f, 1e-3f);
  EXPECT_NEAR(open(cache, image, TextureFilter::Anisotropic).eval(tc).r, 0.1f, 0.05f);
}

// A 2 x 1 image, texels 0 (black) and 255 (white), looked up at the nearest
// texel left of the image (u = -0.25) and right of it (u = 1.25).
TEST_F(CachedTextures, WrapModes) {
  const std::string image = write("two.png", 2, 1, 1, {0, 255});
  TextureCache cache;
  const auto at = [&](TextureWrap w, float u) {
    return open(cache, image, TextureFilter::Point, w, true).eval(TexCoord(Vec2f(u, 0.5f))).r;
  };
  EXPECT_EQ(at(TextureWrap::Repeat, 0.25f), 0.0f);
  EXPECT_EQ(at(TextureWrap::Repeat, 0.75f), 1.0f);
  EXPECT_EQ(at(TextureWrap::Repeat, -0.25f), 1.0f);  // the texel at 0.75
  EXPECT_EQ(at(TextureWrap::Repeat, 1.25f), 0.0f);
  EXPECT_EQ(at(TextureWrap::Clamp, -0.25f), 0.0f);
  EXPECT_EQ(at(TextureWrap::Clamp, 1.25f), 1.0f);
  EXPECT_EQ(at(TextureWrap::Black, 1.25f), 0.0f);
  EXPECT_EQ(at(TextureWrap::Black, -0.75f), 0.0f);
  EXPECT_EQ(at(TextureWrap::Mirror, -0.25f), 0.0f);  // mirrored: the texel at 0.25
  EXPECT_EQ(at(TextureWrap::Mirror, 1.25f), 1.0f);
}

// 8-bit images are sRGB-decoded texel by texel before the cache averages
// them: a 1-texel black and white checker filters to 0.5, not to the 0.21 of
// an average taken in sRGB and decoded afterwards. "encoding": "linear" (raw)
// reads the stored values.
TEST_F(CachedTextures, SrgbIsDecodedBeforeFiltering) {
  std::vector<unsigned char> px(64 * 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) px[static_cast<std::size_t>(y) * 64 + x] = ((x + y) & 1) != 0 ? 255 : 0;
  const std::string image = write("checker.png", 64, 64, 1, px);
  TextureCache cache;
  const Texture srgb = open(cache, image, TextureFilter::Trilinear);
  EXPECT_NEAR(srgb.eval(footprint({0.5f, 0.5f}, 32.0f, 64)).r, 0.5f, 2e-3f);
  const std::string grey = write("grey.png", 1, 1, 3, {128, 64, 255});
  const RGB decoded = open(cache, grey, TextureFilter::Bilinear).eval(TexCoord(Vec2f(0.5f, 0.5f)));
  EXPECT_NEAR(decoded.r, srgb_to_linear(128.0f / 255.0f), 1e-3f);
  EXPECT_NEAR(decoded.g, srgb_to_linear(64.0f / 255.0f), 1e-3f);
  EXPECT_NEAR(decoded.b, 1.0f, 1e-3f);
  const RGB raw = open(cache, grey, TextureFilter::Bilinear, TextureWrap::Repeat, true).eval(TexCoord(Vec2f(0.5f, 0.5f)));
  EXPECT_NEAR(raw.r, 128.0f / 255.0f, 1e-6f);
}

// A .tx beside the image (maketx's output) is what the cache reads; one older
// than the image is not used, with a warning.
TEST_F(CachedTextures, ATxBesideTheImageIsUsedUnlessStale) {
  const std::string image = write("wood.png", 4, 4, 3, std::vector<unsigned char>(48, 255));
  write_levels("wood.tx", 64);
  TextureCache cache;
  std::string warning;
  EXPECT_NEAR(open(cache, image, TextureFilter::Trilinear, TextureWrap::Repeat, false, &warning)
                  .eval(footprint({0.5f, 0.5f}, 4.0f, 64))
                  .r,
              0.2f, 1e-3f);
  EXPECT_EQ(warning, "");
  fs::last_write_time(dir_ / "wood.tx", fs::last_write_time(image) - std::chrono::hours(1));
  TextureCache fresh;
  EXPECT_NEAR(open(fresh, image, TextureFilter::Trilinear, TextureWrap::Repeat, false, &warning)
                  .eval(footprint({0.5f, 0.5f}, 4.0f, 64))
                  .r,
              1.0f, 1e-3f);
  EXPECT_NE(warning.find("wood.tx is older than the image and is not used"), std::string::npos) << warning;
}

// The size a header declares is checked before the cache reads anything.
TEST_F(CachedTextures, AHugeDeclaredSizeIsRefused) {
  TextureCache cache;
  OpenedImage opened;
  std::string error;
  const std::string path = std::string(PT_TEST_DATA_DIR) + "/hostile/files/huge-declared-size.png";
  EXPECT_FALSE(cache.open(path, false, TextureFilter::Anisotropic, TextureWrap::Repeat, TextureLimits{}, opened, error));
  EXPECT_NE(error.find("the image declares 100000x100000 = 10000000000 pixels"), std::string::npos) << error;
  const std::string junk = (dir_ / "junk.png").string();
  std::FILE* f = std::fopen(junk.c_str(), "wb");
  std::fputs("not an image", f);
  std::fclose(f);
  EXPECT_FALSE(cache.open(junk, false, TextureFilter::Anisotropic, TextureWrap::Repeat, TextureLimits{}, opened, error));
  EXPECT_FALSE(error.empty());
}

// A cache of 1 MiB holds a sixth of a 1024 x 1024 image's finest level: tiles
// are dropped and read again, and every lookup gives exactly what a cache
// that holds it all gives (--texture-cache changes memory, not images).
TEST_F(CachedTextures, ASmallCacheGivesTheSameValues) {
  const int n = 1024;
  std::vector<unsigned char> px(static_cast<std::size_t>(n) * n * 3);
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<unsigned char>((i * 2654435761u) >> 24);
  const std::string image = write("noise.png", n, n, 3, px);
  TextureCache small(uint64_t{1} << 20), large;
  const Texture a = open(small, image, TextureFilter::Anisotropic), b = open(large, image, TextureFilter::Anisotropic);
  for (int i = 0; i < 4000; ++i) {
    const Vec2f uv(std::fmod(0.6180339f * static_cast<float>(i), 1.0f), std::fmod(0.4142135f * static_cast<float>(i), 1.0f));
    const float w = std::ldexp(1.0f, -(i % 11));  // footprints from the whole image to one texel
    const TexCoord tc(uv, {w, 0.3f * w}, {-0.2f * w, 0.7f * w});
    ASSERT_EQ(a.eval(tc), b.eval(tc)) << i;
  }
  EXPECT_EQ(small.failure(), "");
}

}  // namespace
}  // namespace pt
