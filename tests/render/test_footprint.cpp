// Texture footprints at hits (RenderScene::intersect, docs/textures.md): from
// a camera ray's differential at the first hit, from the camera's spread at
// any other, carried through an instance's transform, and not computed at all
// in a scene whose textures do not use them.
#include <cmath>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "test_scenes.h"

namespace pt {
namespace {

// A 2 x 2 square at z = 0 (u, v each across 2 units: du/dx = 0.5 per unit),
// seen from z = 2 by a 90-degree camera 100 pixels high: a pixel covers 0.04
// units there, so 0.02 in u. Textured with a checker (which reads footprints).
SceneDescription square_scene(bool textured, bool placed_at_double_size) {
  SceneDescription d = test::empty_scene(100, 100, {0, 0, 2}, {0, 0, 0}, {0, 1, 0}, 90.0f);
  MaterialDesc m = test::diffuse_material(RGB(0.5f));
  if (textured) {
    TextureDesc t;
    t.type = TextureType::Checker;
    d.textures.push_back(t);
    m.texture = 0;
  }
  const int material = test::add_material(d, m);
  if (!placed_at_double_size) {
    test::add_z_square(d, 0.0f, 1.0f, material);
    return d;
  }
  test::add_z_square(d, 0.0f, 0.5f, material);
  d.shapes.back().transform = Sourced<Transform>(Transform(Affine::scale(2, 2, 2)));
  return d;
}

TEST(Footprint, FirstHitFromTheCameraDifferential) {
  WorkerPool pool(1);
  const auto scene = test::build(square_scene(true, false), pool);
  ASSERT_TRUE(scene && scene->footprints);
  const Vec2f px(50.0f, 50.0f);
  CameraRay ray(scene->camera.generate_ray(px));
  ray.differential = scene->camera.differential(px, {0.5f, 0.5f});
  ray.has_differential = true;
  Intersection isect;
  ASSERT_TRUE(scene->intersect(ray, isect, ray.differential_or_null()));
  EXPECT_NEAR(std::hypot(isect.geo.duvdx.x, isect.geo.duvdx.y), 0.02f, 2e-4f);
  EXPECT_NEAR(std::hypot(isect.geo.duvdy.x, isect.geo.duvdy.y), 0.02f, 2e-4f);
  EXPECT_NEAR(length(isect.geo.dpdx), 0.04f, 4e-4f);
  EXPECT_EQ(isect.geo.p_object, isect.geo.p);  // placed directly: object space is world space
  // Without a differential (a bounce): the camera's spread, about the same here.
  Intersection bounce;
  ASSERT_TRUE(scene->intersect(ray, bounce));
  EXPECT_NEAR(std::hypot(bounce.geo.duvdx.x, bounce.geo.duvdx.y), 0.02f, 1e-3f);
}

// The same square made from one half its size, placed by a transform that
// doubles it: the same world footprint is half as much uv; p_object is in the
// square's own space.
TEST(Footprint, ThroughATransform) {
  WorkerPool pool(1);
  const auto scene = test::build(square_scene(true, true), pool);
  ASSERT_TRUE(scene);
  const Vec2f px(60.0f, 40.0f);
  CameraRay ray(scene->camera.generate_ray(px));
  ray.differential = scene->camera.differential(px, {0.5f, 0.5f});
  ray.has_differential = true;
  Intersection isect;
  ASSERT_TRUE(scene->intersect(ray, isect, ray.differential_or_null()));
  ASSERT_NE(isect.hit.instance, kNoInstance);
  EXPECT_NEAR(std::hypot(isect.geo.duvdx.x, isect.geo.duvdx.y), 0.02f, 2e-4f);
  EXPECT_NEAR(length(isect.geo.dpdx), 0.02f, 2e-4f);  // object space: half the world's
  EXPECT_NEAR(length(isect.geo.p_object * 2.0f - isect.geo.p), 0.0f, 1e-5f);
}

TEST(Footprint, NoneWithoutTexturesThatUseThem) {
  WorkerPool pool(1);
  const auto scene = test::build(square_scene(false, false), pool);
  ASSERT_TRUE(scene);
  EXPECT_FALSE(scene->footprints);
  const Vec2f px(50.0f, 50.0f);
  CameraRay ray(scene->camera.generate_ray(px));
  ray.differential = scene->camera.differential(px, {0.5f, 0.5f});
  ray.has_differential = true;
  Intersection isect;
  ASSERT_TRUE(scene->intersect(ray, isect, ray.differential_or_null()));
  EXPECT_EQ(isect.geo.duvdx, Vec2f());
  EXPECT_EQ(isect.geo.dpdx, Vec3f());
}

// A texture only a BSDF parameter reads (a conductor's roughness) or only a
// bump map reads still gets footprints: the materials' textures are one list
// (MaterialDesc::for_each_texture). The bump map's normal is perturbed at the
// same hit (RenderScene::texture_frame), placed directly or through a transform.
TEST(Footprint, BsdfParametersAndBumpMapsGetThemToo) {
  for (const bool bump : {false, true}) {
    for (const bool transformed : {false, true}) {
      SceneDescription d = square_scene(false, transformed);
      TextureDesc t;
      t.type = TextureType::Checker;
      t.scale = Sourced<Vec3f>(Vec3f(3.0f));
      d.textures.push_back(t);
      MaterialDesc& m = d.materials.back();
      m.type = Sourced<MaterialType>(MaterialType::Conductor);
      if (bump) {
        m.displacement = TexturedParam<float>{Sourced<float>(0.05f), 0};
      } else {
        m.uroughness.texture = 0;
      }
      WorkerPool pool(1);
      const auto scene = test::build(d, pool);
      ASSERT_TRUE(scene && scene->footprints) << bump << transformed;
      // Along a row of pixels: footprints at every hit; the bump map's checker
      // edges (u = 1/3, 2/3) tilt the normal at some, never below the surface.
      int tilted = 0;
      for (int x = 0; x < 100; ++x) {
        const Vec2f px(static_cast<float>(x) + 0.5f, 50.5f);
        CameraRay ray(scene->camera.generate_ray(px));
        ray.differential = scene->camera.differential(px, {0.5f, 0.5f});
        ray.has_differential = true;
        Intersection isect;
        if (!scene->intersect(ray, isect, ray.differential_or_null())) continue;
        EXPECT_GT(std::hypot(isect.geo.duvdx.x, isect.geo.duvdx.y), 0.0f);
        EXPECT_GE(dot(isect.geo.ns, isect.geo.ng), 0.0099f);
        tilted += dot(isect.geo.ns, isect.geo.ng) < 0.9999f ? 1 : 0;
      }
      if (bump) {
        EXPECT_GT(tilted, 0) << transformed;
      } else {
        EXPECT_EQ(tilted, 0) << transformed;
      }
    }
  }
}

}  // namespace
}  // namespace pt
