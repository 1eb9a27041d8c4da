// Alpha cutouts (docs/textures.md): camera, bounce and shadow rays pass
// through the holes, on both backends, and the two backends agree hit for
// hit on random rays through a scene of cut-out meshes, spheres and instances.
#include <cmath>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "render/integrators/builtin.h"
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
