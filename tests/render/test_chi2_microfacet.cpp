// The microfacet BSDFs (conductor, rough dielectric, coated diffuse, glTF's
// metallic-roughness blend of the first and the last):
// sampling against the density (chi-square, chi2.h) over roughness 0.05 to 1
// and several angles, sample weights against f cos / pdf, reciprocity,
// energy (albedo <= 1, furnace), the GGX distribution's own normalisation,
// and the exact smooth limits (roughness 0 is the mirror and the glass).
#include <cmath>
#include <cstring>
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

// alpha_x, alpha_y given directly (remaproughness off).
Material microfacet(MaterialType type, float ax, float ay) {
  Material m;
  m.type = type;
  m.remap_roughness = false;
  m.uroughness.value = ax;
  m.vroughness.value = ay;
  m.ior = 1.5f;
  return m;
}

Material conductor(float ax, float ay) {
  Material m = microfacet(MaterialType::Conductor, ax, ay);
  m.eta.value = RGB(0.2f, 0.9f, 1.1f);  // copper-like
  m.k.value = RGB(3.9f, 2.4f, 2.1f);
  return m;
}

Material white_conductor(float ax, float ay) {  // F = 1
  Material m = microfacet(MaterialType::Conductor, ax, ay);
  m.schlick = true;
  m.reflectance.value = RGB(1.0f);
  return m;
}

const CoatingTable& coating_15() {
  static const CoatingTable table(1.5f);
  return table;
}

Material coated(float ax, float ay, RGB albedo = RGB(0.6f, 0.4f, 0.2f)) {
  Material m = microfacet(MaterialType::CoatedDiffuse, ax, ay);
  m.reflectance.value = albedo;
  m.coating = &coating_15();
  return m;
}

// glTF's metallic-roughness: base colour `base`, the blend `metallic`.
Material metallic_roughness(float alpha, float metallic, RGB base = RGB(0.9f, 0.6f, 0.3f)) {
  Material m = microfacet(MaterialType::MetallicRoughness, alpha, alpha);
  m.reflectance.value = base;
  m.metallic.value = metallic;
  m.coating = &coating_15();
  return m;
}

// Chi-square of Bsdf::sample against Bsdf::pdf; delta samples are failures
// (their mass is not in pdf()). Sharp lobes are binned across their peak.
test::Chi2Result bsdf_chi2(const Material& m, Vec3f wo, Vec3f peak, bool sharp) {
  const SurfaceGeometry geo = flat_surface();
  const Bsdf bsdf(m, geo, wo);
  DirectionChi2 t;
  t.bins = sharp ? test::frame_across(peak) : Frame();
  t.n_theta = sharp ? 48 : 16;
  t.n_phi = 2 * t.n_theta;
  t.samples = 200000;
  t.quadrature_depth = 6;
  t.sample = [&](float u0, Vec2f u, Vec3f& d) {
    BsdfSample s;
    if (!bsdf.sample(wo, u0, u, s) || s.delta) return false;
    d = s.wi;
    return true;
  };
  t.pdf = [&](Vec3f d) { return bsdf.pdf(wo, d); };
  return t.run();
}

Vec3f mirror_of(Vec3f wo) { return {-wo.x, -wo.y, wo.z}; }

struct Chi2Case {
  float alpha;
  float theta;
};

void PrintTo(const Chi2Case& c, std::ostream* os) { *os << "alpha " << c.alpha << ", theta " << c.theta; }

class ConductorChi2 : public ::testing::TestWithParam<Chi2Case> {};

TEST_P(ConductorChi2, SamplesMatchPdf) {
  const Chi2Case c = GetParam();
  const Vec3f wo = direction_at(c.theta, 30.0f);
  const auto r = bsdf_chi2(conductor(c.alpha, c.alpha), wo, mirror_of(wo), c.alpha < 0.1f);
  EXPECT_TRUE(r.passed) << r.message;
}

INSTANTIATE_TEST_SUITE_P(RoughnessAndAngles, ConductorChi2,
                         ::testing::Values(Chi2Case{0.05f, 20.0f}, Chi2Case{0.05f, 70.0f}, Chi2Case{0.3f, 20.0f},
                                           Chi2Case{0.3f, 70.0f}, Chi2Case{1.0f, 45.0f}, Chi2Case{1.0f, 85.0f}));

TEST(ConductorChi2, Anisotropic) {
  for (const float phi : {0.0f, 60.0f}) {
    const Vec3f wo = direction_at(50.0f, phi);
    const auto r = bsdf_chi2(conductor(0.08f, 0.5f), wo, mirror_of(wo), false);
    EXPECT_TRUE(r.passed) << "phi " << phi << ": " << r.message;
  }
}

class DielectricChi2 : public ::testing::TestWithParam<Chi2Case> {};

TEST_P(DielectricChi2, SamplesMatchPdf) {
  const Chi2Case c = GetParam();
  const Vec3f wo = direction_at(c.theta, 30.0f);
  // Sharp lobes are binned finely across the straight-through direction, near
  // which the refracted peak lies (the reflected one is still tested).
  const auto r = bsdf_chi2(microfacet(MaterialType::Dielectric, c.alpha, c.alpha), wo, -wo, c.alpha < 0.1f);
  EXPECT_TRUE(r.passed) << r.message;
}

// theta > 90: from inside the medium (120: refracts out; 140: beyond the critical angle).
INSTANTIATE_TEST_SUITE_P(RoughnessAndAngles, DielectricChi2,
                         ::testing::Values(Chi2Case{0.05f, 30.0f}, Chi2Case{0.3f, 30.0f}, Chi2Case{0.3f, 75.0f},
                                           Chi2Case{1.0f, 60.0f}, Chi2Case{0.3f, 160.0f}, Chi2Case{0.3f, 140.0f},
                                           Chi2Case{1.0f, 120.0f}));

TEST(DielectricChi2, Anisotropic) {
  const Vec3f wo = direction_at(40.0f, 20.0f);
  const auto r = bsdf_chi2(microfacet(MaterialType::Dielectric, 0.5f, 0.1f), wo, -wo, false);
  EXPECT_TRUE(r.passed) << r.message;
}

class CoatedChi2 : public ::testing::TestWithParam<Chi2Case> {};

TEST_P(CoatedChi2, SamplesMatchPdf) {
  const Chi2Case c = GetParam();
  const Vec3f wo = direction_at(c.theta, 30.0f);
  const auto r = bsdf_chi2(coated(c.alpha, c.alpha), wo, mirror_of(wo), false);
  EXPECT_TRUE(r.passed) << r.message;
}

INSTANTIATE_TEST_SUITE_P(RoughnessAndAngles, CoatedChi2,
                         ::testing::Values(Chi2Case{0.05f, 30.0f}, Chi2Case{0.3f, 30.0f}, Chi2Case{0.3f, 75.0f},
                                           Chi2Case{1.0f, 60.0f}, Chi2Case{0.0f, 45.0f}));

class MetallicRoughnessChi2 : public ::testing::TestWithParam<Chi2Case> {};

TEST_P(MetallicRoughnessChi2, SamplesMatchPdf) {
  const Chi2Case c = GetParam();
  const Vec3f wo = direction_at(c.theta, 30.0f);
  const auto r = bsdf_chi2(metallic_roughness(c.alpha, 0.5f), wo, mirror_of(wo), c.alpha > 0.0f && c.alpha < 0.1f);
  EXPECT_TRUE(r.passed) << r.message;
}

// Alpha 0: both reflections are delta lobes (not binned), the base's diffuse lobe is.
INSTANTIATE_TEST_SUITE_P(RoughnessAndAngles, MetallicRoughnessChi2,
                         ::testing::Values(Chi2Case{0.05f, 30.0f}, Chi2Case{0.3f, 30.0f}, Chi2Case{0.3f, 75.0f},
                                           Chi2Case{1.0f, 60.0f}, Chi2Case{0.0f, 45.0f}));

// ---------------------------------------------------------------- weights and reciprocity
// Every sample: pdf() gives its density and its weight is f |cos| / pdf
// (times the refraction scale for transmission, which f includes).
void expect_consistent_samples(const Material& m, const char* what) {
  const SurfaceGeometry geo = flat_surface();
  Rng rng(23);
  for (const float theta : {10.0f, 50.0f, 80.0f, 130.0f}) {
    const Vec3f wo = direction_at(theta, 15.0f);
    const Bsdf bsdf(m, geo, wo);
    int good = 0;
    for (int i = 0; i < 3000; ++i) {
      BsdfSample s;
      const float ul = rng.next_float();
      const Vec2f u(rng.next_float(), rng.next_float());
      if (!bsdf.sample(wo, ul, u, s) || s.delta) continue;
      ++good;
      ASSERT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 2e-3f * s.pdf) << what << ", theta " << theta;
      const RGB expected = bsdf.f(wo, s.wi) * (std::fabs(s.wi.z) / s.pdf);
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(s.weight[c], expected[c], 2e-3f * (1.0f + expected[c])) << what << ", theta " << theta;
    }
    if (theta < 90.0f) {
      EXPECT_GT(good, 1000) << what << ", theta " << theta;
    }
  }
}

TEST(Microfacet, SampleWeightIsFCosOverPdf) {
  expect_consistent_samples(conductor(0.3f, 0.3f), "conductor");
  expect_consistent_samples(conductor(0.05f, 0.7f), "anisotropic conductor");
  expect_consistent_samples(microfacet(MaterialType::Dielectric, 0.3f, 0.3f), "dielectric");
  expect_consistent_samples(microfacet(MaterialType::Dielectric, 0.8f, 0.2f), "anisotropic dielectric");
  Material tinted = microfacet(MaterialType::Dielectric, 0.3f, 0.3f);
  tinted.transmittance = RGB(0.2f, 0.6f, 1.0f);
  expect_consistent_samples(tinted, "tinted dielectric");
  expect_consistent_samples(coated(0.2f, 0.2f), "coated diffuse");
  expect_consistent_samples(metallic_roughness(0.2f, 0.5f), "metallic-roughness");
  expect_consistent_samples(metallic_roughness(0.05f, 0.1f), "metallic-roughness, sharp, mostly dielectric");
  expect_consistent_samples(metallic_roughness(0.6f, 0.9f), "metallic-roughness, rough, mostly metal");
}

// f(wo, wi) = f(wi, wo) for reflection; for refraction the radiance BTDF obeys
// f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2 (eta_o, eta_i: the indices on wo's
// and wi's sides; Veach 1997, 5.2).
TEST(Microfacet, Reciprocity) {
  const SurfaceGeometry geo = flat_surface();
  Rng rng(31);
  const Material materials[] = {conductor(0.2f, 0.6f), microfacet(MaterialType::Dielectric, 0.3f, 0.5f),
                                coated(0.4f, 0.4f), metallic_roughness(0.4f, 0.5f)};
  for (const Material& m : materials) {
    int checked = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3f a = sample_uniform_sphere(Vec2f(rng.next_float(), rng.next_float()));
      const Vec3f b = sample_uniform_sphere(Vec2f(rng.next_float(), rng.next_float()));
      const float eta_a = a.z > 0.0f ? 1.0f : m.ior, eta_b = b.z > 0.0f ? 1.0f : m.ior;
      if (!m.glass() && (a.z < 0.0f || b.z < 0.0f)) continue;
      const RGB fab = Bsdf(m, geo, a).f(a, b), fba = Bsdf(m, geo, b).f(b, a);
      const float lhs = fab.g / (eta_a * eta_a), rhs = fba.g / (eta_b * eta_b);
      ASSERT_NEAR(lhs, rhs, 1e-3f * (lhs + rhs) + 1e-6f) << static_cast<int>(m.type) << " a.z " << a.z << " b.z " << b.z;
      if (fab.g > 0.0f) ++checked;
    }
    EXPECT_GT(checked, 500) << static_cast<int>(m.type);
  }
}

// ---------------------------------------------------------------- energy
// Monte Carlo directional albedo: the mean sample weight, the refraction
// scale undone (s.eta2), so it is the fraction of energy scattered.
double albedo(const Material& m, Vec3f wo, int n, double* stddev, int channel = 1) {
  const SurfaceGeometry geo = flat_surface();
  const Bsdf bsdf(m, geo, wo);
  Rng rng(5);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    const float ul = rng.next_float();
    const Vec2f u(rng.next_float(), rng.next_float());
    double w = 0.0;
    if (bsdf.sample(wo, ul, u, s)) w = s.weight[channel] * s.eta2;
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n;
  *stddev = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  return mean;
}

TEST(Microfacet, AlbedoNeverExceedsOne) {
  for (const float alpha : {0.05f, 0.2f, 0.5f, 1.0f}) {
    for (const float theta : {0.0f, 45.0f, 75.0f, 89.0f}) {
      const Vec3f wo = direction_at(theta);
      for (const Material& m : {white_conductor(alpha, alpha), microfacet(MaterialType::Dielectric, alpha, alpha),
                                coated(alpha, alpha, RGB(1.0f)), metallic_roughness(alpha, 0.5f, RGB(1.0f))}) {
        double sd = 0.0;
        const double a = albedo(m, wo, 20000, &sd);
        EXPECT_LE(a, 1.0 + 4.0 * sd + 2e-3) << static_cast<int>(m.type) << " alpha " << alpha << " theta " << theta;
      }
    }
  }
}

// A transmittance (MTL's Tf) scales the transmitted energy, not the reflected.
TEST(Microfacet, TransmittanceTintsOnlyTheTransmission) {
  Material clear = microfacet(MaterialType::Dielectric, 0.3f, 0.3f), tinted = clear;
  tinted.transmittance = RGB(0.5f, 1.0f, 1.0f);
  const SurfaceGeometry geo = flat_surface();
  const Vec3f wo = direction_at(30.0f);
  Rng rng(13);
  for (int i = 0; i < 500; ++i) {
    const Vec3f wi = sample_uniform_sphere(Vec2f(rng.next_float(), rng.next_float()));
    const RGB a = Bsdf(clear, geo, wo).f(wo, wi), b = Bsdf(tinted, geo, wo).f(wo, wi);
    ASSERT_FLOAT_EQ(b.g, a.g);
    ASSERT_FLOAT_EQ(b.r, wi.z < 0.0f ? 0.5f * a.r : a.r);
  }
}

TEST(Microfacet, AlbedoOfTheRoughestMetalHasAClosedForm) {
  // alpha = 1, F = 1, normal incidence: D = 1 / pi, the visible normals are
  // cosine-distributed, a normal at theta_m reflects to cos_i = cos 2 theta_m
  // (below the horizon beyond 45 degrees) with G / G1 = 2 cos_i / (1 + cos_i);
  // with x = sin^2 theta_m, E = integral over [0, 1/2] of (1 - 2x) / (1 - x) dx
  // = 1 - ln 2. (docs/path-tracing.md, "Energy of single scattering".)
  double sd = 0.0;
  const double a = albedo(white_conductor(1.0f, 1.0f), Vec3f(0, 0, 1), 200000, &sd);
  EXPECT_NEAR(a, 1.0 - std::log(2.0), 4.0 * sd);
  EXPECT_LT(sd, 2e-3);
}

TEST(Microfacet, SmoothishSurfacesKeepAlmostAllEnergy) {
  // Single scattering loses energy only where microfacets shadow each other.
  double sd = 0.0;
  EXPECT_GT(albedo(white_conductor(0.05f, 0.05f), direction_at(30.0f), 20000, &sd), 0.99);
  EXPECT_GT(albedo(microfacet(MaterialType::Dielectric, 0.05f, 0.05f), direction_at(30.0f), 20000, &sd), 0.99);
  // A white base under a smooth coating keeps everything (E + T = 1).
  EXPECT_NEAR(albedo(coated(0.0f, 0.0f, RGB(1.0f)), direction_at(30.0f), 40000, &sd), 1.0, 4.0 * sd + 2e-3);
  // The white furnace of metallic-roughness: a white base (F0 1 for the metal) keeps everything, smooth, at any blend.
  for (const float metallic : {0.25f, 0.5f, 0.9f}) {
    const double a = albedo(metallic_roughness(0.0f, metallic, RGB(1.0f)), direction_at(30.0f), 40000, &sd);
    EXPECT_NEAR(a, 1.0, 4.0 * sd + 2e-3) << metallic;
  }
}

bool same_sample(const BsdfSample& a, const BsdfSample& b);

// ---------------------------------------------------------------- metallic-roughness
// glTF's mix(dielectric, metal, metallic): f and the albedo are the blend of
// the coated diffuse's and the Schlick conductor's, at every pair of directions.
TEST(MetallicRoughness, IsTheBlendOfTheCoatedDiffuseAndTheConductor) {
  const SurfaceGeometry geo = flat_surface();
  const RGB base(0.9f, 0.6f, 0.3f);
  Material metal = white_conductor(0.3f, 0.3f);
  metal.reflectance.value = base;
  const Material dielectric = coated(0.3f, 0.3f, base);
  Rng rng(41);
  int checked = 0;
  for (const float metallic : {0.2f, 0.5f, 0.8f}) {
    const Material m = metallic_roughness(0.3f, metallic, base);
    for (int i = 0; i < 2000; ++i) {
      const Vec3f wo = sample_uniform_hemisphere(Vec2f(rng.next_float(), rng.next_float()));
      const Vec3f wi = sample_uniform_hemisphere(Vec2f(rng.next_float(), rng.next_float()));
      const RGB f = Bsdf(m, geo, wo).f(wo, wi);
      const RGB expected = Bsdf(metal, geo, wo).f(wo, wi) * metallic + Bsdf(dielectric, geo, wo).f(wo, wi) * (1.0f - metallic);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(f[c], expected[c], 1e-5f * (1.0f + expected[c])) << metallic;
      const RGB fd = Bsdf(m, geo, wo).f_diffuse(wo, wi);
      ASSERT_NEAR(fd.g, Bsdf(dielectric, geo, wo).f_diffuse(wo, wi).g * (1.0f - metallic), 1e-6f);
      checked += f.g > 0.0f;
    }
    // The albedo is the blend of the albedos (each estimated by its own sampling).
    for (const float theta : {20.0f, 70.0f}) {
      double sd_m = 0, sd_a = 0, sd_b = 0;
      const Vec3f wo = direction_at(theta);
      const double a = albedo(m, wo, 40000, &sd_m);
      const double expected = metallic * albedo(metal, wo, 40000, &sd_a) + (1.0f - metallic) * albedo(dielectric, wo, 40000, &sd_b);
      EXPECT_NEAR(a, expected, 4.0 * std::sqrt(sd_m * sd_m + sd_a * sd_a + sd_b * sd_b)) << metallic << " " << theta;
    }
  }
  EXPECT_GT(checked, 5000);
}

// At metallic 0 and 1 the material is the coated diffuse and the Schlick
// conductor themselves: the same kind, the same samples bit for bit.
TEST(MetallicRoughness, MetallicZeroAndOneAreExactlyTheCoatedDiffuseAndTheConductor) {
  const SurfaceGeometry geo = flat_surface();
  const RGB base(0.7f, 0.5f, 0.2f);
  for (const float alpha : {0.0f, 0.3f}) {
    Material metal = white_conductor(alpha, alpha);
    metal.reflectance.value = base;
    const Material pairs[2][2] = {{metallic_roughness(alpha, 0.0f, base), coated(alpha, alpha, base)},
                                  {metallic_roughness(alpha, 1.0f, base), metal}};
    Rng rng(9);
    for (const auto& pair : pairs) {
      for (int i = 0; i < 1000; ++i) {
        const Vec3f wo = sample_uniform_hemisphere(Vec2f(rng.next_float(), rng.next_float()));
        const Vec3f wi = sample_uniform_hemisphere(Vec2f(rng.next_float(), rng.next_float()));
        const float ul = rng.next_float();
        const Vec2f u(rng.next_float(), rng.next_float());
        const Bsdf a(pair[0], geo, wo), b(pair[1], geo, wo);
        ASSERT_EQ(a.needs_lobe_choice(), b.needs_lobe_choice());
        ASSERT_EQ(a.delta_only(), b.delta_only());
        ASSERT_EQ(a.f(wo, wi), b.f(wo, wi));
        ASSERT_EQ(a.pdf(wo, wi), b.pdf(wo, wi));
        BsdfSample sa, sb;
        ASSERT_EQ(a.sample(wo, ul, u, sa), b.sample(wo, ul, u, sb));
        ASSERT_TRUE(same_sample(sa, sb));
      }
    }
    EXPECT_EQ(metallic_roughness(alpha, 1.0f, base).albedo_at({}), base);
  }
}

TEST(Microfacet, TheVisibleNormalDensityIsNormalised) {
  // The projected area of the microfacets is the macro surface's:
  // integral of D(m) m.z dm = 1, and integral of D_wo(m) dm = 1.
  for (const auto& [ax, ay] : {std::pair{0.05f, 0.05f}, std::pair{0.3f, 0.3f}, std::pair{1.0f, 1.0f},
                              std::pair{0.1f, 0.7f}}) {
    const TrowbridgeReitz d(ax, ay);
    const Vec3f wo = direction_at(60.0f, 20.0f);
    const auto projected = [&](double c, double phi) {
      const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
      const Vec3f m(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                    static_cast<float>(c));
      return static_cast<double>(d.D(m) * m.z);
    };
    const auto visible = [&](double c, double phi) {
      const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
      const Vec3f m(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                    static_cast<float>(c));
      return static_cast<double>(d.visible_D(wo, m));
    };
    // Split at cos theta = 0.9 and 0.99 where sharp distributions live.
    double a = 0.0, b = 0.0;
    for (const auto& [c0, c1] : {std::pair{0.0, 0.9}, std::pair{0.9, 0.99}, std::pair{0.99, 1.0}}) {
      a += test::integrate_2d(projected, c0, c1, 0.0, 2.0 * M_PI, 1e-7, 10);
      b += test::integrate_2d(visible, c0, c1, 0.0, 2.0 * M_PI, 1e-7, 10);
    }
    EXPECT_NEAR(a, 1.0, 2e-3) << ax << " " << ay;
    EXPECT_NEAR(b, 1.0, 2e-3) << ax << " " << ay;
  }
}

// ---------------------------------------------------------------- smooth limits
bool same_sample(const BsdfSample& a, const BsdfSample& b) {
  return std::memcmp(&a.wi, &b.wi, sizeof(Vec3f)) == 0 && a.weight == b.weight && a.pdf == b.pdf &&
         a.delta == b.delta && a.eta2 == b.eta2;
}

TEST(Microfacet, RoughnessZeroIsExactlyTheGlass) {
  Material glass;
  glass.type = MaterialType::Glass;
  glass.ior = 1.5f;
  Material dielectric = microfacet(MaterialType::Dielectric, 0.0f, 0.0f);
  dielectric.remap_roughness = true;
  const SurfaceGeometry geo = flat_surface();
  Rng rng(3);
  for (int i = 0; i < 2000; ++i) {
    const Vec3f wo = sample_uniform_sphere(Vec2f(rng.next_float(), rng.next_float()));
    const float ul = rng.next_float();
    const Vec2f u(rng.next_float(), rng.next_float());
    const Bsdf a(glass, geo, wo), b(dielectric, geo, wo);
    ASSERT_TRUE(b.delta_only());
    ASSERT_EQ(a.needs_lobe_choice(), b.needs_lobe_choice());
    BsdfSample sa, sb;
    ASSERT_EQ(a.sample(wo, ul, u, sa), b.sample(wo, ul, u, sb));
    ASSERT_TRUE(same_sample(sa, sb));
  }
}

TEST(Microfacet, RoughnessZeroIsExactlyTheMirror) {
  Material mirror;
  mirror.type = MaterialType::Mirror;
  const Material metal = white_conductor(0.0f, 0.0f);
  const SurfaceGeometry geo = flat_surface();
  Rng rng(4);
  for (int i = 0; i < 2000; ++i) {
    const Vec3f wo = sample_uniform_sphere(Vec2f(rng.next_float(), rng.next_float()));
    const float ul = rng.next_float();
    const Vec2f u(rng.next_float(), rng.next_float());
    const Bsdf a(mirror, geo, wo), b(metal, geo, wo);
    ASSERT_TRUE(b.delta_only());
    ASSERT_EQ(a.needs_lobe_choice(), b.needs_lobe_choice());
    BsdfSample sa, sb;
    ASSERT_EQ(a.sample(wo, ul, u, sa), b.sample(wo, ul, u, sb));
    ASSERT_TRUE(same_sample(sa, sb));
  }
  // A smooth conductor of complex index reflects F(cos) of it.
  const Vec3f wo = direction_at(60.0f);
  BsdfSample s;
  ASSERT_TRUE(Bsdf(conductor(0.0f, 0.0f), geo, wo).sample(wo, 0.5f, Vec2f(0.5f, 0.5f), s));
  EXPECT_TRUE(s.delta);
  EXPECT_EQ(s.weight, fresnel_conductor(wo.z, RGB(0.2f, 0.9f, 1.1f), RGB(3.9f, 2.4f, 2.1f)));
}

TEST(Microfacet, FresnelOfAConductor) {
  // Normal incidence: ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2); grazing: 1.
  EXPECT_NEAR(fresnel_conductor(1.0f, 0.2f, 3.9f), (0.64f + 15.21f) / (1.44f + 15.21f), 1e-5f);
  EXPECT_NEAR(fresnel_conductor(0.0f, 0.2f, 3.9f), 1.0f, 1e-5f);
  // k = 0 is a dielectric of index eta.
  for (const float c : {0.1f, 0.5f, 0.9f}) EXPECT_NEAR(fresnel_conductor(c, 1.5f, 0.0f), fresnel_dielectric(c, 1.0f, 1.5f), 1e-5f);
  EXPECT_EQ(fresnel_schlick(0.3f, RGB(1.0f)), RGB(1.0f));
}

}  // namespace
}  // namespace pt
