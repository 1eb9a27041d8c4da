// Test-only helpers for running the same test on every backend: the backend
// list (Embree, our BVH with the kernel the CPU gets, our BVH forced to the
// baseline SSE2 kernel and, where Auto gets AVX-512, to the AVX2 one),
// building, and comparing a backend's answer with the brute-force loop of
// brute_force.h.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "accel/accelerator.h"
#include "accel/bvh/bvh_accel.h"
#include "accel/bvh/kernels.h"
#include "accel/unbounded.h"
#include "brute_force.h"
#include "core/parallel.h"

namespace pt::test {

struct Backend {
  AccelKind kind = AccelKind::Embree;
  bvh::Isa isa = bvh::Isa::Auto;
  std::string name;
  // Our BVH finds every hit with the brute-force loop's routines, so it must
  // agree exactly. Embree is held to less: it tests triangles with its own
  // (Plücker) routine, so its answers differ where a ray passes within
  // rounding of a triangle's boundary, and its t is less accurate for slivers.
  bool exact() const { return kind == AccelKind::Bvh; }
};

inline void PrintTo(const Backend& b, std::ostream* os) { *os << b.name; }

inline std::vector<Backend> all_backends() {
  std::vector<Backend> b{Backend{AccelKind::Embree, bvh::Isa::Auto, "embree"},
                         Backend{AccelKind::Bvh, bvh::Isa::Auto, "bvh"},
                         Backend{AccelKind::Bvh, bvh::Isa::Sse2, "bvh_sse2"}};
  // Auto picks the AVX-512 kernel where the CPU has it: the AVX2 one then runs as well.
  if (bvh::cpu_has_avx512()) b.push_back(Backend{AccelKind::Bvh, bvh::Isa::Avx2, "bvh_avx2"});
  return b;
}

// The wide kernels this CPU can run, with the names tree_stats() reports.
inline std::vector<std::pair<bvh::Isa, std::string>> wide_kernels() {
  std::vector<std::pair<bvh::Isa, std::string>> k;
  if (bvh::cpu_has_avx2_fma()) k.emplace_back(bvh::Isa::Avx2, "AVX2");
  if (bvh::cpu_has_avx512()) k.emplace_back(bvh::Isa::Avx512, "AVX-512VL");
  return k;
}

inline std::string backend_name(const ::testing::TestParamInfo<Backend>& info) { return info.param.name; }

inline std::unique_ptr<Accelerator> build_backend(const Backend& b, const SceneGeometry& g, WorkerPool& pool) {
  Diagnostics diag;
  std::unique_ptr<Accelerator> accel;
  if (b.kind == AccelKind::Bvh) {
    bvh::Options options;
    options.isa = b.isa;
    accel = with_unbounded_shapes(bvh::build(g, pool, diag, options), g);  // as build_accelerator()
  } else {
    accel = build_accelerator(b.kind, g, pool, diag);
  }
  EXPECT_FALSE(diag.has_errors()) << diag.format();
  return accel;
}

// The hit of one given primitive, through the src/geometry routines.
// The ray in the space of the shapes `instance` places (the world for kNoInstance).
inline Ray ray_in(const SceneGeometry& g, uint32_t instance, const Ray& ray) {
  return instance == kNoInstance ? ray : g.instances[instance].transform.to_object(ray);
}

inline bool primitive_hit(const SceneGeometry& g, uint32_t shape, uint32_t prim, const Ray& world, PrimHit& h,
                          uint32_t instance = kNoInstance) {
  const Ray ray = ray_in(g, instance, world);
  return std::visit(
      [&](const auto& s) {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, TriangleMesh>) {
          return intersect(s, prim, ray, h);
        } else {
          return intersect_primitive(s, 0, ray, h);
        }
      },
      g.shapes[shape]);
}

// Where the ray's line meets the plane of mesh triangle (shape, prim), in
// double precision: its parameter t and smallest barycentric coordinate (0 on
// an edge, negative outside). False for analytic shapes and parallel rays.
inline bool plane_hit(const SceneGeometry& g, uint32_t shape, uint32_t prim, const Ray& world, double& t,
                      double& min_bary, uint32_t instance = kNoInstance) {
  const Ray ray = ray_in(g, instance, world);
  const auto* m = std::get_if<TriangleMesh>(&g.shapes[shape]);
  if (m == nullptr) return false;
  struct D3 {
    double x, y, z;
  };
  auto d3 = [](Vec3f v) { return D3{v.x, v.y, v.z}; };
  auto sub = [](D3 a, D3 b) { return D3{a.x - b.x, a.y - b.y, a.z - b.z}; };
  auto dot = [](D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  auto cross = [](D3 a, D3 b) { return D3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; };
  const uint32_t* idx = &m->indices[3 * static_cast<std::size_t>(prim)];
  const D3 p0 = d3(m->positions[idx[0]]), p1 = d3(m->positions[idx[1]]), p2 = d3(m->positions[idx[2]]);
  const D3 o = d3(ray.origin), d = d3(ray.dir);
  const D3 e1 = sub(p1, p0), e2 = sub(p2, p0), n = cross(e1, e2);
  const double dn = dot(d, n), nn = dot(n, n);
  if (dn == 0.0 || nn == 0.0) return false;
  t = dot(sub(p0, o), n) / dn;
  const D3 q = sub(D3{o.x + t * d.x, o.y + t * d.y, o.z + t * d.z}, p0);
  const double b1 = dot(cross(q, e2), n) / nn, b2 = dot(cross(e1, q), n) / nn;
  min_bary = std::min({1.0 - b1 - b2, b1, b2});
  return true;
}

enum class Agreement {
  Same,           // same hit (or both miss)
  Tie,            // a different primitive hit at the same distance
  Boundary,       // (inexact backends) differs where the ray passes within `boundary` of a triangle edge
  AtOrigin,       // (inexact backends) a hit within 1e-4 of the ray origin that the reference does not report
  ReferenceMiss,  // (inexact backends) a hit, clearly inside a triangle in double precision, that the
                  // reference routine rejects (its conservative t bound; see LongThinTriangles)
  Different,      // anything else: a real disagreement
};
inline constexpr int kAgreementKinds = 6;

struct Tolerances {
  float t_relative = 1e-5f;  // of max(t, |origin| / |dir|, 1e-3): the error of t grows with the origin's magnitude
  double boundary = 1e-5;    // barycentric distance from an edge counted as "on the boundary"
};

inline Agreement classify(const SceneGeometry& g, const Ray& ray, bool exact, bool have, const Hit& got, bool want,
                          const Hit& expected, const Tolerances& tol = {}) {
  const float scale = std::max({want ? expected.t : 0.0f, have ? got.t : 0.0f,
                                length(ray.origin) / length(ray.dir), 1e-3f});
  const float t_tol = exact ? 0.0f : tol.t_relative * scale;
  auto near_boundary = [&](const Hit& h) {
    double t = 0, b = 0;
    return !exact && plane_hit(g, h.shape, h.prim, ray, t, b, h.instance) && std::fabs(b) <= tol.boundary;
  };
  const bool backend_nearer = have && (!want || got.t < expected.t - t_tol);
  if (!exact && backend_nearer) {
    if (got.t * length(ray.dir) <= 1e-4f * (length(ray.origin) + 1.0f)) return Agreement::AtOrigin;
    double t = 0, b = 0;
    if (plane_hit(g, got.shape, got.prim, ray, t, b, got.instance) && b > tol.boundary && std::fabs(t - got.t) <= t_tol) {
      return Agreement::ReferenceMiss;
    }
  }
  if (have != want) return near_boundary(have ? got : expected) ? Agreement::Boundary : Agreement::Different;
  if (!want) return Agreement::Same;
  if (got.shape == expected.shape && got.prim == expected.prim && got.instance == expected.instance) {
    if (std::fabs(got.t - expected.t) > t_tol) return Agreement::Different;
    if (exact && !(got.uv == expected.uv)) return Agreement::Different;
    return Agreement::Same;
  }
  PrimHit h;
  if (primitive_hit(g, got.shape, got.prim, ray, h, got.instance) && std::fabs(h.t - expected.t) <= t_tol &&
      std::fabs(got.t - expected.t) <= t_tol) {
    return Agreement::Tie;
  }
  return near_boundary(got) || near_boundary(expected) ? Agreement::Boundary : Agreement::Different;
}

inline const char* agreement_name(Agreement a) {
  switch (a) {
    case Agreement::Same: return "same";
    case Agreement::Tie: return "tie";
    case Agreement::Boundary: return "boundary";
    case Agreement::AtOrigin: return "at-origin";
    case Agreement::ReferenceMiss: return "reference-miss";
    case Agreement::Different: return "different";
  }
  return "?";
}

}  // namespace pt::test
