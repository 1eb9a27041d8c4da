// The samplers (docs/samplers.md): determinism, stratification of every
// dimension (jittered strata, the (0,m,2)-net property of the Sobol' sampler
// at powers of two), decorrelation across dimensions and pixels, and the
// convergence rate of 2D integrals of a smooth and a discontinuous integrand.
#include <gtest/gtest.h>

#include <cmath>
#include <array>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "path_test_util.h"
#include "render/samplers/low_discrepancy.h"
#include "render/samplers/sampler.h"
#include "sampler_slopes.h"

namespace pt {
namespace {

constexpr SamplerType kAllTypes[] = {SamplerType::Random, SamplerType::Jittered, SamplerType::Sobol};

// The 2D points of one dimension of the samples [0, n) of pixel (x, y):
// dimension 0 is the pixel area, dimension k >= 1 the k-th get_2d().
std::vector<Vec2f> points(Sampler sampler, int x, int y, int n, int dimension) {
  std::vector<Vec2f> out;
  for (int i = 0; i < n; ++i) {
    sampler.start_pixel_sample(x, y, i);
    Vec2f p = sampler.get_pixel_2d();
    for (int k = 1; k <= dimension; ++k) p = sampler.get_2d();
    out.push_back(p);
  }
  return out;
}

std::vector<float> points_1d(Sampler sampler, int x, int y, int n, int dimension) {
  std::vector<float> out;
  for (int i = 0; i < n; ++i) {
    sampler.start_pixel_sample(x, y, i);
    float u = 0.0f;
    for (int k = 1; k <= dimension; ++k) u = sampler.get_1d();
    out.push_back(u);
  }
  return out;
}

TEST(LowDiscrepancy, SobolDimension1MatchesKnownPoints) {
  // Sobol' dimension 1 (x + 1, m_1 = 1) in index order (not Gray-code order):
  // direction numbers 1/2, 3/4, 5/8, so point 2 = 3/4, point 3 = 1/2 xor 3/4 = 1/4, ...
  const double expected[] = {0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(sobol_dimension1(i) * 0x1.0p-32, expected[i]) << i;
  const double vdc[] = {0.0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(sobol_dimension0(i) * 0x1.0p-32, vdc[i]) << i;
}

TEST(LowDiscrepancy, SobolByteTablesMatchTheMatrixProduct) {
  const std::array<uint32_t, 32> matrix = sobol_dimension1_matrix();
  Rng rng(17);
  for (int n = 0; n < 1000; ++n) {
    const uint32_t index = static_cast<uint32_t>(rng.next_u64());
    uint32_t x = 0;
    for (int k = 0; k < 32; ++k)
      if ((index >> k) & 1u) x ^= matrix[static_cast<std::size_t>(k)];
    ASSERT_EQ(sobol_dimension1(index), x) << index;
  }
}

// Owen scrambling keeps a (0,m,2)-net a net, and the nested scramble of the
// index maps [0, 2^m) onto an aligned block of 2^m indices.
TEST(LowDiscrepancy, IndexScrambleMapsPrefixesOntoAlignedBlocks) {
  for (uint32_t seed : {1u, 0xdeadbeefu, 12345u}) {
    for (int m = 0; m <= 10; ++m) {
      const uint32_t block = owen_scramble(0, seed) >> m;
      for (uint32_t i = 0; i < (1u << m); ++i) ASSERT_EQ(owen_scramble(i, seed) >> m, block) << m;
    }
  }
}

TEST(LowDiscrepancy, PermutationIsABijectionForAnySize) {
  for (uint32_t n : {1u, 2u, 3u, 7u, 12u, 16u, 100u, 257u}) {
    for (uint64_t key : {0ull, 1ull, 0x123456789abcdefull}) {
      std::vector<int> seen(n, 0);
      for (uint32_t i = 0; i < n; ++i) {
        const uint32_t p = permutation_element(i, n, key);
        ASSERT_LT(p, n);
        ++seen[p];
      }
      for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "n " << n << " value " << i;
    }
  }
  // Different keys give different permutations.
  int differ = 0;
  for (uint32_t i = 0; i < 64; ++i) differ += permutation_element(i, 64, 1) != permutation_element(i, 64, 2);
  EXPECT_GT(differ, 32);
}

TEST(Samplers, DeterministicAndInUnitSquare) {
  for (SamplerType type : kAllTypes) {
    const Sampler a = make_sampler(type, 16, 7);
    for (int dim = 0; dim < 6; ++dim) {
      const std::vector<Vec2f> p = points(a, 3, 5, 40, dim);
      const std::vector<Vec2f> q = points(make_sampler(type, 16, 7), 3, 5, 40, dim);
      const std::vector<Vec2f> other_seed = points(make_sampler(type, 16, 8), 3, 5, 40, dim);
      const std::vector<Vec2f> other_pixel = points(a, 4, 5, 40, dim);
      int same_seed = 0, same_pixel = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        EXPECT_EQ(p[i].x, q[i].x);
        EXPECT_EQ(p[i].y, q[i].y);
        EXPECT_GE(p[i].x, 0.0f);
        EXPECT_LT(p[i].x, 1.0f);
        EXPECT_GE(p[i].y, 0.0f);
        EXPECT_LT(p[i].y, 1.0f);
        same_seed += p[i].x == other_seed[i].x;
        same_pixel += p[i].x == other_pixel[i].x;
      }
      EXPECT_LT(same_seed, 3) << sampler_type_name(type) << " dim " << dim;
      EXPECT_LT(same_pixel, 3) << sampler_type_name(type) << " dim " << dim;
    }
  }
}

TEST(Samplers, ParseNames) {
  for (const std::string& name : sampler_type_names()) {
    const auto type = parse_sampler_type(name);
    ASSERT_TRUE(type.has_value()) << name;
    EXPECT_EQ(name, sampler_type_name(*type));
  }
  EXPECT_FALSE(parse_sampler_type("halton").has_value());
}

TEST(JitteredSampler, GridIsClosestToSquare) {
  int a = 0, b = 0;
  JitteredSampler::grid_for(16, a, b);
  EXPECT_EQ(a * 100 + b, 404);
  JitteredSampler::grid_for(12, a, b);
  EXPECT_EQ(a * 100 + b, 304);
  JitteredSampler::grid_for(7, a, b);
  EXPECT_EQ(a * 100 + b, 107);
  JitteredSampler::grid_for(1, a, b);
  EXPECT_EQ(a * 100 + b, 101);
}

// Every cell of the a x b grid of every 2D dimension, and every 1D stratum,
// holds exactly one of the spp samples, in each pass of spp samples.
TEST(JitteredSampler, EveryDimensionIsStratified) {
  for (int spp : {4, 7, 12, 16, 30}) {
    int a = 0, b = 0;
    JitteredSampler::grid_for(spp, a, b);
    const Sampler sampler = make_sampler(SamplerType::Jittered, spp, 11);
    for (int pixel = 0; pixel < 3; ++pixel) {
      for (int dim = 0; dim < 5; ++dim) {
        const std::vector<Vec2f> p = points(sampler, pixel, 2 * pixel, 2 * spp, dim);
        for (int pass = 0; pass < 2; ++pass) {
          std::vector<int> count(static_cast<std::size_t>(spp), 0);
          for (int i = 0; i < spp; ++i) {
            const Vec2f q = p[static_cast<std::size_t>(pass * spp + i)];
            const int cx = static_cast<int>(q.x * a), cy = static_cast<int>(q.y * b);
            ++count[static_cast<std::size_t>(cy * a + cx)];
          }
          for (int c = 0; c < spp; ++c)
            EXPECT_EQ(count[static_cast<std::size_t>(c)], 1) << "spp " << spp << " dim " << dim << " cell " << c;
        }
        const std::vector<float> u = points_1d(sampler, pixel, 0, spp, dim + 1);
        std::vector<int> strata(static_cast<std::size_t>(spp), 0);
        for (float v : u) ++strata[static_cast<std::size_t>(v * spp)];
        for (int c = 0; c < spp; ++c) EXPECT_EQ(strata[static_cast<std::size_t>(c)], 1) << "1D spp " << spp;
      }
    }
  }
}

// The first 2^m samples of every dimension pair form a (0,m,2)-net: each
// elementary interval [i/2^k, (i+1)/2^k) x [j/2^(m-k), (j+1)/2^(m-k)) holds one.
TEST(SobolSampler, ElementaryIntervalsAtPowersOfTwo) {
  const Sampler sampler = make_sampler(SamplerType::Sobol, 1, 3);
  for (int m = 0; m <= 8; ++m) {
    const int n = 1 << m;
    for (int pixel = 0; pixel < 3; ++pixel) {
      for (int dim = 0; dim < 6; ++dim) {
        const std::vector<Vec2f> p = points(sampler, 5 * pixel, pixel, n, dim);
        for (int k = 0; k <= m; ++k) {
          const int nx = 1 << k, ny = 1 << (m - k);
          std::vector<int> count(static_cast<std::size_t>(n), 0);
          for (const Vec2f& q : p)
            ++count[static_cast<std::size_t>(static_cast<int>(q.y * ny) * nx + static_cast<int>(q.x * nx))];
          for (int c = 0; c < n; ++c)
            ASSERT_EQ(count[static_cast<std::size_t>(c)], 1)
                << "m " << m << " shape " << nx << "x" << ny << " dim " << dim << " pixel " << pixel;
        }
        const std::vector<float> u = points_1d(sampler, pixel, 1, n, dim + 1);
        std::vector<int> strata(static_cast<std::size_t>(n), 0);
        for (float v : u) ++strata[static_cast<std::size_t>(v * n)];
        for (int c = 0; c < n; ++c) ASSERT_EQ(strata[static_cast<std::size_t>(c)], 1) << "1D m " << m;
      }
    }
  }
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// Dimensions of one sample, and the same dimension of neighbouring pixels, are
// uncorrelated: 4096 pairs, so |r| has a standard deviation of about 1/64;
// an unshuffled stratified sampler (same stratum in every dimension) gives r near 1.
TEST(Samplers, DimensionsAndPixelsAreDecorrelated) {
  constexpr int kSpp = 16, kPixels = 256;
  for (SamplerType type : kAllTypes) {
    Sampler sampler = make_sampler(type, kSpp, 5);
    std::vector<double> pixel_x, lens_x, light_u, next_pixel_x;
    for (int p = 0; p < kPixels; ++p) {
      for (int i = 0; i < kSpp; ++i) {
        sampler.start_pixel_sample(p, 0, i);
        pixel_x.push_back(sampler.get_pixel_2d().x);
        lens_x.push_back(sampler.get_2d().x);
        light_u.push_back(sampler.get_1d());
        sampler.start_pixel_sample(p, 1, i);
        next_pixel_x.push_back(sampler.get_pixel_2d().x);
      }
    }
    EXPECT_LT(std::abs(correlation(pixel_x, lens_x)), 0.07) << sampler_type_name(type);
    EXPECT_LT(std::abs(correlation(lens_x, light_u)), 0.07) << sampler_type_name(type);
    EXPECT_LT(std::abs(correlation(pixel_x, next_pixel_x)), 0.07) << sampler_type_name(type);
  }
}

// The points of dimension `dimension` of pixel (replica, 0): pixels are independent replicas.
test::PointSet sampler_points(SamplerType type, int dimension) {
  return [type, dimension](int replica, int n) { return points(make_sampler(type, n, 2024), replica, 0, n, dimension); };
}

// Slopes of the RMSE of a smooth and a discontinuous 2D integral, in the
// pixel pair and in dimension pair 3, inside the bands of sampler_slopes.h.
// Measured with these seeds: random -0.54/-0.49, jittered -1.00/-0.78,
// Sobol' -1.34/-0.79.
TEST(Samplers, ConvergenceSlopesOnAnalyticIntegrands) {
  using test::rmse_slope;
  for (int dim : {0, 3}) {
    const double rg = rmse_slope(sampler_points(SamplerType::Random, dim), test::gaussian, test::gaussian_integral());
    const double rd = rmse_slope(sampler_points(SamplerType::Random, dim), test::disk, test::disk_integral());
    EXPECT_TRUE(test::kRandomBand.contains(rg)) << "random gaussian dim " << dim << ": " << rg;
    EXPECT_TRUE(test::kRandomBand.contains(rd)) << "random disk dim " << dim << ": " << rd;
    const double jg = rmse_slope(sampler_points(SamplerType::Jittered, dim), test::gaussian, test::gaussian_integral());
    const double jd = rmse_slope(sampler_points(SamplerType::Jittered, dim), test::disk, test::disk_integral());
    EXPECT_TRUE(test::kJitteredSmoothBand.contains(jg)) << "jittered gaussian dim " << dim << ": " << jg;
    EXPECT_TRUE(test::kJitteredEdgeBand.contains(jd)) << "jittered disk dim " << dim << ": " << jd;
    const double sg = rmse_slope(sampler_points(SamplerType::Sobol, dim), test::gaussian, test::gaussian_integral());
    const double sd = rmse_slope(sampler_points(SamplerType::Sobol, dim), test::disk, test::disk_integral());
    EXPECT_TRUE(test::kSobolSmoothBand.contains(sg)) << "sobol gaussian dim " << dim << ": " << sg;
    EXPECT_TRUE(test::kSobolEdgeBand.contains(sd)) << "sobol disk dim " << dim << ": " << sd;
    std::printf("slopes dim %d: random %.3f %.3f jittered %.3f %.3f sobol %.3f %.3f\n", dim, rg, rd, jg, jd, sg, sd);
  }
}

// ------------------------------------------------- the path integrator's use
// A floor lit by a small spherical emitter (soft shadow of a sphere) and the
// background: direct and one-bounce light, a few seconds at most.
SceneDescription soft_shadow_scene() {
  SceneDescription d = test::empty_scene(16, 12, {0.0f, 1.5f, 4.0f}, {0, 0.3f, 0}, {0, 1, 0}, 40);
  d.render.background = RGB(0.2f);
  MaterialDesc lambert;
  lambert.type = MaterialType::Lambert;
  lambert.diffuse = RGB(0.7f);
  Quad floor;
  floor.v[0] = Vec3f(-3, 0, -3);
  floor.v[1] = Vec3f(-3, 0, 3);
  floor.v[2] = Vec3f(3, 0, 3);
  floor.v[3] = Vec3f(3, 0, -3);
  const int m = test::add_material(d, lambert);
  test::add_shape(d, floor, m);
  test::add_sphere(d, {0.0f, 0.5f, 0.0f}, 0.5f, m);
  test::add_sphere(d, {0.6f, 2.0f, 0.8f}, 0.4f, test::add_material(d, test::emitter_material(RGB(8.0f))));
  return d;
}

double mse(const Image& a, const Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) sum += (a.pixels[i][c] - b.pixels[i][c]) * (a.pixels[i][c] - b.pixels[i][c]);
  return sum / static_cast<double>(a.pixels.size());
}

// Every sampler renders the same image in expectation, and the stratified ones
// with less error at equal sample count. The image mean of the random sampler
// has a standard deviation of about 0.0045 at 64 spp (from its measured
// per-pixel MSE), so about 0.0016 at 512 spp, and the 2048-spp reference's
// about 0.0008: the means must agree within 3% of the reference (0.008, over
// 4 sigma). Measured MSE ratios to random at 16 spp: jittered 0.16, Sobol'
// 0.11; required below 0.5.
TEST(SamplersInPathIntegrator, UnbiasedAndLessNoisyThanRandom) {
  const SceneDescription d = soft_shadow_scene();
  IntegratorSettings ref_settings = test::path_settings(2048, 3, 99);
  const Image reference = test::render_path(d, ref_settings);
  ASSERT_FALSE(reference.pixels.empty());
  const double ref_mean = test::image_stats(reference).mean;
  auto render = [&](SamplerType type, int spp, uint64_t seed) {
    IntegratorSettings s = test::path_settings(spp, 3, seed);
    s.sampler = type;
    return test::render_path(d, s);
  };
  double random_mse = 0.0;
  for (SamplerType type : kAllTypes) {
    const double mean = test::image_stats(render(type, 512, 1)).mean;
    EXPECT_NEAR(mean, ref_mean, 0.03 * ref_mean) << sampler_type_name(type);
    double error = 0.0;
    for (uint64_t seed : {1u, 2u, 3u, 4u}) error += mse(render(type, 16, seed), reference) / 4;
    std::printf("%s: mean %.4f (reference %.4f), MSE at 16 spp %.3g\n", sampler_type_name(type), mean, ref_mean, error);
    if (type == SamplerType::Random) random_mse = error;
    else EXPECT_LT(error, 0.5 * random_mse) << sampler_type_name(type);
  }
}

// The image does not depend on the thread count or the tile size.
TEST(SamplersInPathIntegrator, DeterministicForAnyThreadCount) {
  const SceneDescription d = soft_shadow_scene();
  for (SamplerType type : {SamplerType::Jittered, SamplerType::Sobol}) {
    IntegratorSettings s = test::path_settings(6, 3, 5);
    s.sampler = type;
    const Image a = test::render_path(d, s, 1);
    s.tile_size = 5;
    const Image b = test::render_path(d, s, 3);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(a.pixels[i][c], b.pixels[i][c]) << sampler_type_name(type);
  }
}

}  // namespace
}  // namespace pt
