// Triangles: the watertight ray/triangle test of Woop, Benthin and Wald (JCGT
// 2013) with a conservative bound on the error of t (as in pbrt-v4), and mesh
// surface evaluation.
#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/float_util.h"
#include "geometry/shapes/mesh.h"

namespace pt {

UvDerivatives uv_derivatives(const TriangleMesh& m, uint32_t tri, const SurfaceGeometry& /*sg*/) {
  const uint32_t* idx = &m.indices[3 * static_cast<std::size_t>(tri)];
  const Vec3f p0 = m.positions[idx[0]];
  const Vec3f dp1 = m.positions[idx[1]] - p0, dp2 = m.positions[idx[2]] - p0;
  if (m.uvs.size() == m.positions.size()) {
    const Vec2f uv0 = m.uvs[idx[0]];
    const Vec2f d1 = m.uvs[idx[1]] - uv0, d2 = m.uvs[idx[2]] - uv0;
    const float det = d1.x * d2.y - d1.y * d2.x;
    const float scale = std::max(std::fabs(d1.x * d2.y), std::fabs(d1.y * d2.x));
    if (std::fabs(det) > 1e-8f * scale && std::isfinite(1.0f / det)) {
      const float inv = 1.0f / det;
      return {(dp1 * d2.y - dp2 * d1.y) * inv, (dp2 * d1.x - dp1 * d2.x) * inv};
    }
  }
  return {dp1, dp2};
}

namespace {

// The triangle's vertices in the ray's sheared frame (the ray runs along +z from 0).
struct Sheared {
  Vec3f a, b, c;
};

// The bound on the error of t (pbrt-v4's, "Triangle Intersection" in
// "Floating-Point Error") from the sheared vertices' largest |x|, |y|, |z|
// before the scaling by sz and |z sz|, the largest edge function and |det|.
// pbrt bounds the error of the sheared x and y by gamma(5) (|x| + |z sz|);
// the shear adds sx z with |sx| <= 1, so |z| before the scaling bounds it.
// The scaled |z sz| is |z| / |d.z|: for a short direction (a ray in the space
// of an instance scaled up 1e4 is 1e-4 long) pbrt's bound grows as 1 / |d|^2
// while t grows as 1 / |d|, and hits of triangles reaching behind the origin
// (a ray leaving a closed mesh from inside) were rejected as not certainly
// positive: rays escaped instanced boxes scaled ~1e4 (docs/numerical-
// stability.md, section 11). kernel_avx2.cpp replicates this operation for
// operation.
inline float t_error_bound(float max_xt, float max_yt, float max_z, float max_zt, float max_e, float abs_det) {
  const float delta_z = fp::gamma(3) * max_zt;
  const float delta_x = fp::gamma(5) * (max_xt + max_z);
  const float delta_y = fp::gamma(5) * (max_yt + max_z);
  const float delta_e = 2.0f * (fp::gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  return 3.0f * (fp::gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) / abs_det;
}

}  // namespace

// Two clones chosen at load time: on x86-64-v3 (AVX2, FMA) the three fmaf of
// each difference of products are single instructions instead of libm calls
// (and the registers are not spilled around them). Results are bit-identical:
// fma is exactly rounded either way and nothing is contracted (-ffp-contract=off).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
bool intersect_triangle(Vec3f p0, Vec3f p1, Vec3f p2, const Ray& ray, PrimHit& hit) {
  // Ray frame: translate to the origin, permute so that the dominant direction
  // component is z, shear so that the direction becomes (0, 0, 1).
  const int kz = fp::max_dimension(abs(ray.dir));
  const int kx = kz == 2 ? 0 : kz + 1;
  const int ky = kx == 2 ? 0 : kx + 1;
  const Vec3f d = fp::permute(ray.dir, kx, ky, kz);
  Sheared s{fp::permute(p0 - ray.origin, kx, ky, kz), fp::permute(p1 - ray.origin, kx, ky, kz),
            fp::permute(p2 - ray.origin, kx, ky, kz)};
  const float sz = 1.0f / d.z;
  const float sx = -d.x * sz;
  const float sy = -d.y * sz;
  s.a.x += sx * s.a.z;
  s.a.y += sy * s.a.z;
  s.b.x += sx * s.b.z;
  s.b.y += sy * s.b.z;
  s.c.x += sx * s.c.z;
  s.c.y += sy * s.c.z;

  // Edge functions (twice the signed areas of the sub-triangles seen from the
  // ray). e0 weighs p0, e1 weighs p1, e2 weighs p2.
  float e0 = fp::difference_of_products(s.b.x, s.c.y, s.b.y, s.c.x);
  float e1 = fp::difference_of_products(s.c.x, s.a.y, s.c.y, s.a.x);
  float e2 = fp::difference_of_products(s.a.x, s.b.y, s.a.y, s.b.x);
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    // Exactly on an edge in float: decide in double so that neighbouring
    // triangles sharing the edge agree (no cracks, no double hits).
    const double ax = s.a.x, ay = s.a.y, bx = s.b.x, by = s.b.y, cx = s.c.x, cy = s.c.y;
    e0 = static_cast<float>(bx * cy - by * cx);
    e1 = static_cast<float>(cx * ay - cy * ax);
    e2 = static_cast<float>(ax * by - ay * bx);
  }
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) return false;
  const float det = e0 + e1 + e2;
  if (det == 0.0f) return false;

  // The largest |z| before the scaling by sz: the shear's error term in x and y
  // (sx z, |sx| <= 1 since z is the dominant axis) is bounded by it.
  const float max_z = std::max({std::fabs(s.a.z), std::fabs(s.b.z), std::fabs(s.c.z)});
  s.a.z *= sz;
  s.b.z *= sz;
  s.c.z *= sz;
  const float t = (e0 * s.a.z + e1 * s.b.z + e2 * s.c.z) / det;
  if (!(t > ray.tmin && t < ray.tmax)) return false;  // also rejects NaN

  // Reject t that is not conservatively positive given the rounding error of
  // the computation above: this is what keeps a ray leaving the surface from
  // re-hitting it when combined with the origin offset (docs/geometry.md).
  // Only a triangle reaching back to the origin's side (some scaled z <= 0)
  // can be hit at t <= 0: with every z > 0 (signs of differences are exact),
  // t is a non-negative weighting of positive numbers, and rejecting it on the
  // bound alone would open cracks wherever the bound exceeds t -- slivers, and
  // the bound's 1/|ray.dir| growth (10 in 100,000 unit rays aimed at the
  // vertices of a 500x500 sphere 2.7e5 from the origin slipped through).
  const bool certainly_ahead = s.a.z > 0.0f && s.b.z > 0.0f && s.c.z > 0.0f;
  const float max_zt = std::max({std::fabs(s.a.z), std::fabs(s.b.z), std::fabs(s.c.z)});
  const float max_xt = std::max({std::fabs(s.a.x), std::fabs(s.b.x), std::fabs(s.c.x)});
  const float max_yt = std::max({std::fabs(s.a.y), std::fabs(s.b.y), std::fabs(s.c.y)});
  const float max_e = std::max({std::fabs(e0), std::fabs(e1), std::fabs(e2)});
  if (t <= t_error_bound(max_xt, max_yt, max_z, max_zt, max_e, std::fabs(det)) && !certainly_ahead) return false;

  // Exactly degenerate triangles (repeated or collinear vertices) can pass the
  // edge tests with a rounding-noise determinant; they never hit. Checked only
  // here, off the miss path.
  if (degenerate_triangle(p0, p1, p2)) return false;

  hit.t = t;
  hit.uv = {e1 / det, e2 / det};
  return true;
}

Bounds3f bounds(const TriangleMesh& m) {
  Bounds3f b;
  const std::size_t n = m.positions.size();
  for (uint32_t idx : m.indices) {
    if (idx < n) b.extend(m.positions[idx]);
  }
  return fp::pad(b);
}

Bounds3f bounds(const TriangleMesh& m, uint32_t tri) {
  const uint32_t* idx = &m.indices[3 * static_cast<std::size_t>(tri)];
  Bounds3f b;
  b.extend(m.positions[idx[0]]);
  b.extend(m.positions[idx[1]]);
  b.extend(m.positions[idx[2]]);
  return fp::pad(b);
}

bool intersect(const TriangleMesh& m, uint32_t tri, const Ray& ray, PrimHit& hit) {
  const uint32_t* idx = &m.indices[3 * static_cast<std::size_t>(tri)];
  return intersect_triangle(m.positions[idx[0]], m.positions[idx[1]], m.positions[idx[2]], ray, hit);
}

SurfaceGeometry surface(const TriangleMesh& m, uint32_t tri, const Ray& /*ray*/, const PrimHit& hit) {
  const uint32_t* idx = &m.indices[3 * static_cast<std::size_t>(tri)];
  const Vec3f p0 = m.positions[idx[0]];
  const Vec3f p1 = m.positions[idx[1]];
  const Vec3f p2 = m.positions[idx[2]];
  const float b1 = hit.uv.x;
  const float b2 = hit.uv.y;
  const float b0 = 1.0f - b1 - b2;

  SurfaceGeometry sg;
  // The point from the barycentrics, not ray.at(t): its error depends only on
  // the vertices, not on how far the ray travelled.
  sg.p = b0 * p0 + b1 * p1 + b2 * p2;
  sg.p_error = fp::gamma(7) * (abs(b0 * p0) + abs(b1 * p1) + abs(b2 * p2));

  const Vec3f n = cross(p1 - p0, p2 - p0);
  const float len = length(n);
  sg.ng = len > 0.0f ? n / len : Vec3f(0, 0, 1);

  sg.ns = sg.ng;
  const std::size_t nv = m.positions.size();
  if (m.normals.size() == nv) {
    const Vec3f ns = b0 * m.normals[idx[0]] + b1 * m.normals[idx[1]] + b2 * m.normals[idx[2]];
    const float ls = length(ns);
    if (ls > 0.0f && std::isfinite(ls)) sg.ns = dot(ns, sg.ng) < 0.0f ? -(ns / ls) : ns / ls;
  }
  if (m.uvs.size() == nv) {
    sg.uv = m.uvs[idx[0]] * b0 + m.uvs[idx[1]] * b1 + m.uvs[idx[2]] * b2;
  } else {
    sg.uv = {b1, b2};
  }
  return sg;
}

namespace {

void check_triangle(const TriangleMesh& m, ShapeChecker& c) {
  if (m.positions.size() != 3) return;
  if (zero_area_triangle(m.positions[0], m.positions[1], m.positions[2]))
    c.warning("", "triangle is degenerate (zero area, corners in a line); it will not be visible");
}

// Each mismatch of a per-vertex list.
void check_vertex_lists(const TriangleMesh& m, ShapeChecker& c, const std::string& what) {
  for (const Vec3f& p : m.positions) {
    if (!is_finite(p)) {
      c.unusable("file", what + " has a vertex position that is not a finite number");
      break;
    }
  }
  if (!m.normals.empty() && m.normals.size() != m.positions.size())
    c.unusable("file", what + " has " + std::to_string(m.normals.size()) + " normals for " +
                        std::to_string(m.positions.size()) + " vertices");
  if (!m.uvs.empty() && m.uvs.size() != m.positions.size())
    c.unusable("file", what + " has " + std::to_string(m.uvs.size()) + " texture coordinates for " +
                        std::to_string(m.positions.size()) + " vertices");
}

}  // namespace

void check(const TriangleMesh& m, ShapeChecker& c) {
  if (c.type() == "triangle") return check_triangle(m, c);
  const std::string what = c.file().empty() ? std::string("mesh") : "mesh '" + c.file() + "'";
  if (m.indices.size() % 3 != 0) {
    c.unusable("file", what + " has " + std::to_string(m.indices.size()) + " indices, not a multiple of 3");
    return;
  }
  std::size_t bad = 0;
  uint32_t first_bad = 0;
  for (uint32_t i : m.indices) {
    if (i >= m.positions.size() && bad++ == 0) first_bad = i;
  }
  if (bad > 0)
    c.unusable("file", what + ": " + std::to_string(bad) + " vertex indices are out of range (e.g. " +
                        std::to_string(first_bad) + "; the mesh has " + std::to_string(m.positions.size()) +
                        " vertices)");
  check_vertex_lists(m, c, what);
  if (m.indices.empty()) c.warning("file", what + " has no triangles; it will not be visible");
}

TriangleAreaSampler make_area_sampler(const TriangleMesh& m) {
  TriangleAreaSampler s;
  std::vector<float> areas(m.triangle_count());
  s.triangles.reserve(areas.size());
  double total = 0.0;
  for (std::size_t t = 0; t < areas.size(); ++t) {
    const uint32_t* idx = &m.indices[3 * t];
    const Vec3f p0 = m.positions[idx[0]], p1 = m.positions[idx[1]], p2 = m.positions[idx[2]];
    const Vec3f cr = cross(p1 - p0, p2 - p0);
    const float len = length(cr);
    areas[t] = 0.5f * len;
    total += areas[t];
    s.triangles.push_back({p0, p1 - p0, p2 - p0, len > 0.0f ? cr / len : Vec3f(0, 0, 1)});
  }
  s.area = static_cast<float>(total);
  s.parts = Distribution1D(areas);
  return s;
}

}  // namespace pt
