// The planar convex quad (corners in perimeter order): its data and every
// routine that follows from it. Intersected as the two triangles (v0 v1 v2)
// and (v0 v2 v3) with the watertight triangle test, so quads sharing an edge
// (the walls of a box) have no cracks between them. Texture coordinates are
// the bilinear (u, v): v0 at (0, 0), v1 at (1, 0), v3 at (0, 1).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "geometry/float_util.h"
#include "geometry/shape_base.h"

namespace pt {

// Planar convex quad, corners in perimeter order.
struct Quad {
  Vec3f v[4];
};

// Watertight ray/triangle test (Woop, Benthin, Wald 2013; geometry/triangle.cpp).
// uv = barycentrics of p1, p2.
bool intersect_triangle(Vec3f p0, Vec3f p1, Vec3f p2, const Ray& ray, PrimHit& hit);

namespace quad_detail {

inline Vec3f quad_normal(const Quad& q) {
  // The cross product of the diagonals: for a planar convex quad it has the
  // orientation of cross(v1 - v0, v3 - v0) and survives one collapsed corner.
  Vec3f n = cross(q.v[2] - q.v[0], q.v[3] - q.v[1]);
  float len = length(n);
  if (!(len > 0.0f) || !std::isfinite(len)) {
    n = cross(q.v[1] - q.v[0], q.v[2] - q.v[0]);
    len = length(n);
  }
  return (len > 0.0f && std::isfinite(len)) ? n / len : Vec3f(0, 0, 1);
}

inline double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

inline double distance_to_unit_interval(double x) { return x < 0.0 ? -x : (x > 1.0 ? x - 1.0 : 0.0); }

// Solves p = bilerp(u, v) for p in the quad's plane, in the 2D projection that
// drops the dominant axis of the normal (double precision: once per shading point).
inline Vec2f inverse_bilinear(const Quad& q, Vec3f n, Vec3f p, Vec2f guess) {
  const int drop = fp::max_dimension(abs(n));
  const int ix = drop == 0 ? 1 : 0;
  const int iy = drop == 2 ? 1 : 2;
  const double ax = q.v[0][ix], ay = q.v[0][iy];
  const double ex = q.v[1][ix] - ax, ey = q.v[1][iy] - ay;        // v0 -> v1
  const double fx = q.v[3][ix] - ax, fy = q.v[3][iy] - ay;        // v0 -> v3
  const double gx = ax - q.v[1][ix] + q.v[2][ix] - q.v[3][ix];    // bilinear twist
  const double gy = ay - q.v[1][iy] + q.v[2][iy] - q.v[3][iy];
  const double hx = p[ix] - ax, hy = p[iy] - ay;

  // p - v0 = u e + v f + u v g  =>  k2 v^2 + k1 v + k0 = 0.
  const double k2 = cross2(gx, gy, fx, fy);
  const double k1 = cross2(ex, ey, fx, fy) + cross2(hx, hy, gx, gy);
  const double k0 = cross2(hx, hy, ex, ey);
  double v;
  if (std::fabs(k2) <= 1e-12 * std::fabs(k1)) {
    v = -k0 / k1;  // a parallelogram (or a trapezoid with v0v1 parallel to v3v2)
  } else {
    const double disc = std::max(0.0, k1 * k1 - 4.0 * k0 * k2);
    const double qq = -0.5 * (k1 + std::copysign(std::sqrt(disc), k1));
    const double r1 = qq / k2;
    const double r2 = qq != 0.0 ? k0 / qq : r1;
    const double d1 = distance_to_unit_interval(r1), d2 = distance_to_unit_interval(r2);
    if (d1 != d2) {
      v = d1 < d2 ? r1 : r2;
    } else {
      v = std::fabs(r1 - guess.y) <= std::fabs(r2 - guess.y) ? r1 : r2;
    }
  }
  const double dx = ex + gx * v, dy = ey + gy * v;
  const double u = std::fabs(dx) >= std::fabs(dy) ? (hx - fx * v) / dx : (hy - fy * v) / dy;
  if (!std::isfinite(u) || !std::isfinite(v)) return guess;
  return {static_cast<float>(std::clamp(u, 0.0, 1.0)), static_cast<float>(std::clamp(v, 0.0, 1.0))};
}

}  // namespace quad_detail

inline Bounds3f bounds(const Quad& q) {
  Bounds3f b;
  for (const Vec3f& v : q.v) b.extend(v);
  return fp::pad(b);
}

inline bool intersect(const Quad& q, const Ray& ray, PrimHit& hit) {
  // Both halves are tested (the second with tmax shortened) so that a slightly
  // non-planar quad still reports its nearest hit.
  Ray r = ray;
  PrimHit h;
  bool found = false;
  if (intersect_triangle(q.v[0], q.v[1], q.v[2], r, h)) {
    hit.t = h.t;
    hit.uv = {h.uv.x + h.uv.y, h.uv.y};  // u >= v
    r.tmax = h.t;
    found = true;
  }
  if (intersect_triangle(q.v[0], q.v[2], q.v[3], r, h)) {
    hit.t = h.t;
    hit.uv = {h.uv.x, h.uv.x + h.uv.y};  // v >= u
    found = true;
  }
  return found;
}

inline SurfaceGeometry surface(const Quad& q, const Ray& /*ray*/, const PrimHit& hit) {
  // Back from the two-triangle parameters to barycentrics of the hit half.
  const float u = hit.uv.x;
  const float v = hit.uv.y;
  Vec3f pa, pb;
  float b1, b2, b0;
  if (u >= v) {
    pa = q.v[1];
    pb = q.v[2];
    b1 = u - v;
    b2 = v;
    b0 = 1.0f - u;
  } else {
    pa = q.v[2];
    pb = q.v[3];
    b1 = u;
    b2 = v - u;
    b0 = 1.0f - v;
  }
  SurfaceGeometry sg;
  sg.p = b0 * q.v[0] + b1 * pa + b2 * pb;
  sg.p_error = fp::gamma(7) * (abs(b0 * q.v[0]) + abs(b1 * pa) + abs(b2 * pb));
  sg.ng = quad_detail::quad_normal(q);
  sg.ns = sg.ng;
  sg.uv = quad_detail::inverse_bilinear(q, sg.ng, sg.p, hit.uv);
  return sg;
}

// The bilinear map: v0 at (0, 0), v1 at (1, 0), v2 at (1, 1), v3 at (0, 1).
inline UvDerivatives uv_derivatives(const Quad& q, const SurfaceGeometry& sg) {
  const float u = sg.uv.x, v = sg.uv.y;
  return {(q.v[1] - q.v[0]) * (1.0f - v) + (q.v[2] - q.v[3]) * v,
          (q.v[3] - q.v[0]) * (1.0f - u) + (q.v[2] - q.v[1]) * u};
}

inline uint32_t primitive_count(const Quad&) { return 1; }

// Validation: planar (within 1e-3 of its size), corners in perimeter order
// around a convex quad; a quad of zero area is only a warning.
inline void check(const Quad& q, ShapeChecker& c) {
  const Vec3f* v = q.v;
  if (!is_finite(v[0]) || !is_finite(v[1]) || !is_finite(v[2]) || !is_finite(v[3])) {
    c.unusable("", "quad has a non-finite corner");
    return;
  }
  float size = 0.0f;
  for (int i = 0; i < 4; ++i) size = std::max(size, length(v[(i + 1) % 4] - v[i]));
  // Reference normal: the largest corner cross product (a bow-tie's corners
  // then disagree with it in sign, which the order check below catches).
  Vec3f n(0.0f);
  for (int i = 0; i < 4; ++i) {
    const Vec3f k = cross(v[(i + 1) % 4] - v[i], v[(i + 3) % 4] - v[i]);
    if (length(k) > length(n)) n = k;
  }
  if (size == 0.0f || length(n) <= 1e-7f * size * size) {
    c.warning("", "quad is degenerate (zero area); it will not be visible");
    return;
  }
  n = normalize(n);
  const Vec3f centre = (v[0] + v[1] + v[2] + v[3]) * 0.25f;
  float off_plane = 0.0f;
  for (int i = 0; i < 4; ++i) off_plane = std::max(off_plane, std::fabs(dot(v[i] - centre, n)));
  const float tolerance = 1e-3f * size;
  if (off_plane > tolerance) {
    c.error("", "quad is not planar: its corners are up to " + format_number(off_plane) +
                    " away from a common plane (tolerance " + format_number(tolerance) + ")");
    return;
  }
  for (int i = 0; i < 4; ++i) {
    const Vec3f k = cross(v[(i + 1) % 4] - v[i], v[(i + 3) % 4] - v[i]);
    if (dot(k, n) < -1e-6f * size * size) {
      c.error("", "quad corners are not in perimeter order, or the quad is not convex");
      return;
    }
  }
}

// Sampling by area: one of the two triangles in proportion to its area.
inline TriangleAreaSampler make_area_sampler(const Quad& q) {
  const auto triangle_area = [](Vec3f a, Vec3f b, Vec3f c) { return 0.5f * length(cross(b - a, c - a)); };
  // The orientation of cross(v1 - v0, v3 - v0) (as quad_normal(), without its
  // finiteness test: a light's quad is finite).
  Vec3f n = cross(q.v[2] - q.v[0], q.v[3] - q.v[1]);
  if (!(length(n) > 0.0f)) n = cross(q.v[1] - q.v[0], q.v[2] - q.v[0]);
  const float len = length(n);
  n = len > 0.0f ? n / len : Vec3f(0, 0, 1);  // both halves share the quad's normal
  const float a0 = triangle_area(q.v[0], q.v[1], q.v[2]), a1 = triangle_area(q.v[0], q.v[2], q.v[3]);
  TriangleAreaSampler s;
  s.area = a0 + a1;
  s.parts = Distribution1D({a0, a1});
  s.triangles.push_back({q.v[0], q.v[1] - q.v[0], q.v[2] - q.v[0], n});
  s.triangles.push_back({q.v[0], q.v[2] - q.v[0], q.v[3] - q.v[0], n});
  return s;
}

}  // namespace pt
