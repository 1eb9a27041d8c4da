#include "render/film/film.h"

#include <algorithm>

namespace pt {

Film::Film(int width, int height)
    : width_(std::max(width, 0)), height_(std::max(height, 0)),
      pixels_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_)) {}

Image Film::image() const {
  Image out(width_, height_);
  for (std::size_t i = 0; i < pixels_.size(); ++i) out.pixels[i] = pixels_[i].value();
  return out;
}

void Film::clear() { std::fill(pixels_.begin(), pixels_.end(), PixelSum{}); }

}  // namespace pt
