// Test-only helpers: deterministic random numbers, directions, and closed
// meshes (a UV sphere and a box) for leak and self-intersection tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "geometry/shapes.h"

namespace pt::test {

class Rng {
 public:
  explicit Rng(uint32_t seed) : gen_(seed) {}
  float uniform() { return std::uniform_real_distribution<float>(0.0f, 1.0f)(gen_); }
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(gen_); }
  Vec3f unit_vector() {
    const float z = uniform(-1.0f, 1.0f);
    const float phi = uniform(0.0f, 2.0f * kPi);
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {s * std::cos(phi), s * std::sin(phi), z};
  }
  // A unit vector in the hemisphere around n with |cos| >= min_cos.
  Vec3f hemisphere(Vec3f n, float min_cos) {
    for (;;) {
      Vec3f v = unit_vector();
      const float c = dot(v, n);
      if (std::fabs(c) < min_cos) continue;
      return c < 0.0f ? -v : v;
    }
  }

 private:
  std::mt19937 gen_;
};

// A closed UV sphere, triangles wound counter-clockwise seen from outside.
inline TriangleMesh make_uv_sphere(Vec3f centre, float radius, int rings, int segments) {
  TriangleMesh m;
  m.positions.push_back(centre + Vec3f(0, 0, radius));  // north pole: 0
  for (int i = 1; i < rings; ++i) {
    const float theta = kPi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j < segments; ++j) {
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
      m.positions.push_back(centre + radius * Vec3f(std::sin(theta) * std::cos(phi),
                                                    std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  const auto south = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back(centre + Vec3f(0, 0, -radius));
  auto ring_vertex = [&](int ring, int seg) {  // ring in [1, rings - 1]
    return static_cast<uint32_t>(1 + (ring - 1) * segments + (seg % segments));
  };
  auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
    m.indices.push_back(a);
    m.indices.push_back(b);
    m.indices.push_back(c);
  };
  for (int j = 0; j < segments; ++j) tri(0, ring_vertex(1, j), ring_vertex(1, j + 1));
  for (int i = 1; i < rings - 1; ++i) {
    for (int j = 0; j < segments; ++j) {
      tri(ring_vertex(i, j), ring_vertex(i + 1, j), ring_vertex(i + 1, j + 1));
      tri(ring_vertex(i, j), ring_vertex(i + 1, j + 1), ring_vertex(i, j + 1));
    }
  }
  for (int j = 0; j < segments; ++j) tri(south, ring_vertex(rings - 1, j + 1), ring_vertex(rings - 1, j));
  return m;
}

// The 8 corners of an axis-aligned box, index = x | y << 1 | z << 2.
inline Vec3f box_corner(Vec3f lo, Vec3f hi, int i) {
  return {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
}

// The six faces of a box as corner indices in counter-clockwise order seen from outside.
inline constexpr int kBoxFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                        {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

inline TriangleMesh make_box_mesh(Vec3f lo, Vec3f hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back(box_corner(lo, hi, i));
  for (const auto& f : kBoxFaces) {
    for (int k : {f[0], f[1], f[2], f[0], f[2], f[3]}) m.indices.push_back(static_cast<uint32_t>(k));
  }
  return m;
}

inline Quad box_face_quad(Vec3f lo, Vec3f hi, int face) {
  Quad q;
  for (int k = 0; k < 4; ++k) q.v[k] = box_corner(lo, hi, kBoxFaces[face][k]);
  return q;
}

// For a convex shape S (whole shape): points its area sampler draws, seen
// along their normal from distance 0.5, are hit at t = 0.5 with the sampler's
// point and normal; the mean of the points is returned (for centroid checks).
template <class S>
Vec3f expect_samples_hit_along_normal(const S& shape, int n = 2000, float tol = 1e-4f) {
  const auto sampler = make_area_sampler(shape);
  Rng rng(7);
  Vec3f sum(0.0f);
  int failures = 0;
  for (int i = 0; i < n; ++i) {
    Vec3f q, nq;
    sampler.sample({rng.uniform(), rng.uniform()}, q, nq);
    sum += q;
    const Ray ray{q + 0.5f * nq, -nq};
    PrimHit hit;
    const bool found = intersect(shape, ray, hit);
    SurfaceGeometry sg;
    if (found) sg = surface(shape, ray, hit);
    const bool ok = found && std::fabs(hit.t - 0.5f) < tol && length(sg.p - q) < 10 * tol &&
                    dot(sg.ng, nq) > 1.0f - 1e-4f && sg.uv.x >= 0 && sg.uv.x <= 1 && sg.uv.y >= 0 && sg.uv.y <= 1;
    if (!ok && failures++ < 3) {
      ADD_FAILURE() << "sample " << i << " at (" << q.x << ", " << q.y << ", " << q.z << ")"
                    << (found ? " hit at t " + std::to_string(hit.t) : std::string(" missed"));
    }
  }
  return sum / static_cast<float>(n);
}

// The hit of `ray` on a whole shape, expected at t = expected_t; its surface.
template <class S>
SurfaceGeometry hit_surface(const S& shape, const Ray& ray, float expected_t) {
  PrimHit hit;
  EXPECT_TRUE(intersect(shape, ray, hit));
  EXPECT_NEAR(hit.t, expected_t, 1e-5f);
  return surface(shape, ray, hit);
}

}  // namespace pt::test
