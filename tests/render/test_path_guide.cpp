// The path guide (render/guiding/path_guide.h): its direction tree's square
// map is equal-area, the tree's density integrates to one and its samples
// follow it, a leaf's density integrates to one and its samples follow
// it, the mixture's bounces are an unbiased L/pdf estimator of the BSDF's
// albedo, it is a function of the seed alone (the same for any thread count),
// and a closed box that both emits and reflects renders its closed-form
// radiance with it. That guided and plain renders converge to the same image:
// PathAgreement.PathGuiding* (test_path_agreement.cpp).
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "core/rng.h"
#include "bsdf_test_util.h"
#include "light_guide_scenes.h"
#include "path_test_util.h"
#include "render/guiding/path_guide.h"
#include "render/render_scene.h"

namespace pt {
namespace {

using Learned = test::Learned<PathGuide>;

Learned learn(const SceneDescription& d, int threads, int paths_per_pixel = 8, uint64_t seed = 1) {
  return test::learn_guide<PathGuide>(d, threads, paths_per_pixel, seed);
}

using test::courtyard_point;
// Points on its floor (normal +y), lit mostly by the walls.
Vec3f floor_point(Rng& rng) { return Vec3f(rng.next_float() * 3.8f - 1.9f, 0.001f, rng.next_float() * 3.8f - 1.9f); }
const Vec3f kUp(0, 1, 0);

// The probability of each of the k x k equal cells of DirectionTree's square
// under `density` (a direction's density per solid angle), exactly for a
// tree: its finest cells are 1/2^kMaxDepth of the square on a side, and the
// density is constant over each.
template <class Density>
std::vector<double> cell_probabilities(int k, const Density& density) {
  constexpr int kFine = 1 << DirectionTree::kMaxDepth;
  std::vector<double> p(static_cast<std::size_t>(k * k), 0.0);
  const double area = 4.0 * kPi / (static_cast<double>(kFine) * kFine);
  for (int i = 0; i < kFine; ++i)
    for (int j = 0; j < kFine; ++j) {
      const Vec2f s((static_cast<float>(i) + 0.5f) / kFine, (static_cast<float>(j) + 0.5f) / kFine);
      p[static_cast<std::size_t>(i * k / kFine * k + j * k / kFine)] += density(DirectionTree::from_square(s)) * area;
    }
  return p;
}

int cell_of(Vec3f w, int k) {
  const Vec2f s = DirectionTree::to_square(w);
  return static_cast<int>(s.x * static_cast<float>(k)) * k + static_cast<int>(s.y * static_cast<float>(k));
}

// A tree from points clustered around two directions (and a few spread):
// deep where the value is.
DirectionTree clustered_tree(Rng& rng) {
  std::vector<DirectionTree::Point> points;
  for (int i = 0; i < 20000; ++i) {
    const float r = rng.next_float();
    Vec2f s(rng.next_float(), rng.next_float());
    float value = 0.1f;
    if (r < 0.5f) {
      s = Vec2f(0.8f + 0.01f * rng.next_float(), 0.3f + 0.02f * rng.next_float());
      value = 2.0f;
    } else if (r < 0.8f) {
      s = Vec2f(0.55f + 0.1f * rng.next_float(), 0.7f + 0.05f * rng.next_float());
      value = 1.0f;
    }
    points.push_back({s, value});
  }
  DirectionTree tree;
  tree.build(points.data(), points.size(), 0.01f, 16);
  return tree;
}

TEST(DirectionTree, TheSquareMapIsEqualAreaAndInvertible) {
  Rng rng(3);
  for (int k = 0; k < 20000; ++k) {
    const Vec3f w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    const Vec2f s = DirectionTree::to_square(w);
    ASSERT_GE(s.x, 0.0f);
    ASSERT_LT(s.x, 1.0f);
    ASSERT_GE(s.y, 0.0f);
    ASSERT_LT(s.y, 1.0f);
    const Vec3f back = DirectionTree::from_square(s);
    ASSERT_NEAR(length(back - w), 0.0f, 1e-3f) << k;
  }
  // Uniform directions fall into the square's 8 x 8 cells equally often (5 standard deviations).
  constexpr int k = 8;
  std::vector<int> count(k * k, 0);
  const int n = 200000;
  for (int i = 0; i < n; ++i) ++count[static_cast<std::size_t>(cell_of(sample_uniform_sphere({rng.next_float(), rng.next_float()}), k))];
  const double expect = static_cast<double>(n) / (k * k);
  for (int c : count) ASSERT_NEAR(c, expect, 5.0 * std::sqrt(expect));
}

TEST(DirectionTree, RefinesWhereTheValueIsAndItsDensityIntegratesToOne) {
  Rng rng(5);
  const DirectionTree tree = clustered_tree(rng);
  ASSERT_FALSE(tree.empty());
  EXPECT_GT(tree.cells(), 40);
  // Exactly (the density is constant over the finest cells).
  double sum = 0.0;
  for (double p : cell_probabilities(1, [&](Vec3f w) { return tree.pdf(w); })) sum += p;
  EXPECT_NEAR(sum, 1.0, 1e-4);
  // The clusters are dense, the rest is not empty (the prior).
  EXPECT_GT(tree.pdf(DirectionTree::from_square({0.805f, 0.31f})), 100.0f / (4.0f * kPi));
  EXPECT_GT(tree.pdf(DirectionTree::from_square({0.1f, 0.1f})), 0.0f);
  EXPECT_LT(tree.pdf(DirectionTree::from_square({0.1f, 0.1f})), 1.0f / (4.0f * kPi));
  // An empty or valueless set of points: no tree.
  DirectionTree none;
  DirectionTree::Point zero{{0.5f, 0.5f}, 0.0f};
  none.build(&zero, 1, 0.01f, 1);
  EXPECT_TRUE(none.empty());
}

// Samples come with the density pdf() gives, and fall into the square's
// 16 x 16 cells as often as the density integrates to over them: 5 standard
// deviations per cell, and a chi-square over the cells.
TEST(DirectionTree, SamplesFollowItsDensity) {
  Rng rng(7);
  const DirectionTree tree = clustered_tree(rng);
  constexpr int k = 16;
  const std::vector<double> p = cell_probabilities(k, [&](Vec3f w) { return tree.pdf(w); });
  constexpr int kN = 400000;
  std::vector<int> count(k * k, 0);
  for (int i = 0; i < kN; ++i) {
    float pdf = 0.0f;
    const Vec3f w = tree.sample({rng.next_float(), rng.next_float()}, pdf);
    ASSERT_NEAR(length(w), 1.0f, 1e-4f);
    ASSERT_GT(pdf, 0.0f);
    ASSERT_EQ(pdf, tree.pdf(w));
    ++count[static_cast<std::size_t>(cell_of(w, k))];
  }
  double chi2 = 0.0;
  int cells = 0;
  for (std::size_t c = 0; c < p.size(); ++c) {
    const double e = kN * p[c];
    ASSERT_NEAR(count[c], e, 5.0 * std::sqrt(e * (1.0 - p[c])) + 1.0) << "cell " << c;
    if (e > 5.0) {
      chi2 += (count[c] - e) * (count[c] - e) / e;
      ++cells;
    }
  }
  // Chi-square with cells - 1 degrees of freedom: mean cells - 1, sd sqrt(2 (cells - 1)); 5 sd.
  EXPECT_LT(chi2, (cells - 1) + 5.0 * std::sqrt(2.0 * (cells - 1))) << cells << " cells";
}

// The courtyard under a sky and a sun: the floor and walls are lit mostly by
// each other (indirect light), which the guide learns.
TEST(PathGuide, LearnsLeavesAndItsDensityIntegratesToOne) {
  const Learned l = learn(test::courtyard_scene(true), 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  EXPECT_GT(l.guide->leaves(), 4);
  Rng rng(7);
  int guided = 0;
  for (int point = 0; point < 40; ++point) {
    const PathGuide::Leaf* leaf = l.guide->leaf(floor_point(rng), kUp);
    if (leaf == nullptr) continue;
    ++guided;
    // Exactly (the density is constant over the direction tree's finest cells).
    if (point < 4) {
      double sum = 0.0;
      for (double p : cell_probabilities(1, [&](Vec3f w) { return PathGuide::pdf(*leaf, w, Vec3f()); })) sum += p;
      EXPECT_NEAR(sum, 1.0, 1e-4) << "point " << point;
    }
    // And by Monte Carlo over uniform directions (pdf 1 / 4 pi), folded about
    // the floor's normal or not: within 5 standard errors.
    for (const Vec3f n : {Vec3f(), kUp}) {
      constexpr int kN = 40000;
      double mc = 0.0, mc2 = 0.0;
      for (int k = 0; k < kN; ++k) {
        const double v = 4.0 * kPi * PathGuide::pdf(*leaf, sample_uniform_sphere({rng.next_float(), rng.next_float()}), n);
        mc += v;
        mc2 += v * v;
      }
      const double mean = mc / kN, error = std::sqrt(std::max(0.0, mc2 / kN - mean * mean) / kN);
      EXPECT_NEAR(mean, 1.0, 5.0 * error) << "point " << point;
    }
  }
  EXPECT_GT(guided, 30);
}

// Sampled directions come out as often as their density says, over the
// square's 8 x 8 cells (5 standard deviations per cell), folded about the
// floor's normal or not, with the density pdf() gives.
TEST(PathGuide, SamplesFollowItsDensity) {
  const Learned l = learn(test::courtyard_scene(true), 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  Rng rng(11);
  int tested = 0;
  for (int point = 0; point < 6; ++point) {
    const PathGuide::Leaf* leaf = l.guide->leaf(floor_point(rng), kUp);
    if (leaf == nullptr) continue;
    ++tested;
    const Vec3f n = point % 2 == 0 ? Vec3f() : kUp;
    constexpr int k = 8;
    const std::vector<double> p = cell_probabilities(k, [&](Vec3f w) { return PathGuide::pdf(*leaf, w, n); });
    constexpr int kN = 100000;
    std::vector<int> count(k * k, 0);
    for (int i = 0; i < kN; ++i) {
      float pdf = 0.0f;
      const Vec3f w = PathGuide::sample(*leaf, {rng.next_float(), rng.next_float()}, n, pdf);
      ASSERT_NEAR(pdf, PathGuide::pdf(*leaf, w, n), 1e-4f * pdf);
      ++count[static_cast<std::size_t>(cell_of(w, k))];
    }
    for (std::size_t c = 0; c < p.size(); ++c)
      ASSERT_NEAR(count[c], kN * p[c], 5.0 * std::sqrt(kN * p[c] * (1.0 - p[c])) + 1.0) << "cell " << c;
  }
  EXPECT_GT(tested, 3);
}

// The mixture's bounce is an unbiased estimator: over many bounces from a
// Lambert surface of albedo 0.7 (and a glossy Blinn-Phong one), the mean
// weight f |cos| / pdf is the albedo (the BSDF's plain sampling's mean), and
// every sample's pdf is bounce_pdf(). Tolerance: 5 standard errors.
TEST(PathGuide, MixtureBouncesAreAnUnbiasedEstimatorOfTheAlbedo) {
  const Learned l = learn(test::courtyard_scene(true), 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  Rng rng(13);
  const PathGuide::Leaf* leaf = nullptr;
  while (leaf == nullptr) leaf = l.guide->leaf(floor_point(rng), kUp);
  MaterialDesc glossy = test::diffuse_material(RGB(0.4f));
  glossy.ks = 0.3f;
  glossy.exponent = 20.0f;
  for (const MaterialDesc& desc : {test::diffuse_material(RGB(0.7f)), glossy}) {
    const Material m = make_material(desc);
    const SurfaceGeometry geo = test::flat_surface();
    const Vec3f wo = test::direction_at(35.0f, 20.0f);
    const Bsdf bsdf(m, geo, wo);
    auto mean_weight = [&](const PathGuide::Leaf* region, double& error) {
      constexpr int kN = 400000;
      double sum = 0.0, sum2 = 0.0;
      for (int k = 0; k < kN; ++k) {
        BsdfSample s;
        double w = 0.0;
        if (PathGuide::sample_bounce(bsdf, region, wo, rng.next_float(), {rng.next_float(), rng.next_float()}, s)) {
          w = s.weight.g;
          if (!s.delta) {
            EXPECT_NEAR(s.pdf, PathGuide::bounce_pdf(bsdf, region, wo, s.wi), 1e-4f * s.pdf);
          }
        }
        sum += w;
        sum2 += w * w;
      }
      const double mean = sum / kN;
      error = std::sqrt(std::max(0.0, sum2 / kN - mean * mean) / kN);
      return mean;
    };
    double e_plain = 0.0, e_guided = 0.0;
    const double plain = mean_weight(nullptr, e_plain), guided = mean_weight(leaf, e_guided);
    EXPECT_NEAR(guided, plain, 5.0 * std::sqrt(e_plain * e_plain + e_guided * e_guided)) << "ks " << desc.ks;
  }
}

TEST(PathGuide, TheSameForAnyThreadCount) {
  const SceneDescription d = test::courtyard_scene(true);
  const Learned one = learn(d, 1), two = learn(d, 2);
  ASSERT_TRUE(one.guide->active());
  ASSERT_EQ(one.guide->leaves(), two.guide->leaves());
  Rng rng(5);
  for (int k = 0; k < 2000; ++k) {
    const Vec3f p = courtyard_point(rng), w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    const Vec3f n = Vec3f(0, k % 2 == 0 ? 1.0f : -1.0f, 0);
    const PathGuide::Leaf *a = one.guide->leaf(p, n), *b = two.guide->leaf(p, n);
    ASSERT_EQ(a == nullptr, b == nullptr);
    if (a != nullptr) {
      ASSERT_EQ(PathGuide::pdf(*a, w, Vec3f()), PathGuide::pdf(*b, w, Vec3f()));
    }
  }
  IntegratorSettings s = test::path_settings(4, 6, 2);
  s.path_guiding = 4;
  const Image x = test::render_path(d, s, 1), y = test::render_path(d, s, 2);
  ASSERT_EQ(x.pixels.size(), y.pixels.size());
  for (std::size_t i = 0; i < x.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(x.pixels[i][c], y.pixels[i][c]) << "pixel " << i;
  // And it changes the samples (it is not the plain render).
  s.path_guiding = 0;
  EXPECT_GT(test::rmse(x, test::render_path(d, s, 2)), 0.0);
}

// The passes of one render share one RenderCache: the first learns the
// guides and stores them, the next ones reuse them (the same object, no
// second pre-pass), and two passes of 2 samples are the render of 4.
TEST(PathGuide, LearnedOncePerRenderAndSharedByItsPasses) {
  const SceneDescription d = test::courtyard_scene(true);
  WorkerPool pool(2);
  const auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  IntegratorSettings s = test::path_settings(2, 6, 3);
  s.path_guiding = 4;
  s.light_guiding = 4;
  RenderCache cache;
  s.cache = &cache;
  Film passes(scene->width, scene->height);
  std::string error;
  make_integrator("path", s, error)->render(*scene, passes, pool);
  const void* learned = cache.slot.get();
  ASSERT_NE(learned, nullptr);
  s.first_sample = 2;
  make_integrator("path", s, error)->render(*scene, passes, pool);
  EXPECT_EQ(cache.slot.get(), learned);
  s.cache = nullptr;
  s.first_sample = 0;
  s.spp = 4;
  Film whole(scene->width, scene->height);
  make_integrator("path", s, error)->render(*scene, whole, pool);
  const Image a = passes.image(), b = whole.image();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(a.pixels[i][c], b.pixels[i][c], 1e-5f * (1.0f + b.pixels[i][c])) << i;
}

// A closed box whose six inward faces all emit 1 and reflect with albedo
// 0.5: every camera ray sees sum_{k=0..D} 0.5^k after D bounces (emission
// at each of the D + 1 vertices), guided or not. All of it after the first
// vertex is indirect light, which the guide learns. Tolerance: 4 standard
// errors of the mean over the pixels.
TEST(PathGuide, EmittingFurnaceBoxIsItsClosedForm) {
  SceneDescription d = test::empty_scene(16, 16, {0.2f, 1.0f, 1.2f}, {-0.3f, 0.9f, -1.0f}, {0, 1, 0}, 70);
  MaterialDesc wall = test::diffuse_material(RGB(0.5f));
  wall.emission = RGB(1.0f);
  const int m = test::add_material(d, wall);
  auto quad = [&](Vec3f a, Vec3f b, Vec3f c, Vec3f e) {
    Quad q;
    q.v[0] = a; q.v[1] = b; q.v[2] = c; q.v[3] = e;
    test::add_shape(d, q, m);
  };
  const float w = 2.0f, h = 3.0f;
  quad({-w, 0, -w}, {-w, 0, w}, {w, 0, w}, {w, 0, -w});    // floor, facing up
  quad({-w, 0, -w}, {w, 0, -w}, {w, h, -w}, {-w, h, -w});  // walls, facing in
  quad({-w, 0, w}, {-w, h, w}, {w, h, w}, {w, 0, w});
  quad({-w, 0, -w}, {-w, h, -w}, {-w, h, w}, {-w, 0, w});
  quad({w, 0, -w}, {w, 0, w}, {w, h, w}, {w, h, -w});
  quad({-w, h, -w}, {w, h, -w}, {w, h, w}, {-w, h, w});    // ceiling, facing down
  constexpr int kDepth = 6;
  const Learned l = learn(d, 2);
  ASSERT_TRUE(l.guide->active());
  IntegratorSettings s = test::path_settings(64, kDepth, 4);
  s.path_guiding = 8;
  const Image img = test::render_path(d, s);
  const double expect = (1.0 - std::pow(0.5, kDepth + 1)) / 0.5;
  // One channel: the box is grey, so the three are the same numbers.
  const test::Stats st = test::channel_stats(img, 1, [](int, int) { return true; });
  ASSERT_EQ(st.count, 256u);
  EXPECT_NEAR(st.mean, expect, 4.0 * st.stddev / std::sqrt(static_cast<double>(st.count)) + 1e-4)
      << "stddev " << st.stddev;
}

}  // namespace
}  // namespace pt
