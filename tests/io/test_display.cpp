// The OpenColorIO display pipeline: built-in views and views of a config file.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "io/display.h"
#include "io/image_io.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

DisplaySettings view(const std::string& name) {
  DisplaySettings s;
  s.view = name;
  return s;
}

int code(float linear, const DisplaySettings& s) { return display_encode(linear, s); }

TEST(DisplayOcio, StandardViewIsThePiecewiseSrgbCurve) {
  // The built-in "DISPLAY - CIE-XYZ-D65_to_sRGB" after the Rec.709 -> XYZ matrix
  // must reproduce the sRGB OETF exactly (to the 8-bit code) for neutrals.
  for (int i = 0; i <= 1000; ++i) {
    const float v = static_cast<float>(i) / 1000.0f;
    const float srgb = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    ASSERT_EQ(code(v, view("standard")), std::lround(srgb * 255.0f)) << v;
  }
}

TEST(DisplayOcio, AcesViewRollsHighlightsOffInsteadOfClipping) {
  const DisplaySettings aces = view("aces");
  EXPECT_EQ(code(0.0f, aces), 0);
  // Standard clips everything above 1; the ACES tone curve keeps separating.
  EXPECT_EQ(code(2.0f, view("standard")), 255);
  EXPECT_LT(code(2.0f, aces), code(8.0f, aces));
  EXPECT_LT(code(8.0f, aces), 255);
  // Monotonic over a wide range.
  int previous = -1;
  for (float v = 1e-3f; v < 64.0f; v *= 1.25f) {
    const int c = code(v, aces);
    EXPECT_GE(c, previous) << v;
    previous = c;
  }
  // Middle grey: ACES 1.0 SDR video puts 0.18 at about 10 nits of 100, i.e.
  // a display value near 0.1 linear, 0.35 sRGB-encoded (code ~90): darker than
  // the standard view's 118. Band, not a point: the curve is the library's.
  const int grey = code(0.18f, aces);
  EXPECT_GT(grey, 75);
  EXPECT_LT(grey, 110);
  // Neutrals stay neutral.
  std::string error;
  const auto enc = DisplayEncoder::create(aces, error);
  ASSERT_NE(enc, nullptr) << error;
  const RGB g = enc->apply(RGB(0.18f));
  EXPECT_NEAR(g.r, g.g, 2e-3f);
  EXPECT_NEAR(g.b, g.g, 2e-3f);
}

TEST(DisplayOcio, UnknownViewIsAnErrorNamingTheValidOnes) {
  std::string error;
  EXPECT_EQ(DisplayEncoder::create(view("filmic-ish"), error), nullptr);
  EXPECT_NE(error.find("'filmic-ish'"), std::string::npos) << error;
  for (const std::string& name : builtin_view_names()) EXPECT_NE(error.find("'" + name + "'"), std::string::npos);
}

TEST(DisplayOcio, CourseCurvesIgnoreTheView) {
  DisplaySettings s = view("aces");
  s.transform = DisplayTransform::Linear;
  EXPECT_EQ(code(0.2f, s), 51);  // Path of Light: value x 255
  s.transform = DisplayTransform::CgrCourse;
  EXPECT_EQ(code(0.25f, s), 87);
}

// A config file with one display, two views and a look.
class OcioConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pt_ocio_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    config_ = std::string(PT_TEST_DATA_DIR) + "/data/ocio/two-views-one-look.ocio";
  }
  void TearDown() override { fs::remove_all(dir_); }

  DisplaySettings settings(const std::string& display, const std::string& view_name, const std::string& look = "") {
    DisplaySettings s;
    s.ocio_config = config_;
    s.display = display;
    s.view = view_name;
    s.look = look;
    return s;
  }

  fs::path dir_;
  std::string config_;
};

TEST_F(OcioConfig, DefaultDisplayAndViewComeFromTheConfig) {
  EXPECT_EQ(code(0.5f, settings("", "")), 188);  // Standard: sRGB-encoded
  EXPECT_EQ(code(0.18f, settings("sRGB", "Standard")), 118);
}

TEST_F(OcioConfig, ViewAndLookSelectFromTheConfig) {
  EXPECT_EQ(code(0.5f, settings("sRGB", "Raw")), 128);                // no encoding
  EXPECT_EQ(code(0.25f, settings("sRGB", "Raw", "brighter")), 128);   // x2 look, then raw
  EXPECT_EQ(code(0.25f, settings("sRGB", "Standard", "brighter")), 188);
}

TEST_F(OcioConfig, WrongNamesListWhatTheConfigHas) {
  std::string error;
  EXPECT_EQ(DisplayEncoder::create(settings("P3", ""), error), nullptr);
  EXPECT_NE(error.find("no display 'P3'"), std::string::npos) << error;
  EXPECT_NE(error.find("'sRGB'"), std::string::npos) << error;
  EXPECT_EQ(DisplayEncoder::create(settings("sRGB", "Filmic"), error), nullptr);
  EXPECT_NE(error.find("no view 'Filmic'"), std::string::npos) << error;
  EXPECT_NE(error.find("'Standard', 'Raw'"), std::string::npos) << error;
  EXPECT_EQ(DisplayEncoder::create(settings("sRGB", "Raw", "nosuchlook"), error), nullptr);
  EXPECT_NE(error.find("nosuchlook"), std::string::npos) << error;
}

TEST_F(OcioConfig, BadConfigFileIsAnErrorAndWritesNothing) {
  DisplaySettings s = settings("", "");
  s.ocio_config = (dir_ / "missing.ocio").string();
  Image img(2, 2);
  std::string error;
  EXPECT_FALSE(write_image((dir_ / "out.png").string(), img, s, error));
  EXPECT_NE(error.find("OpenColorIO"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

TEST_F(OcioConfig, JpegGoesThroughTheDisplayPipeline) {
  Image img(8, 8);
  for (RGB& p : img.pixels) p = RGB(0.18f);
  std::string error;
  ASSERT_TRUE(write_image((dir_ / "grey.jpg").string(), img, settings("sRGB", "Standard"), error)) << error;
  Image back;
  ASSERT_TRUE(read_image((dir_ / "grey.jpg").string(), back, error)) << error;
  EXPECT_NEAR(back.at(3, 3).g * 255.0f, 118.0f, 2.0f);  // JPEG is lossy: within 2 codes
}

}  // namespace
}  // namespace pt
