// Film: the image being rendered, row 0 at the top. Each pixel holds sums, not
// a final value: the filter-weighted sum of its samples' radiance and the sum of
// their weights (both in double, so that 10^5 samples and more add up without
// losing precision), and the number of samples. The pixel value is
// sum / weight_sum. Because sums add, passes over sample ranges rendered one
// after another (or elsewhere) merge into the same image.
//
// Each pixel is written by exactly one task at a time (the render loop gives
// every pixel to one task), so adding needs no synchronisation and the result
// does not depend on the tile order.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/image.h"

namespace pt {

// The running sums of one pixel.
struct PixelSum {
  double r = 0, g = 0, b = 0;  // sum of weight * radiance
  double weight = 0;           // sum of filter weights
  uint64_t samples = 0;        // number of samples (non-finite ones included, as black)

  void add(RGB value, float w) {
    r += static_cast<double>(w) * value.r;
    g += static_cast<double>(w) * value.g;
    b += static_cast<double>(w) * value.b;
    weight += w;
    ++samples;
  }
  void add(const PixelSum& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    weight += o.weight;
    samples += o.samples;
  }
  // sum / weight; black for a pixel without weight.
  RGB value() const {
    if (weight == 0.0) return {};
    const double inv = 1.0 / weight;
    return {static_cast<float>(r * inv), static_cast<float>(g * inv), static_cast<float>(b * inv)};
  }
};

class Film {
 public:
  Film(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }

  void add(int x, int y, const PixelSum& s) { pixels_[index(x, y)].add(s); }
  const PixelSum& sum(int x, int y) const { return pixels_[index(x, y)]; }
  RGB pixel(int x, int y) const { return pixels_[index(x, y)].value(); }
  // The image: every pixel's sum / weight.
  Image image() const;
  void clear();

  // The film's complete state (every pixel's sums and counts), for checkpoints:
  // written and read back bit for bit, so that a render resumed from it adds up
  // to exactly the image of an uninterrupted one. Binary, little-endian; the
  // layout is in film.cpp. write_state returns false when the stream fails.
  bool write_state(std::ostream& out) const;
  // Replaces this film's state. Returns false, with `error` set and the film
  // unchanged, when the stream does not hold a state of a film of this size.
  bool read_state(std::istream& in, std::string& error);

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x; }

  int width_, height_;
  std::vector<PixelSum> pixels_;
};

}  // namespace pt
