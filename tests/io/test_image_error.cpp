// The image error metrics (io/image_error.h) against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "io/image_error.h"

namespace pt {
namespace {

Image two_pixels(RGB a, RGB b) {
  Image image(2, 1);
  image.at(0, 0) = a;
  image.at(1, 0) = b;
  return image;
}

TEST(ImageError, HandComputedWholeFrame) {
  const Image test = two_pixels({0.5f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f});
  const Image ref = two_pixels({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 0.0f});
  ImageError e;
  std::string error;
  ASSERT_TRUE(compute_image_error(test, ref, std::nullopt, e, error)) << error;
  // Pixel 0: 3 * 0.25 = 0.75; pixel 1: 1. MSE = 1.75 / 2.
  EXPECT_EQ(e.pixels, 2);
  EXPECT_DOUBLE_EQ(e.mse, 0.875);
  EXPECT_DOUBLE_EQ(e.rmse, std::sqrt(0.875));
  // relMSE: (3 * 0.25 / 0.01 + 1 / 1.01) / 6.
  EXPECT_NEAR(e.rel_mse, (75.0 + 1.0 / 1.01) / 6.0, 1e-9);
}

TEST(ImageError, RectangleSelectsPixels) {
  const Image test = two_pixels({0.5f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f});
  const Image ref = two_pixels({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 0.0f});
  ImageError e;
  std::string error;
  ASSERT_TRUE(compute_image_error(test, ref, ImageRect{1, 0, 1, 1}, e, error)) << error;
  EXPECT_EQ(e.pixels, 1);
  EXPECT_DOUBLE_EQ(e.mse, 1.0);
  EXPECT_NEAR(e.rel_mse, 1.0 / 3.03, 1e-9);
}

TEST(ImageError, MseClampsToUnitRangeRelMseDoesNot) {
  const Image test = two_pixels({2.0f, -1.0f, 0.25f}, {0.0f, 0.0f, 0.0f});
  const Image ref = two_pixels({1.0f, 0.0f, 0.25f}, {0.0f, 0.0f, 0.0f});
  ImageError e;
  std::string error;
  ASSERT_TRUE(compute_image_error(test, ref, std::nullopt, e, error)) << error;
  EXPECT_DOUBLE_EQ(e.mse, 0.0);  // 2 -> 1 and -1 -> 0 after clamping
  EXPECT_NEAR(e.rel_mse, (1.0 / 1.01 + 1.0 / 0.01) / 6.0, 1e-9);
}

TEST(ImageError, IdenticalImagesHaveZeroError) {
  const Image a = two_pixels({0.3f, 0.7f, 5.0f}, {0.1f, 0.2f, 0.3f});
  ImageError e;
  std::string error;
  ASSERT_TRUE(compute_image_error(a, a, std::nullopt, e, error));
  EXPECT_EQ(e.mse, 0.0);
  EXPECT_EQ(e.rel_mse, 0.0);
  EXPECT_EQ(e.rmse, 0.0);
}

TEST(ImageError, RejectsSizeMismatchAndBadRectangles) {
  const Image a(2, 1), b(1, 2);
  ImageError e;
  std::string error;
  EXPECT_FALSE(compute_image_error(a, b, std::nullopt, e, error));
  EXPECT_NE(error.find("sizes differ"), std::string::npos) << error;
  for (const ImageRect& r : {ImageRect{0, 0, 3, 1}, ImageRect{1, 0, 2, 1}, ImageRect{0, 0, 0, 1},
                             ImageRect{-1, 0, 1, 1}, ImageRect{0, 1, 1, 1}}) {
    error.clear();
    EXPECT_FALSE(compute_image_error(a, a, r, e, error));
    EXPECT_NE(error.find("not inside"), std::string::npos) << error;
  }
}

TEST(ImageError, ParsesRectangles) {
  ImageRect r;
  ASSERT_TRUE(parse_image_rect("3,4,10,20", r));
  EXPECT_EQ(r.x, 3);
  EXPECT_EQ(r.y, 4);
  EXPECT_EQ(r.width, 10);
  EXPECT_EQ(r.height, 20);
  for (const char* bad : {"", "1,2,3", "1,2,3,4,5", "1,2,0,4", "-1,2,3,4", "a,b,c,d", "1, 2,3,4", "1,2,3,4x"})
    EXPECT_FALSE(parse_image_rect(bad, r)) << bad;
}

}  // namespace
}  // namespace pt
