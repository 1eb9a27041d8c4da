#include "render/textures/footprint.h"

#include <algorithm>
#include <cmath>

namespace pt {

namespace {

// Where the ray (o, d) meets the plane dot(n, x) = dot(n, p); false if it is
// parallel to it or meets it behind its origin.
bool meet_plane(Vec3f o, Vec3f d, Vec3f p, Vec3f n, Vec3f& x) {
  const float dn = dot(n, d);
  if (dn == 0.0f) return false;
  const float t = dot(n, p - o) / dn;
  if (!(t >= 0.0f) || !std::isfinite(t)) return false;
  x = o + d * t;
  return is_finite(x);
}

// Solves the 1D least-squares problem along one partial, for a degenerate pair.
float along(Vec3f partial, Vec3f dp) {
  const float l2 = length_squared(partial);
  return l2 > 0.0f ? dot(partial, dp) / l2 : 0.0f;
}

float clamp_derivative(float v) { return std::isfinite(v) ? std::clamp(v, -1e8f, 1e8f) : 0.0f; }

}  // namespace

CameraSpread CameraSpread::of(const Camera& camera, int width, int height) {
  const Vec2f centre(0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height));
  const Ray r = camera.generate_ray(centre);
  const RayDifferential d = camera.differential(centre, Vec2f(0.5f, 0.5f));
  CameraSpread s;
  s.position = camera.position();
  s.origin = std::min(length(d.dx_origin - r.origin), length(d.dy_origin - r.origin));
  s.direction = std::min(length(normalize(d.dx_dir) - r.dir), length(normalize(d.dy_dir) - r.dir));
  return s;
}

bool footprint_from_differential(const RayDifferential& d, Vec3f p, Vec3f n, Vec3f& dpdx, Vec3f& dpdy) {
  Vec3f px, py;
  if (!meet_plane(d.dx_origin, d.dx_dir, p, n, px) || !meet_plane(d.dy_origin, d.dy_dir, p, n, py)) return false;
  dpdx = px - p;
  dpdy = py - p;
  return true;
}

void footprint_from_camera(const CameraSpread& c, Vec3f p, Vec3f n, Vec3f& dpdx, Vec3f& dpdy) {
  const Vec3f to = p - c.position;
  const float dist = length(to);
  if (!(dist > 0.0f) || !std::isfinite(dist)) {
    dpdx = dpdy = Vec3f(0.0f);
    return;
  }
  const Vec3f w = to / dist;
  Vec3f e1, e2;
  orthonormal_basis(w, e1, e2);
  // The pixel's footprint across the view direction at the hit's distance,
  // projected along it onto the tangent plane (no further than 1/0.01 times:
  // at grazing angles the footprint is long, not infinite).
  const float width = c.origin + c.direction * dist;
  const float dn = dot(w, n);
  const float cos = std::copysign(std::max(std::fabs(dn), 0.01f), dn == 0.0f ? 1.0f : dn);
  dpdx = (e1 - w * (dot(e1, n) / cos)) * width;
  dpdy = (e2 - w * (dot(e2, n) / cos)) * width;
}

void uv_footprint(Vec3f dpdu, Vec3f dpdv, Vec3f dpdx, Vec3f dpdy, Vec2f& duvdx, Vec2f& duvdy) {
  const float a00 = dot(dpdu, dpdu), a01 = dot(dpdu, dpdv), a11 = dot(dpdv, dpdv);
  const float det = a00 * a11 - a01 * a01;
  // A well-conditioned pair: the 2x2 normal equations (pbrt-v4's SurfaceInteraction::ComputeDifferentials).
  if (det > 1e-6f * a00 * a11 && std::isfinite(det)) {
    const float inv = 1.0f / det;
    const float bx0 = dot(dpdu, dpdx), bx1 = dot(dpdv, dpdx);
    const float by0 = dot(dpdu, dpdy), by1 = dot(dpdv, dpdy);
    duvdx = {clamp_derivative((a11 * bx0 - a01 * bx1) * inv), clamp_derivative((a00 * bx1 - a01 * bx0) * inv)};
    duvdy = {clamp_derivative((a11 * by0 - a01 * by1) * inv), clamp_derivative((a00 * by1 - a01 * by0) * inv)};
    return;
  }
  // One partial (or none) has length: each coordinate along its own.
  duvdx = {clamp_derivative(along(dpdu, dpdx)), clamp_derivative(along(dpdv, dpdx))};
  duvdy = {clamp_derivative(along(dpdu, dpdy)), clamp_derivative(along(dpdv, dpdy))};
}

}  // namespace pt
