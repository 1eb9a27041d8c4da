// Image textures through the texture cache (render/textures/texture_cache.h):
// MIP level selection from the footprint, wrap modes, sRGB decoding before
// filtering, .tx files beside an image, the size limits, and a cache far
// smaller than the image giving the very same values.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
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

// Every stored value of 8- and 16-bit files is decoded through a table
// (srgb_input.cpp): colour channels by the sRGB curve, alpha as stored. A
// 256 x 1 8-bit RGBA image holds every code in its colour channels (and the
// code reversed in alpha); a 16-bit one samples the range.
TEST_F(CachedTextures, EveryStoredValueIsDecoded) {
  for (const int bits : {8, 16}) {
    const int n = 256, max = (1 << bits) - 1;
    std::vector<uint16_t> codes(static_cast<std::size_t>(n) * 4);
    for (int x = 0; x < n; ++x) {
      const int v = bits == 8 ? x : (x * 257 + x * 13) % (max + 1);
      codes[4 * x] = codes[4 * x + 1] = codes[4 * x + 2] = static_cast<uint16_t>(v);
      codes[4 * x + 3] = static_cast<uint16_t>(max - v);
    }
    const std::string path = (dir_ / ("codes" + std::to_string(bits) + ".png")).string();
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out != nullptr);
    const OIIO::TypeDesc type = bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
    OIIO::ImageSpec spec(n, 1, 4, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // stored as given, not divided by alpha
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    const std::vector<unsigned char> bytes(codes.begin(), codes.end());
    ASSERT_TRUE(bits == 8 ? out->write_image(type, bytes.data()) : out->write_image(type, codes.data()))
        << out->geterror();
    out->close();
    TextureCache cache;
    const Texture t = open(cache, path, TextureFilter::Point);
    for (int x = 0; x < n; ++x) {
      const TexCoord at(Vec2f((static_cast<float>(x) + 0.5f) / n, 0.5f));
      const float v = static_cast<float>(codes[4 * x]) / static_cast<float>(max);
      const float a = static_cast<float>(codes[4 * x + 3]) / static_cast<float>(max);
      ASSERT_NEAR(t.eval(at).g, srgb_to_linear(v), 1e-3f * srgb_to_linear(v) + 1e-7f) << bits << " bits, code " << codes[4 * x];
      ASSERT_NEAR(t.alpha(at), a, 1e-3f * a + 1e-7f) << bits << " bits, code " << codes[4 * x + 3];
    }
  }
}

// A thread that outlives the caches, as a thread pool's worker does: it runs
// one job at a time, handed over by run().
class Worker {
 public:
  Worker() : thread_([this] { loop(); }) {}
  ~Worker() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      quit_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
  // Runs `job` on the worker and waits for it.
  void run(std::function<void()> job) {
    std::unique_lock<std::mutex> lock(mutex_);
    job_ = std::move(job);
    pending_ = true;
    changed_.notify_all();
    changed_.wait(lock, [this] { return !pending_; });
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock, [this] { return pending_ || quit_; });
      if (quit_) return;
      job_();
      pending_ = false;
      changed_.notify_all();
    }
  }
  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> job_;
  bool pending_ = false, quit_ = false;
  std::thread thread_;  // last: started once the rest is ready
};

// Caches created and destroyed one after another in one process while a
// thread that outlives them looks up in each, as a program rendering several
// scenes does (the regression goldens, a test binary). OpenImageIO 2.4 keeps a
// thread's state for a cache in a thread-specific pointer keyed by the cache's
// address: the worker's state outlived its cache, a later cache at the same
// address took it over unregistered, and its tiles outlived that cache in turn
// (an abort in ImageCacheImpl::decr_tiles, or a crash). Every cache gives the
// values of the first, alone or with two alive at once, destroyed in either
// order.
TEST_F(CachedTextures, CachesComeAndGoAcrossThreads) {
  const int n = 256;
  std::vector<unsigned char> px(static_cast<std::size_t>(n) * n * 3);
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<unsigned char>((i * 2654435761u) >> 24);
  const std::string image = write("noise.png", n, n, 3, px);
  Worker worker;
  const auto look_up = [&](const TextureCache& cache) {
    const Texture t = open(cache, image, TextureFilter::Anisotropic);
    std::vector<float> out(2048);
    worker.run([&] {
      for (std::size_t i = 0; i < out.size(); ++i) {
        const float x = static_cast<float>(i);
        const float w = std::ldexp(1.0f, -static_cast<int>(i % 9));
        out[i] = t.eval(TexCoord(Vec2f(std::fmod(0.618034f * x, 1.0f), std::fmod(0.414214f * x, 1.0f)), {w, 0.0f},
                                 {0.0f, w})).g;
      }
    });
    EXPECT_EQ(cache.failure(), "");
    return out;
  };
  std::vector<float> first;
  for (int round = 0; round < 24; ++round) {
    auto a = std::make_unique<TextureCache>(uint64_t{1} << 20);  // small: tiles come and go
    const std::vector<float> from_a = look_up(*a);
    if (round == 0) first = from_a;
    ASSERT_EQ(from_a, first) << "round " << round;
    if (round % 3 == 0) continue;  // one cache alone
    auto b = std::make_unique<TextureCache>(uint64_t{1} << 20);
    ASSERT_EQ(look_up(*b), first) << "round " << round;
    ASSERT_EQ(look_up(*a), first) << "round " << round;
    if (round % 3 == 1) a.reset();  // a first, then b; else b first
  }
}

}  // namespace
}  // namespace pt
