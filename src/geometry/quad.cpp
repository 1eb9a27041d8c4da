// Planar convex quads (corners in perimeter order), intersected as the two
// triangles (v0 v1 v2) and (v0 v2 v3) with the watertight triangle test, so
// quads sharing an edge (the walls of a box) have no cracks between them.
// Texture coordinates are the bilinear (u, v): v0 at (0, 0), v1 at (1, 0),
// v3 at (0, 1).
#include <algorithm>
#include <cmath>

#include "geometry/float_util.h"
#include "geometry/shapes.h"

namespace pt {

namespace {

Vec3f quad_normal(const Quad& q) {
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

double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

double distance_to_unit_interval(double x) { return x < 0.0 ? -x : (x > 1.0 ? x - 1.0 : 0.0); }

// Solves p = bilerp(u, v) for p in the quad's plane, in the 2D projection that
// drops the dominant axis of the normal (double precision: once per shading point).
Vec2f inverse_bilinear(const Quad& q, Vec3f n, Vec3f p, Vec2f guess) {
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

}  // namespace

Bounds3f bounds(const Quad& q) {
  Bounds3f b;
  for (const Vec3f& v : q.v) b.extend(v);
  return fp::pad(b);
}

bool intersect(const Quad& q, const Ray& ray, PrimHit& hit) {
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

SurfaceGeometry surface(const Quad& q, const Ray& /*ray*/, const PrimHit& hit) {
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
  sg.ng = quad_normal(q);
  sg.ns = sg.ng;
  sg.uv = inverse_bilinear(q, sg.ng, sg.p, hit.uv);
  return sg;
}

}  // namespace pt
