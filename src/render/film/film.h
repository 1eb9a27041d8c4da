// Film: the image being rendered, linear RGB radiance per pixel, row 0 at the top.
// AOV buffers will live here too, allocated only when requested.
#pragma once

#include "core/color.h"
#include "core/image.h"

namespace pt {

class Film {
 public:
  Film(int width, int height) : image_(width, height) {}
  int width() const { return image_.width; }
  int height() const { return image_.height; }
  // Each pixel is written by exactly one task (deterministic whatever the tile order).
  void set_pixel(int x, int y, RGB value) { image_.at(x, y) = value; }
  const Image& image() const { return image_; }

 private:
  Image image_;
};

}  // namespace pt
