#include "render/materials/normal_map.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace pt {

namespace {

constexpr float kMinElevation = 0.01f;  // of a perturbed normal above the geometric tangent plane

// A unit tangent along `dpdu`, perpendicular to n (any perpendicular where dpdu is degenerate).
Vec3f tangent_along(Vec3f dpdu, Vec3f n) {
  const Vec3f t = dpdu - n * dot(n, dpdu);
  const float len = length(t);
  if (len > 1e-12f && std::isfinite(len)) return t / len;
  Vec3f s, b;
  orthonormal_basis(n, s, b);
  return s;
}

// pbrt-v4's BumpMap: forward differences over half the lookup's footprint
// (du = (|du/dx| + |du/dy|) / 2), or over 0.0005 where the hit has none. The
// shifted lookups move the object-space point along dp/du and dp/dv too (the
// world-space partials: exact for shapes placed directly), so that a bump map
// with "mapping": "object" varies as well.
Vec3f bumped_normal(const FloatParam& h, const UvDerivatives& d, const TexCoord& tc, Vec3f n) {
  float du = 0.5f * (std::abs(tc.duvdx.x) + std::abs(tc.duvdy.x));
  float dv = 0.5f * (std::abs(tc.duvdx.y) + std::abs(tc.duvdy.y));
  if (!(du > 0.0f)) du = 0.0005f;
  if (!(dv > 0.0f)) dv = 0.0005f;
  const float h0 = h.at(tc);
  const float hu = h.at(TexCoord(tc.uv + Vec2f(du, 0.0f), tc.duvdx, tc.duvdy, tc.p + d.dpdu * du, tc.dpdx, tc.dpdy));
  const float hv = h.at(TexCoord(tc.uv + Vec2f(0.0f, dv), tc.duvdx, tc.duvdy, tc.p + d.dpdv * dv, tc.dpdx, tc.dpdy));
  const Vec3f dpdu = d.dpdu + n * ((hu - h0) / du);
  const Vec3f dpdv = d.dpdv + n * ((hv - h0) / dv);
  // The orientation of the unperturbed frame keeps n' on n's side.
  const float side = dot(cross(d.dpdu, d.dpdv), n) < 0.0f ? -1.0f : 1.0f;
  const Vec3f c = cross(dpdu, dpdv) * side;
  const float len = length(c);
  return len > 0.0f && std::isfinite(len) ? c / len : n;
}

// glTF's normalTexture.scale s: (x, y) scaled by s before normalising.
Vec3f mapped_normal(const Texture& map, float scale, const UvDerivatives& d, const TexCoord& tc, Vec3f n) {
  const RGB c = texture_rgb(map, tc);
  const Vec3f t((2.0f * c.r - 1.0f) * scale, (2.0f * c.g - 1.0f) * scale, 2.0f * c.b - 1.0f);
  const Vec3f tu = tangent_along(d.dpdu, n);
  // The image's up is -v: B points against dp/dv (or is n x T if dp/dv is degenerate).
  Vec3f b = cross(n, tu);
  if (dot(b, d.dpdv) > 0.0f) b = -b;
  const Vec3f m = tu * t.x + b * t.y + n * t.z;
  const float len = length(m);
  return len > 0.0f && std::isfinite(len) ? m / len : n;
}

}  // namespace

void perturb_shading_normal(const Material& m, const UvDerivatives& d, SurfaceGeometry& geo) {
  const TexCoord tc = tex_coord(geo);
  Vec3f n = geo.ns;
  if (m.displacement.textured()) n = bumped_normal(m.displacement, d, tc, n);
  if (m.normal_map) n = mapped_normal(*m.normal_map, m.normal_scale, d, tc, n);
  // Never below (or too close to) the geometric tangent plane.
  const float e = dot(n, geo.ng);
  if (e < kMinElevation) n = normalize(n + geo.ng * (kMinElevation - e));
  geo.ns = n;
}

}  // namespace pt
