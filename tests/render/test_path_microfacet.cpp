// The microfacet materials in the path integrator: white furnaces (a surface
// never returns more than it receives; single scattering loses energy only
// where the BSDF test says), and roughness 0 renders exactly the smooth glass
// and mirror. The strategies' agreement is in test_path_agreement.cpp.
#include <cstring>

#include <gtest/gtest.h>

#include "path_test_util.h"

namespace pt {
namespace {

using test::add_material;
using test::add_sphere;

MaterialDesc microfacet(MaterialType type, float alpha) { return test::microfacet_desc(type, alpha, alpha); }

MaterialDesc white_conductor(float alpha) {  // F = 1
  MaterialDesc m = microfacet(MaterialType::Conductor, alpha);
  m.schlick = true;
  m.reflectance.value = RGB(1.0f);
  return m;
}

// A unit sphere in a uniform environment of radiance 1, filling the middle of the image.
SceneDescription furnace(const MaterialDesc& material, int size = 8) {
  SceneDescription d = test::empty_scene(size, size, {0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 30);
  d.render.background = RGB(1.0f);
  add_sphere(d, {0, 0, 0}, 1.0f, add_material(d, material));
  return d;
}

TEST(PathMicrofacetFurnace, NoSurfaceReflectsMoreThanItReceives) {
  // At 1024 spp a pixel's standard deviation is below 0.004 (measured): 1.02 is 5 sigma.
  MaterialDesc plastic = microfacet(MaterialType::CoatedDiffuse, 0.5f);
  plastic.reflectance.value = RGB(1.0f);
  for (const MaterialDesc& m : {white_conductor(0.2f), white_conductor(1.0f), microfacet(MaterialType::Dielectric, 0.3f),
                                microfacet(MaterialType::Dielectric, 1.0f), plastic}) {
    const Image img = test::render_path(furnace(m), test::path_settings(1024));
    for (const RGB& p : img.pixels) ASSERT_LE(p.max_component(), 1.02f) << static_cast<int>(m.type.value);
    EXPECT_LE(test::image_stats(img).mean, 1.003) << static_cast<int>(m.type.value);
  }
}

TEST(PathMicrofacetFurnace, RoughMetalLosesEnergyAndSmoothCoatingNone) {
  // A very rough F = 1 metal loses what its microfacets shadow (docs/path-tracing.md,
  // "Energy of single scattering": about 20% at normal incidence, more towards
  // the rim). A white base under a smooth coating reflects everything.
  const Image rough = test::render_path(furnace(white_conductor(1.0f)), test::path_settings(1024));
  EXPECT_LT(test::image_stats(rough).mean, 0.95);
  MaterialDesc plastic = microfacet(MaterialType::CoatedDiffuse, 0.0f);
  plastic.reflectance.value = RGB(1.0f);
  const Image img = test::render_path(furnace(plastic), test::path_settings(2048));
  for (const RGB& p : img.pixels)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(p[c], 1.0f, 0.02f);
}

bool bit_identical(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(RGB)) == 0;
}

// A sphere of `m` on a lit floor under a sky.
SceneDescription still_life(const MaterialDesc& m) {
  SceneDescription d = test::empty_scene(24, 24, {0, 1.0f, 3.5f}, {0, 0.5f, 0}, {0, 1, 0}, 40);
  d.render.background = RGB(0.4f, 0.5f, 0.7f);
  MaterialDesc floor;
  floor.type = MaterialType::Lambert;
  floor.diffuse = RGB(0.6f, 0.5f, 0.4f);
  add_sphere(d, {0, -100.0f, 0}, 100.0f, add_material(d, floor));
  add_sphere(d, {0, 0.6f, 0}, 0.6f, add_material(d, m));
  test::add_point_light(d, {1.5f, 3.0f, 2.0f}, RGB(8.0f), RGB(8.0f));
  return d;
}

TEST(PathMicrofacet, RoughnessZeroRendersExactlyTheGlassAndTheMirror) {
  MaterialDesc glass;
  glass.type = MaterialType::Glass;
  glass.ior = 1.5f;
  MaterialDesc mirror;
  mirror.type = MaterialType::Mirror;
  const IntegratorSettings s = test::path_settings(16, 8, 7);
  EXPECT_TRUE(bit_identical(test::render_path(still_life(glass), s),
                            test::render_path(still_life(microfacet(MaterialType::Dielectric, 0.0f)), s)));
  EXPECT_TRUE(bit_identical(test::render_path(still_life(mirror), s),
                            test::render_path(still_life(white_conductor(0.0f)), s)));
  // ... and a rough one is a different picture (the comparison can fail).
  EXPECT_FALSE(bit_identical(test::render_path(still_life(glass), s),
                             test::render_path(still_life(microfacet(MaterialType::Dielectric, 0.2f)), s)));
}

}  // namespace
}  // namespace pt
