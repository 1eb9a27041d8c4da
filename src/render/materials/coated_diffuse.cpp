#include "render/materials/coated_diffuse.h"

#include <algorithm>
#include <cmath>

#include "render/materials/dielectric.h"

namespace pt {

namespace {

constexpr int kStrata = 16;  // per axis: the quadrature of each table entry

// The directional albedo of a rough coating's reflection lobe at incidence mu:
// the mean of its visible-normal sample weights F G / G1 over a midpoint grid.
float coating_albedo(float mu, float alpha, float ior) {
  mu = std::max(mu, 1e-3f);
  if (TrowbridgeReitz::smooth(alpha, alpha)) return fresnel_dielectric(mu, 1.0f, ior);
  const TrowbridgeReitz d(alpha, alpha);
  const Vec3f wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
  double sum = 0.0;
  for (int i = 0; i < kStrata; ++i) {
    for (int j = 0; j < kStrata; ++j) {
      const Vec2f u((static_cast<float>(i) + 0.5f) / kStrata, (static_cast<float>(j) + 0.5f) / kStrata);
      const Vec3f m = d.sample_visible(wo, u);
      const float c = dot(wo, m);
      const Vec3f wi = reflect(wo, m);
      if (!(c > 0.0f) || !(wi.z > 0.0f)) continue;
      sum += fresnel_dielectric(c, 1.0f, ior) * d.G(wo, wi) / d.G1(wo);
    }
  }
  return static_cast<float>(sum / (kStrata * kStrata));
}

float grid(int i, int n) { return static_cast<float>(i) / static_cast<float>(n - 1); }

float mean(RGB c) { return (c.r + c.g + c.b) * (1.0f / 3.0f); }

}  // namespace

CoatingTable::CoatingTable(float ior) : ior_(ior) {
  for (int a = 0; a < kAlpha; ++a) {
    for (int m = 0; m < kMu; ++m) e_[static_cast<std::size_t>(a * kMu + m)] = coating_albedo(grid(m, kMu), grid(a, kAlpha), ior);
    // Trapezoid rule for 2 * integral of E(mu) mu dmu.
    double sum = 0.0;
    for (int m = 0; m + 1 < kMu; ++m) {
      const float m0 = grid(m, kMu), m1 = grid(m + 1, kMu);
      sum += 0.5 * (m1 - m0) * (e_[static_cast<std::size_t>(a * kMu + m)] * m0 + e_[static_cast<std::size_t>(a * kMu + m + 1)] * m1);
    }
    average_[static_cast<std::size_t>(a)] = static_cast<float>(2.0 * sum);
  }
}

float CoatingTable::albedo(float mu, float alpha) const {
  const float x = std::clamp(mu, 0.0f, 1.0f) * (kMu - 1), y = std::clamp(alpha, 0.0f, 1.0f) * (kAlpha - 1);
  const int i = std::min(static_cast<int>(x), kMu - 2), j = std::min(static_cast<int>(y), kAlpha - 2);
  const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
  const auto e = [&](int a, int m) { return e_[static_cast<std::size_t>(a * kMu + m)]; };
  const float lo = e(j, i) + (e(j, i + 1) - e(j, i)) * fx;
  const float hi = e(j + 1, i) + (e(j + 1, i + 1) - e(j + 1, i)) * fx;
  return lo + (hi - lo) * fy;
}

float CoatingTable::average(float alpha) const {
  const float y = std::clamp(alpha, 0.0f, 1.0f) * (kAlpha - 1);
  const int j = std::min(static_cast<int>(y), kAlpha - 2);
  const float fy = y - static_cast<float>(j);
  return average_[static_cast<std::size_t>(j)] + (average_[static_cast<std::size_t>(j + 1)] - average_[static_cast<std::size_t>(j)]) * fy;
}

CoatedDiffuseBsdf::CoatedDiffuseBsdf(RGB albedo, float alpha_x, float alpha_y, const CoatingTable& table, Vec3f wo) noexcept
    : table_(&table),
      distribution_(alpha_x, alpha_y),
      alpha_(std::sqrt(alpha_x * alpha_y)),
      smooth_(TrowbridgeReitz::smooth(alpha_x, alpha_y)) {
  const float eta2 = table.ior() * table.ior();
  const float t_int = (1.0f - table.average(alpha_)) / eta2;
  const float fdr = 1.0f - t_int;
  const RGB series(albedo.r / (1.0f - albedo.r * fdr), albedo.g / (1.0f - albedo.g * fdr),
                   albedo.b / (1.0f - albedo.b * fdr));
  diffuse_scale_ = series * (kInvPi / eta2);
  if (!(wo.z > 0.0f)) return;
  const float e = table.albedo(wo.z, alpha_);
  const float d = (1.0f - e) * t_int * mean(series);
  albedo_estimate_ = e + d;
  p_spec_ = e + d > 0.0f ? e / (e + d) : 1.0f;
}

float CoatedDiffuseBsdf::spec_f(Vec3f wo, Vec3f wi) const {
  const Vec3f s = wo + wi;
  const float len = length(s);
  if (smooth_ || !(len > 0.0f)) return 0.0f;
  const Vec3f h = s / len;
  const float F = fresnel_dielectric(dot(wo, h), 1.0f, table_->ior());
  return F * distribution_.D(h) * distribution_.G(wo, wi) / (4.0f * wo.z * wi.z);
}

float CoatedDiffuseBsdf::spec_pdf(Vec3f wo, Vec3f wi) const {
  const Vec3f s = wo + wi;
  const float len = length(s);
  if (smooth_ || !(len > 0.0f)) return 0.0f;
  const Vec3f h = s / len;
  const float c = dot(wo, h);
  return c > 0.0f ? distribution_.visible_D(wo, h) / (4.0f * c) : 0.0f;
}

RGB CoatedDiffuseBsdf::f_diffuse(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return {};
  return diffuse_scale_ * (transmittance(wo.z) * transmittance(wi.z));
}

RGB CoatedDiffuseBsdf::f(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return {};
  return f_diffuse(wo, wi) + RGB(spec_f(wo, wi));
}

float CoatedDiffuseBsdf::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
  return p_spec_ * spec_pdf(wo, wi) + (1.0f - p_spec_) * cosine_hemisphere_pdf(wi.z);
}

bool CoatedDiffuseBsdf::sample(Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s) const {
  if (!(wo.z > 0.0f)) return false;
  if (u_lobe < p_spec_) {
    if (smooth_) {  // the smooth coating's mirror reflection
      s.wi = {-wo.x, -wo.y, wo.z};
      s.weight = RGB(fresnel_dielectric(wo.z, 1.0f, table_->ior()) / p_spec_);
      s.pdf = p_spec_;
      s.delta = true;
      return true;
    }
    const Vec3f h = distribution_.sample_visible(wo, u);
    if (!(dot(wo, h) > 0.0f)) return false;
    s.wi = reflect(wo, h);
  } else {
    s.wi = sample_cosine_hemisphere(u);
  }
  if (!(s.wi.z > 0.0f)) return false;
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return false;
  s.weight = f(wo, s.wi) * (s.wi.z / s.pdf);
  s.delta = false;
  return true;
}

}  // namespace pt
