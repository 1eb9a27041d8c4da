// The light guide (render/guiding/light_guide.h): its densities integrate to
// one, it samples what its pdf says, its choice probabilities sum to one, it
// is a function of the seed alone (the same for any thread count), and a
// furnace renders exactly its albedo with it. That guided and plain renders
// converge to the same image: PathAgreement.LightGuiding* (test_path_agreement.cpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "core/rng.h"
#include "light_guide_scenes.h"
#include "path_test_util.h"
#include "render/guiding/environment_bins.h"
#include "render/guiding/light_guide.h"
#include "render/lights/environment.h"
#include "render/render_scene.h"

namespace pt {
namespace {

using Learned = test::Learned<LightGuide>;

Learned learn(const SceneDescription& d, int threads, int paths_per_pixel = 4, uint64_t seed = 1) {
  return test::learn_guide<LightGuide>(d, threads, paths_per_pixel, seed);
}

using test::courtyard_point;

TEST(LightGuide, LearnsLeavesAndItsEnvironmentDensityIntegratesToOne) {
  const Learned l = learn(test::courtyard_scene(true), 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  EXPECT_GT(l.guide->leaves(), 4);
  const int env = l.scene->lights.environment();
  ASSERT_GE(env, 0);
  Rng rng(3);
  constexpr int kN = 200000;
  for (int point = 0; point < 6; ++point) {
    const Vec3f p = courtyard_point(rng);
    double sum = 0.0;  // uniform directions: E[pdf * 4 pi] = 1
    for (int k = 0; k < kN; ++k) {
      const Vec3f w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      sum += static_cast<double>(l.guide->pdf(env, p, w, Vec3f(), Vec3f())) * 4.0 * kPi;
    }
    EXPECT_NEAR(sum / kN, 1.0, 0.03) << "point " << point;
  }
}

// E[f(w) / pdf(w)] over the guide's own samples equals the integral of f: with
// f = the map's radiance luminance, the map's power per steradian summed.
TEST(LightGuide, SamplesFollowItsDensity) {
  const Learned l = learn(test::courtyard_scene(false), 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  const int env = l.scene->lights.environment();
  Rng rng(9);
  constexpr int kN = 400000;
  double reference = 0.0;  // the integral by uniform directions
  for (int k = 0; k < kN; ++k) {
    const Vec3f w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    reference += l.scene->lights.escaped_radiance(w, RGB()).luminance() * 4.0 * kPi;
  }
  reference /= kN;
  for (int point = 0; point < 4; ++point) {
    const Vec3f p = courtyard_point(rng);
    double sum = 0.0;
    for (int k = 0; k < kN; ++k) {
      LightSample s;
      if (!l.guide->sample(env, p, {rng.next_float(), rng.next_float()}, s)) continue;
      ASSERT_NEAR(s.pdf, l.guide->pdf(env, p, s.wi, Vec3f(), Vec3f()), 1e-4f * s.pdf);
      sum += s.L.luminance() / s.pdf;
    }
    EXPECT_NEAR(sum / kN, reference, 0.02 * reference) << "point " << point;
  }
}

// The courtyard with its opening closed: no pre-pass test reaches the sky, so
// no leaf learns environment directions and each samples the sky the plain
// way (session 16 tried the bins' coarse grid there instead of the map's own
// tables: docs/bench/sample-cost.md). That sampling must still be a density
// that integrates to one, and its samples must be what its pdf says:
// E[L / pdf] is the map's integral, as in SamplesFollowItsDensity, and each
// sample states exactly pdf() and the escaped radiance at its direction
// (the map's sample once stated its drawn texel's, which float rounding at a
// texel's edge could put next to the direction's texel: SamplesStateExactly...).
TEST(LightGuide, LeavesThatSawNoSkyStillSampleItByItsDensity) {
  SceneDescription d = test::courtyard_scene(false);
  Quad lid;
  const float o = 0.7f, h = 3.0f;  // wider than the opening, at the roof's height
  lid.v[0] = {-o, h, -o}; lid.v[1] = {o, h, -o}; lid.v[2] = {o, h, o}; lid.v[3] = {-o, h, o};
  test::add_shape(d, lid, d.shapes.front().material);  // the walls' white
  const Learned l = learn(d, 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  const int env = l.scene->lights.environment();
  ASSERT_GE(env, 0);
  Rng rng(5);
  constexpr int kN = 200000;
  double reference = 0.0;
  for (int k = 0; k < kN; ++k) {
    const Vec3f w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    reference += l.scene->lights.escaped_radiance(w, RGB()).luminance() * 4.0 * kPi;
  }
  reference /= kN;
  for (int point = 0; point < 3; ++point) {
    const Vec3f p = courtyard_point(rng);
    double integral = 0.0, estimate = 0.0;
    for (int k = 0; k < kN; ++k) {
      const Vec3f w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      integral += static_cast<double>(l.guide->pdf(env, p, w, Vec3f(), Vec3f())) * 4.0 * kPi;
      LightSample s;
      if (!l.guide->sample(env, p, {rng.next_float(), rng.next_float()}, s)) continue;
      ASSERT_EQ(s.pdf, l.guide->pdf(env, p, s.wi, Vec3f(), Vec3f())) << "point " << point << ", sample " << k;
      ASSERT_EQ(s.L, l.scene->lights.escaped_radiance(s.wi, RGB())) << "point " << point << ", sample " << k;
      estimate += s.L.luminance() / s.pdf;
    }
    EXPECT_NEAR(integral / kN, 1.0, 0.03) << "point " << point;
    EXPECT_NEAR(estimate / kN, reference, 0.02 * reference) << "point " << point;
  }
}

// A sample's density and radiance are exactly pdf() and the escaped radiance
// at its direction, for each of 10^5 samples: MIS weighs a BSDF ray escaping
// in that direction by pdf() there, so a sample stating another density (its
// drawn texel's, where float rounding puts the direction in the next texel)
// would weigh the two strategies inconsistently. The map alone (a checkerboard
// of contrast 2500, odd size, tilted and rotated) and the guide's three
// environment paths: the plain map (a leaf that learned no sky), the mixture
// with the map's own fine part (a sun in the map) and with the coarse grid.
TEST(LightGuide, SamplesStateExactlyPdfAndRadianceAtTheirDirection) {
  constexpr int kW = 97, kH = 43, kN = 100000;
  Image img(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) img.at(x, y) = (x + y) % 2 ? RGB(50.0f, 40.0f, 30.0f) : RGB(0.02f);
  const auto path = std::filesystem::temp_directory_path() / "pt_test_environment_checkerboard.exr";
  std::string error;
  ASSERT_TRUE(write_image(path.string(), img, DisplaySettings{}, error)) << error;
  EnvironmentDesc desc;
  desc.resolved = path.string();
  desc.up.value = Vec3f(0.3f, 1.0f, 0.2f);
  desc.rotation_deg.value = 37.0f;
  const std::unique_ptr<EnvironmentMap> map = EnvironmentMap::load(desc, error);
  ASSERT_TRUE(map) << error;
  Rng rng(12);
  int drawn = 0;
  for (int k = 0; k < kN; ++k) {
    LightSample s;
    if (!map->sample({rng.next_float(), rng.next_float()}, s)) continue;
    ++drawn;
    ASSERT_EQ(s.pdf, map->pdf(s.wi)) << "sample " << k;
    ASSERT_EQ(s.L, map->radiance(s.wi)) << "sample " << k;
  }
  EXPECT_GT(drawn, kN - kN / 1000);

  SceneDescription closed = test::courtyard_scene(false);
  Quad lid;
  lid.v[0] = {-0.7f, 3.0f, -0.7f}; lid.v[1] = {0.7f, 3.0f, -0.7f}; lid.v[2] = {0.7f, 3.0f, 0.7f}; lid.v[3] = {-0.7f, 3.0f, 0.7f};
  test::add_shape(closed, lid, closed.shapes.front().material);
  const SceneDescription scenes[] = {closed, test::courtyard_scene(true, true), test::courtyard_scene(false)};
  for (const SceneDescription& d : scenes) {
    const Learned l = learn(d, 2);
    ASSERT_TRUE(l.guide && l.guide->active());
    const int env = l.scene->lights.environment();
    ASSERT_GE(env, 0);
    for (int point = 0; point < 2; ++point) {
      const Vec3f p = courtyard_point(rng);
      for (int k = 0; k < kN / 2; ++k) {
        LightSample s;
        if (!l.guide->sample(env, p, {rng.next_float(), rng.next_float()}, s)) continue;
        ASSERT_EQ(s.pdf, l.guide->pdf(env, p, s.wi, Vec3f(), Vec3f())) << "point " << point << ", sample " << k;
        ASSERT_EQ(s.L, l.scene->lights.escaped_radiance(s.wi, RGB())) << "point " << point << ", sample " << k;
      }
    }
  }
}

// The bins' importance grids (environment_bins.h) on a 300 x 70 map (bins of
// 9-10 x 4-5 texels: cells of 1-2 texels, uneven) with one bright texel: in
// every bin the density integrates to one over the bin, samples land in their
// bin where the density is positive, and E[1 / density] over a bin's samples
// is its area (every texel is lit, so the grid's support is the whole bin,
// within 3%); the bright texel's cell (1-2 texels) gets most of its bin's samples; the
// table is bins x kCells^2 floats and a few indices.
TEST(LightGuide, EnvironmentBinsSampleTheirImportanceGrids) {
  constexpr int kW = 300, kH = 70;
  Image img(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) img.at(x, y) = RGB(0.1f + 0.05f * static_cast<float>((x * 7 + y * 3) % 11));
  img.at(101, 20) = RGB(500.0f);
  const auto path = std::filesystem::temp_directory_path() / "pt_test_environment_bins.exr";
  std::string error;
  ASSERT_TRUE(write_image(path.string(), img, DisplaySettings{}, error)) << error;
  EnvironmentDesc desc;
  desc.resolved = path.string();
  const std::unique_ptr<EnvironmentMap> map = EnvironmentMap::load(desc, error);
  ASSERT_TRUE(map) << error;
  const EnvironmentBins bins(*map);
  ASSERT_EQ(bins.size(), 32 * 16);
  EXPECT_LE(bins.table_bytes(), static_cast<std::size_t>(bins.size()) * EnvironmentBins::kCells *
                                        EnvironmentBins::kCells * sizeof(float) + 16384);
  const auto texel_uv = [](int x, int y) { return Vec2f((x + 0.5f) / kW, (y + 0.5f) / kH); };
  std::vector<double> integral(static_cast<std::size_t>(bins.size()), 0.0), area(integral);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int b = bins.bin_at(texel_uv(x, y));
      integral[static_cast<std::size_t>(b)] += bins.density(b, texel_uv(x, y)) / (kW * kH);
      area[static_cast<std::size_t>(b)] += 1.0 / (kW * kH);
    }
  Rng rng(11);
  const int bright = bins.bin_at(texel_uv(101, 20));
  for (int b = 0; b < bins.size(); ++b) {
    ASSERT_NEAR(integral[static_cast<std::size_t>(b)], 1.0, 1e-4) << "bin " << b;
    if (b % 37 != 0 && b != bright) continue;  // a sample of the bins, and the bright one
    constexpr int kN = 20000;
    double inverse = 0.0;
    int hits = 0;
    for (int k = 0; k < kN; ++k) {
      const Vec2f uv = bins.sample(b, {rng.next_float(), rng.next_float()});
      ASSERT_EQ(bins.bin_at(uv), b);
      const float d = bins.density(b, uv);
      ASSERT_GT(d, 0.0f);
      inverse += 1.0 / d;
      hits += std::abs(static_cast<int>(uv.x * kW) - 101) <= 1 && static_cast<int>(uv.y * kH) == 20;
    }
    EXPECT_NEAR(inverse / kN, area[static_cast<std::size_t>(b)], 0.03 * area[static_cast<std::size_t>(b)]) << "bin " << b;
    if (b == bright) {
      EXPECT_GT(hits, kN / 2) << "the bright texel's share of its bin";
    }
  }
}

// The coarse grid's chi-square divergence from the map's own distribution
// (EnvironmentBins::coarse_chi2) is about 0 for a uniform or smooth sky, whose
// plain sampling the guide then takes from the bins, and above
// LightGuide::kMaxCoarseChi2 for a sky with a sun disc, which keeps the map's.
TEST(LightGuide, CoarsePlainSamplingOnlyForASmoothSky) {
  std::string error;
  const auto chi2 = [&](const std::string& file) {
    EnvironmentDesc desc;
    desc.resolved = file;
    const std::unique_ptr<EnvironmentMap> map = EnvironmentMap::load(desc, error);
    EXPECT_TRUE(map) << error;
    return map ? EnvironmentBins(*map).coarse_chi2() : -1.0f;
  };
  EXPECT_NEAR(chi2(test::guide_test_environment(true)), 0.0f, 1e-3f);
  EXPECT_NEAR(chi2(test::guide_test_environment(false)), 0.0f, 1e-3f);  // 2 x 2 texels a bin: cells are texels
  const float sun = chi2(test::guide_test_sun_environment());
  EXPECT_GT(sun, LightGuide::kMaxCoarseChi2);
  EXPECT_LT(sun, 100.0f);
}

TEST(LightGuide, ChoiceProbabilitiesSumToOneAndMatchChoose) {
  const Learned l = learn(test::courtyard_scene(true), 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  Rng rng(4);
  for (int point = 0; point < 50; ++point) {
    const Vec3f p = courtyard_point(rng), n(0, 1, 0);
    double sum = 0.0;
    for (std::size_t i = 0; i < l.scene->lights.size(); ++i) sum += l.guide->pmf(p, n, static_cast<int>(i));
    EXPECT_NEAR(sum, 1.0, 1e-5) << "point " << point;
    for (int k = 0; k < 16; ++k) {
      float pmf = 0.0f;
      const int i = l.guide->choose(p, n, (k + 0.5f) / 16.0f, pmf);
      ASSERT_GE(i, 0);
      EXPECT_EQ(pmf, l.guide->pmf(p, n, i));
      EXPECT_GE(pmf, LightGuide::kPlainChoice * l.scene->lights.pmf(p, n, i));  // never below the plain share
    }
  }
}

TEST(LightGuide, TheSameForAnyThreadCount) {
  const SceneDescription d = test::courtyard_scene(true);
  const Learned one = learn(d, 1), two = learn(d, 2);
  ASSERT_EQ(one.guide->leaves(), two.guide->leaves());
  const int env = one.scene->lights.environment();
  Rng rng(5);
  for (int k = 0; k < 2000; ++k) {
    const Vec3f p = courtyard_point(rng), w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    ASSERT_EQ(one.guide->pdf(env, p, w, Vec3f(), Vec3f()), two.guide->pdf(env, p, w, Vec3f(), Vec3f()));
    ASSERT_EQ(one.guide->pmf(p, Vec3f(), env), two.guide->pmf(p, Vec3f(), env));
  }
  IntegratorSettings s = test::path_settings(4, 6, 2);
  s.light_guiding = 4;
  const Image a = test::render_path(d, s, 1), b = test::render_path(d, s, 2);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(a.pixels[i][c], b.pixels[i][c]) << "pixel " << i;
}

// With nothing to guide (a sun alone: no map, no choice) the guide stays
// inactive and a render with light_guiding on is the plain one bit for bit;
// with a sky it does change the samples.
TEST(LightGuide, InactiveWithNothingToGuideAndThenThePlainRenderBitForBit) {
  SceneDescription d = test::courtyard_scene(true);
  d.environment.reset();
  IntegratorSettings s = test::path_settings(2, 6, 3);
  const Image plain = test::render_path(d, s);
  s.light_guiding = 4;
  const Learned l = learn(d, 2);
  EXPECT_FALSE(l.guide->active());
  const Image guided = test::render_path(d, s);
  ASSERT_EQ(plain.pixels.size(), guided.pixels.size());
  for (std::size_t i = 0; i < plain.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(plain.pixels[i][c], guided.pixels[i][c]) << "pixel " << i;
  const SceneDescription sky = test::courtyard_scene(true);
  s.light_guiding = 0;
  const Image sky_plain = test::render_path(sky, s);
  s.light_guiding = 4;
  EXPECT_GT(test::rmse(sky_plain, test::render_path(sky, s)), 0.0);
}

// A white-ish convex sphere under a uniform sky of 1 is its albedo in every
// pixel it covers, guided or not (the guide learns the sphere's visible
// hemispheres; a wrong normalisation would scale the answer). Tolerance: 4
// standard errors of the mean over the sphere's pixels.
// Every unit normal falls in one of the 26 classes (light_guide.h) and lies
// within kClassChord of its class's direction; the axes are their own classes.
TEST(LightGuide, NormalClassesAreWithinTheirChord) {
  Rng rng(21);
  float worst = 0.0f;
  for (int k = 0; k < 200000; ++k) {
    const Vec3f n = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    const int c = LightGuide::normal_class(n);
    ASSERT_GE(c, 0);
    ASSERT_LT(c, LightGuide::kNormalClasses);
    ASSERT_NE(c, 13) << "the zero pattern is no class";
    worst = std::max(worst, length(n - LightGuide::class_direction(c)));
  }
  EXPECT_LE(worst, LightGuide::kClassChord);
  EXPECT_GT(worst, 0.5f) << "the bound is near the classes' real extent (0.523)";
  for (const Vec3f axis : {Vec3f(1, 0, 0), Vec3f(0, -1, 0), Vec3f(0, 0, 1)}) {
    EXPECT_EQ(LightGuide::class_direction(LightGuide::normal_class(axis)), axis);
  }
  EXPECT_EQ(LightGuide::normal_class(Vec3f()), -1);
}

// EnvironmentBins::cosine_bound bounds the cosine between any direction of a
// bin and any unit vector within `slack` of n: every bin of a tilted, rotated
// map (so the bins' axes go through the map's frame), directions drawn in the
// bin, normals at random and perturbed by up to 0.3.
TEST(LightGuide, CosineBoundsHoldOverEveryBin) {
  EnvironmentDesc desc;
  desc.resolved = test::guide_test_environment(false);
  desc.up.value = Vec3f(0.3f, 1.0f, 0.2f);
  desc.rotation_deg.value = 37.0f;
  std::string error;
  const std::unique_ptr<EnvironmentMap> map = EnvironmentMap::load(desc, error);
  ASSERT_TRUE(map) << error;
  const EnvironmentBins bins(*map);
  Rng rng(22);
  int tight = 0;  // pairs where the bound is within 0.2 of the cosine: it is not vacuous
  for (int b = 0; b < bins.size(); ++b) {
    for (int k = 0; k < 200; ++k) {
      const Vec3f x = map->uv_to_direction(bins.sample(b, {rng.next_float(), rng.next_float()}));
      const Vec3f n = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      const Vec3f m = normalize(n + 0.3f * rng.next_float() * sample_uniform_sphere({rng.next_float(), rng.next_float()}));
      const float slack = length(m - n);
      ASSERT_LE(dot(n, x), bins.cosine_bound(b, n, 0.0f) + 1e-5f) << "bin " << b;
      ASSERT_LE(dot(m, x), bins.cosine_bound(b, n, slack) + 1e-5f) << "bin " << b;
      tight += bins.cosine_bound(b, n, 0.0f) - std::max(0.0f, dot(n, x)) < 0.2f;
    }
  }
  EXPECT_GT(tight, bins.size() * 200 / 2);
}

// A site with a normal (site(p, n): the leaf's bins times the normal class's
// cosine bounds) is a density that integrates to one, its samples state exactly
// pdf() at their direction (MIS weighs a BSDF ray by it), E[L / pdf] is the
// map's integral, and at least as many of its samples lie in front of the
// normal as the leaf's own distribution puts there (most, on the floor and the
// walls). Points on the courtyard's floor, walls and roof with their normals
// (tables exist for the classes a leaf's pre-pass records had).
TEST(LightGuide, SitesWithANormalSampleTheSkyInFrontByTheirDensity) {
  const Learned l = learn(test::courtyard_scene(false), 2);
  ASSERT_TRUE(l.guide && l.guide->active());
  const int env = l.scene->lights.environment();
  ASSERT_GE(env, 0);
  Rng rng(23);
  constexpr int kN = 100000;
  double reference = 0.0;
  for (int k = 0; k < 4 * kN; ++k) {
    const Vec3f w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    reference += l.scene->lights.escaped_radiance(w, RGB()).luminance() * 4.0 * kPi;
  }
  reference /= 4 * kN;
  struct Surface {
    Vec3f p, n;
    bool roof;
  };
  std::vector<Surface> surfaces;
  const auto in = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
  for (int i = 0; i < 2; ++i) {
    surfaces.push_back({{in(-1.9f, 1.9f), 1e-3f, in(-1.9f, 1.9f)}, {0, 1, 0}, false});
    surfaces.push_back({{-2.0f + 1e-3f, in(0.1f, 2.9f), in(-1.9f, 1.9f)}, {1, 0, 0}, false});
    surfaces.push_back({{2.0f - 1e-3f, in(0.1f, 2.9f), in(-1.9f, 1.9f)}, {-1, 0, 0}, false});
    surfaces.push_back({{in(-1.9f, 1.9f), in(0.1f, 2.9f), -2.0f + 1e-3f}, {0, 0, 1}, false});
    surfaces.push_back({{in(-1.9f, 1.9f), in(0.1f, 2.9f), 2.0f - 1e-3f}, {0, 0, -1}, false});
    surfaces.push_back({{in(0.8f, 1.9f), 3.0f - 1e-3f, in(-1.9f, 1.9f)}, {0, -1, 0}, true});
  }
  int product_sites = 0;
  for (const Surface& sf : surfaces) {
    const Vec3f n = sf.n;
    const LightGuide::Site at = l.guide->site(sf.p, n), plain = l.guide->site(sf.p);
    if (at.environment == nullptr) continue;  // no table for this class in this leaf
    ++product_sites;
    double integral = 0.0, estimate = 0.0;
    int front = 0, plain_front = 0;
    for (int k = 0; k < kN; ++k) {
      const Vec3f w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      integral += static_cast<double>(l.guide->pdf(env, at, w, Vec3f(), Vec3f())) * 4.0 * kPi;
      const Vec2f u(rng.next_float(), rng.next_float());
      LightSample s, q;
      if (l.guide->sample(env, plain, u, q)) plain_front += dot(q.wi, n) > 0.0f;
      if (!l.guide->sample(env, at, u, s)) continue;
      ASSERT_EQ(s.pdf, l.guide->pdf(env, at, s.wi, Vec3f(), Vec3f())) << "normal " << n.x << " " << n.y << " " << n.z;
      ASSERT_EQ(s.L, l.scene->lights.escaped_radiance(s.wi, RGB()));
      estimate += s.L.luminance() / s.pdf;
      front += dot(s.wi, n) > 0.0f;
    }
    EXPECT_NEAR(integral / kN, 1.0, 0.03) << "normal " << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(estimate / kN, reference, 0.03 * reference) << "normal " << n.x << " " << n.y << " " << n.z;
    EXPECT_GE(front, plain_front) << "normal " << n.x << " " << n.y << " " << n.z;
    if (!sf.roof) {
      EXPECT_GT(front, kN * 6 / 10) << "normal " << n.x << " " << n.y << " " << n.z;
    }
  }
  EXPECT_GE(product_sites, 8);
  // Without a normal (a transmitting BSDF), or with a zero one, or of a class
  // no record of the leaf had (no surface of the courtyard faces a corner of
  // the cube): the leaf's own distribution.
  EXPECT_EQ(l.guide->site(surfaces.front().p, Vec3f()).environment, nullptr);
  EXPECT_EQ(l.guide->site(surfaces.front().p, normalize(Vec3f(1, 1, 1))).environment, nullptr);
}

TEST(LightGuide, FurnaceSphereIsItsAlbedo) {
  const SceneDescription d = test::furnace_scene(0.8f);
  IntegratorSettings s = test::path_settings(64, 8, 1);
  s.light_guiding = 8;
  const Image img = test::render_path(d, s);
  // The pixels well inside the sphere's disc (radius about 7.5 px at this fov).
  const auto inside = [&](int x, int y) {
    const float dx = x + 0.5f - 8.0f, dy = y + 0.5f - 8.0f;
    return dx * dx + dy * dy < 5.5f * 5.5f;
  };
  const test::Stats st = test::channel_stats(img, -1, inside);
  ASSERT_GT(st.count, 200u);
  EXPECT_NEAR(st.mean, 0.8, 4.0 * st.stddev / std::sqrt(static_cast<double>(st.count)) + 1e-4)
      << "stddev " << st.stddev;
}

}  // namespace
}  // namespace pt
