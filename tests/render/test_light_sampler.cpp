// The light choice of next-event estimation (LightSet::choose and pmf, the
// light BVH; docs/path-tracing.md, "Choosing a light"): at every shading point
// the probabilities sum to one (less the walks that find no light), choose()
// returns each light as often as pmf() says (exactly for stratified numbers,
// and by chi-square for random ones), a light gets probability 0 only where it
// sends the point nothing, and the spot + sky case that motivated it.
#include <bit>
#include <cmath>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "chi2.h"
#include "core/rng.h"
#include "geometry/shapes.h"
#include "render/lights/light_set.h"

namespace pt {
namespace {

Vec3f random_unit(Rng& rng) { return sample_uniform_sphere({rng.next_float(), rng.next_float()}); }
Vec3f random_point(Rng& rng, float r) {
  return Vec3f(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1) * r;
}

// Every kind of light at random places: point and spot lights, one-sided and
// two-sided quads facing every way, spheres, a bent two-triangle mesh, a disc,
// a point light without falloff, a directional light and a uniform sky.
struct Lights {
  std::deque<Shape> shapes;
  std::deque<Material> materials;
  LightSet set;

  explicit Lights(LightSamplerType sampler, uint64_t seed = 7) {
    Rng rng(seed);
    std::vector<Light> l;
    for (int i = 0; i < 6; ++i)
      l.emplace_back(PointLight{random_point(rng, 4), RGB(rng.next_float() * 5 + 0.1f), RGB(), true});
    for (int i = 0; i < 5; ++i) {
      const float cone = 15.0f + 30.0f * rng.next_float(), delta = i == 0 ? 0.0f : 8.0f * rng.next_float();
      l.emplace_back(SpotLight{random_point(rng, 4), random_unit(rng), RGB(rng.next_float() * 20 + 1), RGB(),
                               std::cos(cone * kPi / 180), std::cos((cone - delta) * kPi / 180)});
    }
    for (int i = 0; i < 8; ++i) {
      const Vec3f c = random_point(rng, 4), n = random_unit(rng);
      Vec3f t, b;
      orthonormal_basis(n, t, b);
      const float s = 0.1f + 0.4f * rng.next_float();
      Quad q;
      q.v[0] = c - t * s - b * s; q.v[1] = c + t * s - b * s; q.v[2] = c + t * s + b * s; q.v[3] = c - t * s + b * s;
      add_shape_light(q, RGB(rng.next_float() * 10 + 0.5f), i % 3 == 0, l);
    }
    for (int i = 0; i < 3; ++i) {
      Sphere sp;
      sp.center = random_point(rng, 4);
      sp.radius = 0.05f + 0.2f * rng.next_float();
      add_shape_light(sp, RGB(rng.next_float() * 10 + 0.5f), false, l);
    }
    TriangleMesh bent;  // two triangles at a right angle
    bent.positions = {Vec3f(0, 1, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 1), Vec3f(0, 2, 0)};
    bent.indices = {0, 1, 2, 0, 2, 3};
    add_shape_light(bent, RGB(4.0f), false, l);
    Disc disc;
    disc.center = Vec3f(2, -1, 1);
    disc.normal = normalize(Vec3f(1, 1, 0));
    disc.radius = 0.3f;
    add_shape_light(disc, RGB(6.0f), false, l);
    l.emplace_back(PointLight{Vec3f(1, 2, 3), RGB(0.2f), RGB(), false});
    l.emplace_back(DirectionalLight{normalize(Vec3f(1, -2, 0.5f)), RGB(0.5f)});
    l.emplace_back(UniformEnvironment{RGB(0.2f, 0.3f, 0.4f)});
    set = LightSet(std::move(l), shapes.size(), 8.0f, sampler);
  }

  void add_shape_light(const Shape& s, RGB emission, bool two_sided, std::vector<Light>& l) {
    shapes.push_back(s);
    Material m;
    m.emission = emission;
    m.two_sided = two_sided;
    materials.push_back(m);
    l.emplace_back(ShapeLight(shapes.back(), static_cast<uint32_t>(shapes.size() - 1), materials.back()));
  }
};

TEST(LightSampler, TheBvhHoldsTheBoundedLightsAndEveryLightCanBeChosen) {
  const Lights lights(LightSamplerType::Bvh);
  ASSERT_EQ(lights.set.size(), 27u);
  EXPECT_EQ(lights.set.bvh().light_count(), 24u);  // all but the three unbounded ones
  EXPECT_TRUE(lights.set.needs_choice());
}

// choose() maps [0, 1) onto the lights in one interval each, of length pmf():
// stratified numbers find each light pmf * N times, give or take the ends. The
// rest of [0, 1) is walks that end with no light (both children of a node
// importance 0 where their merged bounds are not): pmfs + that share = 1.
int stratified_check(const LightSet& set, Vec3f p, Vec3f n, int point, double& sum) {
  constexpr int kN = 4096;
  std::vector<int> count(set.size() + 1, 0);
  for (int k = 0; k < kN; ++k) {
    float pmf = 0.0f;
    const int i = set.choose(p, n, (k + 0.5f) / kN, pmf);
    ++count[i < 0 ? set.size() : static_cast<std::size_t>(i)];
    if (i >= 0) {
      EXPECT_NEAR(pmf, set.pmf(p, n, i), 1e-5f * pmf) << "point " << point << " light " << i;
    }
  }
  sum = 0.0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const float pmf = set.pmf(p, n, static_cast<int>(i));
    sum += pmf;
    EXPECT_NEAR(count[i] / double(kN), pmf, 2.0 / kN + 1e-4) << "point " << point << " light " << i;
  }
  EXPECT_NEAR(sum + count.back() / double(kN), 1.0, 2.0 / kN) << "point " << point;
  return count.back();
}

TEST(LightSampler, StratifiedChoicesMatchThePmfEverywhere) {
  const Lights lights(LightSamplerType::Bvh);
  Rng rng(11);
  for (int point = 0; point < 60; ++point) {
    const Vec3f p = random_point(rng, 5), n = point % 5 == 0 ? Vec3f() : random_unit(rng);
    double sum = 0.0;
    stratified_check(lights.set, p, n, point, sum);
  }
}

// Where no walk can die — lamps under a ceiling, all facing down, point lights
// and spheres, seen from below — the probabilities sum to exactly one.
TEST(LightSampler, PmfsSumToOneUnderACeilingOfLamps) {
  std::deque<Shape> shapes;
  std::deque<Material> materials;
  std::vector<Light> l;
  Rng rng(2);
  for (int i = 0; i < 40; ++i) {
    const Vec3f c(rng.next_float() * 8 - 4, 3.0f, rng.next_float() * 8 - 4);
    Quad q;  // facing down
    q.v[0] = c + Vec3f(-0.1f, 0, -0.1f); q.v[1] = c + Vec3f(0.1f, 0, -0.1f);
    q.v[2] = c + Vec3f(0.1f, 0, 0.1f); q.v[3] = c + Vec3f(-0.1f, 0, 0.1f);
    shapes.push_back(q);
    Material m;
    m.emission = RGB(1.0f + 9.0f * rng.next_float());
    materials.push_back(m);
    l.emplace_back(ShapeLight(shapes.back(), static_cast<uint32_t>(shapes.size() - 1), materials.back()));
  }
  for (int i = 0; i < 8; ++i) l.emplace_back(PointLight{random_point(rng, 2.5f), RGB(2.0f), RGB(), true});
  l.emplace_back(UniformEnvironment{RGB(0.1f)});
  const LightSet set(std::move(l), shapes.size(), 6.0f, LightSamplerType::Bvh);
  for (int point = 0; point < 40; ++point) {
    const Vec3f p(rng.next_float() * 10 - 5, rng.next_float() * 2.8f, rng.next_float() * 10 - 5);
    const Vec3f n = random_unit(rng);
    double sum = 0.0;
    EXPECT_EQ(stratified_check(set, p, n, point, sum), 0) << "point " << point;
    EXPECT_NEAR(sum, 1.0, 1e-4) << "point " << point;
  }
}

TEST(LightSampler, ChoiceFrequenciesMatchThePmfChiSquare) {
  const Lights lights(LightSamplerType::Bvh);
  Rng rng(5);
  constexpr int kSamples = 200000;
  for (int point = 0; point < 3; ++point) {
    const Vec3f p = random_point(rng, 4), n = random_unit(rng);
    std::vector<double> observed(lights.set.size() + 1, 0.0), expected(lights.set.size() + 1, 0.0);
    for (int k = 0; k < kSamples; ++k) {
      float pmf = 0.0f;
      const int i = lights.set.choose(p, n, rng.next_float(), pmf);
      observed[i < 0 ? lights.set.size() : static_cast<std::size_t>(i)] += 1.0;
    }
    double sum = 0.0;
    for (std::size_t i = 0; i < lights.set.size(); ++i) {
      expected[i] = kSamples * lights.set.pmf(p, n, static_cast<int>(i));
      sum += expected[i];
    }
    expected.back() = std::max(0.0, kSamples - sum);
    const test::Chi2Result r = test::chi2_gof(observed, expected);
    EXPECT_TRUE(r.passed) << "point " << point << ": " << r.message;
  }
}

// A light whose probability is 0 at (p, n) must send p nothing that a surface
// with normal n could receive: every sample of it is black, or edge-on to n.
TEST(LightSampler, ALightGetsProbabilityZeroOnlyWhereItSendsNothing) {
  const Lights lights(LightSamplerType::Bvh);
  Rng rng(3);
  int zero_cases = 0;
  for (int point = 0; point < 400; ++point) {
    const Vec3f p = random_point(rng, 5), n = random_unit(rng);
    for (std::size_t i = 0; i < lights.set.size(); ++i) {
      if (lights.set.pmf(p, n, static_cast<int>(i)) > 0.0f) continue;
      ++zero_cases;
      for (int k = 0; k < 64; ++k) {
        LightSample s;
        if (!sample_light(lights.set[i], p, {rng.next_float(), rng.next_float()}, s) || !(s.pdf > 0.0f)) continue;
        const float received = s.L.max_component() * std::fabs(dot(s.wi, n));
        ASSERT_EQ(received, 0.0f) << "light " << i << " at point " << point << " has pmf 0 but sends "
                                  << received;
      }
    }
  }
  // One-sided quads, discs and spots facing away: the rule is used, not vacuous.
  EXPECT_GT(zero_cases, 400);
}

// The case that motivated the BVH: a spot and a uniform sky. Far outside the
// spot's cone the sky is chosen always; in its pool of light mostly the spot,
// where power alone chose it 1 time in 7.
TEST(LightSampler, ASpotOutsideItsConeIsNeverChosenAndInsideItMostly) {
  const auto make = [](LightSamplerType sampler) {
    const Vec3f pos(-2, 4, 2);
    std::vector<Light> l;
    l.emplace_back(SpotLight{pos, normalize(Vec3f(-1.2f, 0, 0) - pos), RGB(30, 28, 24), RGB(),
                             std::cos(25.0f * kPi / 180), std::cos(19.0f * kPi / 180)});
    l.emplace_back(UniformEnvironment{RGB(0.3f, 0.35f, 0.45f)});
    return LightSet(std::move(l), 0, 4.2f, sampler);
  };
  const LightSet bvh = make(LightSamplerType::Bvh), power = make(LightSamplerType::Power);
  const Vec3f up(0, 1, 0), far(3, 0, -3), lit(-1.2f, 0, 0);
  EXPECT_EQ(bvh.pmf(far, up, 0), 0.0f);
  EXPECT_EQ(bvh.pmf(far, up, 1), 1.0f);
  EXPECT_GT(bvh.pmf(lit, up, 0), 0.7f);
  EXPECT_NEAR(bvh.pmf(lit, up, 0) + bvh.pmf(lit, up, 1), 1.0f, 1e-6f);
  EXPECT_LT(power.pmf(lit, up, 0), 0.2f);
  EXPECT_EQ(power.pmf(far, up, 0), power.pmf(lit, up, 0));  // power ignores the point
}

TEST(LightSampler, OneLightNeedsNoChoiceWithEitherSampler) {
  for (const LightSamplerType sampler : {LightSamplerType::Bvh, LightSamplerType::Power}) {
    std::vector<Light> l;
    l.emplace_back(PointLight{Vec3f(0, 1, 0), RGB(1.0f), RGB(), true});
    const LightSet set(std::move(l), 0, 1.0f, sampler);
    EXPECT_FALSE(set.needs_choice());
    float pmf = 0.0f;
    EXPECT_EQ(set.choose(Vec3f(5, 0, 0), Vec3f(0, 1, 0), 0.3f, pmf), 0);
    EXPECT_EQ(pmf, 1.0f);
    EXPECT_EQ(set.pmf(Vec3f(5, 0, 0), Vec3f(0, 1, 0), 0), 1.0f);
  }
}

// LightSet::each_lights (docs/path-tracing.md, "Every infinite light at every
// vertex"): the lights next-event estimation samples each at every vertex are
// a sun and a sky, or a few infinite lights; never where a finite light or one
// light alone is there (one light, an area or point light beside the sky, five
// suns), and lights without power are left out, with either sampler.
TEST(LightSampler, EveryLightIsEstimatedOnlyWhereTheyAreAFewInfiniteOnes) {
  const auto sun = [](float e) { return DirectionalLight{normalize(Vec3f(0.3f, -1, 0.2f)), RGB(e)}; };
  const UniformEnvironment sky{RGB(0.3f, 0.35f, 0.45f)};
  const auto each = [](std::vector<Light> l, LightSamplerType sampler) {
    const LightSet set(std::move(l), 0, 4.0f, sampler);
    const std::span<const int> e = set.each_lights();
    return std::vector<int>(e.begin(), e.end());
  };
  for (const LightSamplerType sampler : {LightSamplerType::Bvh, LightSamplerType::Power}) {
    // The set keeps delta lights first: the sun is light 0, the sky light 1.
    EXPECT_EQ(each({sky, sun(3.0f)}, sampler), (std::vector<int>{0, 1}));
    EXPECT_EQ(each({sun(3.0f), sun(1.0f), sky}, sampler), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(each({sky, sun(3.0f), sun(0.0f)}, sampler), (std::vector<int>{0, 2})) << "a black sun is left out";
    EXPECT_TRUE(each({sky}, sampler).empty()) << "one light: nothing to choose";
    EXPECT_TRUE(each({sun(3.0f)}, sampler).empty());
    EXPECT_TRUE(each({sky, sun(0.0f)}, sampler).empty()) << "one light with power";
    EXPECT_TRUE(each({sun(1.0f), sun(2.0f), sun(3.0f), sun(4.0f), sky}, sampler).empty()) << "more than kMaxEachLights";
    EXPECT_TRUE(each({sky, sun(3.0f), PointLight{Vec3f(0, 1, 0), RGB(1.0f), RGB(), true}}, sampler).empty())
        << "a point light";
    EXPECT_TRUE(each({sky, PointLight{Vec3f(0, 1, 0), RGB(1.0f), RGB(), false}}, sampler).empty())
        << "a point light without falloff is unbounded, not infinite";
  }
  Lights area(LightSamplerType::Bvh);  // area, point and spot lights beside a sun and a sky
  EXPECT_TRUE(area.set.each_lights().empty());
}

// A merged cone holds every direction of both cones it was made from.
TEST(LightBounds, ConeUnionHoldsBothCones) {
  Rng rng(9);
  for (int t = 0; t < 2000; ++t) {
    const DirectionCone a{random_unit(rng), std::cos(rng.next_float() * 1.5f), false};
    const DirectionCone b{random_unit(rng), std::cos(rng.next_float() * 1.5f), false};
    const DirectionCone u = cone_union(a, b);
    for (const DirectionCone& c : {a, b}) {
      // The direction of c farthest from u's axis: c's axis turned away from it by c's angle.
      // The angle between the axes as 2 asin(|a - b| / 2): acos of their dot
      // product is off by up to 5e-4 rad for (nearly) equal float vectors.
      const float axis_angle = 2.0f * std::asin(std::min(1.0f, 0.5f * length(c.w - u.w)));
      const float farthest = axis_angle + std::acos(std::clamp(c.cos_theta, -1.0f, 1.0f));
      if (farthest >= kPi) {
        EXPECT_LE(u.cos_theta, -1.0f + 1e-5f);
      } else {
        EXPECT_LE(u.cos_theta, std::cos(farthest) + 1e-5f) << "trial " << t;
      }
    }
  }
}

// The light BVH's nodes evaluate four children at once (ImportanceBounds4,
// SSE2 where available): each lane must be what ImportanceBounds gives, bit for
// bit, for every kind of bounds (points, one- and two-sided cones, spots' narrow
// emission, empty lanes) at points inside, near and far from them, with and
// without a receiver normal.
TEST(LightBounds, FourLanesAreTheScalarImportanceBitForBit) {
  Rng rng(13);
  int positive = 0, zero = 0;
  for (int t = 0; t < 3000; ++t) {
    ImportanceBounds4 four;
    ImportanceBounds lanes[4];
    for (int k = 0; k < 4; ++k) {
      if (t % 7 == k) continue;  // an empty lane
      LightBounds b;
      const Vec3f c = random_point(rng, 3);
      const float half = (t + k) % 5 == 0 ? 0.0f : rng.next_float();  // a point, or a box
      b.bounds.extend(c - Vec3f(half));
      b.bounds.extend(c + Vec3f(half * rng.next_float()));
      b.intensity = 0.1f + 10.0f * rng.next_float();
      b.normals = (t + k) % 4 == 0 ? DirectionCone::all()
                                   : DirectionCone{random_unit(rng), std::cos(rng.next_float() * 2.5f), false};
      b.cos_theta_e = (t + k) % 3 == 0 ? std::cos(rng.next_float() * 0.5f) : 0.0f;
      b.two_sided = (t + k) % 2 == 0;
      lanes[k] = ImportanceBounds(b);
      four.set(k, lanes[k]);
    }
    const Vec3f p = random_point(rng, 4), n = t % 3 == 0 ? Vec3f() : random_unit(rng);
    alignas(16) float out[4];
    four.importance(p, n, out);
    for (int k = 0; k < 4; ++k) {
      const float expected = lanes[k].importance(p, n);
      EXPECT_EQ(std::bit_cast<uint32_t>(out[k]), std::bit_cast<uint32_t>(expected))
          << "trial " << t << " lane " << k << ": " << out[k] << " against " << expected;
      (expected > 0.0f ? positive : zero) += 1;
    }
  }
  EXPECT_GT(positive, 3000);  // the cases are not all trivial
  EXPECT_GT(zero, 1000);
}

}  // namespace
}  // namespace pt
