#include "io/image_error.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace pt {

namespace {

double clamp01(float v) { return std::clamp(static_cast<double>(v), 0.0, 1.0); }

}  // namespace

bool compute_image_error(const Image& test, const Image& reference, const std::optional<ImageRect>& rect,
                         ImageError& out, std::string& error) {
  if (test.width != reference.width || test.height != reference.height) {
    error = "image sizes differ: " + std::to_string(test.width) + "x" + std::to_string(test.height) + " vs " +
            std::to_string(reference.width) + "x" + std::to_string(reference.height);
    return false;
  }
  const ImageRect r = rect.value_or(ImageRect{0, 0, test.width, test.height});
  if (r.width <= 0 || r.height <= 0 || r.x < 0 || r.y < 0 || r.x > test.width - r.width ||
      r.y > test.height - r.height) {
    error = "rectangle " + std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.width) + "," +
            std::to_string(r.height) + " is empty or not inside the " + std::to_string(test.width) + "x" +
            std::to_string(test.height) + " image";
    return false;
  }
  double sum_sq = 0.0, sum_rel = 0.0;
  for (int y = r.y; y < r.y + r.height; ++y) {
    for (int x = r.x; x < r.x + r.width; ++x) {
      const RGB& t = test.at(x, y);
      const RGB& ref = reference.at(x, y);
      const float tc[3] = {t.r, t.g, t.b};
      const float rc[3] = {ref.r, ref.g, ref.b};
      for (int c = 0; c < 3; ++c) {
        const double d01 = clamp01(tc[c]) - clamp01(rc[c]);
        sum_sq += d01 * d01;
        const double d = static_cast<double>(tc[c]) - static_cast<double>(rc[c]);
        sum_rel += d * d / (static_cast<double>(rc[c]) * rc[c] + kRelMseEpsilon);
      }
    }
  }
  out.pixels = static_cast<int64_t>(r.width) * r.height;
  const double n = static_cast<double>(out.pixels);
  out.mse = sum_sq / n;
  out.rmse = std::sqrt(out.mse);
  out.rel_mse = sum_rel / (3.0 * n);
  return true;
}

bool parse_image_rect(const std::string& text, ImageRect& out) {
  int values[4];
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 4; ++i) {
    if (i > 0) {
      if (p == end || *p != ',') return false;
      ++p;
    }
    const auto [next, ec] = std::from_chars(p, end, values[i]);
    if (ec != std::errc() || next == p || values[i] < 0) return false;
    p = next;
  }
  if (p != end || values[2] <= 0 || values[3] <= 0) return false;
  out = {values[0], values[1], values[2], values[3]};
  return true;
}

}  // namespace pt
