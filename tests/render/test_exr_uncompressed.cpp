// The uncompressed EXR writer without the image module (io/exr_uncompressed.h):
// the same bytes, but the time of writing (capDate), as the image module's
// writer, for the renderer's metadata (long names, empty strings, NaN, both
// matrices, a Cryptomatte manifest), a crop of a frame, half and float
// layers, and bands of any height; other metadata names go to the module.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "imagelib/image_library.h"
#include "io/exr_pack.h"
#include "io/exr_uncompressed.h"
#include "io/image_io.h"
#include "exr_bytes_image.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

// The file's bytes, the capDate attribute's value zeroed.
std::string bytes_without_date(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string key("capDate\0string\0", 15);
  const std::size_t at = data.find(key);
  if (at != std::string::npos && at + key.size() + 4 <= data.size()) {
    const std::size_t size = static_cast<unsigned char>(data[at + key.size()]);
    data.replace(at + key.size() + 4, size, size, '\0');
  }
  return data;
}

ImageMetadata renderer_metadata() {
  ImageMetadata m = test::exr_bytes_metadata();
  m.set("pathtracer:sampler", "");  // empty
  m.set("pathtracer:shadowTerminatorOffset", 0.25f);  // 33 characters: the long-names flag
  m.set("pathtracer:clamp", std::numeric_limits<float>::quiet_NaN());
  m.set("pathtracer:partial", 1);
  m.set("worldToNDC", ImageMetadata::Matrix{2, 0, 0, 0, 0, 3, 0, 0, 0, 0, -1, -1, 0, 0, -0.5f, 0});
  m.set("cryptomatte/a1b2c3d/manifest", std::string(300, 'x') + "{\"name\":\"00000000\"}");
  m.set("pathtracer:shards", "2 shards: 0/2 1/2");
  return m;
}

// Writes `image` band by band (`band` rows) with the writer write_exr_bands picks.
bool write_bands(const std::string& path, const LayeredImage& image, const ImageMetadata& metadata,
                 const ExrSettings& exr, int band, std::string& error) {
  const std::vector<const ImageLayer*> layers = every_layer(image);
  const PackedLayout packed = packed_layout(layers);
  return write_exr_bands(path, image, metadata, exr, [&](ExrBandWriter& writer, std::string& why) {
    const auto width = static_cast<std::size_t>(image.width);
    std::vector<unsigned char> rows(static_cast<std::size_t>(band) * writer.row_bytes());
    for (int y0 = 0; y0 < image.height; y0 += band) {
      const int y1 = std::min(image.height, y0 + band);
      for (int y = y0; y < y1; ++y)
        for (std::size_t l = 0; l < layers.size(); ++l) {
          const PackedLayer& p = packed.layers[l];
          const float* v = layers[l]->values.data() + static_cast<std::size_t>(y) * width * p.channels;
          unsigned char* out = rows.data() + static_cast<std::size_t>(y - y0) * writer.row_bytes() + p.offset;
          (p.half ? pack_halves : pack_floats)(v, p.channels, p.channels, width, out, packed.pixel_bytes);
        }
      if (!writer.write(image.y + y0, image.y + y1, rows.data(), why)) return false;
    }
    return true;
  }, error);
}

// The same with the file's lines (uncompressed_exr_lines, pack_lines,
// write_lines), `pixels` pixels of a row packed at a time.
bool write_lines(const std::string& path, const LayeredImage& image, const ImageMetadata& metadata,
                 const ExrSettings& exr, int band, std::size_t pixels, std::string& error) {
  const std::vector<const ImageLayer*> layers = every_layer(image);
  const LineLayout lines = uncompressed_exr_lines(image);
  return write_exr_bands(path, image, metadata, exr, [&](ExrBandWriter& writer, std::string& why) {
    const auto width = static_cast<std::size_t>(image.width);
    const std::size_t channels = lines.channels.size();
    std::vector<unsigned char> rows(static_cast<std::size_t>(band) * lines.row_bytes);
    std::vector<float> values(pixels * channels);
    for (int y0 = 0; y0 < image.height; y0 += band) {
      const int y1 = std::min(image.height, y0 + band);
      for (int y = y0; y < y1; ++y)
        for (std::size_t x = 0; x < width; x += pixels) {
          const std::size_t n = std::min(pixels, width - x);
          for (std::size_t i = 0; i < n; ++i) {  // every layer's channels of a pixel, in order
            float* v = values.data() + i * channels;
            for (const ImageLayer* l : layers) {
              const std::size_t k = l->channels.size();
              v = std::copy_n(l->values.data() + (static_cast<std::size_t>(y) * width + x + i) * k, k, v);
            }
          }
          pack_lines(lines, values.data(), x, n, rows.data() + static_cast<std::size_t>(y - y0) * lines.row_bytes);
        }
      if (!writer.write_lines(image.y + y0, image.y + y1, rows.data(), why)) return false;
    }
    return true;
  }, error);
}

class ExrUncompressed : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pt_exr_none_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(ExrUncompressed, WritesTheImageModulesBytes) {
  const LayeredImage image = test::exr_bytes_image();
  const ExrSettings none{"none", false};
  const ImageMetadata metadata = renderer_metadata();
  ASSERT_TRUE(writes_uncompressed_exr(image, metadata, none));
  std::string error;
  ASSERT_TRUE(write_layered_image(path("module.exr"), image, DisplaySettings{}, error, metadata, none)) << error;
  const std::string expected = bytes_without_date(path("module.exr"));
  ASSERT_GT(expected.size(), 20000u);
  EXPECT_EQ(static_cast<unsigned char>(expected[5]) & 4, 4) << "the long-names flag";
  for (const int band : {1, 7, 21}) {
    ASSERT_TRUE(write_bands(path("bands.exr"), image, metadata, none, band, error)) << error;
    const std::string written = bytes_without_date(path("bands.exr"));
    EXPECT_EQ(written.size(), expected.size()) << band;
    EXPECT_TRUE(written == expected) << "bands of " << band << " rows";
  }
  // Without a long name, and the golden file of the writer before (tests/data/exr_bytes).
  ASSERT_TRUE(write_bands(path("golden.exr"), image, test::exr_bytes_metadata(), none, 4, error)) << error;
  if (std::string(PT_VERSION) == "0.1.0") {  // the golden file names pathtracer 0.1.0 as its Software
    EXPECT_TRUE(bytes_without_date(path("golden.exr")) ==
                bytes_without_date(std::string(PT_TEST_DATA_DIR) + "/data/exr_bytes/none.exr"));
  }
}

// The rows packed as the file stores them (the streamed merge's uncompressed
// write): the same bytes; the image module's writer does not take them.
TEST_F(ExrUncompressed, WritesLinesAsTheFileStoresThem) {
  const LayeredImage image = test::exr_bytes_image();
  const ExrSettings none{"none", false};
  const ImageMetadata metadata = renderer_metadata();
  std::string error;
  ASSERT_TRUE(write_layered_image(path("module.exr"), image, DisplaySettings{}, error, metadata, none)) << error;
  const std::string expected = bytes_without_date(path("module.exr"));
  const LineLayout lines = uncompressed_exr_lines(image);
  ASSERT_EQ(lines.channels.size(), 11u);
  EXPECT_EQ(lines.row_bytes, 8 + static_cast<std::size_t>(image.width) * (5 * 4 + 6 * 2));
  for (const auto& [band, pixels] : {std::pair{1, std::size_t{32}}, {7, 5}, {21, 37}}) {
    ASSERT_TRUE(write_lines(path("lines.exr"), image, metadata, none, band, pixels, error)) << error;
    EXPECT_TRUE(bytes_without_date(path("lines.exr")) == expected) << "bands of " << band << " rows, " << pixels << " pixels";
  }
  ImageMetadata other = renderer_metadata();
  other.set("comments", "written by the module");
  EXPECT_FALSE(write_lines(path("module_lines.exr"), image, other, none, 4, 32, error));
  EXPECT_NE(error.find("packed rows"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(path("module_lines.exr")));
  // Out of order, as write().
  EXPECT_FALSE(write_exr_bands(path("gap.exr"), image, metadata, none, [&](ExrBandWriter& w, std::string& why) {
    std::vector<unsigned char> rows(lines.row_bytes * 2);
    return w.write_lines(image.y, image.y + 1, rows.data(), why) && w.write_lines(image.y + 2, image.y + 3, rows.data(), why);
  }, error));
  EXPECT_NE(error.find("out of order"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(path("gap.exr")));
}

TEST_F(ExrUncompressed, OtherNamesAndCompressionsGoToTheImageModule) {
  const LayeredImage image = test::exr_bytes_image();
  const ExrSettings none{"none", false};
  EXPECT_FALSE(writes_uncompressed_exr(image, renderer_metadata(), ExrSettings{"zip", false}));
  for (const char* name : {"Software", "DateTime", "oiio:ColorSpace", "compression", "screenWindowWidth", "comments"}) {
    ImageMetadata m = renderer_metadata();
    m.set(name, "x");
    EXPECT_FALSE(writes_uncompressed_exr(image, m, none)) << name;
  }
  ImageMetadata twice = renderer_metadata();
  twice.set("PathTracer:SPP", 3);  // pathtracer:spp in another case
  EXPECT_FALSE(writes_uncompressed_exr(image, twice, none));
  ImageMetadata matrix = renderer_metadata();
  matrix.set("pathtracer:matrix", ImageMetadata::Matrix{});
  EXPECT_FALSE(writes_uncompressed_exr(image, matrix, none));
  ImageMetadata zero = renderer_metadata();
  zero.set("pathtracer:backend2", std::string("a\0b", 3));
  EXPECT_FALSE(writes_uncompressed_exr(image, zero, none));
  LayeredImage same = image;
  same.layers[2].channels = {"A"};  // a channel named twice
  EXPECT_FALSE(writes_uncompressed_exr(same, renderer_metadata(), none));
  // Such a file is still written, by the module, band by band.
  std::string error;
  ImageMetadata other = renderer_metadata();
  other.set("comments", "written by the module");
  ASSERT_TRUE(write_bands(path("other.exr"), image, other, none, 5, error)) << error;
  ASSERT_TRUE(write_layered_image(path("other_whole.exr"), image, DisplaySettings{}, error, other, none)) << error;
  EXPECT_TRUE(bytes_without_date(path("other.exr")) == bytes_without_date(path("other_whole.exr")));
}

TEST_F(ExrUncompressed, RowsOutOfOrderOrMissingFailAndLeaveNoFile) {
  const LayeredImage image = test::exr_bytes_image();
  const ExrSettings none{"none", false};
  std::string error;
  EXPECT_FALSE(write_exr_bands(path("gap.exr"), image, renderer_metadata(), none, [&](ExrBandWriter& w, std::string& why) {
    std::vector<unsigned char> rows(w.row_bytes() * 2);
    return w.write(image.y, image.y + 1, rows.data(), why) && w.write(image.y + 2, image.y + 3, rows.data(), why);
  }, error));
  EXPECT_NE(error.find("out of order"), std::string::npos) << error;
  EXPECT_FALSE(write_exr_bands(path("short.exr"), image, renderer_metadata(), none, [&](ExrBandWriter& w, std::string& why) {
    std::vector<unsigned char> rows(w.row_bytes());
    return w.write(image.y, image.y + 1, rows.data(), why);
  }, error));
  EXPECT_NE(error.find("before its last row"), std::string::npos) << error;
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace pt
