// Catalogue section 12 (docs/numerical-stability.md): the shadow terminator.
// A coarse smooth-shaded sphere mesh under a grazing directional light: the
// triangles near the terminator face away from the light while their shading
// normals still face it, so rays leaving the flat triangles are blocked by
// the sphere itself (faceted dark bands); with the shadow-terminator offset
// (geometry/terminator.h) they leave from the smooth surface the normals
// imply, and the band renders as that smooth surface's analytic shading
// (Lambert at the interpolated normal, unshadowed). For every backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "render_util.h"

namespace pt {
namespace {

using test::add_material;
using test::add_shape;

class ShadowTerminator : public test::PerBackend {};

constexpr int kSize = 64;
const Vec3f kEye(0, 0, 4);
const Vec3f kToLight = normalize(Vec3f(1.0f, 0.35f, 0.25f));

// A white Lambert UV sphere mesh of radius 1 at the origin, 6 rings and 10
// segments, with the sphere's normals at its vertices, lit by a directional
// light from kToLight.
SceneDescription sphere_scene() {
  SceneDescription d = test::empty_scene(kSize, kSize, kEye, {0, 0, 0}, {0, 1, 0}, 32.0f);
  const int white = add_material(d, test::lambert_material(RGB(0.8f)));
  TriangleMesh m = test::sphere_mesh({0, 0, 0}, 1.0f, 6, 10);
  for (const Vec3f& p : m.positions) m.normals.push_back(normalize(p));
  add_shape(d, std::move(m), white);
  DirectionalLightDesc light;
  light.direction = -kToLight;
  light.irradiance = RGB(3.0f);
  d.lights.emplace_back(light);
  return d;
}

Image render(AccelKind kind, const SceneDescription& d, float terminator_offset) {
  BuildOptions options;
  options.accel = kind;
  options.shadow_terminator_offset = terminator_offset;
  const test::Rendered r = test::render_film(d, "path", test::path_settings(16, 1), 2, options);
  EXPECT_EQ(r.non_finite.total(), 0u) << r.non_finite.describe();
  return r.image;
}

// The camera ray through the centre of pixel (x, y) (the test camera: eye on
// +z looking at the origin, y up, vertical field of view 32 degrees).
Ray pixel_ray(int x, int y) {
  const float tan_half = std::tan(0.5f * 32.0f * kPi / 180.0f);
  const Vec3f dir = normalize(Vec3f((2.0f * (static_cast<float>(x) + 0.5f) / kSize - 1.0f) * tan_half,
                                    (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / kSize) * tan_half, -1.0f));
  return Ray{kEye, dir, 0.0f, kInfinity};
}

// The smooth shading a mesh render should have at each pixel: the radiance of
// the white Lambert surface lit by the light at the cosine of the shading
// normal where the pixel's centre ray meets the mesh (the analytic smooth
// surface's shading: nothing of the sphere shadows a point whose smooth normal
// faces the light), and that cosine; -1 where the ray misses or the point is
// near the silhouette (the view at more than 60 degrees from the normal).
struct Expected {
  float radiance = 0.0f, cos_light = -1.0f;
};

Expected smooth_shading(const TriangleMesh& m, int x, int y) {
  Ray ray = pixel_ray(x, y);
  PrimHit hit, nearest;
  uint32_t tri = 0;
  for (uint32_t i = 0; i < m.triangle_count(); ++i) {
    if (intersect(m, i, ray, hit)) {
      nearest = hit;
      tri = i;
      ray.tmax = hit.t;
    }
  }
  if (ray.tmax == kInfinity) return {};
  const SurfaceGeometry sg = surface(m, tri, ray, nearest);
  if (dot(sg.ns, -ray.dir) < 0.5f) return {};
  const float c = dot(sg.ns, kToLight);
  return {0.8f * kInvPi * 3.0f * std::max(0.0f, c), c};
}

// A render of the mesh against its smooth shading over the terminator band:
// the pixels whose expected cosine is in (0.02, 0.25).
struct BandComparison {
  int pixels = 0;
  double rendered = 0, expected = 0;
  int dark = 0;  // pixels below half their expected value
  double ratio() const { return rendered / expected; }
  double dark_share() const { return static_cast<double>(dark) / pixels; }
};

BandComparison compare_band(const Image& img, const TriangleMesh& m) {
  BandComparison c;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const Expected e = smooth_shading(m, x, y);
      if (!(e.cos_light > 0.02f && e.cos_light < 0.25f)) continue;
      const float v = img.at(x, y).luminance();
      ++c.pixels;
      c.rendered += v;
      c.expected += e.radiance;
      if (v < 0.5f * e.radiance) ++c.dark;
    }
  }
  return c;
}

// Measured (both backends, 64x64, 16 spp, a band of 369 pixels): without the
// offset the band renders at 0.884 of its smooth shading and 15.2% of its
// pixels are below half of it (the faceted dark bands); with Cycles' default
// 0.1, at 1.000 and none. Allowed: within 0.02 of 1 and at most 1% with the
// offset; below 0.95 and above 8% without (so the test sees the bands).
TEST_P(ShadowTerminator, CoarseSmoothSphereShadesLikeItsSmoothSurface) {
  const SceneDescription scene = sphere_scene();
  const TriangleMesh& mesh = std::get<TriangleMesh>(scene.shapes[0].geometry);
  const BandComparison off = compare_band(render(kind(), scene, 0.0f), mesh);
  const BandComparison on = compare_band(render(kind(), scene, kDefaultShadowTerminatorOffset), mesh);
  ASSERT_GT(on.pixels, 200);
  EXPECT_NEAR(on.ratio(), 1.0, 0.02);
  EXPECT_LE(on.dark_share(), 0.01);
  EXPECT_LT(off.ratio(), 0.95);
  EXPECT_GT(off.dark_share(), 0.08);
}

INSTANTIATE_TEST_SUITE_P(Backends, ShadowTerminator, ::testing::ValuesIn(accel_kind_names()), test::backend_test_name);

}  // namespace
}  // namespace pt
