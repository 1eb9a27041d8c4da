#include "render/lights/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

namespace {

std::string texel_text(int x, int y, const RGB& c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "texel (%d, %d) = (%g, %g, %g)", x, y, static_cast<double>(c.r),
                static_cast<double>(c.g), static_cast<double>(c.b));
  return buf;
}

// A map's texels are radiance: a non-finite one, or one that overflows once
// scaled by the intensity, is refused (false with `error`); negative channels
// are clamped to 0 with `warning` (resampled HDR images often hold small
// negative lobes; as radiance they would subtract light).
bool check_texels(Texture& image, float intensity, std::string& error, std::string& warning) {
  const int w = image.width(), h = image.height();
  int64_t negative = 0;
  std::string first_negative;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const RGB& c = image.texel(x, y);
      if (!c.is_finite()) {
        error = texel_text(x, y, c) + " is not finite (x from the left, y from the top)";
        return false;
      }
      if (static_cast<double>(c.max_component()) * intensity > 1e30) {
        error = texel_text(x, y, c) + " times the intensity " + std::to_string(intensity) +
                " exceeds 1e30: a path's radiance would overflow the float range (docs/scene-format.md, \"Value limits\")";
        return false;
      }
      if (c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) {
        if (negative++ == 0) first_negative = texel_text(x, y, c);
      }
    }
  if (negative == 0) return true;
  std::vector<RGB> pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const RGB& c = image.texel(x, y);
      pixels[static_cast<std::size_t>(y) * w + x] = RGB(std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f));
    }
  image = Texture(w, h, std::move(pixels));
  warning = std::to_string(negative) + " texel" + (negative == 1 ? " has" : "s have") +
            " negative values, clamped to 0 (the first: " + first_negative + ", x from the left, y from the top)";
  return true;
}

}  // namespace

std::unique_ptr<EnvironmentMap> EnvironmentMap::load(const EnvironmentDesc& desc, std::string& error,
                                                     const TextureLimits& limits, std::string* warning) {
  Texture image;
  if (!Texture::load(desc.resolved, image, error, limits)) return nullptr;
  std::string clamped;
  if (!check_texels(image, desc.intensity.value, error, clamped)) return nullptr;
  if (warning != nullptr) *warning = clamped;
  return std::make_unique<EnvironmentMap>(std::move(image), desc.up.value, desc.rotation_deg.value,
                                          desc.intensity.value);
}

Vec2f EnvironmentMap::direction_to_uv(Vec3f dir) const {
  // Normalised here, so that every lookup of a direction (radiance, pdf, the
  // light guide's bins) maps it to the same texel, whatever its length.
  const Vec3f d = normalize(frame_.to_local(dir));
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

RGB EnvironmentMap::radiance(Vec3f dir) const { return texel(direction_to_uv(dir)) * intensity_; }

bool EnvironmentMap::sample_direction(Vec2f u, Vec3f& wi) const {
  float pdf_uv = 0.0f;
  const Vec2f uv = distribution_.sample(u, &pdf_uv);
  prefetch(uv);
  if (!(pdf_uv > 0.0f) || !(std::sin(kPi * uv.y) > 0.0f)) return false;
  wi = uv_to_direction(uv);
  return true;
}

// The density and radiance are those of the direction mapped back, not of the
// drawn texel: at a texel's edge float rounding can put the direction in the
// neighbouring texel, and the sample must state what pdf() and radiance() say
// there (MIS weighs a BSDF ray escaping in that direction by pdf()).
bool EnvironmentMap::sample(Vec2f u, LightSample& s) const {
  if (!sample_direction(u, s.wi)) return false;
  const Vec2f uv = direction_to_uv(s.wi);
  s.pdf = pdf_at(uv);
  s.L = radiance_at(uv);
  return s.pdf > 0.0f;
}

float EnvironmentMap::pdf(Vec3f dir) const { return pdf_at(direction_to_uv(dir)); }

float EnvironmentMap::pdf_at(Vec2f uv) const {
  const float sin_theta = std::sin(kPi * uv.y);
  if (!(sin_theta > 0.0f)) return 0.0f;
  return distribution_.pdf(uv) / (2.0f * kPi * kPi * sin_theta);
}

float EnvironmentMap::power(float scene_radius) const {
  return 4.0f * kPi * kPi * scene_radius * scene_radius * mean_luminance_;
}

}  // namespace pt
