// Our BVH's own properties: the builder's invariants, bounded depth on
// adversarial input, build determinism across thread counts, the two kernels
// agreeing bit for bit, tree statistics and traversal counters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

#include "accel/bvh/build.h"
#include "accel/bvh/bvh_accel.h"
#include "accel/bvh/kernels.h"
#include "backend_cases.h"
#include "core/parallel.h"
#include "../geometry/test_util.h"

namespace pt {
namespace {

bool contains(const Bounds3f& outer, const Bounds3f& inner) {
  return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
         outer.hi.x >= inner.hi.x && outer.hi.y >= inner.hi.y && outer.hi.z >= inner.hi.z;
}

std::vector<bvh::PrimRef> random_boxes(test::Rng& rng, uint32_t n) {
  std::vector<bvh::PrimRef> refs;
  for (uint32_t i = 0; i < n; ++i) {
    const Vec3f c{rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
    const Vec3f h{rng.uniform(0, 0.5f), rng.uniform(0, 0.5f), rng.uniform(0, 0.5f)};
    refs.push_back(bvh::PrimRef{Bounds3f{c - h, c + h}, i});
  }
  return refs;
}

// Checks the tree's invariants; returns its depth.
int check_tree(const bvh::BuildTree& tree, const std::vector<bvh::PrimRef>& input, const bvh::BuildSettings& s) {
  std::vector<int> seen(input.size(), 0);
  int depth = 0;
  std::function<void(uint32_t, const Bounds3f&, int)> visit = [&](uint32_t ref, const Bounds3f& box, int level) {
    depth = std::max(depth, level);
    if (ref & bvh::kLeafRef) {
      const bvh::BuildLeaf& leaf = tree.leaves[ref & ~bvh::kLeafRef];
      EXPECT_GE(leaf.count, 1u);
      EXPECT_LE(leaf.count, static_cast<uint32_t>(s.max_leaf_size));
      for (uint32_t k = leaf.begin; k < leaf.begin + leaf.count; ++k) {
        const uint32_t id = tree.prims[k];
        ++seen[id];
        EXPECT_TRUE(contains(box, input[id].box())) << "primitive " << id << " outside its leaf's box";
      }
      return;
    }
    const bvh::BuildNode& node = tree.nodes[ref];
    EXPECT_GE(node.count, 2);
    EXPECT_LE(node.count, bvh::kWidth);
    for (int i = 0; i < node.count; ++i) {
      EXPECT_TRUE(contains(box, node.box[i])) << "child box outside its parent's";
      visit(node.child[i], node.box[i], level + 1);
    }
  };
  visit(tree.root, tree.bounds, 0);
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }))
      << "every primitive must be in exactly one leaf";
  return depth;
}

TEST(BvhBuild, EveryPrimitiveInExactlyOneBoundedLeaf) {
  WorkerPool pool(2);
  test::Rng rng(1);
  for (const uint32_t n : {1u, 2u, 7u, 100u, 50000u}) {
    for (const int max_leaf : {1, 4, 16}) {
      for (const int bins : {4, 16, 32}) {
        const std::vector<bvh::PrimRef> refs = random_boxes(rng, n);
        bvh::BuildSettings s;
        s.max_leaf_size = max_leaf;
        s.bins = bins;
        bvh::BuildTree tree;
        pool.run([&] { tree = bvh::build_tree(refs, s); });
        ASSERT_EQ(tree.prims.size(), n);
        check_tree(tree, refs, s);
      }
    }
  }
  EXPECT_TRUE(bvh::build_tree({}, bvh::BuildSettings{}).empty());
}

TEST(BvhBuild, SahSeparatesDistantClusters) {
  test::Rng rng(2);
  std::vector<bvh::PrimRef> refs = random_boxes(rng, 200);
  for (uint32_t i = 100; i < 200; ++i) {
    refs[i].lo.x += 1000.0f;
    refs[i].hi.x += 1000.0f;
  }
  const bvh::BuildTree tree = bvh::build_tree(refs, bvh::BuildSettings{});
  ASSERT_FALSE(tree.root & bvh::kLeafRef);
  const bvh::BuildNode& root = tree.nodes[tree.root];
  for (int i = 0; i < root.count; ++i) {
    const bool left = root.box[i].hi.x < 500.0f, right = root.box[i].lo.x > 500.0f;
    EXPECT_TRUE(left || right) << "child " << i << " spans both clusters";
  }
}

TEST(BvhBuild, DepthStaysBoundedOnAdversarialInput) {
  // Centres spaced geometrically over 25 orders of magnitude: every binned
  // split peels off a handful of primitives, so without the median fallback
  // the tree would be hundreds of levels deep.
  std::vector<bvh::PrimRef> refs;
  for (uint32_t i = 0; i < 3000; ++i) {
    const float x = std::pow(1.02f, static_cast<float>(i));
    refs.push_back(bvh::PrimRef{Bounds3f{{x, 0, 0}, {x * 1.001f, 1, 1}}, i});
  }
  bvh::BuildSettings s;
  s.max_leaf_size = 2;
  const bvh::BuildTree tree = bvh::build_tree(refs, s);
  const int depth = check_tree(tree, refs, s);
  EXPECT_GT(depth, bvh::kMedianDepth / 2);  // the input really is adversarial
  EXPECT_LE(depth, bvh::kMaxDepth);

  // And the traversal (whose stack is sized from kMaxDepth) still answers right.
  SceneGeometry g;
  TriangleMesh m;
  for (uint32_t i = 0; i < 3000; ++i) {
    const float x = std::pow(1.02f, static_cast<float>(i));
    m.positions.insert(m.positions.end(), {{x, 0, 0}, {x, 1, 0}, {x, 0, 1}});
    m.indices.insert(m.indices.end(), {3 * i, 3 * i + 1, 3 * i + 2});
  }
  g.shapes.push_back(m);
  WorkerPool pool(2);
  auto accel = bvh::build(g, pool, *std::make_unique<Diagnostics>());
  ASSERT_NE(accel, nullptr);
  EXPECT_LE(bvh::tree_stats(*accel)->bottom.depth, bvh::kMaxDepth);
  test::Rng rng(3);
  for (int i = 0; i < 2000; ++i) {
    const float x = std::pow(1.02f, rng.uniform(0, 3000));
    const Ray ray{{x, 0.25f, -1}, {rng.uniform(-1, 1), rng.uniform(0, 0.2f), 1}};
    Hit got, want;
    const bool have = accel->intersect(ray, got), expect = test::brute_intersect(g, ray, want);
    ASSERT_TRUE(test::classify(g, ray, true, have, got, expect, want) <= test::Agreement::Tie) << i;
  }
}

SceneGeometry large_scene() {
  SceneGeometry g;
  g.shapes.push_back(test::make_uv_sphere({0, 0, 0}, 5.0f, 220, 300));  // ~130k triangles
  test::Rng rng(4);
  for (int i = 0; i < 30; ++i) {
    const Vec3f c{rng.uniform(-9, 9), rng.uniform(-9, 9), rng.uniform(-9, 9)};
    g.shapes.push_back(i % 2 ? Shape(Sphere{c, 0.5f, {0, 0, 1}}) : Shape(test::make_uv_sphere(c, 0.7f, 10, 20)));
  }
  return g;
}

TEST(Bvh, BuildIsDeterministicAcrossThreadCounts) {
  const SceneGeometry g = large_scene();
  std::vector<uint64_t> prints;
  for (const int threads : {1, 2, 3, 8}) {
    WorkerPool pool(threads);
    for (int repeat = 0; repeat < 2; ++repeat) {
      Diagnostics diag;
      auto accel = bvh::build(g, pool, diag);
      ASSERT_NE(accel, nullptr);
      prints.push_back(bvh::layout_fingerprint(*accel));
    }
  }
  EXPECT_NE(prints[0], 0u);
  for (const uint64_t p : prints) EXPECT_EQ(p, prints[0]);
}

TEST(Bvh, KernelsAgreeBitForBit) {
  if (!bvh::cpu_has_avx2_fma()) GTEST_SKIP() << "this CPU has no AVX2 kernel to compare";
  SceneGeometry g = large_scene();
  TriangleMesh grid;  // shared edges and vertices to aim at exactly
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i) grid.positions.push_back({-10.0f + i, -10.0f, -10.0f + j});
  for (uint32_t j = 0; j < 20; ++j) {
    for (uint32_t i = 0; i < 20; ++i) {
      const uint32_t v = j * 21 + i, w = v + 21;
      grid.indices.insert(grid.indices.end(), {v, w, w + 1, v, w + 1, v + 1});
    }
  }
  g.shapes.push_back(grid);
  WorkerPool pool(2);
  Diagnostics diag;
  bvh::Options sse2;
  sse2.isa = bvh::Isa::Sse2;
  auto a = bvh::build(g, pool, diag, sse2);
  ASSERT_TRUE(a) << diag.format();
  EXPECT_EQ(bvh::tree_stats(*a)->isa, "SSE2");
  const auto& sphere = std::get<TriangleMesh>(g.shapes[0]);
  test::Rng rng(5);
  std::vector<Ray> rays;
  for (int i = 0; i < 20000; ++i) rays.push_back(Ray{12.0f * rng.unit_vector(), rng.unit_vector()});
  for (std::size_t i = 0; i < sphere.positions.size(); i += 7) {
    const Vec3f o = 12.0f * rng.unit_vector();
    rays.push_back(Ray{o, sphere.positions[i] - o});  // exactly at vertices
  }
  for (const Vec3f& v : grid.positions) {
    rays.push_back(Ray{v + Vec3f(0.3f, 4, -0.2f), Vec3f(-0.3f, -4, 0.2f)});
    rays.push_back(Ray{v + Vec3f(0.5f, 4, 0), Vec3f(-0.5f, -4, 0)});  // along an edge's line
  }
  // Every wide kernel this CPU runs against the SSE2 one.
  for (const auto& [isa, name] : test::wide_kernels()) {
    SCOPED_TRACE(name);
    bvh::Options wide;
    wide.isa = isa;
    auto b = bvh::build(g, pool, diag, wide);
    ASSERT_TRUE(b) << diag.format();
    EXPECT_EQ(bvh::tree_stats(*b)->isa, name);
    int hits = 0;
    for (const Ray& ray : rays) {
      Hit ha, hb;
      TraversalCounters ca, cb;
      const bool fa = a->intersect_counted(ray, ha, ca), fb = b->intersect_counted(ray, hb, cb);
      ASSERT_EQ(fa, fb);
      ASSERT_EQ(a->occluded(ray), b->occluded(ray));
      ASSERT_EQ(ca.nodes, cb.nodes);
      ASSERT_EQ(ca.primitives, cb.primitives);
      if (!fa) continue;
      ++hits;
      ASSERT_EQ(ha.t, hb.t);
      ASSERT_EQ(ha.shape, hb.shape);
      ASSERT_EQ(ha.prim, hb.prim);
      ASSERT_EQ(ha.uv, hb.uv);
    }
    EXPECT_GT(hits, 5000);
  }
}

TEST(Bvh, TriangleFilterMatchesReference) {
  // The wide kernels replicate the reference triangle test (kernel_wide.h);
  // here it meets the cases where the reference's branches matter: slivers,
  // triangles far from the origin and tiny ones, rays starting on a surface
  // (the t-error rejection), rays nearly in a triangle's plane.
  if (!bvh::cpu_has_avx2_fma()) GTEST_SKIP() << "this CPU has no AVX2 kernel";
  WorkerPool pool(1);
  for (const auto& [isa, name] : test::wide_kernels()) {
    SCOPED_TRACE(name);
    test::Rng rng(9);
    bvh::Options wide;
    wide.isa = isa;
    for (int family = 0; family < 5; ++family) {
      SceneGeometry g;
      TriangleMesh m;
      const Vec3f centre = family == 2 ? Vec3f(1e5f, -2e5f, 5e4f) : Vec3f(0.0f);
      const float size = family == 3 ? 1e-4f : 1.0f;
      for (uint32_t i = 0; i < 200; ++i) {
        const Vec3f c = centre + size * Vec3f(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 4));
        Vec3f a = size * rng.unit_vector(), b = size * rng.unit_vector();
        if (family == 1) {  // slivers
          a = 10.0f * size * rng.unit_vector();
          b = a + 1e-3f * size * normalize(cross(a, rng.unit_vector()));
        }
        m.positions.insert(m.positions.end(), {c - a, c + a, c + b});
        m.indices.insert(m.indices.end(), {3 * i, 3 * i + 1, 3 * i + 2});
      }
      g.shapes.push_back(m);
      Diagnostics diag;
      auto accel = bvh::build(g, pool, diag, wide);
      ASSERT_NE(accel, nullptr) << diag.format();
      int hits = 0;
      for (int i = 0; i < 6000; ++i) {
        const uint32_t tri = static_cast<uint32_t>(rng.uniform() * 199.0f);
        const Vec3f* p = &m.positions[3 * tri];
        const float u = rng.uniform(), v = rng.uniform() * (1 - u);
        const Vec3f target = (1 - u - v) * p[0] + u * p[1] + v * p[2];
        Ray ray{target + size * rng.uniform(0.5f, 8.0f) * rng.unit_vector(), Vec3f(0.0f)};
        ray.dir = target - ray.origin;
        if (family == 4) {  // from the surface itself, or nearly in the triangle's plane
          const Vec3f n = normalize(cross(p[1] - p[0], p[2] - p[0]));
          if (i % 2 == 0) {
            ray = Ray{target, rng.unit_vector()};
          } else {
            ray.dir = ray.dir - (dot(ray.dir, n) * 0.999f) * n;
          }
        }
        Hit got, want;
        const bool have = accel->intersect(ray, got), expect = test::brute_intersect(g, ray, want);
        ASSERT_EQ(have, expect) << "family " << family << " ray " << i;
        ASSERT_EQ(accel->occluded(ray), expect) << "family " << family << " ray " << i;
        if (!have) continue;
        ++hits;
        ASSERT_EQ(got.t, want.t) << "family " << family << " ray " << i;
        if (got.prim == want.prim) {
          ASSERT_EQ(got.uv, want.uv) << "family " << family << " ray " << i;
        }
      }
      EXPECT_GT(hits, 1000) << "family " << family;
    }
  }
}

TEST(Bvh, TreeStatisticsAreConsistent) {
  const SceneGeometry g = large_scene();
  WorkerPool pool(2);
  Diagnostics diag;
  auto accel = bvh::build(g, pool, diag);
  ASSERT_NE(accel, nullptr);
  const bvh::SceneTreeStats& s = *bvh::tree_stats(*accel);
  const AccelStats stats = accel->stats();
  EXPECT_EQ(s.bottom.prims, stats.primitive_count);
  EXPECT_EQ(s.bottom_levels, 17u);  // 16 meshes and one over the 15 spheres
  EXPECT_EQ(s.top.prims, 17u);
  std::size_t leaves = 0, prims = 0;
  for (std::size_t k = 0; k < s.bottom.leaf_sizes.size(); ++k) {
    leaves += s.bottom.leaf_sizes[k];
    prims += k * s.bottom.leaf_sizes[k];
  }
  EXPECT_EQ(leaves, s.bottom.leaves);
  EXPECT_EQ(prims, s.bottom.prims);
  EXPECT_GE(s.bottom.blocks * 4, s.bottom.prims - 15);  // triangle blocks hold up to 4
  EXPECT_GE(s.bottom.child_slots_used, 2 * s.bottom.nodes);
  EXPECT_LE(s.bottom.child_slots_used, 8 * s.bottom.nodes);
  EXPECT_GT(s.bottom.depth, 2);
  EXPECT_LE(s.bottom.depth, bvh::kMaxDepth);
  EXPECT_GT(s.bottom.sah_cost, 1.0);
  EXPECT_GT(s.top.sah_cost, 1.0);
  EXPECT_GE(stats.memory_bytes, s.bottom.bytes + s.top.bytes);
  EXPECT_LT(stats.memory_bytes, 100 * stats.primitive_count);
  EXPECT_EQ(stats.backend.rfind("bvh (", 0), 0u) << stats.backend;
  EXPECT_NE(stats.backend.find(s.isa), std::string::npos) << stats.backend;
  EXPECT_GE(stats.build_seconds, 0.0);
  // The same scene bounds as Embree reports.
  auto embree = build_accelerator(AccelKind::Embree, g, pool, diag);
  ASSERT_NE(embree, nullptr);
  EXPECT_EQ(accel->bounds().lo, embree->bounds().lo);
  EXPECT_EQ(accel->bounds().hi, embree->bounds().hi);
}

TEST(Bvh, CountsTraversalWork) {
  SceneGeometry g;
  for (int i = 0; i < 64; ++i) {
    const float z = static_cast<float>(i);  // a stack of parallel squares
    g.shapes.push_back(Quad{{{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}}});
  }
  g.shapes.push_back(test::make_uv_sphere({5, 0, 30}, 1.0f, 16, 32));
  WorkerPool pool(1);
  Diagnostics diag;
  auto accel = bvh::build(g, pool, diag);
  auto embree = build_accelerator(AccelKind::Embree, g, pool, diag);
  ASSERT_TRUE(accel && embree);
  EXPECT_TRUE(accel->counts_traversal());
  EXPECT_FALSE(embree->counts_traversal());

  Hit hit, plain;
  TraversalCounters front;
  ASSERT_TRUE(accel->intersect_counted(Ray{{0, 0, -5}, {0, 0, 1}}, hit, front));  // the first square stops it
  ASSERT_TRUE(accel->intersect(Ray{{0, 0, -5}, {0, 0, 1}}, plain));
  EXPECT_EQ(hit.t, plain.t);
  EXPECT_EQ(hit.shape, 0u);
  TraversalCounters along;  // down the stack from the far end: nearest first, so little work
  ASSERT_TRUE(accel->intersect_counted(Ray{{0, 0, 70}, {0, 0, -1}}, hit, along));
  EXPECT_EQ(hit.shape, 63u);
  EXPECT_GT(front.nodes, 0u);
  EXPECT_GT(front.primitives, 0u);
  EXPECT_LT(front.primitives, 20u);
  EXPECT_GT(along.primitives, 0u);
  EXPECT_LT(along.primitives, 20u);
  TraversalCounters miss;  // misses the scene's bounds: the top node only
  EXPECT_FALSE(accel->intersect_counted(Ray{{100, 100, 100}, {1, 0, 0}}, hit, miss));
  EXPECT_LE(miss.nodes, 1u);
  EXPECT_EQ(miss.primitives, 0u);
  // Counters add up over calls; Embree leaves them alone.
  TraversalCounters sum = front;
  accel->intersect_counted(Ray{{0, 0, -5}, {0, 0, 1}}, hit, sum);
  EXPECT_EQ(sum.nodes, 2 * front.nodes);
  TraversalCounters untouched;
  EXPECT_TRUE(embree->intersect_counted(Ray{{0, 0, -5}, {0, 0, 1}}, hit, untouched));
  EXPECT_EQ(untouched.nodes, 0u);
  EXPECT_EQ(untouched.primitives, 0u);
}

}  // namespace
}  // namespace pt
