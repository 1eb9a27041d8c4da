#include "render/materials/bsdf.h"

#include <algorithm>

namespace pt {

namespace {

float mean(RGB c) { return (c.r + c.g + c.b) * (1.0f / 3.0f); }

}  // namespace

Bsdf::Bsdf(const Material& m, const SurfaceGeometry& geo, Vec3f wo) {
  const bool above = dot(geo.ng, wo) > 0.0f;
  if (m.glass()) {
    // The dielectric's frame keeps the shape's orientation (+z = outside).
    glass_ = true;
    dielectric_.ior = m.ior;
    ng_ = geo.ng;
    const Vec3f n = (dot(geo.ns, wo) > 0.0f) == above ? geo.ns : geo.ng;
    frame_ = Frame::from_normal(n);
    return;
  }

  ng_ = above ? geo.ng : -geo.ng;
  Vec3f n = above ? geo.ns : -geo.ns;
  if (!(dot(n, wo) > 0.0f)) n = ng_;  // viewer below the shading hemisphere
  frame_ = Frame::from_normal(n);

  RGB kd_cd, ks_cs, tint(1.0f);
  float rho = 0.0f;
  switch (m.type) {
    case MaterialType::Lambert:
      kd_cd = m.diffuse_at(tex_coord(geo)) * m.kd;
      break;
    case MaterialType::Mirror:
      rho = 1.0f;
      tint = m.specular;
      break;
    case MaterialType::Glass:  // built above
      break;
    case MaterialType::Phong:
      if (m.kd > 0.0f) kd_cd = m.diffuse_at(tex_coord(geo)) * m.kd;
      ks_cs = m.specular * m.ks;
      rho = std::clamp(m.reflectivity, 0.0f, 1.0f);
      break;
  }
  // Energy conservation: kd Cd + ks Cs may exceed 1 in a course file.
  const float total = (kd_cd + ks_cs).max_component();
  if (total > 1.0f) {
    kd_cd *= 1.0f / total;
    ks_cs *= 1.0f / total;
  }
  diffuse_.albedo = kd_cd * (1.0f - rho);
  glossy_weight_ = ks_cs * (1.0f - rho);
  glossy_.exponent = m.exponent;
  mirror_.tint = tint * rho;

  const float wd = mean(diffuse_.albedo), ws = mean(glossy_weight_), wm = mean(mirror_.tint);
  const float sum = wd + ws + wm;
  if (sum > 0.0f) {
    p_diffuse_ = wd / sum;
    p_glossy_ = ws / sum;
    p_mirror_ = wm / sum;
  }
}

RGB Bsdf::f(Vec3f wo, Vec3f wi) const {
  if (delta_only() || !(dot(wi, ng_) > 0.0f)) return {};
  const Vec3f lo = frame_.to_local(wo), li = frame_.to_local(wi);
  RGB result = diffuse_.f(lo, li);
  if (p_glossy_ > 0.0f) result += glossy_weight_ * glossy_.f(lo, li);
  return result;
}

float Bsdf::pdf(Vec3f wo, Vec3f wi) const {
  if (delta_only() || !(dot(wi, ng_) > 0.0f)) return 0.0f;
  const Vec3f lo = frame_.to_local(wo), li = frame_.to_local(wi);
  float p = p_diffuse_ * diffuse_.pdf(lo, li);
  if (p_glossy_ > 0.0f) p += p_glossy_ * glossy_.pdf(lo, li);
  return p;
}

bool Bsdf::sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const {
  const Vec3f lo = frame_.to_local(wo);
  if (glass_) {
    if (!dielectric_.sample(lo, u_lobe, s)) return false;
    s.wi = frame_.from_local(s.wi);
    return true;
  }
  if (u_lobe >= p_diffuse_ + p_glossy_) {
    if (!(p_mirror_ > 0.0f) || !mirror_.sample(lo, s)) return false;
    s.wi = frame_.from_local(s.wi);
    if (!(dot(s.wi, ng_) > 0.0f)) return false;
    s.weight *= 1.0f / p_mirror_;
    s.pdf = p_mirror_;
    return true;
  }
  const bool ok = u_lobe < p_diffuse_ ? diffuse_.sample(lo, u, s) : glossy_.sample(lo, u, s);
  if (!ok) return false;
  const Vec3f li = s.wi;
  s.wi = frame_.from_local(li);
  if (!(dot(s.wi, ng_) > 0.0f)) return false;
  // The whole non-delta mixture: its f and its density.
  RGB fv = diffuse_.f(lo, li);
  float p = p_diffuse_ * diffuse_.pdf(lo, li);
  if (p_glossy_ > 0.0f) {
    fv += glossy_weight_ * glossy_.f(lo, li);
    p += p_glossy_ * glossy_.pdf(lo, li);
  }
  if (!(p > 0.0f)) return false;
  s.pdf = p;
  s.weight = fv * (li.z / p);
  s.delta = false;
  return true;
}

}  // namespace pt
