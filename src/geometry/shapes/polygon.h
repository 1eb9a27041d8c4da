// The planar convex polygon with any number (>= 3) of corners in perimeter
// order: its data and every routine that follows from it. Intersected as the
// fan of triangles (v0, vi, vi+1) with the watertight triangle test, so it has
// no crack along its diagonals nor along an edge it shares with a quad,
// triangle or another polygon. Texture coordinates are planar: the polygon's
// bounding rectangle in the frame of its first edge (u along v0 -> v1, v along
// normal x u) maps onto [0, 1]^2, so a rectangle given as a polygon has the
// quad's (u, v): v0 at (0, 0), v1 at (1, 0), v3 at (0, 1).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/float_util.h"
#include "geometry/shape_base.h"
#include "geometry/shapes/plane.h"

namespace pt {

// Watertight ray/triangle test (geometry/triangle.cpp); uv = barycentrics of p1, p2.
bool intersect_triangle(Vec3f p0, Vec3f p1, Vec3f p2, const Ray& ray, PrimHit& hit);

struct ConvexPolygon {
  std::vector<Vec3f> vertices;  // in perimeter order; the normal follows the right-hand rule
  // Derived by make_polygon() from the vertices:
  Vec3f normal{0, 0, 1};        // unit (Newell's normal)
  Vec3f eu{1, 0, 0}, ev{0, 1, 0};  // texture frame: eu along v0 -> v1 in the plane, ev = normal x eu
  Vec2f uv_lo, uv_inv{1, 1};       // uv = ((dot(p - v0, eu), dot(p - v0, ev)) - uv_lo) * uv_inv
};

namespace polygon_detail {

// Newell's normal (twice the vector area), exact for planar polygons, stable
// for nearly planar and nearly degenerate ones.
inline Vec3f newell(const std::vector<Vec3f>& v) {
  Vec3f n(0.0f);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3f& a = v[i];
    const Vec3f& b = v[(i + 1) % v.size()];
    n += Vec3f((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  return n;
}

// The longest edge: the polygon's size for relative tolerances.
inline float size(const std::vector<Vec3f>& v) {
  float s = 0.0f;
  for (std::size_t i = 0; i < v.size(); ++i) s = std::max(s, length(v[(i + 1) % v.size()] - v[i]));
  return s;
}

}  // namespace polygon_detail

// A polygon from its corners, with its derived frame. Degenerate input is kept
// for check() to report.
inline ConvexPolygon make_polygon(std::vector<Vec3f> vertices) {
  ConvexPolygon p;
  p.vertices = std::move(vertices);
  if (p.vertices.size() < 3) return p;
  const Vec3f n = polygon_detail::newell(p.vertices);
  const float ln = length(n);
  if (!(ln > 0.0f) || !std::isfinite(ln)) return p;
  p.normal = n / ln;
  const Vec3f v0 = p.vertices[0];
  Vec3f e = p.vertices[1] - v0;
  e = e - p.normal * dot(e, p.normal);
  const float le = length(e);
  if (le > 0.0f) p.eu = e / le;
  else fp::axis_frame(p.normal, p.eu, p.ev);
  p.ev = cross(p.normal, p.eu);
  Vec2f lo(kInfinity, kInfinity), hi(-kInfinity, -kInfinity);
  for (const Vec3f& v : p.vertices) {
    const Vec2f c(dot(v - v0, p.eu), dot(v - v0, p.ev));
    lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
    hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
  }
  p.uv_lo = lo;
  p.uv_inv = {hi.x > lo.x ? 1.0f / (hi.x - lo.x) : 0.0f, hi.y > lo.y ? 1.0f / (hi.y - lo.y) : 0.0f};
  return p;
}

inline Bounds3f bounds(const ConvexPolygon& p) {
  Bounds3f b;
  for (const Vec3f& v : p.vertices) b.extend(v);
  return fp::pad(b);
}

inline bool intersect(const ConvexPolygon& p, const Ray& ray, PrimHit& hit) {
  // Every triangle of the fan is tested (tmax shortened) so that a slightly
  // non-planar polygon still reports its nearest hit.
  Ray r = ray;
  PrimHit h;
  bool found = false;
  const std::size_t n = p.vertices.size();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (intersect_triangle(p.vertices[0], p.vertices[i], p.vertices[i + 1], r, h)) {
      r.tmax = h.t;
      found = true;
    }
  }
  if (found) {
    hit.t = r.tmax;
    hit.uv = {0.0f, 0.0f};
  }
  return found;
}

inline SurfaceGeometry surface(const ConvexPolygon& p, const Ray& ray, const PrimHit& hit) {
  SurfaceGeometry sg;
  const Vec3f v0 = p.vertices[0];
  sg.p = plane_detail::project(v0, p.normal, ray.at(hit.t));
  sg.ng = p.normal;
  sg.ns = p.normal;
  const Vec3f q = sg.p - v0;
  sg.uv = {std::clamp((dot(q, p.eu) - p.uv_lo.x) * p.uv_inv.x, 0.0f, 1.0f),
           std::clamp((dot(q, p.ev) - p.uv_lo.y) * p.uv_inv.y, 0.0f, 1.0f)};
  sg.p_error = fp::gamma(8) * (abs(sg.p) + abs(v0) + Vec3f(polygon_detail::size(p.vertices)));
  return sg;
}

// uv = ((dot(p - v0, eu), dot(p - v0, ev)) - uv_lo) * uv_inv.
inline UvDerivatives uv_derivatives(const ConvexPolygon& p, const SurfaceGeometry&) {
  return {p.eu / p.uv_inv.x, p.ev / p.uv_inv.y};
}

inline uint32_t primitive_count(const ConvexPolygon&) { return 1; }

namespace polygon_detail {

// The corner farthest from the plane through the centroid, if farther than
// 1e-3 of the polygon's size; -1 if planar.
inline int off_plane_corner(const std::vector<Vec3f>& v, Vec3f n, float size, float& distance) {
  Vec3f centre(0.0f);
  for (const Vec3f& p : v) centre += p;
  centre = centre / static_cast<float>(v.size());
  int worst = -1;
  distance = 1e-3f * size;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const float d = std::fabs(dot(v[i] - centre, n));
    if (d > distance) {
      distance = d;
      worst = static_cast<int>(i);
    }
  }
  return worst;
}

// The first corner where the boundary turns against the normal; -1 if none.
inline int reflex_corner(const std::vector<Vec3f>& v, Vec3f n, float size) {
  const std::size_t m = v.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3f k = cross(v[(i + 1) % m] - v[i], v[(i + m - 1) % m] - v[i]);
    if (dot(k, n) < -1e-6f * size * size) return static_cast<int>(i);
  }
  return -1;
}

// The total turning of the boundary in units of a full turn (1 for a simple
// convex polygon; 2 or more for a star such as a pentagram).
inline float turns(const std::vector<Vec3f>& v, Vec3f n) {
  const std::size_t m = v.size();
  double total = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3f a = v[i] - v[(i + m - 1) % m];
    const Vec3f b = v[(i + 1) % m] - v[i];
    if (length(a) == 0.0f || length(b) == 0.0f) continue;
    total += std::atan2(static_cast<double>(dot(cross(a, b), n)), static_cast<double>(dot(a, b)));
  }
  return static_cast<float>(total / (2.0 * kPi));
}

}  // namespace polygon_detail

// Validation: at least 3 corners; planar within 1e-3 of its size (the longest
// edge); convex, corners in perimeter order (each problem at its corner,
// "vertices[i]"); zero area is only a warning.
inline void check(const ConvexPolygon& p, ShapeChecker& c) {
  const std::vector<Vec3f>& v = p.vertices;
  if (v.size() < 3) {
    c.unusable("vertices", "a polygon needs at least 3 vertices, got " + std::to_string(v.size()));
    return;
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!is_finite(v[i])) {
      c.unusable("vertices[" + std::to_string(i) + "]", "polygon has a non-finite corner");
      return;
    }
  }
  const float size = polygon_detail::size(v);
  const Vec3f nn = polygon_detail::newell(v);
  if (size == 0.0f || length(nn) <= 1e-7f * size * size) {
    c.warning("", "polygon is degenerate (zero area); it will not be visible");
    return;
  }
  const Vec3f n = normalize(nn);
  float off = 0.0f;
  const int far = polygon_detail::off_plane_corner(v, n, size, off);
  if (far >= 0) {
    c.error("vertices[" + std::to_string(far) + "]",
            "polygon is not planar: this corner is " + format_number(off) +
                " away from the plane of the others (tolerance " + format_number(1e-3f * size) + ")");
    return;
  }
  const int reflex = polygon_detail::reflex_corner(v, n, size);
  if (reflex >= 0) {
    c.error("vertices[" + std::to_string(reflex) + "]",
            "polygon is not convex at this corner (or its corners are not in perimeter order)");
    return;
  }
  if (std::fabs(polygon_detail::turns(v, n) - 1.0f) > 0.01f)
    c.error("vertices", "polygon's corners wind round it more than once (a star); give them in perimeter order");
}

// Sampling by area: a triangle of the fan in proportion to its area.
inline TriangleAreaSampler make_area_sampler(const ConvexPolygon& p) {
  TriangleAreaSampler s;
  std::vector<float> areas;
  const Vec3f v0 = p.vertices[0];
  for (std::size_t i = 1; i + 1 < p.vertices.size(); ++i) {
    const Vec3f e1 = p.vertices[i] - v0, e2 = p.vertices[i + 1] - v0;
    areas.push_back(0.5f * length(cross(e1, e2)));
    s.area += areas.back();
    s.triangles.push_back({v0, e1, e2, p.normal});
  }
  s.parts = Distribution1D(areas);
  return s;
}

}  // namespace pt
