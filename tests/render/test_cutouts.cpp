// Alpha cutouts (docs/textures.md): camera, bounce and shadow rays pass
// through the holes, on both backends, and the two backends agree hit for
// hit on random rays through a scene of cut-out meshes, spheres and instances.
// Blended surfaces (stochastic opacity: glTF's BLEND, MTL's partial dissolve)
// stop a fraction alpha of the camera, bounce and shadow rays, independently
// per surface, on both backends.
#include <cmath>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "render/integrators/builtin.h"
#include "path_test_util.h"
#include "test_scenes.h"

namespace pt {
namespace {

// A checker alpha: holes (black, alpha 0) where floor(2u) + floor(2v) is even.
int add_checker_alpha(SceneDescription& d, Vec3f scale = Vec3f(2, 2, 1)) {
  TextureDesc t;
  t.type = TextureType::Checker;
  t.color0 = RGB(0.0f);
  t.color1 = RGB(1.0f);
  t.scale = scale;
  d.textures.push_back(t);
  return static_cast<int>(d.textures.size()) - 1;
}

// A cut-out square at z = 1 (half size 1: uv = ((x + 1) / 2, (y + 1) / 2), so
// the holes are the squares of side 0.5 where floor(x + 1) + floor(y + 1) is
// even, e.g. around (-0.5, -0.5); opaque around (0.5, -0.5)) over a floor at z = 0.
SceneDescription cutout_scene() {
  SceneDescription d = test::empty_scene(16, 16, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  MaterialDesc leaf = test::diffuse_material(RGB(0.2f, 0.8f, 0.2f));
  leaf.alpha_texture = add_checker_alpha(d);
  const int cut = test::add_material(d, leaf);
  const int floor = test::add_material(d, test::diffuse_material(RGB(0.8f)));
  test::add_z_square(d, 1.0f, 1.0f, cut);
  test::add_z_square(d, 0.0f, 2.0f, floor);
  test::add_point_light(d, {0, 0, 4}, RGB(4.0f), RGB(4.0f));
  return d;
}

class Cutouts : public ::testing::TestWithParam<AccelKind> {
 protected:
  std::unique_ptr<RenderScene> build(const SceneDescription& d) {
    BuildOptions options;
    options.accel = GetParam();
    return test::build(d, pool_, options);
  }
  WorkerPool pool_{2};
};

const Vec3f kHole(-0.5f, -0.5f, 0.0f), kOpaque(0.5f, -0.5f, 0.0f);

TEST_P(Cutouts, CameraRaysPassThroughHoles) {
  const auto scene = build(cutout_scene());
  ASSERT_TRUE(scene);
  Intersection isect;
  ASSERT_TRUE(scene->intersect(Ray{kHole + Vec3f(0, 0, 5), {0, 0, -1}}, isect));
  EXPECT_EQ(isect.hit.shape, 1u);  // the floor
  EXPECT_NEAR(isect.hit.t, 5.0f, 1e-5f);
  ASSERT_TRUE(scene->intersect(Ray{kOpaque + Vec3f(0, 0, 5), {0, 0, -1}}, isect));
  EXPECT_EQ(isect.hit.shape, 0u);
  EXPECT_NEAR(isect.hit.t, 4.0f, 1e-5f);
}

TEST_P(Cutouts, ShadowRaysPassThroughHoles) {
  const auto scene = build(cutout_scene());
  ASSERT_TRUE(scene);
  EXPECT_FALSE(scene->occluded(Ray{kHole, {0, 0, 1}, 1e-3f, 3.0f}));
  EXPECT_TRUE(scene->occluded(Ray{kOpaque, {0, 0, 1}, 1e-3f, 3.0f}));
  // The floor under a hole is lit by the light above, under the leaf it is in shadow.
  const Vec3f eye(0, 0, 5);
  const RGB lit = whitted_radiance(*scene, Ray{eye, normalize(Vec3f(-0.55f, -0.55f, 0) - eye)}, 1);
  EXPECT_GT(lit.r, 0.05f);
  const Vec3f under(2.0f / 3.0f, -1.0f, 0.0f);  // its way to the light crosses the leaf at (0.5, -0.75): opaque
  ASSERT_TRUE(scene->occluded(Ray{under, normalize(Vec3f(0, 0, 4) - under), 1e-3f, 0.999f * length(Vec3f(0, 0, 4) - under)}));
}

// Bounce rays are rays from a surface like any other: through a hole they go
// on (here: to nothing), onto the opaque part they hit its back.
TEST_P(Cutouts, BounceRaysPassThroughHoles) {
  const auto scene = build(cutout_scene());
  ASSERT_TRUE(scene);
  Intersection floor;
  ASSERT_TRUE(scene->intersect(Ray{kHole + Vec3f(0, 0, 5), {0, 0, -1}}, floor));
  Intersection isect;
  EXPECT_FALSE(scene->intersect(spawn_ray(floor.geo, {0, 0, 1}), isect));
  ASSERT_TRUE(scene->intersect(Ray{kOpaque + Vec3f(0, 0, 5), {0, 0, -1}}, isect));
  Intersection back;
  ASSERT_TRUE(scene->intersect(Ray{kOpaque + Vec3f(0, 0, 0.5f), {0, 0, 1}}, back));
  EXPECT_EQ(back.hit.shape, 0u);
  EXPECT_NEAR(back.hit.t, 0.5f, 1e-5f);
}

// Past a cut-out hit the shape's next one: a sphere whose upper half is cut
// away (a 3D checker in object space: holes where floor(z - 2) is even) shows
// its lower half from above; a constant alpha of 0 hides a shape from every ray.
TEST_P(Cutouts, TheNextHitOfTheSameShapeAndConstantAlpha) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  TextureDesc half;
  half.type = TextureType::Checker;
  half.color0 = RGB(0.0f);
  half.color1 = RGB(1.0f);
  half.object_mapping = true;
  half.scale = Vec3f(0.01f, 0.01f, 1.0f);
  half.transform = Sourced<Transform>(Transform(Affine::translate(-50, -50, 2)));
  d.textures.push_back(half);
  MaterialDesc m = test::diffuse_material(RGB(0.5f));
  m.alpha_texture = 0;
  test::add_sphere(d, {0, 0, 2}, 0.5f, test::add_material(d, m));
  MaterialDesc invisible = test::diffuse_material(RGB(0.5f));
  invisible.alpha = 0.0f;
  test::add_z_square(d, 4.0f, 3.0f, test::add_material(d, invisible));
  const auto scene = build(d);
  ASSERT_TRUE(scene);
  Intersection isect;
  ASSERT_TRUE(scene->intersect(Ray{{0, 0, 5}, {0, 0, -1}}, isect));
  EXPECT_EQ(isect.hit.shape, 0u);
  EXPECT_NEAR(isect.hit.t, 3.5f, 1e-4f);  // z = 1.5, the far side
  EXPECT_FALSE(scene->occluded(Ray{{0, 0, 5}, {0, 0, -1}, 0.0f, 2.9f}));  // through the square and the upper half
  EXPECT_TRUE(scene->occluded(Ray{{0, 0, 5}, {0, 0, -1}, 0.0f, 3.6f}));
}

// An instance's material replaces its object's, cutout included: two
// placements of one square, the second with an alpha-0 material.
TEST_P(Cutouts, AnInstanceMaterialCutsOut) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  const int solid = test::add_material(d, test::diffuse_material(RGB(0.5f)));
  MaterialDesc invisible = test::diffuse_material(RGB(0.5f));
  invisible.alpha = 0.0f;
  const int hidden = test::add_material(d, invisible);
  ObjectDesc o;
  o.name = "square";
  Quad q;
  q.v[0] = Vec3f(-0.5f, -0.5f, 0);
  q.v[1] = Vec3f(0.5f, -0.5f, 0);
  q.v[2] = Vec3f(0.5f, 0.5f, 0);
  q.v[3] = Vec3f(-0.5f, 0.5f, 0);
  ShapeDesc s;
  s.geometry = q;
  s.material = solid;
  o.shapes.push_back(s);
  d.objects.push_back(o);
  InstanceDesc left, right;
  left.transform = Sourced<Transform>(Transform(Affine::translate(-1, 0, 0)));
  right.transform = Sourced<Transform>(Transform(Affine::translate(1, 0, 0)));
  right.material = hidden;
  d.instances = {left, right};
  const auto scene = build(d);
  ASSERT_TRUE(scene);
  Intersection isect;
  ASSERT_TRUE(scene->intersect(Ray{{-1, 0, 5}, {0, 0, -1}}, isect));
  EXPECT_EQ(isect.hit.instance, 0u);
  EXPECT_FALSE(scene->intersect(Ray{{1, 0, 5}, {0, 0, -1}}, isect));
  EXPECT_FALSE(scene->occluded(Ray{{1, 0, 5}, {0, 0, -1}, 0.0f, 10.0f}));
}

// ---------------------------------------------------------------- blended (stochastic) opacity
MaterialDesc blended(float alpha, RGB colour = RGB(0.5f)) {
  MaterialDesc m = test::diffuse_material(colour);
  m.alpha = alpha;
  m.alpha_blend = true;
  return m;
}

// The share of `n` rays a test stops, within 4 standard deviations of p.
void expect_fraction(int stopped, int n, double p, const char* what) {
  const double sigma = std::sqrt(p * (1.0 - p) / n);
  EXPECT_NEAR(static_cast<double>(stopped) / n, p, 4.0 * sigma + 1e-9) << what;
}

// A 0.25-alpha square over the floor: a quarter of the camera rays stop on it
// and a quarter of the shadow rays from the floor; two such squares stop
// 1 - 0.75^2 (independent surfaces), a 0.5-alpha sphere on the way in and on
// the way out independently (its two hits are two surfaces), and with an
// alpha texture the opacity is alpha times the texel (holes let everything through).
TEST_P(Cutouts, BlendedSurfacesStopAFractionAlphaOfEveryKindOfRay) {
  SceneDescription d = test::empty_scene(8, 8, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  const int floor = test::add_material(d, test::diffuse_material(RGB(0.8f)));
  test::add_z_square(d, 0.0f, 4.0f, floor);                          // object 0
  test::add_z_square(d, 1.0f, 1.0f, test::add_material(d, blended(0.25f)));  // object 1
  MaterialDesc textured = blended(0.5f);
  textured.alpha_texture = add_checker_alpha(d);
  SceneDescription two = d, tex = d, ball = d;
  test::add_z_square(two, 2.0f, 1.0f, test::add_material(two, blended(0.25f)));
  tex.shapes.pop_back();
  test::add_z_square(tex, 1.0f, 1.0f, test::add_material(tex, textured));
  ball.shapes.pop_back();
  test::add_sphere(ball, {0, 0, 2}, 0.5f, test::add_material(ball, blended(0.5f)));
  const auto one_scene = build(d), two_scene = build(two), tex_scene = build(tex), ball_scene = build(ball);
  ASSERT_TRUE(one_scene && two_scene && tex_scene && ball_scene);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.45f, 0.45f);
  const int n = 20000;
  int camera = 0, shadow = 0, both = 0, ball_front = 0, ball_through = 0, tex_opaque = 0, tex_hole = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3f o(u(rng), u(rng), 5.0f), target(u(rng), u(rng), 0.0f);
    const Ray down{o, normalize(target - o)};
    Intersection isect;
    ASSERT_TRUE(one_scene->intersect(down, isect));
    camera += isect.hit.shape == 1u;
    const Ray up{target, normalize(Vec3f(u(rng), u(rng), 3.0f) - target), 1e-3f, 2.5f};
    shadow += one_scene->occluded(up);
    ASSERT_TRUE(two_scene->intersect(down, isect));
    both += isect.hit.shape != 0u;
    ASSERT_TRUE(ball_scene->intersect(Ray{Vec3f(o.x * 0.6f, o.y * 0.6f, o.z), {0, 0, -1}}, isect));  // all meet the ball
    ball_front += isect.hit.shape == 1u && isect.hit.t < 3.0f;
    ball_through += isect.hit.shape == 0u;
    // The checker's opaque square around (0.5, -0.5) and its hole around (-0.5, -0.5).
    ASSERT_TRUE(tex_scene->intersect(Ray{kOpaque + Vec3f(u(rng) * 0.5f, u(rng) * 0.5f, 5.0f), {0, 0, -1}}, isect));
    tex_opaque += isect.hit.shape == 1u;
    ASSERT_TRUE(tex_scene->intersect(Ray{kHole + Vec3f(u(rng) * 0.5f, u(rng) * 0.5f, 5.0f), {0, 0, -1}}, isect));
    tex_hole += isect.hit.shape == 1u;
  }
  expect_fraction(camera, n, 0.25, "camera rays stopped by a 0.25 square");
  expect_fraction(shadow, n, 0.25, "shadow rays stopped by a 0.25 square");
  expect_fraction(both, n, 1.0 - 0.75 * 0.75, "rays stopped by one of two 0.25 squares");
  expect_fraction(ball_front, n, 0.5, "rays stopped by a 0.5 sphere's near side");
  expect_fraction(ball_through, n, 0.25, "rays through both sides of a 0.5 sphere");
  expect_fraction(tex_opaque, n, 0.5, "rays stopped by the opaque texels (alpha 0.5 x 1)");
  EXPECT_EQ(tex_hole, 0) << "rays stopped by the holes (alpha 0.5 x 0)";
}

// What a user sees: a black 0.25-alpha plane in front of an emitter of
// radiance 1 lets 75% of it through, to the camera (path and whitted) and to
// a floor lit through it (light sampling and BSDF sampling alike: MIS).
TEST_P(Cutouts, ABlendedPlaneInFrontOfAnEmitterTransmitsOneMinusAlpha) {
  SceneDescription d = test::empty_scene(16, 16, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 20.0f);
  test::add_z_square(d, 0.0f, 3.0f, test::add_material(d, test::emitter_material(RGB(1.0f))));
  test::add_z_square(d, 1.0f, 3.0f, test::add_material(d, blended(0.25f, RGB(0.0f))));
  BuildOptions options;
  options.accel = GetParam();
  for (const char* integrator : {"path", "whitted"}) {
    const Image img = test::render_with(d, integrator, test::path_settings(64, 4, 3), 2, options);
    const test::Stats s = test::image_stats(img);
    EXPECT_NEAR(s.mean, 0.75, 0.015) << integrator;  // 16 x 16 x 64 binary samples: sigma 0.0034
  }
  // A white floor under an emitter (facing down, 4 x 4 at height 2) seen through the same plane at height 1:
  // lit through it (x 0.75) and seen through it from above (x 0.75 again): 0.5625 of the unblocked image.
  SceneDescription lit = test::empty_scene(8, 8, {0, 0, 0.9f}, {0, 0, 0}, {0, 1, 0}, 30.0f);
  test::add_z_square(lit, 0.0f, 3.0f, test::add_material(lit, test::diffuse_material(RGB(1.0f))));
  Quad lamp;
  lamp.v[0] = Vec3f(-2, -2, 2);
  lamp.v[1] = Vec3f(-2, 2, 2);
  lamp.v[2] = Vec3f(2, 2, 2);
  lamp.v[3] = Vec3f(2, -2, 2);
  test::add_shape(lit, lamp, test::add_material(lit, test::emitter_material(RGB(1.0f))));
  SceneDescription open = lit;
  test::add_z_square(lit, 1.0f, 3.0f, test::add_material(lit, blended(0.25f, RGB(0.0f))));
  for (const LightStrategy strategy : {LightStrategy::Mis, LightStrategy::LightOnly, LightStrategy::BsdfOnly}) {
    IntegratorSettings settings = test::path_settings(512, 1, 5);  // direct light only
    settings.light_strategy = strategy;
    const double through = test::image_stats(test::render_with(lit, "path", settings, 2, options)).mean;
    const double clear = test::image_stats(test::render_with(open, "path", settings, 2, options)).mean;
    EXPECT_NEAR(through / clear, 0.75, 0.02) << static_cast<int>(strategy);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Cutouts, ::testing::Values(AccelKind::Embree, AccelKind::Bvh),
                         [](const auto& p) { return std::string(accel_kind_name(p.param)); });

// Both backends, one scene (a cut-out mesh of 800 triangles, cut-out and
// whole spheres, a cut-out square placed by instances, the floor), 4000 random
// rays: the same nearest hit (object, primitive, instance, t) and the same
// any-hit answer for every ray.
TEST(CutoutBackends, AgreeOnRandomRays) {
  SceneDescription d = cutout_scene();
  TriangleMesh grid;
  const int n = 20;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      grid.positions.emplace_back(-1.5f + 3.0f * static_cast<float>(x) / n, -1.5f + 3.0f * static_cast<float>(y) / n,
                                  0.5f + 0.1f * std::sin(static_cast<float>(x + y)));
      grid.uvs.emplace_back(static_cast<float>(x) / n, static_cast<float>(y) / n);
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t i = static_cast<uint32_t>(y * (n + 1) + x), r = static_cast<uint32_t>(n + 1);
      grid.indices.insert(grid.indices.end(), {i, i + 1, i + r + 1, i, i + r + 1, i + r});
    }
  MaterialDesc holes = test::diffuse_material(RGB(0.5f));
  holes.alpha_texture = add_checker_alpha(d, Vec3f(6, 6, 1));
  const int cut = test::add_material(d, holes);
  test::add_shape(d, grid, cut);
  test::add_sphere(d, {0.8f, 0.8f, 2.0f}, 0.4f, cut);
  test::add_sphere(d, {-0.8f, 0.8f, 2.0f}, 0.4f, 1);
  ShapeDesc placed;
  Quad q;
  q.v[0] = Vec3f(-0.5f, -0.5f, 0);
  q.v[1] = Vec3f(0.5f, -0.5f, 0);
  q.v[2] = Vec3f(0.5f, 0.5f, 0);
  q.v[3] = Vec3f(-0.5f, 0.5f, 0);
  placed.geometry = q;
  placed.material = 0;
  placed.transform = Sourced<Transform>(Transform(Affine::rotate(1, 0, 0, 30) * Affine::translate(0, 1, 3)));
  d.shapes.push_back(placed);
  WorkerPool pool(2);
  BuildOptions bvh_options, embree_options;
  bvh_options.accel = AccelKind::Bvh;
  embree_options.accel = AccelKind::Embree;
  const auto bvh = test::build(d, pool, bvh_options);
  const auto embree = test::build(d, pool, embree_options);
  SceneDescription whole = d;  // the same without cutouts, to show the rays meet them
  for (MaterialDesc& m : whole.materials) m.alpha_texture.reset();
  const auto uncut = test::build(whole, pool, bvh_options);
  ASSERT_TRUE(bvh && embree && uncut);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int hits = 0, through = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3f o(2.5f * u(rng), 2.5f * u(rng), 4.0f + u(rng));
    const Vec3f target(1.6f * u(rng), 1.6f * u(rng), 1.2f * (u(rng) + 1.0f));
    const Ray ray{o, normalize(target - o)};
    Hit a, b;
    const bool ha = bvh->accel->intersect(ray, a), hb = embree->accel->intersect(ray, b);
    Hit c;
    if (!uncut->accel->intersect(ray, c) || !ha || c.shape != a.shape || c.t != a.t) ++through;
    ASSERT_EQ(ha, hb) << i;
    ASSERT_EQ(bvh->accel->occluded(ray), embree->accel->occluded(ray)) << i;
    if (!ha) continue;
    ++hits;
    ASSERT_EQ(a.shape, b.shape) << i;
    ASSERT_EQ(a.prim, b.prim) << i;
    ASSERT_EQ(a.instance, b.instance) << i;
    ASSERT_NEAR(a.t, b.t, 1e-5f * std::max(a.t, 1.0f)) << i;
  }
  EXPECT_GT(hits, 2000);     // most rays hit something (2878 of 4000 when written)
  EXPECT_GT(through, 400);   // and many pass a hole (1000 to 1500 expected: half of the cut surfaces is holes)
  EXPECT_NE(bvh->accel->stats().backend, embree->accel->stats().backend);
}

}  // namespace
}  // namespace pt
