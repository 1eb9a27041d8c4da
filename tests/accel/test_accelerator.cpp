// build_accelerator(), kind names, error reporting and stats.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "accel/accelerator.h"
#include "core/parallel.h"
#include "../geometry/test_util.h"

namespace pt {
namespace {

TEST(AccelKind, ParsesAndNamesEveryKind) {
  AccelKind kind = AccelKind::Bvh;
  ASSERT_TRUE(parse_accel_kind("embree", kind));
  EXPECT_EQ(kind, AccelKind::Embree);
  ASSERT_TRUE(parse_accel_kind("bvh", kind));
  EXPECT_EQ(kind, AccelKind::Bvh);
  EXPECT_FALSE(parse_accel_kind("Embree", kind));
  EXPECT_FALSE(parse_accel_kind("", kind));
  EXPECT_FALSE(parse_accel_kind("kdtree", kind));
  const std::vector<std::string> names = accel_kind_names();
  ASSERT_EQ(names.size(), 2u);
  for (const std::string& name : names) {
    ASSERT_TRUE(parse_accel_kind(name, kind)) << name;
    EXPECT_EQ(accel_kind_name(kind), name);
  }
}

TEST(BuildAccelerator, BvhIsBuiltAndFillsStats) {
  SceneGeometry g;
  g.shapes.push_back(Sphere{{0, 0, 0}, 1.0f});
  g.shapes.push_back(test::make_uv_sphere({-3, 0, 0}, 1.0f, 10, 20));
  const std::size_t triangles = std::get<TriangleMesh>(g.shapes[1]).triangle_count();
  WorkerPool pool(2);
  Diagnostics diag;
  auto accel = build_accelerator(AccelKind::Bvh, g, pool, diag);
  ASSERT_NE(accel, nullptr) << diag.format();
  EXPECT_FALSE(diag.has_errors());
  const AccelStats stats = accel->stats();
  EXPECT_EQ(stats.backend.rfind("bvh (", 0), 0u) << stats.backend;
  EXPECT_EQ(stats.primitive_count, triangles + 1);
  EXPECT_GT(stats.memory_bytes, 1000u);
  Hit hit;
  ASSERT_TRUE(accel->intersect(Ray{{0, 0, -5}, {0, 0, 1}}, hit));
  EXPECT_EQ(hit.shape, 0u);
  EXPECT_FLOAT_EQ(hit.t, 4.0f);
}

TEST(BuildAccelerator, EmbreeFillsStats) {
  SceneGeometry g;
  g.shapes.push_back(Sphere{{0, 0, 0}, 1.0f});
  g.shapes.push_back(Quad{{{-5, -1, -5}, {-5, -1, 5}, {5, -1, 5}, {5, -1, -5}}});
  g.shapes.push_back(Cylinder{{3, 0, 0}, {3, 2, 0}, 0.5f});
  g.shapes.push_back(test::make_uv_sphere({-3, 0, 0}, 1.0f, 10, 20));
  const std::size_t triangles = std::get<TriangleMesh>(g.shapes[3]).triangle_count();
  WorkerPool pool(2);
  Diagnostics diag;
  auto accel = build_accelerator(AccelKind::Embree, g, pool, diag);
  ASSERT_NE(accel, nullptr) << diag.format();
  EXPECT_FALSE(diag.has_errors());
  const AccelStats stats = accel->stats();
  EXPECT_EQ(stats.backend.rfind("embree 3.", 0), 0u) << stats.backend;
  EXPECT_NE(stats.backend.find(" ("), std::string::npos) << stats.backend;
  EXPECT_EQ(stats.primitive_count, triangles + 3);
  EXPECT_GT(stats.memory_bytes, 1000u);
  EXPECT_GE(stats.build_seconds, 0.0);
  EXPECT_LT(stats.build_seconds, 60.0);
  const Bounds3f b = accel->bounds();
  EXPECT_LE(b.lo.x, -5.0f);
  EXPECT_LE(b.lo.y, -1.0f);
  EXPECT_GE(b.hi.x, 5.0f);
  EXPECT_GE(b.hi.y, 2.0f);
  EXPECT_LT(b.hi.y, 2.01f);
}

TEST(BuildAccelerator, EmptySceneNeverHits) {
  SceneGeometry g;
  WorkerPool pool(1);
  Diagnostics diag;
  auto accel = build_accelerator(AccelKind::Embree, g, pool, diag);
  ASSERT_NE(accel, nullptr);
  Hit hit;
  EXPECT_FALSE(accel->intersect(Ray{{0, 0, 0}, {0, 0, 1}}, hit));
  EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, {0, 0, 1}}));
  EXPECT_TRUE(accel->bounds().empty());
  EXPECT_EQ(accel->stats().primitive_count, 0u);
}

}  // namespace
}  // namespace pt
