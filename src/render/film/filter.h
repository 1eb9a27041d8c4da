// Pixel reconstruction filters, applied by filter importance sampling
// (pbrt-v4): the offset of a camera ray from its pixel centre is drawn from
// the filter's own distribution and the sample carries the weight f/pdf, so
// every sample contributes to its own pixel only, and the pixel value is
// sum(w L) / sum(w). This keeps one task per pixel (determinism) and exact
// accumulation. Separable filters are sampled one axis at a time from a
// tabulated |f|; for a filter with negative lobes (Mitchell) w is negative
// where f is.
//
//  - box:      a 1-pixel box (radius 0.5); every weight is 1.
//  - gaussian: radius 1.5, sigma 0.5, shifted to reach 0 at the radius (pbrt).
//  - mitchell: Mitchell-Netravali, radius 2, B = C = 1/3.
#pragma once

#include <optional>
#include <string_view>

#include "core/math.h"
#include "core/sampling.h"
#include "scene/scene_description.h"

namespace pt {

struct FilterSample {
  Vec2f offset;        // position in pixels relative to the pixel's top-left corner
  float weight = 1.0f;
};

class PixelFilter {
 public:
  explicit PixelFilter(PixelFilterType type = PixelFilterType::Box);

  PixelFilterType type() const { return type_; }
  float radius() const { return radius_; }
  // The 1D filter at distance x (pixels) from the pixel centre; f(x, y) = f(x) f(y).
  float evaluate(float x) const;
  // Maps u in [0,1)^2 to an offset (from the pixel corner) whose density is
  // pdf(offset), proportional to a tabulation of |f| (64 cells per pixel and
  // axis); the weight is f(offset) / pdf(offset), so the pixel estimate is
  // exact whatever the tabulation.
  FilterSample sample(Vec2f u) const;
  // The density of sample()'s offsets (relative to the pixel corner).
  float pdf(Vec2f offset) const;

 private:
  float sample_axis(float u, float& weight) const;

  PixelFilterType type_;
  float radius_;
  Distribution1D table_;  // |f| over [-radius, radius]
};

const char* pixel_filter_name(PixelFilterType type);
// The filter named `name` (kPixelFilterNames), or nothing.
std::optional<PixelFilterType> parse_pixel_filter(std::string_view name);

}  // namespace pt
