// Image textures: decoded once with OpenImageIO into linear float RGB,
// looked up with bilinear filtering and repeat wrapping. uv (0,0) is the
// image's top-left pixel corner, u to the right, v downwards.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/math.h"

namespace pt {

// What a texture or environment map may cost once decoded. The size an image
// declares in its header is checked against these before anything is
// allocated, so a small file claiming 100000 x 100000 pixels is refused, not
// decoded (docs/scene-format.md, "Textures").
struct TextureLimits {
  int64_t max_pixels = int64_t{1} << 28;  // width * height, as the film (LoadOptions::max_pixels)
  // Decoded bytes: the channels read (at most 3) as float, plus the RGB texels.
  uint64_t max_bytes = uint64_t{1} << 32;

  // The bytes Texture::load allocates to decode `pixels` pixels of an image
  // with `file_channels` channels: the channels it reads (1 for grey and grey +
  // alpha, else 3) as float, and the RGB texels. Saturates at UINT64_MAX.
  static uint64_t decoded_bytes(uint64_t pixels, int file_channels);
  // Whether Texture::load decodes such an image (it refuses any other before
  // allocating anything); the memory pre-flight asks the same.
  bool admit(uint64_t pixels, int file_channels) const {
    return pixels <= static_cast<uint64_t>(max_pixels) && decoded_bytes(pixels, file_channels) <= max_bytes;
  }
};

class Texture {
 public:
  Texture() = default;
  Texture(int width, int height, std::vector<RGB> pixels);

  // Loads an image file; 8-bit sRGB-encoded images are linearised unless `raw`
  // (values used as they are). Returns false and fills `error` if the file cannot
  // be read or declares a size beyond `limits`.
  static bool load(const std::string& path, Texture& out, std::string& error, const TextureLimits& limits = {},
                   bool raw = false);
  // The same for an image held in memory (a model file's embedded PNG or
  // JPEG); `format` is its kind as a file extension without the dot ("png").
  static bool load_memory(const std::vector<unsigned char>& bytes, const std::string& format, Texture& out,
                          std::string& error, const TextureLimits& limits = {}, bool raw = false);

  RGB lookup(Vec2f uv) const;  // bilinear, repeat wrap
  // Texel (x, y), 0 <= x < width, 0 <= y < height, row 0 at the top.
  const RGB& texel(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<RGB> pixels_;  // row-major, row 0 at the top
};

}  // namespace pt
