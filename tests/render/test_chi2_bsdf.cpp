// Every BSDF's sampling routine against its density (chi-square, chi2.h),
// its weights against f cos / pdf, and energy conservation.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bsdf_test_util.h"
#include "chi2.h"
#include "render/materials/bsdf.h"

namespace pt {
namespace {

using test::DirectionChi2;
using test::direction_at;
using test::flat_surface;

// Chi-square test of Bsdf::sample against Bsdf::pdf for one material and wo.
// Delta samples count as failures (their mass is not in pdf()).
test::Chi2Result bsdf_chi2(const Material& m, Vec3f wo, const Frame& bins, int n_theta) {
  const SurfaceGeometry geo = flat_surface();
  const Bsdf bsdf(m, geo, wo);
  DirectionChi2 t;
  t.bins = bins;
  t.n_theta = n_theta;
  t.n_phi = 2 * n_theta;
  t.sample = [&](float u0, Vec2f u, Vec3f& d) {
    BsdfSample s;
    if (!bsdf.sample(wo, u0, u, s) || s.delta) return false;
    d = s.wi;
    return true;
  };
  t.pdf = [&](Vec3f d) { return bsdf.pdf(wo, d); };
  return t.run();
}

Material blinn_phong(float exponent) {
  Material m;
  m.kd = 0.0f;
  m.ks = 1.0f;
  m.exponent = exponent;
  return m;
}

class BlinnPhongChi2 : public ::testing::TestWithParam<std::tuple<float, float>> {};

TEST_P(BlinnPhongChi2, SamplesMatchPdf) {
  const auto [exponent, theta] = GetParam();
  const Vec3f wo = direction_at(theta);
  const Vec3f mirror(-wo.x, -wo.y, wo.z);
  // Sharp lobes are binned finely across their mirror direction.
  const bool sharp = exponent >= 100.0f;
  const auto r = bsdf_chi2(blinn_phong(exponent), wo, sharp ? test::frame_across(mirror) : Frame(), sharp ? 96 : 32);
  EXPECT_TRUE(r.passed) << "exponent " << exponent << ", theta " << theta << ": " << r.message;
}

INSTANTIATE_TEST_SUITE_P(ExponentsAndAngles, BlinnPhongChi2,
                         ::testing::Combine(::testing::Values(1.0f, 10.0f, 100.0f, 1000.0f),
                                            ::testing::Values(10.0f, 45.0f, 75.0f)));

TEST(BsdfChi2, Lambert) {
  for (float theta : {10.0f, 70.0f}) {
    Material m;
    m.type = MaterialType::Lambert;
    m.diffuse = RGB(0.5f, 0.7f, 0.9f);
    const auto r = bsdf_chi2(m, direction_at(theta), Frame(), 32);
    EXPECT_TRUE(r.passed) << "theta " << theta << ": " << r.message;
  }
}

TEST(BsdfChi2, PhongMixtureWithMirrorLobe) {
  // Diffuse + glossy chosen by weight; the mirror lobe's delta samples are
  // excluded from the test and from pdf() alike.
  Material m;
  m.kd = 0.6f;
  m.diffuse = RGB(0.5f, 0.6f, 0.7f);
  m.ks = 0.4f;
  m.exponent = 20.0f;
  for (float reflectivity : {0.0f, 0.3f}) {
    m.reflectivity = reflectivity;
    const auto r = bsdf_chi2(m, direction_at(40.0f), Frame(), 32);
    EXPECT_TRUE(r.passed) << "reflectivity " << reflectivity << ": " << r.message;
  }
}

TEST(Bsdf, SampleWeightIsFCosOverPdf) {
  Material m;
  m.kd = 0.7f;
  m.ks = 0.6f;  // kd + ks > 1: scaled down
  m.exponent = 30.0f;
  const SurfaceGeometry geo = flat_surface();
  Rng rng(11);
  for (float theta : {5.0f, 50.0f, 85.0f}) {
    const Vec3f wo = direction_at(theta);
    const Bsdf bsdf(m, geo, wo);
    for (int i = 0; i < 2000; ++i) {
      BsdfSample s;
      const float ul = rng.next_float();
      const Vec2f u(rng.next_float(), rng.next_float());
      if (!bsdf.sample(wo, ul, u, s)) continue;
      ASSERT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-4f * s.pdf);
      const RGB expected = bsdf.f(wo, s.wi) * (s.wi.z / s.pdf);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], expected[c], 1e-4f * (1.0f + expected[c]));
    }
  }
}

// Monte Carlo estimate of the directional albedo: the mean sample weight.
double albedo(const Material& m, Vec3f wo, int n, double* stddev) {
  const SurfaceGeometry geo = flat_surface();
  const Bsdf bsdf(m, geo, wo);
  Rng rng(5);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    const float ul = rng.next_float();
    const Vec2f u(rng.next_float(), rng.next_float());
    double w = 0.0;
    if (bsdf.sample(wo, ul, u, s)) w = s.weight.max_component();
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n;
  *stddev = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  return mean;
}

TEST(Bsdf, NormalisedBlinnPhongNeverReflectsMoreThanItReceives) {
  // Every sample weight is at most 1 (the lobe's construction), so the albedo
  // is at most 1; at normal incidence a sharp lobe reflects nearly everything.
  for (float exponent : {0.0f, 1.0f, 10.0f, 100.0f, 1000.0f, 100000.0f}) {
    for (float theta : {0.0f, 30.0f, 60.0f, 85.0f, 89.5f}) {
      double sd = 0.0;
      const double a = albedo(blinn_phong(exponent), direction_at(theta), 20000, &sd);
      EXPECT_LE(a, 1.0) << "exponent " << exponent << ", theta " << theta;
      if (exponent >= 1000.0f && theta <= 30.0f) {
        EXPECT_GT(a, 0.97) << "exponent " << exponent;
      }
    }
  }
}

TEST(Bsdf, CourseMaterialWithKdPlusKsAboveOneIsScaled) {
  Material m;
  m.kd = 0.9f;
  m.diffuse = RGB(1.0f);
  m.ks = 0.9f;
  m.exponent = 5.0f;
  for (float theta : {0.0f, 45.0f, 80.0f}) {
    double sd = 0.0;
    const double a = albedo(m, direction_at(theta), 40000, &sd);
    EXPECT_LE(a, 1.0 + 4.0 * sd) << "theta " << theta;
  }
}

TEST(Bsdf, LambertAlbedoIsExact) {
  Material m;
  m.type = MaterialType::Lambert;
  m.diffuse = RGB(0.25f, 0.5f, 0.75f);
  const SurfaceGeometry geo = flat_surface();
  const Bsdf bsdf(m, geo, direction_at(30.0f));
  BsdfSample s;
  ASSERT_TRUE(bsdf.sample(direction_at(30.0f), 0.3f, Vec2f(0.2f, 0.7f), s));
  EXPECT_NEAR(s.weight.r, 0.25f, 1e-6f);
  EXPECT_NEAR(s.weight.b, 0.75f, 1e-6f);
}

// The path integrator draws the lobe-choice number only where
// needs_lobe_choice() says so; where it does not, sample() must not read it
// (any u_lobe gives the same sample), and where there are two lobes it must.
TEST(Bsdf, LobeChoiceIsDrawnOnlyWhereThereIsAChoice) {
  const SurfaceGeometry geo = flat_surface();
  const Vec3f wo = direction_at(30.0f);
  const Vec2f u(0.2f, 0.7f);
  const auto sample_with = [&](const Bsdf& bsdf, float u_lobe) {
    BsdfSample s;
    EXPECT_TRUE(bsdf.sample(wo, u_lobe, u, s));
    return s;
  };
  Material lambert;
  lambert.type = MaterialType::Lambert;
  Material glossy = lambert;  // Phong with its specular lobe alone
  glossy.type = MaterialType::Phong;
  glossy.kd = 0.0f;
  glossy.ks = 0.8f;
  glossy.exponent = 20.0f;
  Material mirror;
  mirror.type = MaterialType::Mirror;
  for (const Material* m : {&lambert, &glossy, &mirror}) {
    const Bsdf bsdf(*m, geo, wo);
    EXPECT_FALSE(bsdf.needs_lobe_choice()) << static_cast<int>(m->type);
    const BsdfSample a = sample_with(bsdf, 0.0f), b = sample_with(bsdf, 0.999f);
    EXPECT_EQ(a.wi, b.wi);
    EXPECT_EQ(a.weight, b.weight);
  }
  Material phong = glossy;  // diffuse and specular lobes
  phong.kd = 0.5f;
  phong.ks = 0.5f;
  Material glass;
  glass.type = MaterialType::Glass;
  glass.ior = 1.5f;
  for (const Material* m : {&phong, &glass}) {
    const Bsdf bsdf(*m, geo, wo);
    EXPECT_TRUE(bsdf.needs_lobe_choice()) << static_cast<int>(m->type);
    EXPECT_FALSE(sample_with(bsdf, 0.0f).wi == sample_with(bsdf, 0.999f).wi) << static_cast<int>(m->type);
  }
}

TEST(Bsdf, MirrorReflectsExactlyWithTint) {
  Material m;
  m.type = MaterialType::Mirror;
  m.specular = RGB(0.9f, 0.5f, 0.1f);
  const SurfaceGeometry geo = flat_surface();
  const Vec3f wo = normalize(Vec3f(0.3f, -0.4f, 0.8f));
  const Bsdf bsdf(m, geo, wo);
  EXPECT_TRUE(bsdf.delta_only());
  BsdfSample s;
  ASSERT_TRUE(bsdf.sample(wo, 0.5f, Vec2f(0.1f, 0.9f), s));
  EXPECT_TRUE(s.delta);
  EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(s.wi.y, -wo.y, 1e-6f);
  EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
  EXPECT_EQ(s.weight, m.specular);
  EXPECT_EQ(bsdf.f(wo, s.wi), RGB());
}

TEST(Bsdf, BackFacesReflectOnTheViewersSide) {
  Material m;
  m.type = MaterialType::Lambert;
  m.diffuse = RGB(0.5f);
  const SurfaceGeometry geo = flat_surface();
  const Vec3f wo(0.0f, 0.0f, -1.0f);  // seen from below
  const Bsdf bsdf(m, geo, wo);
  BsdfSample s;
  ASSERT_TRUE(bsdf.sample(wo, 0.5f, Vec2f(0.3f, 0.3f), s));
  EXPECT_LT(s.wi.z, 0.0f);
  EXPECT_EQ(bsdf.f(wo, Vec3f(0, 0, 1)), RGB());  // no light through the surface
}

// ---------------------------------------------------------------- glass
struct GlassCase {
  float theta;     // angle of wo from +z (> 90: from inside)
  float ior;
};

class GlassSampling : public ::testing::TestWithParam<GlassCase> {};

TEST_P(GlassSampling, ReflectsWithProbabilityFresnelAndRefractsBySnell) {
  const GlassCase c = GetParam();
  Material m;
  m.type = MaterialType::Glass;
  m.ior = c.ior;
  const SurfaceGeometry geo = flat_surface();
  const Vec3f wo = direction_at(c.theta);
  const Bsdf bsdf(m, geo, wo);
  ASSERT_TRUE(bsdf.delta_only());
  const bool entering = wo.z > 0.0f;
  const float eta_i = entering ? 1.0f : c.ior, eta_t = entering ? c.ior : 1.0f;
  const float F = fresnel_dielectric(std::fabs(wo.z), eta_i, eta_t);
  Rng rng(17);
  const int n = 200000;
  std::vector<double> observed(2, 0.0);
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    ASSERT_TRUE(bsdf.sample(wo, rng.next_float(), Vec2f(0.5f, 0.5f), s));
    ASSERT_TRUE(s.delta);
    const bool reflected = (s.wi.z > 0.0f) == (wo.z > 0.0f);
    if (reflected) {
      ASSERT_NEAR(s.wi.x, -wo.x, 1e-5f);
      ASSERT_NEAR(s.wi.z, wo.z, 1e-5f);
      ASSERT_NEAR(s.weight.r, 1.0f, 1e-6f);
    } else {
      // Snell: eta_i sin_i = eta_t sin_t, in the plane of incidence, on the far side.
      const float sin_i = std::sqrt(std::max(0.0f, 1.0f - wo.z * wo.z));
      const float sin_t = std::sqrt(std::max(0.0f, 1.0f - s.wi.z * s.wi.z));
      ASSERT_NEAR(eta_i * sin_i, eta_t * sin_t, 1e-5f);
      ASSERT_NEAR(s.wi.y, 0.0f, 1e-6f);
      ASSERT_LT(s.wi.x * wo.x, 1e-7f);
      // Radiance is scaled by (eta_i / eta_t)^2 going into the denser medium.
      ASSERT_NEAR(s.weight.r, (eta_i / eta_t) * (eta_i / eta_t), 1e-5f);
    }
    observed[reflected ? 0 : 1] += 1.0;
  }
  if (F >= 1.0f) {
    EXPECT_EQ(observed[1], 0.0) << "total internal reflection must reflect everything";
    return;
  }
  const std::vector<double> expected = {n * F, n * (1.0 - F)};
  const auto r = test::chi2_gof(observed, expected, test::chi2_significance(), 0.0);
  // One degree of freedom: chi2_gof needs two bins with non-zero expectation.
  EXPECT_TRUE(r.passed) << "theta " << c.theta << ", F " << F << ": " << r.message;
}

INSTANTIATE_TEST_SUITE_P(AnglesAndSides, GlassSampling,
                         ::testing::Values(GlassCase{0.0f, 1.5f}, GlassCase{30.0f, 1.5f}, GlassCase{80.0f, 1.5f},
                                           GlassCase{150.0f, 1.5f},   // inside, 30 deg: refracts out
                                           GlassCase{130.0f, 1.5f},   // inside, 50 deg: beyond critical (41.8)
                                           GlassCase{40.0f, 2.4f}));

TEST(Glass, IndexOneIsTransparent) {
  Material m;
  m.type = MaterialType::Glass;
  m.ior = 1.0f;
  const SurfaceGeometry geo = flat_surface();
  for (float theta : {0.0f, 45.0f, 89.0f, 120.0f}) {
    const Vec3f wo = direction_at(theta);
    const Bsdf bsdf(m, geo, wo);
    BsdfSample s;
    ASSERT_TRUE(bsdf.sample(wo, 0.0f, Vec2f(), s));  // u = 0: reflection would be chosen if F > 0
    EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
    EXPECT_NEAR(s.wi.z, -wo.z, 1e-6f);
    EXPECT_EQ(s.weight, RGB(1.0f));
  }
}

}  // namespace
}  // namespace pt
