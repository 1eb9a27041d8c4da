// Normal and bump maps (render/materials/normal_map.h): the tangent frame's
// conventions (u along x, image up = green), the bump map's normal, and the
// policy that a perturbed normal never lets light through the surface.
#include <cmath>

#include <gtest/gtest.h>

#include "render/materials/bsdf.h"
#include "render/materials/normal_map.h"

namespace pt {
namespace {

// A flat patch in the plane z = 0, u along +x and v along -y (so the image's
// up, -v, is +y), normal +z.
SurfaceGeometry patch() {
  SurfaceGeometry g;
  g.ng = g.ns = Vec3f(0, 0, 1);
  g.uv = Vec2f(0.3f, 0.6f);
  return g;
}
const UvDerivatives kPatch{Vec3f(2, 0, 0), Vec3f(0, -3, 0)};

// A one-texel normal map storing the tangent-space normal t.
Texture normal_texture(Vec3f t) {
  return Texture(1, 1, {RGB(0.5f * t.x + 0.5f, 0.5f * t.y + 0.5f, 0.5f * t.z + 0.5f)});
}

Vec3f mapped(Vec3f t, const SurfaceGeometry& g = patch(), const UvDerivatives& d = kPatch) {
  const Texture map = normal_texture(t);
  Material m;
  m.normal_map = &map;
  SurfaceGeometry out = g;
  perturb_shading_normal(m, d, out);
  return out.ns;
}

void expect_near(Vec3f a, Vec3f b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(NormalMap, FlatTexelKeepsTheNormal) { expect_near(mapped(Vec3f(0, 0, 1)), Vec3f(0, 0, 1)); }

TEST(NormalMap, RedLeansAlongUAndGreenTowardsTheImagesUp) {
  const float s = std::sin(0.5f), c = std::cos(0.5f);
  expect_near(mapped(Vec3f(s, 0, c)), Vec3f(s, 0, c));   // +u is +x
  expect_near(mapped(Vec3f(0, s, c)), Vec3f(0, s, c));   // green up: -v, which is +y here
  // The same texel on a patch whose v runs up the image (dp/dv = +y) leans the other way.
  expect_near(mapped(Vec3f(0, s, c), patch(), {Vec3f(2, 0, 0), Vec3f(0, 3, 0)}), Vec3f(0, -s, c));
}

TEST(NormalMap, TangentIsMadePerpendicularToTheShadingNormal) {
  SurfaceGeometry g = patch();
  g.ns = normalize(Vec3f(0.3f, 0.0f, 1.0f));  // an interpolated normal, tilted along u
  const Vec3f n = mapped(Vec3f(0, 0, 1), g);
  expect_near(n, g.ns);
}

TEST(NormalMap, NeverBelowTheGeometricSurface) {
  // A texel pointing along the surface (or below it) is pulled up to 0.01
  // above the tangent plane, and the BSDF built on it reflects nothing
  // through the surface.
  for (const Vec3f t : {Vec3f(1, 0, 0), Vec3f(0.6f, 0, -0.8f), Vec3f(0, -1, 0)}) {
    SurfaceGeometry g = patch();
    const Texture map = normal_texture(t);
    Material m;
    m.type = MaterialType::Lambert;
    m.diffuse = RGB(0.8f);
    m.normal_map = &map;
    perturb_shading_normal(m, kPatch, g);
    EXPECT_GE(dot(g.ns, g.ng), 0.0099f);
    EXPECT_NEAR(length(g.ns), 1.0f, 1e-5f);
    const Vec3f wo = normalize(Vec3f(-0.5f, 0.2f, 0.6f));
    const Bsdf bsdf(m, g, wo);
    EXPECT_EQ(bsdf.f(wo, normalize(Vec3f(0.3f, 0.1f, -0.2f))), RGB());
    BsdfSample s;
    for (float u = 0.05f; u < 1.0f; u += 0.1f) {
      if (bsdf.sample(wo, 0.5f, Vec2f(u, 1.0f - u), s)) {
        EXPECT_GT(dot(s.wi, g.ng), 0.0f);
      }
    }
  }
}

TEST(BumpMap, ARampTiltsTheNormalAgainstItsSlope) {
  // h = 0.4 u over a 256-texel ramp: dh/du = 0.4, dp/du = (2, 0, 0), so
  // dp'/du = (2, 0, 0.4), dp'/dv = (0, -3, 0) and n' = (-0.2, 0, 1) / |.|.
  std::vector<RGB> texels;
  for (int x = 0; x < 256; ++x) texels.emplace_back(static_cast<float>(x) / 256.0f);
  const Texture ramp(256, 1, texels);
  Material m;
  m.displacement.value = 0.4f;
  m.displacement.texture = &ramp;
  SurfaceGeometry g = patch();
  perturb_shading_normal(m, kPatch, g);
  expect_near(g.ns, normalize(Vec3f(-0.2f, 0.0f, 1.0f)), 1e-3f);
}

// Textured parameters read their textures as every texture is read: filtered
// over the hit's footprint (texture_rgb -> Texture::eval). A checker of unit
// squares: a point lookup sees one square, a footprint of many squares their mean.
TEST(TexturedParameters, AreFilteredOverTheFootprint) {
  const Texture checker(CheckerTexture{RGB(0.0f), RGB(1.0f), false}, TextureMapping{false, Vec3f(64.0f, 64.0f, 1.0f), {}});
  FloatParam roughness{0.8f, &checker};
  RGBParam reflectance{RGB(1.0f), &checker};
  const Vec2f uv(0.3f / 64.0f, 0.3f / 64.0f);  // inside the square at (0, 0): color0
  EXPECT_EQ(roughness.at(TexCoord(uv)), 0.0f);
  // A footprint of half the texture (32 squares) each way: the mean, 0.5.
  const TexCoord wide(uv, Vec2f(0.5f, 0.0f), Vec2f(0.0f, 0.5f));
  EXPECT_NEAR(roughness.at(wide), 0.4f, 0.05f);
  EXPECT_NEAR(reflectance.at(wide).g, 0.5f, 0.06f);
  // The normal map and the bump map go through the same lookup.
  Material m;
  m.displacement = FloatParam{0.01f, &checker};
  SurfaceGeometry g = patch();
  g.uv = uv;
  g.duvdx = Vec2f(0.5f, 0.0f);
  g.duvdy = Vec2f(0.0f, 0.5f);
  perturb_shading_normal(m, kPatch, g);
  // Over a footprint of many squares the filtered height is flat: the normal stays.
  expect_near(g.ns, Vec3f(0, 0, 1), 0.05f);
}

}  // namespace
}  // namespace pt
