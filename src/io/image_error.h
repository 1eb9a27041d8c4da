// Error metrics between a test image and a reference (docs/samplers.md), over
// the whole frame or a rectangle of it. With N the pixels compared and c the
// R, G, B channels of test t and reference r:
//   mse     = 1/N sum_pixels sum_c (clamp01(t_c) - clamp01(r_c))^2
//             (linear RGB clamped to [0,1], channels summed: the course handout's MSE)
//   rmse    = sqrt(mse)
//   rel_mse = 1/N sum_pixels 1/3 sum_c (t_c - r_c)^2 / (r_c^2 + 0.01)
//             (unclamped values: meaningful for HDR images)
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/image.h"

namespace pt {

// Pixels [x, x + width) x [y, y + height), y down from the top row.
struct ImageRect {
  int x = 0, y = 0, width = 0, height = 0;
};

struct ImageError {
  double mse = 0.0;
  double rmse = 0.0;
  double rel_mse = 0.0;
  int64_t pixels = 0;  // N
};

constexpr double kRelMseEpsilon = 0.01;

// Returns false and fills `error` if the images differ in size, or the
// rectangle is empty or not inside the image.
bool compute_image_error(const Image& test, const Image& reference, const std::optional<ImageRect>& rect,
                         ImageError& out, std::string& error);

// Parses "X,Y,W,H" (non-negative integers, W and H > 0); false on bad syntax.
bool parse_image_rect(const std::string& text, ImageRect& out);

}  // namespace pt
