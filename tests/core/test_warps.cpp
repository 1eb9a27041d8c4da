// The warps of core/sampling.h against their densities: chi-square tests
// (tests/render/chi2.h) and exact checks of the distributions.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "../render/chi2.h"
#include "core/sampling.h"

namespace pt {
namespace {

using test::DirectionChi2;
using test::PlaneChi2;

TEST(Warps, UniformHemisphere) {
  DirectionChi2 t;
  t.sample = [](float, Vec2f u, Vec3f& d) { d = sample_uniform_hemisphere(u); return true; };
  t.pdf = [](Vec3f d) { return d.z >= 0.0f ? uniform_hemisphere_pdf() : 0.0f; };
  const auto r = t.run();
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Warps, CosineHemisphere) {
  DirectionChi2 t;
  t.sample = [](float, Vec2f u, Vec3f& d) { d = sample_cosine_hemisphere(u); return true; };
  t.pdf = [](Vec3f d) { return cosine_hemisphere_pdf(d.z); };
  const auto r = t.run();
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Warps, UniformSphere) {
  DirectionChi2 t;
  t.sample = [](float, Vec2f u, Vec3f& d) { d = sample_uniform_sphere(u); return true; };
  t.pdf = [](Vec3f) { return uniform_sphere_pdf(); };
  const auto r = t.run();
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Warps, UniformCone) {
  for (float cos_max : {0.999f, 0.9f, 0.2f, -0.6f}) {
    const float omc = 1.0f - cos_max;
    DirectionChi2 t;
    t.sample = [&](float, Vec2f u, Vec3f& d) { d = sample_uniform_cone(u, omc); return true; };
    t.pdf = [&](Vec3f d) { return d.z >= cos_max ? uniform_cone_pdf(omc) : 0.0f; };
    if (cos_max > 0.99f) t.bins = test::frame_across({0, 0, 1});  // a narrow cone: bin it across
    const auto r = t.run();
    EXPECT_TRUE(r.passed) << "cos_max " << cos_max << ": " << r.message;
  }
}

TEST(Warps, ConcentricDisk) {
  PlaneChi2 t;
  t.x0 = t.y0 = -1.0f;
  t.sample = [](Vec2f u, Vec2f& p) { p = sample_uniform_disk_concentric(u); return true; };
  t.pdf = [](Vec2f p) { return p.x * p.x + p.y * p.y <= 1.0f ? uniform_disk_pdf() : 0.0f; };
  const auto r = t.run();
  EXPECT_TRUE(r.passed) << r.message;
}

// The concentric map's polynomial cos/sin agree with the library's to float
// precision: Shirley-Chiu's map evaluated with std::cos/std::sin in double.
TEST(Warps, ConcentricDiskMatchesTheExactMap) {
  double worst = 0;
  for (int i = 0; i <= 256; ++i) {
    for (int j = 0; j <= 256; ++j) {
      const Vec2f u(std::min(i / 256.0f, 0x1.fffffep-1f), std::min(j / 256.0f, 0x1.fffffep-1f));
      const double a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
      double x = 0, y = 0;
      if (std::fabs(a) > std::fabs(b)) {
        x = a * std::cos(M_PI / 4 * (b / a));
        y = a * std::sin(M_PI / 4 * (b / a));
      } else if (b != 0.0) {
        x = b * std::cos(M_PI / 2 - M_PI / 4 * (a / b));
        y = b * std::sin(M_PI / 2 - M_PI / 4 * (a / b));
      }
      const Vec2f p = sample_uniform_disk_concentric(u);
      worst = std::max({worst, std::fabs(p.x - x), std::fabs(p.y - y)});
    }
  }
  EXPECT_LT(worst, 3e-7);
}

TEST(Warps, UniformTriangle) {
  // The triangle (0,0), (1,0), (0.3,1): area 0.5.
  const Vec2f a(0, 0), b(1, 0), c(0.3f, 1);
  PlaneChi2 t;
  t.sample = [&](Vec2f u, Vec2f& p) {
    const Vec3f w = sample_uniform_triangle(u);
    p = a * w.x + b * w.y + c * w.z;
    return w.x >= 0 && w.y >= 0 && w.z >= -1e-6f;
  };
  t.pdf = [&](Vec2f p) {
    // Inside if on the left of every edge (counter-clockwise).
    auto side = [](Vec2f o, Vec2f e, Vec2f q) { return (e.x - o.x) * (q.y - o.y) - (e.y - o.y) * (q.x - o.x); };
    return side(a, b, p) >= 0 && side(b, c, p) >= 0 && side(c, a, p) >= 0 ? 2.0f : 0.0f;
  };
  const auto r = t.run();
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Warps, Distribution2D) {
  // A lumpy 7 x 5 function with a zero cell.
  const int nu = 7, nv = 5;
  std::vector<float> f(nu * nv);
  for (int v = 0; v < nv; ++v)
    for (int u = 0; u < nu; ++u) f[v * nu + u] = 0.2f + static_cast<float>((u * 3 + v * 5) % 7);
  f[2 * nu + 3] = 0.0f;
  const Distribution2D dist(f, nu, nv);
  PlaneChi2 t;
  t.nx = 28;
  t.ny = 20;
  t.sample = [&](Vec2f u, Vec2f& p) {
    float pdf = 0.0f;
    p = dist.sample(u, &pdf);
    return std::fabs(pdf - dist.pdf(p)) <= 1e-4f * pdf;  // the returned pdf is the density at p
  };
  t.pdf = [&](Vec2f p) { return dist.pdf(p); };
  const auto r = t.run();
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Warps, Distribution1DDiscreteAndContinuous) {
  const std::vector<float> f = {1, 0, 3, 0.5f, 0};
  const Distribution1D d(f);
  EXPECT_FLOAT_EQ(d.integral(), 4.5f / 5.0f);
  EXPECT_FLOAT_EQ(d.pmf(0), 1.0f / 4.5f);
  EXPECT_FLOAT_EQ(d.pmf(1), 0.0f);
  EXPECT_FLOAT_EQ(d.pmf(2), 3.0f / 4.5f);
  std::vector<double> observed(f.size(), 0.0), expected(f.size(), 0.0);
  Rng rng(3);
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    float pmf = 0.0f;
    const std::size_t k = d.sample_discrete(rng.next_float(), &pmf);
    ASSERT_LT(k, f.size());
    ASSERT_FLOAT_EQ(pmf, d.pmf(k));
    observed[k] += 1.0;
  }
  for (std::size_t k = 0; k < f.size(); ++k) expected[k] = n * d.pmf(k);
  const auto r = test::chi2_gof(observed, expected);
  EXPECT_TRUE(r.passed) << r.message;
  // Continuous samples land in cells of non-zero value and carry their density.
  for (int i = 0; i < 1000; ++i) {
    float pdf = 0.0f;
    std::size_t cell = 0;
    const float x = d.sample_continuous(rng.next_float(), &pdf, &cell);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    ASSERT_GT(f[cell], 0.0f);
    ASSERT_FLOAT_EQ(pdf, d.pdf(x));
  }
}

// Distribution1D inverts its CDF. Swept over a fine grid of u in order, the
// sample never moves backwards, never lands in a zero cell, and each cell
// receives a share of the grid equal to its probability (to the grid's step and
// the CDF's float rounding): a search that picked a neighbouring cell would
// break all three. The function has long runs of zeros, a spike holding most of
// the mass (a sun in a sky) and many tiny cells.
TEST(Warps, Distribution1DInversionIsMonotoneAndExact) {
  for (const std::size_t n : {std::size_t{1}, std::size_t{3}, std::size_t{7}, std::size_t{64}, std::size_t{1000},
                              std::size_t{1024}}) {
    std::vector<float> f(n);
    Rng rng(static_cast<uint64_t>(n));
    for (std::size_t i = 0; i < n; ++i) f[i] = (i % 7 == 3) ? 0.0f : 1e-4f * rng.next_float();
    for (std::size_t i = n / 3; i < n / 2; ++i) f[i] = 0.0f;
    f[(2 * n) / 3] = static_cast<float>(n);  // the spike
    const Distribution1D d(f);
    const int grid = 1 << 20;
    std::vector<int> hits(n, 0);
    float last = 0.0f;
    for (int g = 0; g < grid; ++g) {
      const float u = (static_cast<float>(g) + 0.5f) / static_cast<float>(grid);
      float pdf = 0.0f;
      std::size_t cell = 0;
      const float x = d.sample_continuous(u, &pdf, &cell);
      ASSERT_GE(x, last) << "n " << n << ", u " << u;
      ASSERT_GT(f[cell], 0.0f) << "n " << n << ", u " << u;
      // x lies in its cell (at its far end when u rounds onto the next cell's CDF).
      ASSERT_LE(static_cast<float>(cell), x * static_cast<float>(n));
      ASSERT_GE(static_cast<float>(cell + 1), x * static_cast<float>(n));
      ASSERT_EQ(cell, d.sample_discrete(u));
      last = x;
      ++hits[cell];
    }
    for (std::size_t i = 0; i < n; ++i)
      EXPECT_NEAR(hits[i] / static_cast<double>(grid), d.pmf(i), 2.0 / grid + 1e-6) << "n " << n << ", cell " << i;
    // The ends of u's range, and what lies outside it, still find a cell.
    EXPECT_LT(d.sample_discrete(0.0f), n);
    EXPECT_LT(d.sample_discrete(kOneMinusEpsilon), n);
    EXPECT_GT(f[d.sample_discrete(kOneMinusEpsilon)], 0.0f);
    EXPECT_LT(d.sample_discrete(1.0f), n);
    EXPECT_LT(d.sample_discrete(std::nanf("")), n);
  }
}

TEST(Warps, AllZeroDistributionIsUniform) {
  const Distribution1D d(std::vector<float>{0, 0, 0, 0});
  EXPECT_FLOAT_EQ(d.pmf(2), 0.25f);
  float pdf = 0.0f;
  const float x = d.sample_continuous(0.6f, &pdf);
  EXPECT_NEAR(x, 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(pdf, 1.0f);
}

TEST(Warps, PowerHeuristic) {
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(3.0f, 1.0f), 0.9f);
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(power_heuristic(0.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(kInfinity, 5.0f), 1.0f);
}

TEST(Warps, BalanceHeuristic) {
  EXPECT_FLOAT_EQ(balance_heuristic(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(balance_heuristic(3.0f, 1.0f), 0.75f);
  EXPECT_FLOAT_EQ(balance_heuristic(1.0f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(balance_heuristic(0.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(balance_heuristic(0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(balance_heuristic(kInfinity, 5.0f), 1.0f);
}

TEST(Warps, HarnessRejectsAWrongDensity) {
  // The harness must be able to fail: cosine-weighted samples against the
  // uniform hemisphere density, and uniform samples outside the claimed support.
  DirectionChi2 t;
  t.samples = 200000;
  t.sample = [](float, Vec2f u, Vec3f& d) { d = sample_cosine_hemisphere(u); return true; };
  t.pdf = [](Vec3f d) { return d.z >= 0.0f ? uniform_hemisphere_pdf() : 0.0f; };
  EXPECT_FALSE(t.run().passed);
  t.sample = [](float, Vec2f u, Vec3f& d) { d = sample_uniform_sphere(u); return true; };
  EXPECT_FALSE(t.run().passed);
  // A 1% error in a cone's density is caught with a million samples.
  t.samples = 1000000;
  t.sample = [](float, Vec2f u, Vec3f& d) { d = sample_uniform_cone(u, 0.5f); return true; };
  t.pdf = [](Vec3f d) { return d.z >= 0.5f ? uniform_cone_pdf(0.5f * 1.02f) : 0.0f; };
  EXPECT_FALSE(t.run().passed);
}

}  // namespace
}  // namespace pt
