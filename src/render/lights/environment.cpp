#include "render/lights/environment.h"

#include <cmath>
#include <utility>
#include <vector>

namespace pt {

namespace {

// A unit vector along v, also for tiny v (whose squared length would flush to 0).
Vec3f robust_normalize(Vec3f v) {
  const float m = max_component(abs(v));
  return m > 0.0f && std::isfinite(m) ? normalize(v / m) : Vec3f(0, 1, 0);
}

}  // namespace

EnvironmentMap::EnvironmentMap(Texture image, Vec3f up, float rotation_deg, float intensity)
    : image_(std::move(image)),
      frame_(Frame::from_normal(robust_normalize(up))),
      u_offset_(std::isfinite(rotation_deg) ? std::fmod(rotation_deg, 360.0f) / 360.0f : 0.0f),
      intensity_(intensity) {
  const int w = image_.width(), h = image_.height();
  std::vector<float> f(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  double weighted = 0.0, solid_angle = 0.0;
  for (int y = 0; y < h; ++y) {
    const float sin_theta = std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(h));
    for (int x = 0; x < w; ++x) {
      const float lum = image_.texel(x, y).luminance();
      f[static_cast<std::size_t>(y) * w + x] = std::max(0.0f, lum) * sin_theta;
      weighted += std::max(0.0f, lum) * sin_theta;
    }
    solid_angle += static_cast<double>(sin_theta) * w;
  }
  distribution_ = Distribution2D(f, w, h);
  mean_luminance_ = solid_angle > 0.0 ? static_cast<float>(weighted / solid_angle) * intensity_ : 0.0f;
}

std::unique_ptr<EnvironmentMap> EnvironmentMap::load(const EnvironmentDesc& desc, std::string& error,
                                                     const TextureLimits& limits) {
  Texture image;
  if (!Texture::load(desc.resolved, image, error, limits)) return nullptr;
  return std::make_unique<EnvironmentMap>(std::move(image), desc.up.value, desc.rotation_deg.value,
                                          desc.intensity.value);
}

Vec2f EnvironmentMap::direction_to_uv(Vec3f dir) const {
  const Vec3f d = frame_.to_local(dir);
  if (!is_finite(d)) return {0.0f, 0.0f};
  const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
  float u = 0.5f + std::atan2(d.x, d.y) * kInv2Pi + u_offset_;
  u -= std::floor(u);
  if (!(u >= 0.0f)) u = 0.0f;  // a huge rotation leaves no fraction
  return {std::min(u, kOneMinusEpsilon), std::min(theta * kInvPi, kOneMinusEpsilon)};
}

Vec3f EnvironmentMap::uv_to_direction(Vec2f uv) const {
  const float theta = kPi * uv.y;
  const float psi = 2.0f * kPi * (uv.x - 0.5f - u_offset_);
  const float sin_theta = std::sin(theta);
  return frame_.from_local({sin_theta * std::sin(psi), sin_theta * std::cos(psi), std::cos(theta)});
}

const RGB& EnvironmentMap::texel(Vec2f uv) const {
  const int w = image_.width(), h = image_.height();
  const int x = std::min(static_cast<int>(uv.x * static_cast<float>(w)), w - 1);
  const int y = std::min(static_cast<int>(uv.y * static_cast<float>(h)), h - 1);
  return image_.texel(std::max(x, 0), std::max(y, 0));
}

RGB EnvironmentMap::radiance(Vec3f dir) const { return texel(direction_to_uv(normalize(dir))) * intensity_; }

bool EnvironmentMap::sample(Vec2f u, LightSample& s) const {
  float pdf_uv = 0.0f;
  const Vec2f uv = distribution_.sample(u, &pdf_uv);
  const float sin_theta = std::sin(kPi * uv.y);
  if (!(pdf_uv > 0.0f) || !(sin_theta > 0.0f)) return false;
  s.wi = uv_to_direction(uv);
  s.pdf = pdf_uv / (2.0f * kPi * kPi * sin_theta);
  s.L = texel(uv) * intensity_;
  return true;
}

float EnvironmentMap::pdf(Vec3f dir) const {
  const Vec2f uv = direction_to_uv(dir);
  const float sin_theta = std::sin(kPi * uv.y);
  if (!(sin_theta > 0.0f)) return 0.0f;
  return distribution_.pdf(uv) / (2.0f * kPi * kPi * sin_theta);
}

float EnvironmentMap::power(float scene_radius) const {
  return 4.0f * kPi * kPi * scene_radius * scene_radius * mean_luminance_;
}

}  // namespace pt
