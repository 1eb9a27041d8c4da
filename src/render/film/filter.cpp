#include "render/film/filter.h"

#include <cmath>
#include <iterator>
#include <vector>

namespace pt {

namespace {

constexpr float kGaussianSigma = 0.5f;
constexpr float kMitchellB = 1.0f / 3.0f, kMitchellC = 1.0f / 3.0f;
constexpr int kCellsPerPixel = 64;  // resolution of the tabulated |f|

float gaussian(float x) {
  return std::exp(-x * x / (2.0f * kGaussianSigma * kGaussianSigma)) /
         std::sqrt(2.0f * kPi * kGaussianSigma * kGaussianSigma);
}

float mitchell(float x) {
  constexpr float B = kMitchellB, C = kMitchellC;
  x = std::fabs(x);
  if (x <= 1.0f)
    return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) / 6.0f;
  if (x <= 2.0f)
    return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x + (8 * B + 24 * C)) / 6.0f;
  return 0.0f;
}

float radius_of(PixelFilterType type) {
  switch (type) {
    case PixelFilterType::Gaussian: return 1.5f;
    case PixelFilterType::Mitchell: return 2.0f;
    case PixelFilterType::Box: break;
  }
  return 0.5f;
}

}  // namespace

const char* pixel_filter_name(PixelFilterType type) { return kPixelFilterNames[static_cast<int>(type)]; }

std::optional<PixelFilterType> parse_pixel_filter(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kPixelFilterNames); ++i)
    if (name == kPixelFilterNames[i]) return static_cast<PixelFilterType>(i);
  return std::nullopt;
}

PixelFilter::PixelFilter(PixelFilterType type) : type_(type), radius_(radius_of(type)) {
  if (type_ == PixelFilterType::Box) return;  // sampled exactly, no table
  const int n = static_cast<int>(2.0f * radius_ * kCellsPerPixel);
  std::vector<float> f(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const float x = -radius_ + (static_cast<float>(i) + 0.5f) * (2.0f * radius_ / static_cast<float>(n));
    f[static_cast<std::size_t>(i)] = std::fabs(evaluate(x));
  }
  table_ = Distribution1D(f);
}

float PixelFilter::evaluate(float x) const {
  if (std::fabs(x) > radius_) return 0.0f;
  switch (type_) {
    case PixelFilterType::Gaussian: return std::max(0.0f, gaussian(x) - gaussian(radius_));
    case PixelFilterType::Mitchell: return mitchell(x);
    case PixelFilterType::Box: break;
  }
  return 1.0f;
}

float PixelFilter::sample_axis(float u, float& weight) const {
  float pdf01 = 0.0f;
  const float t = table_.sample_continuous(u, &pdf01);
  const float x = -radius_ + 2.0f * radius_ * t;
  const float pdf = pdf01 / (2.0f * radius_);
  weight *= pdf > 0.0f ? evaluate(x) / pdf : 0.0f;
  return x;
}

float PixelFilter::pdf(Vec2f offset) const {
  if (type_ == PixelFilterType::Box)
    return (offset.x >= 0.0f && offset.x < 1.0f && offset.y >= 0.0f && offset.y < 1.0f) ? 1.0f : 0.0f;
  const float scale = 1.0f / (2.0f * radius_);
  auto axis = [&](float o) { return table_.pdf((o - 0.5f + radius_) * scale) * scale; };
  return axis(offset.x) * axis(offset.y);
}

FilterSample PixelFilter::sample(Vec2f u) const {
  // The box is the identity on the pixel: the offset is u itself, weight 1.
  if (type_ == PixelFilterType::Box) return {u, 1.0f};
  FilterSample s;
  const float x = sample_axis(u.x, s.weight);
  const float y = sample_axis(u.y, s.weight);
  s.offset = {0.5f + x, 0.5f + y};
  return s;
}

}  // namespace pt
