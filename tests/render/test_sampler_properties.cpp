// More sampler properties (docs/samplers.md), beside test_samplers.cpp: every
// aligned block of 2^m Sobol' samples is a net (progressive passes), uniform
// marginals for every sampler, integrands that couple two dimension pairs, and
// proof that the convergence checks fail for deliberately broken samplers
// (no scrambling, identical dimensions, no stratification).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "core/rng.h"
#include "render/samplers/low_discrepancy.h"
#include "render/samplers/sampler.h"
#include "sampler_slopes.h"

namespace pt {
namespace {

constexpr SamplerType kAllTypes[] = {SamplerType::Random, SamplerType::Jittered, SamplerType::Sobol};

// Dimension pair `dim` (0: the pixel area, k: the k-th get_2d) of samples [first, first + n) of pixel (x, y).
std::vector<Vec2f> pair_points(Sampler sampler, int x, int y, int first, int n, int dim) {
  std::vector<Vec2f> out;
  for (int i = first; i < first + n; ++i) {
    sampler.start_pixel_sample(x, y, i);
    Vec2f p = sampler.get_pixel_2d();
    for (int k = 1; k <= dim; ++k) p = sampler.get_2d();
    out.push_back(p);
  }
  return out;
}

// True if each elementary interval of area 1/n (every shape 2^k x 2^(m-k)) holds one point.
bool is_net(const std::vector<Vec2f>& p, int m) {
  const int n = 1 << m;
  for (int k = 0; k <= m; ++k) {
    const int nx = 1 << k, ny = 1 << (m - k);
    std::vector<int> count(static_cast<std::size_t>(n), 0);
    for (const Vec2f& q : p) ++count[static_cast<std::size_t>(static_cast<int>(q.y * ny) * nx + static_cast<int>(q.x * nx))];
    for (int c : count)
      if (c != 1) return false;
  }
  return true;
}

// Progressive rendering adds passes [k 2^m, (k+1) 2^m): each of them is a net
// too, not only the first (the index scramble maps aligned blocks to aligned blocks).
TEST(SobolSampler, EveryAlignedBlockIsANet) {
  const Sampler sampler = make_sampler(SamplerType::Sobol, 1, 9);
  for (int m : {2, 4, 6}) {
    for (int block = 1; block < 4; ++block)
      for (int dim = 0; dim < 4; ++dim)
        EXPECT_TRUE(is_net(pair_points(sampler, 7, 3, block << m, 1 << m, dim), m))
            << "m " << m << " block " << block << " dim " << dim;
  }
  // A block that is not aligned is not a net in general: the check can fail.
  int nets = 0;
  for (int dim = 0; dim < 8; ++dim) nets += is_net(pair_points(sampler, 7, 3, 3, 16, dim), 4);
  EXPECT_LT(nets, 8);
}

// The negative control of the stratification tests: independent samples are
// almost never one per cell (16 samples in 16 cells: probability 16!/16^16 = 1e-6).
TEST(Samplers, RandomIsNotStratified) {
  const Sampler sampler = make_sampler(SamplerType::Random, 16, 4);
  int stratified = 0;
  for (int pixel = 0; pixel < 64; ++pixel) stratified += is_net(pair_points(sampler, pixel, 0, 0, 16, 0), 4);
  EXPECT_EQ(stratified, 0);
}

// Every sampler's dimensions are uniform over many pixels: chi-square of 16 x 16
// bins of 64 pixels x 64 samples (255 degrees of freedom: mean 255, standard
// deviation 22.6; the bound is 5 standard deviations above the mean).
TEST(Samplers, MarginalsAreUniform) {
  for (SamplerType type : kAllTypes) {
    const Sampler sampler = make_sampler(type, 64, 21);
    for (int dim : {0, 2, 5}) {
      std::vector<int> bins(256, 0);
      for (int pixel = 0; pixel < 64; ++pixel)
        for (const Vec2f& q : pair_points(sampler, pixel, 1, 0, 64, dim))
          ++bins[static_cast<std::size_t>(static_cast<int>(q.y * 16) * 16 + static_cast<int>(q.x * 16))];
      double chi2 = 0.0;
      for (int c : bins) chi2 += (c - 16.0) * (c - 16.0) / 16.0;
      EXPECT_LT(chi2, 255 + 5 * 22.6) << sampler_type_name(type) << " dim " << dim;
    }
  }
}

// (x from dimension pair 1, y from dimension pair 2): the padded samplers pair
// the two at random, so the coupled part of the integrand converges at the
// random rate and the estimate stays unbiased; the slope is at least random's.
test::PointSet cross_points(SamplerType type) {
  return [type](int replica, int n) {
    const Sampler sampler = make_sampler(type, n, 77);
    const std::vector<Vec2f> a = pair_points(sampler, replica, 5, 0, n, 1);
    const std::vector<Vec2f> b = pair_points(sampler, replica, 5, 0, n, 2);
    std::vector<Vec2f> out;
    for (int i = 0; i < n; ++i) out.push_back({a[static_cast<std::size_t>(i)].x, b[static_cast<std::size_t>(i)].x});
    return out;
  };
}

// A jittered sampler with one permutation for every dimension: sample s is in
// stratum perm(s) of every dimension, so dimensions are correlated.
test::PointSet identical_dimensions() {
  return [](int replica, int n) {
    std::vector<Vec2f> out;
    Rng rng(static_cast<uint64_t>(replica) * 7919 + static_cast<uint64_t>(n));
    for (int s = 0; s < n; ++s) {
      const uint32_t cell = permutation_element(static_cast<uint32_t>(s), static_cast<uint32_t>(n), 1234 + replica);
      const float u = (static_cast<float>(cell) + rng.next_float()) / static_cast<float>(n);
      const float v = (static_cast<float>(cell) + rng.next_float()) / static_cast<float>(n);
      out.push_back({u, v});
    }
    return out;
  };
}

// The Sobol' (0,2)-sequence without any scrambling: every replica (pixel) gets
// the same points, so the error is one deterministic number, not a random one.
test::PointSet unscrambled_sobol() {
  return [](int, int n) {
    std::vector<Vec2f> out;
    for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i)
      out.push_back({fraction_to_float(sobol_dimension0(i)), fraction_to_float(sobol_dimension1(i))});
    return out;
  };
}

// A sampler whose samples of a pixel all repeat the first one.
test::PointSet frozen_random() {
  return [](int replica, int n) {
    Rng rng(static_cast<uint64_t>(replica) + 1);
    const Vec2f p{rng.next_float(), rng.next_float()};
    return std::vector<Vec2f>(static_cast<std::size_t>(n), p);
  };
}

TEST(Samplers, CoupledDimensionPairsConverge) {
  for (SamplerType type : kAllTypes) {
    const double g = test::rmse_slope(cross_points(type), test::gaussian, test::gaussian_integral());
    const double d = test::rmse_slope(cross_points(type), test::disk, test::disk_integral());
    std::printf("%s coupled pairs: gaussian %.3f disk %.3f\n", sampler_type_name(type), g, d);
    EXPECT_LT(g, test::kRandomBand.centre + test::kRandomBand.tolerance) << sampler_type_name(type);
    EXPECT_LT(d, test::kRandomBand.centre + test::kRandomBand.tolerance) << sampler_type_name(type);
  }
}

// The checks above and in test_samplers.cpp can fail: broken samplers land
// outside the bands. Identical dimensions are biased (the error stops falling:
// slope near 0); unscrambled Sobol' gives a deterministic error whose slope is
// not the scrambled net's; a sampler that repeats one sample does not converge.
TEST(Samplers, SlopeChecksRejectBrokenSamplers) {
  using test::rmse_slope;
  const double same_g = rmse_slope(identical_dimensions(), test::gaussian, test::gaussian_integral());
  const double same_d = rmse_slope(identical_dimensions(), test::disk, test::disk_integral());
  std::printf("identical dimensions: gaussian %.3f disk %.3f\n", same_g, same_d);
  EXPECT_GT(same_g, test::kRandomBand.centre + test::kRandomBand.tolerance);
  EXPECT_GT(same_d, test::kRandomBand.centre + test::kRandomBand.tolerance);

  const double plain_g = rmse_slope(unscrambled_sobol(), test::gaussian, test::gaussian_integral());
  const double plain_d = rmse_slope(unscrambled_sobol(), test::disk, test::disk_integral());
  std::printf("unscrambled sobol: gaussian %.3f disk %.3f\n", plain_g, plain_d);
  EXPECT_FALSE(test::kSobolSmoothBand.contains(plain_g)) << plain_g;  // measured -2.39
  EXPECT_FALSE(test::kSobolEdgeBand.contains(plain_d)) << plain_d;    // measured -1.50

  const double frozen = rmse_slope(frozen_random(), test::gaussian, test::gaussian_integral());
  EXPECT_FALSE(test::kRandomBand.contains(frozen)) << frozen;
}

}  // namespace
}  // namespace pt
