// Filter importance sampling (render/film/filter.h): the film offsets of the
// Gaussian and Mitchell filters are distributed as |f(x) f(y)| (chi-square),
// and each sample's weight carries the sign and the ratio f / pdf.
#include <cmath>

#include <gtest/gtest.h>

#include "chi2.h"
#include "render/film/filter.h"

namespace pt {
namespace {

TEST(FilterChi2, OffsetsFollowTheFilter) {
  // The offsets are drawn from a tabulation of |f(x) f(y)| (pdf()), and the
  // weight f / pdf makes the estimate exact; the tabulated density stays close
  // to |f| / integral |f|.
  for (PixelFilterType type : {PixelFilterType::Gaussian, PixelFilterType::Mitchell}) {
    const PixelFilter filter(type);
    const float r = filter.radius();
    const double norm = test::adaptive_simpson(
        [&](double x) { return std::fabs(filter.evaluate(static_cast<float>(x))); }, -r, r, 1e-9, 14);
    test::PlaneChi2 t;
    t.x0 = t.y0 = 0.5f - r;
    t.x1 = t.y1 = 0.5f + r;
    t.nx = t.ny = 24;
    t.sample = [&](Vec2f u, Vec2f& p) {
      const FilterSample s = filter.sample(u);
      p = s.offset;
      const float f = filter.evaluate(p.x - 0.5f) * filter.evaluate(p.y - 0.5f);
      const float pdf = filter.pdf(p);
      return pdf > 0.0f && std::fabs(s.weight - f / pdf) <= 1e-3f * std::fabs(f / pdf) + 1e-6f;
    };
    t.pdf = [&](Vec2f p) { return filter.pdf(p); };
    const auto result = t.run();
    EXPECT_TRUE(result.passed) << pixel_filter_name(type) << ": " << result.message;
    for (float x : {-0.7f * r, -0.2f, 0.0f, 0.3f, 0.6f * r}) {
      const float exact = static_cast<float>(std::fabs(filter.evaluate(x)) / norm);
      const float tabulated = filter.pdf(Vec2f(0.5f + x, 0.5f)) / filter.pdf(Vec2f(0.5f, 0.5f)) *
                              static_cast<float>(std::fabs(filter.evaluate(0.0f)) / norm);
      EXPECT_NEAR(tabulated, exact, 0.02f * static_cast<float>(std::fabs(filter.evaluate(0.0f)) / norm)) << x;
    }
  }
}

TEST(Filter, BoxIsTheIdentityOnThePixel) {
  const PixelFilter box(PixelFilterType::Box);
  const FilterSample s = box.sample(Vec2f(0.25f, 0.75f));
  EXPECT_EQ(s.offset, Vec2f(0.25f, 0.75f));
  EXPECT_EQ(s.weight, 1.0f);
}

TEST(Filter, EveryNameParsesBackToItsFilter) {
  // One table of names (kPixelFilterNames) serves the scene files, --filter,
  // the EXR header and the run record.
  for (PixelFilterType type : {PixelFilterType::Box, PixelFilterType::Gaussian, PixelFilterType::Mitchell}) {
    const std::optional<PixelFilterType> parsed = parse_pixel_filter(pixel_filter_name(type));
    ASSERT_TRUE(parsed.has_value()) << pixel_filter_name(type);
    EXPECT_EQ(*parsed, type);
  }
  EXPECT_STREQ(pixel_filter_name(PixelFilterType::Mitchell), "mitchell");
  EXPECT_FALSE(parse_pixel_filter("").has_value());
  EXPECT_FALSE(parse_pixel_filter("Gaussian").has_value());
}

}  // namespace
}  // namespace pt
