// A linear RGB image, row-major, row 0 at the top.
#pragma once

#include <cstddef>
#include <vector>

#include "core/color.h"

namespace pt {

struct Image {
  int width = 0, height = 0;
  std::vector<RGB> pixels;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h) {}
  RGB& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const RGB& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

}  // namespace pt
