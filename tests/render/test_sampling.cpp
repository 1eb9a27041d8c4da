#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "core/rng.h"
#include "render/integrators/render_loop.h"

namespace pt {
namespace {

TEST(Sampling, OneSampleIsThePixelCentre) {
  const Vec2f p = sample_position(7, 3, 0, 1, 1234, 99);
  EXPECT_EQ(p, Vec2f(7.5f, 3.5f));
}

TEST(Sampling, SquareCountsAreStratified) {
  const int spp = 16, n = 4;
  std::set<std::pair<int, int>> cells;
  for (int s = 0; s < spp; ++s) {
    const Vec2f p = sample_position(10, 20, s, spp, 7, 12345);
    ASSERT_GE(p.x, 10.0f);
    ASSERT_LT(p.x, 11.0f);
    ASSERT_GE(p.y, 20.0f);
    ASSERT_LT(p.y, 21.0f);
    cells.insert({static_cast<int>((p.x - 10.0f) * n), static_cast<int>((p.y - 20.0f) * n)});
  }
  EXPECT_EQ(cells.size(), 16u);  // one sample in every cell
}

// Progressive passes of n = 4 samples (docs/cli.md): sample i is sample
// i mod n of pass i / n, and every pass is stratified on its own, inside the
// pixel (samples 4..7 used to land in the rows below it: cell i / 2 >= 2).
TEST(Sampling, EveryPassIsStratifiedInsideThePixel) {
  const int n = 4, k = 2;
  for (int pass = 0; pass < 3; ++pass) {
    std::set<std::pair<int, int>> cells;
    for (int s = pass * n; s < (pass + 1) * n; ++s) {
      const Vec2f p = sample_position(10, 20, s, n, 7, 12345);
      ASSERT_GE(p.x, 10.0f) << s;
      ASSERT_LT(p.x, 11.0f) << s;
      ASSERT_GE(p.y, 20.0f) << s;
      ASSERT_LT(p.y, 21.0f) << s;
      cells.insert({static_cast<int>((p.x - 10.0f) * k), static_cast<int>((p.y - 20.0f) * k)});
    }
    EXPECT_EQ(cells.size(), 4u) << "pass " << pass;
  }
  // Later passes jitter differently from the first.
  EXPECT_FALSE(sample_position(10, 20, 0, n, 7, 12345) == sample_position(10, 20, n, n, 7, 12345));
}

TEST(Sampling, OtherCountsStayInThePixelAndDiffer) {
  std::set<std::pair<float, float>> seen;
  for (int s = 0; s < 5; ++s) {
    const Vec2f p = sample_position(0, 0, s, 5, 1, 0);
    EXPECT_GE(p.x, 0.0f);
    EXPECT_LT(p.x, 1.0f);
    EXPECT_GE(p.y, 0.0f);
    EXPECT_LT(p.y, 1.0f);
    seen.insert({p.x, p.y});
  }
  EXPECT_EQ(seen.size(), 5u);
}

TEST(Sampling, DependsOnlyOnSeedPixelAndIndex) {
  EXPECT_EQ(sample_position(3, 4, 2, 5, 42, 1000), sample_position(3, 4, 2, 5, 42, 1000));
  EXPECT_FALSE(sample_position(3, 4, 2, 5, 42, 1000) == sample_position(3, 4, 2, 5, 43, 1000));
  EXPECT_FALSE(sample_position(3, 4, 2, 5, 42, 1000) == sample_position(3, 4, 3, 5, 42, 1000));
}

TEST(Rng, UniformInUnitInterval) {
  Rng rng(hash_keys(1, 2, 3));
  double sum = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_float();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);  // 5 sigma of the mean is ~0.0046
}

TEST(Rng, KeysAreOrderSensitive) {
  EXPECT_NE(hash_keys(1, 2), hash_keys(2, 1));
  EXPECT_NE(hash_keys(0, 0, 1), hash_keys(0, 1, 0));
}

}  // namespace
}  // namespace pt
