#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "io/image_io.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

DisplaySettings display(DisplayTransform t, float exposure = 0) {
  DisplaySettings s;
  s.transform = t;
  s.exposure = exposure;
  return s;
}

// ---------------------------------------------------------------- display transforms
TEST(Display, SrgbKnownCodes) {
  const DisplaySettings s = display(DisplayTransform::Srgb);
  EXPECT_EQ(display_encode(0.0f, s), 0);
  EXPECT_EQ(display_encode(1.0f, s), 255);
  EXPECT_EQ(display_encode(0.5f, s), 188);     // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
  EXPECT_EQ(display_encode(0.18f, s), 118);    // middle grey: 0.4614
  EXPECT_EQ(display_encode(0.001f, s), 3);     // linear toe: 12.92 * 0.001 * 255 = 3.29
  EXPECT_EQ(display_encode(7.0f, s), 255);     // clamped
  EXPECT_EQ(display_encode(-1.0f, s), 0);
  EXPECT_EQ(display_encode(std::nanf(""), s), 0);
  EXPECT_EQ(display_encode(0.25f, display(DisplayTransform::Srgb, 1.0f)), 188);  // one stop up
}

// The Path of Light course writes value x 255, no gamma, rounded to nearest.
TEST(Display, LinearIsValueTimes255) {
  const DisplaySettings s = display(DisplayTransform::Linear);
  for (int k = 0; k <= 255; ++k) EXPECT_EQ(display_encode(static_cast<float>(k) / 255.0f, s), k) << k;
  EXPECT_EQ(display_encode(0.5f, s), 128);  // 127.5 rounds up
  EXPECT_EQ(display_encode(0.2f, s), 51);
  EXPECT_EQ(display_encode(0.01f, s), 3);
  EXPECT_EQ(display_encode(1.5f, s), 255);
  EXPECT_EQ(display_encode(1.0f, display(DisplayTransform::Linear, -1.0f)), 128);
}

// The CGR course's mapping (docs/rendering.md, "The CGR mapping"):
// its one fixed point (a 0.25 grey background shows as 87), monotonic in grey,
// and a colour is compressed by its luminance: the same red channel is
// darker beside a bright green than beside nothing.
TEST(Display, CgrCourseMapping) {
  const DisplaySettings s = display(DisplayTransform::CgrCourse);
  EXPECT_EQ(display_encode(0.25f, s), 87);
  EXPECT_EQ(display_encode(0.0f, s), 0);
  EXPECT_EQ(display_encode(1.0f, s), 247);  // white reaches 255 from about 1.06
  EXPECT_EQ(display_encode(1.1f, s), 255);
  int previous = 0;
  for (int i = 0; i <= 1000; ++i) {
    const int code = display_encode(static_cast<float>(i) / 1000.0f, s);
    EXPECT_GE(code, previous) << i;
    previous = code;
  }
  std::string error;
  const auto encoder = DisplayEncoder::create(s, error);
  ASSERT_TRUE(encoder) << error;
  const RGB colours[3] = {RGB(0.1125f, 0.1125f, 0.1125f), RGB(0.1125f, 0.18f, 0.1125f), RGB(0.1125f, 0.25f, 0.1125f)};
  unsigned char codes[9];
  encoder->encode(colours, 3, codes);
  EXPECT_GT(codes[0], codes[3]);
  EXPECT_GT(codes[3], codes[6]);
  EXPECT_EQ(codes[0], codes[2]);  // grey stays grey
}

// Binary-mode renders (exactly 0 and pure red 1, 0, 0) stay pure under every
// transform; 0 and 1 are 0 and 255 wherever the curve is per channel.
TEST(Display, ZeroAndOneArePureUnderEveryTransform) {
  for (DisplayTransform t : {DisplayTransform::Srgb, DisplayTransform::Linear, DisplayTransform::CgrCourse}) {
    std::string error;
    const auto encoder = DisplayEncoder::create(display(t), error);
    ASSERT_TRUE(encoder) << error;
    const RGB pixels[2] = {RGB(0, 0, 0), RGB(1, 0, 0)};
    unsigned char codes[6];
    encoder->encode(pixels, 2, codes);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(codes[i], i == 3 ? 255 : 0) << i;
    if (t != DisplayTransform::CgrCourse) {
      EXPECT_EQ(display_encode(1.0f, display(t)), 255);
    }
  }
}

// ---------------------------------------------------------------- files
class ImageFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pt_image_io_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

  static Image test_image() {
    Image img(3, 2);
    img.at(0, 0) = RGB(0, 0, 0);
    img.at(1, 0) = RGB(1, 0.5f, 0.25f);
    img.at(2, 0) = RGB(2.5f, 1e-3f, 0.75f);
    img.at(0, 1) = RGB(0.1f, 0.2f, 0.3f);
    img.at(1, 1) = RGB(1, 1, 1);
    img.at(2, 1) = RGB(0.9f, 0.05f, 0.6f);
    return img;
  }

  fs::path dir_;
};

TEST_F(ImageFiles, PpmIsBinaryP6WithDisplayCodes) {
  const Image img = test_image();
  const DisplaySettings s = display(DisplayTransform::Linear);
  std::string error;
  ASSERT_TRUE(write_image(path("a.ppm"), img, s, error)) << error;
  std::ifstream in(path("a.ppm"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string header = "P6\n3 2\n255\n";
  ASSERT_EQ(bytes.size(), header.size() + 3 * 2 * 3);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(static_cast<unsigned char>(bytes[header.size() + 3 * i + c]), display_encode(img.pixels[i][c], s));

  Image back;
  ASSERT_TRUE(read_image(path("a.ppm"), back, error)) << error;
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  EXPECT_FLOAT_EQ(back.at(1, 0).g, 128.0f / 255.0f);
}

TEST_F(ImageFiles, PngRoundTripGivesDisplayCodes) {
  const Image img = test_image();
  const DisplaySettings s = display(DisplayTransform::Srgb);
  std::string error;
  ASSERT_TRUE(write_image(path("a.png"), img, s, error)) << error;
  Image back;
  ASSERT_TRUE(read_image(path("a.png"), back, error)) << error;
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back.pixels[i][c], display_encode(img.pixels[i][c], s) / 255.0f, 1e-6f);
  auto in = OIIO::ImageInput::open(path("a.png"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->format_name(), std::string("png"));
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
}

TEST_F(ImageFiles, ExrRoundTripIsExactFloat) {
  const Image img = test_image();
  std::string error;
  ASSERT_TRUE(write_image(path("a.exr"), img, display(DisplayTransform::Srgb, 3.0f), error)) << error;
  Image back;
  ASSERT_TRUE(read_image(path("a.exr"), back, error)) << error;
  ASSERT_EQ(back.pixels.size(), img.pixels.size());
  for (std::size_t i = 0; i < img.pixels.size(); ++i) EXPECT_EQ(back.pixels[i], img.pixels[i]) << i;
  auto in = OIIO::ImageInput::open(path("a.exr"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(in->spec().nchannels, 3);
  EXPECT_NE(in->spec().get_string_attribute("Software").find("pathtracer"), std::string::npos);
}

TEST_F(ImageFiles, ExrCarriesTypedMetadataPngItsStrings) {
  ImageMetadata meta;
  meta.set("pathtracer:integrator", "path");
  meta.set("pathtracer:spp", 64);
  meta.set("pathtracer:renderSeconds", 1.5f);
  ImageMetadata::Matrix m{};
  for (int i = 0; i < 16; ++i) m[static_cast<std::size_t>(i)] = static_cast<float>(i) - 3.5f;
  meta.set("worldToCamera", m);
  std::string error;
  ASSERT_TRUE(write_image(path("m.exr"), test_image(), display(DisplayTransform::Srgb), error, meta)) << error;
  ASSERT_TRUE(write_image(path("m.png"), test_image(), display(DisplayTransform::Srgb), error, meta)) << error;

  auto exr = OIIO::ImageInput::open(path("m.exr"));
  ASSERT_TRUE(exr);
  const OIIO::ImageSpec& spec = exr->spec();
  EXPECT_EQ(spec.get_string_attribute("pathtracer:integrator"), "path");
  EXPECT_EQ(spec.get_int_attribute("pathtracer:spp"), 64);
  EXPECT_EQ(spec.get_float_attribute("pathtracer:renderSeconds"), 1.5f);
  const OIIO::ParamValue* p = spec.find_attribute("worldToCamera");
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->type(), OIIO::TypeMatrix44);
  const float* back = static_cast<const float*>(p->data());
  for (int i = 0; i < 16; ++i) EXPECT_EQ(back[i], m[static_cast<std::size_t>(i)]) << i;

  auto png = OIIO::ImageInput::open(path("m.png"));
  ASSERT_TRUE(png);
  EXPECT_EQ(png->spec().get_string_attribute("pathtracer:integrator"), "path");
}

TEST_F(ImageFiles, ExtensionIsCaseInsensitive) {
  EXPECT_TRUE(is_supported_image_path("x/y/OUT.PNG"));
  EXPECT_TRUE(is_supported_image_path("a.Exr"));
  EXPECT_TRUE(is_supported_image_path("a.pPm"));
  std::string error;
  ASSERT_TRUE(write_image(path("UP.PNG"), test_image(), display(DisplayTransform::Srgb), error)) << error;
  auto in = OIIO::ImageInput::open(path("UP.PNG"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->format_name(), std::string("png"));
}

TEST_F(ImageFiles, UnsupportedExtensionIsAnErrorListingTheSupportedOnes) {
  for (const char* name : {"a.tiff", "noext", "a.png.bak", "dir.png/file"}) {
    EXPECT_FALSE(is_supported_image_path(name)) << name;
    std::string error;
    EXPECT_FALSE(write_image(path(name), test_image(), display(DisplayTransform::Srgb), error)) << name;
    for (const std::string& ext : supported_image_extensions())
      EXPECT_NE(error.find(ext), std::string::npos) << error;
  }
  EXPECT_TRUE(files().empty());
}

TEST_F(ImageFiles, UnwritableFolderLeavesNothing) {
  std::string error;
  EXPECT_FALSE(write_image(path("missing/sub/out.png"), test_image(), display(DisplayTransform::Srgb), error));
  EXPECT_FALSE(error.empty());
  // A regular file where a folder should be.
  std::ofstream(path("plain")) << "x";
  error.clear();
  EXPECT_FALSE(write_image(path("plain/out.exr"), test_image(), display(DisplayTransform::Srgb), error));
  EXPECT_FALSE(error.empty());
  // The destination is a directory: the rename fails and the temporary file is removed.
  fs::create_directories(path("taken.ppm"));
  error.clear();
  EXPECT_FALSE(write_image(path("taken.ppm"), test_image(), display(DisplayTransform::Srgb), error));
  EXPECT_FALSE(error.empty());
  std::vector<std::string> names = files();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"plain", "taken.ppm"}));
  EXPECT_TRUE(fs::is_empty(path("taken.ppm")));
}

TEST_F(ImageFiles, ExistingFileIsReplacedWhole) {
  Image big(64, 32);
  for (RGB& p : big.pixels) p = RGB(0.3f, 0.6f, 0.9f);
  const Image small = test_image();
  for (const char* name : {"r.ppm", "r.png", "r.exr"}) {
    std::string error;
    ASSERT_TRUE(write_image(path(name), big, display(DisplayTransform::Linear), error)) << error;
    ASSERT_TRUE(write_image(path(name), small, display(DisplayTransform::Linear), error)) << error;
    Image back;
    ASSERT_TRUE(read_image(path(name), back, error)) << error;
    EXPECT_EQ(back.width, 3) << name;
    EXPECT_EQ(back.height, 2) << name;
  }
  std::vector<std::string> names = files();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"r.exr", "r.png", "r.ppm"}));  // no temporaries left
}

TEST_F(ImageFiles, EmptyImageIsRefused) {
  std::string error;
  EXPECT_FALSE(write_image(path("e.png"), Image(), display(DisplayTransform::Srgb), error));
  EXPECT_TRUE(files().empty());
}

TEST_F(ImageFiles, ReadingMissingFileFails) {
  Image img;
  std::string error;
  EXPECT_FALSE(read_image(path("none.exr"), img, error));
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace pt
